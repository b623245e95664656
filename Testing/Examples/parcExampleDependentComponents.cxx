// Dependent components (vtkVolumeProperty::IndependentComponentsOff), as VTK defines them:
// four unsigned char components are RGBA, colour from the first three and opacity from the
// fourth through the scalar opacity function; two components are colour from the first
// through the colour function and opacity from the second. The colours come from blobs, the
// opacity from the wavelet. And the maximum and minimum intensity of RGBA volumes: the
// extreme of the opacity component (a bright blob, or a dark one as in VTK's
// TestGPURayCastFourComponentsMinIP), coloured by the RGB there. Compared with
// vtkFixedPointVolumeRayCastMapper, the extremes with vtkGPUVolumeRayCastMapper: FixedPoint
// colours some rays of the extremes from the wrong place (blocks of wrong colour along one
// side of the blob).
#include "parcExampleHarness.h"

#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkImageAppendComponents.h>
#include <vtkImageShiftScale.h>

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

/// Maximum (or, inverted, minimum) intensity of RGBA: colour blobs, and a blob as the
/// opacity component whose extreme each ray meets once. inverted: every component is
/// 255 minus itself and the opacity falls from 1 at 0 to 0 at 255, as in VTK's test.
auto ExtremeRGBAScene(bool inverted)
{
  return [=](vtkRenderer* renderer, auto* mapper) {
    using parcexample::MakeBlob;
    vtkNew<vtkImageAppendComponents> append;
    for (const auto& component : { MakeBlob(-10, 0, 0, 12), MakeBlob(10, 6, 0, 12),
           MakeBlob(0, -10, 6, 12), MakeBlob(0, 0, 0, 10) })
    {
      append->AddInputData(component);
    }
    vtkNew<vtkImageShiftScale> invert;
    invert->SetInputConnection(append->GetOutputPort());
    invert->SetShift(inverted ? -255.0 : 0.0);
    invert->SetScale(inverted ? -1.0 : 1.0);
    invert->SetOutputScalarTypeToUnsignedChar();
    mapper->SetInputConnection(invert->GetOutputPort());
    mapper->SetBlendMode(inverted ? vtkVolumeMapper::MINIMUM_INTENSITY_BLEND
                                  : vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND);
    parcexample::SampleAlike(mapper);
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0, inverted ? 1.0 : 0.0);
    opacity->AddPoint(255, inverted ? 0.0 : 1.0);
    vtkNew<vtkVolumeProperty> property;
    property->IndependentComponentsOff();
    property->SetScalarOpacity(opacity);
    property->SetInterpolationTypeToLinear();
    parcexample::AddVolume(renderer, mapper, property);
  };
}
}

int main(int argc, char* argv[])
{
  using parcexample::MakeBlob;
  using FixedPoint = vtkFixedPointVolumeRayCastMapper;
  using GPU = vtkGPUVolumeRayCastMapper;
  const auto wavelet = parcexample::MakeWavelet();
  const auto rgba = DependentScene({ MakeBlob(-12, 0, 0, 14), MakeBlob(12, 6, 0, 14),
    MakeBlob(0, -12, 8, 14), wavelet });
  const auto colorAndOpacity = DependentScene({ MakeBlob(10, 10, 0, 16), wavelet });
  return parcexample::CompareWithVTK<FixedPoint>(
           argc, argv, "DependentRGBA", rgba, parcexample::AgainstFixedPoint) |
    parcexample::CompareWithVTK<FixedPoint>(
      argc, argv, "DependentColorOpacity", colorAndOpacity, parcexample::AgainstFixedPoint) |
    parcexample::CompareWithVTK<GPU>(
      argc, argv, "DependentRGBAMIP", ExtremeRGBAScene(false), parcexample::AgainstGPU) |
    parcexample::CompareWithVTK<GPU>(
      argc, argv, "DependentRGBAMinIP", ExtremeRGBAScene(true), parcexample::AgainstGPU);
}
