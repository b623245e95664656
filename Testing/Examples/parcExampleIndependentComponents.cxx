// A volume of two independent components (vtkVolumeProperty::IndependentComponentsOn, VTK's
// default), each with its own transfer functions and weight: the wavelet in component 0 and
// a green blob at its edge in component 1, at weight 0.7; composite and maximum
// intensity. And minimum intensity over four components, each a dark blob (255 minus a
// Gaussian) in its own place and colour, so that every component's minimum shows as
// structure. Compared with vtkFixedPointVolumeRayCastMapper.
#include "parcExampleHarness.h"

#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkImageAppendComponents.h>
#include <vtkImageShiftScale.h>

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

/// A dark blob: 255 minus MakeBlob's Gaussian.
vtkSmartPointer<vtkImageData> DarkBlob(double x, double y, double z, double sigma)
{
  vtkNew<vtkImageShiftScale> invert;
  invert->SetInputData(parcexample::MakeBlob(x, y, z, sigma));
  invert->SetShift(-255.0);
  invert->SetScale(-1.0);
  invert->SetOutputScalarTypeToUnsignedChar();
  invert->Update();
  return invert->GetOutput();
}

/// Minimum intensity over four independent components, each opaque and coloured where it
/// is dark.
auto FourDarkBlobs()
{
  return [=](vtkRenderer* renderer, auto* mapper) {
    constexpr double Centres[4][3] = { { -8, -8, 0 }, { 8, -8, 4 }, { -8, 8, -4 }, { 8, 8, 0 } };
    constexpr double Colours[4][3] = { { 1, 0.2, 0.2 }, { 0.2, 1, 0.2 }, { 0.3, 0.4, 1 },
      { 1, 0.9, 0.2 } };
    vtkNew<vtkImageAppendComponents> components;
    for (const auto& c : Centres)
    {
      components->AddInputData(DarkBlob(c[0], c[1], c[2], 10));
    }
    components->Update();
    mapper->SetInputConnection(components->GetOutputPort());
    mapper->SetBlendMode(vtkVolumeMapper::MINIMUM_INTENSITY_BLEND);
    parcexample::SampleAlike(mapper);

    vtkNew<vtkVolumeProperty> property;
    property->IndependentComponentsOn();
    property->SetInterpolationTypeToLinear();
    for (int i = 0; i < 4; ++i)
    {
      vtkNew<vtkPiecewiseFunction> opacity;
      opacity->AddPoint(0, 1.0);
      opacity->AddPoint(255, 0.0);
      vtkNew<vtkColorTransferFunction> colour;
      colour->AddRGBPoint(0, Colours[i][0], Colours[i][1], Colours[i][2]);
      colour->AddRGBPoint(255, 0.0, 0.0, 0.0);
      property->SetScalarOpacity(i, opacity);
      property->SetColor(i, colour);
    }
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
      TwoComponentScene(vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND), AgainstFixedPoint) |
    parcexample::CompareWithVTK<FixedPoint>(
      argc, argv, "IndependentComponentsMinIP4", FourDarkBlobs(), AgainstFixedPoint);
}
