// Dependent components (vtkVolumeProperty::IndependentComponentsOff), as VTK defines them:
// four unsigned char components are RGBA, colour from the first three and opacity from the
// fourth through the scalar opacity function; two components are colour from the first
// through the colour function and opacity from the second. The colours come from blobs, the
// opacity from the wavelet. Compared with vtkFixedPointVolumeRayCastMapper.
#include "parcExampleHarness.h"

#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkImageAppendComponents.h>

#include <vector>

namespace
{
auto DependentScene(const std::vector<vtkSmartPointer<vtkImageData>>& components)
{
  return [=](vtkRenderer* renderer, auto* mapper) {
    vtkNew<vtkImageAppendComponents> append;
    for (const auto& component : components)
    {
      append->AddInputData(component);
    }
    mapper->SetInputConnection(append->GetOutputPort());
    parcexample::SampleAlike(mapper);
    auto property = parcexample::MakeWaveletProperty();
    property->IndependentComponentsOff();
    parcexample::AddVolume(renderer, mapper, property);
  };
}
}

int main(int argc, char* argv[])
{
  using parcexample::MakeBlob;
  using FixedPoint = vtkFixedPointVolumeRayCastMapper;
  const auto wavelet = parcexample::MakeWavelet();
  const auto rgba = DependentScene({ MakeBlob(-12, 0, 0, 14), MakeBlob(12, 6, 0, 14),
    MakeBlob(0, -12, 8, 14), wavelet });
  const auto colorAndOpacity = DependentScene({ MakeBlob(10, 10, 0, 16), wavelet });
  return parcexample::CompareWithVTK<FixedPoint>(
           argc, argv, "DependentRGBA", rgba, parcexample::AgainstFixedPoint) |
    parcexample::CompareWithVTK<FixedPoint>(
      argc, argv, "DependentColorOpacity", colorAndOpacity, parcexample::AgainstFixedPoint);
}
