// A volume of two independent components (vtkVolumeProperty::IndependentComponentsOn, VTK's
// default), each with its own transfer functions and weight: the wavelet in component 0 and
// a green blob at its edge in component 1, at weight 0.7; composite and maximum
// intensity. Compared with vtkFixedPointVolumeRayCastMapper.
#include "parcExampleHarness.h"

#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkImageAppendComponents.h>

namespace
{
auto TwoComponentScene(int blendMode)
{
  return [=](vtkRenderer* renderer, auto* mapper) {
    vtkNew<vtkImageAppendComponents> components;
    components->AddInputData(parcexample::MakeWavelet());
    components->AddInputData(parcexample::MakeBlob(16, -14, 10, 7));
    components->Update();
    mapper->SetInputConnection(components->GetOutputPort());
    mapper->SetBlendMode(blendMode);
    parcexample::SampleAlike(mapper);

    auto property = parcexample::MakeWaveletProperty();
    property->IndependentComponentsOn();
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0, 0.0);
    opacity->AddPoint(100, 0.0);
    opacity->AddPoint(254, 0.8);
    vtkNew<vtkColorTransferFunction> green;
    green->AddRGBPoint(0, 0.0, 0.3, 0.0);
    green->AddRGBPoint(254, 0.3, 1.0, 0.3);
    property->SetScalarOpacity(1, opacity);
    property->SetColor(1, green);
    property->SetComponentWeight(1, 0.7);
    parcexample::AddVolume(renderer, mapper, property);
  };
}
}

int main(int argc, char* argv[])
{
  using parcexample::AgainstFixedPoint;
  using FixedPoint = vtkFixedPointVolumeRayCastMapper;
  return parcexample::CompareWithVTK<FixedPoint>(argc, argv, "IndependentComponentsComposite",
           TwoComponentScene(vtkVolumeMapper::COMPOSITE_BLEND), AgainstFixedPoint) |
    parcexample::CompareWithVTK<FixedPoint>(argc, argv, "IndependentComponentsMIP",
      TwoComponentScene(vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND), AgainstFixedPoint);
}
