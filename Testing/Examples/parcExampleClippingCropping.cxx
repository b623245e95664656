// Clipping planes and cropping, as a program for VTK's ray cast mappers sets them: the
// wavelet, composite and maximum intensity, cut by an oblique clipping plane (compared
// with vtkFixedPointVolumeRayCastMapper) and cropped to VTK's "fence" regions (compared
// with vtkGPUVolumeRayCastMapper).
#include "parcExampleHarness.h"

#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkPlane.h>

namespace
{
auto WaveletScene(int blendMode, bool clip, bool crop)
{
  return [=](vtkRenderer* renderer, auto* mapper) {
    mapper->SetInputData(parcexample::MakeWavelet());
    mapper->SetBlendMode(blendMode);
    parcexample::SampleAlike(mapper);
    if (clip)
    {
      vtkNew<vtkPlane> plane; // keeps x - 0.4 y >= -6
      plane->SetOrigin(-6, 0, 0);
      plane->SetNormal(1, -0.4, 0);
      mapper->AddClippingPlane(plane);
    }
    if (crop)
    {
      mapper->CroppingOn();
      mapper->SetCroppingRegionPlanes(-20, 12, -15, 18, -10, 9);
      mapper->SetCroppingRegionFlagsToFence();
    }
    parcexample::AddVolume(renderer, mapper, parcexample::MakeWaveletProperty());
  };
}
}

int main(int argc, char* argv[])
{
  using parcexample::AgainstFixedPoint;
  using parcexample::AgainstGPU;
  using parcexample::CompareWithVTK;
  using FixedPoint = vtkFixedPointVolumeRayCastMapper;
  using GPU = vtkGPUVolumeRayCastMapper;
  constexpr int composite = vtkVolumeMapper::COMPOSITE_BLEND;
  constexpr int mip = vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND;
  const auto clipped = [](int blendMode) { return WaveletScene(blendMode, true, false); };
  const auto cropped = [](int blendMode) { return WaveletScene(blendMode, false, true); };
  return CompareWithVTK<FixedPoint>(
           argc, argv, "ClippingComposite", clipped(composite), AgainstFixedPoint) |
    CompareWithVTK<FixedPoint>(argc, argv, "ClippingMIP", clipped(mip), AgainstFixedPoint) |
    CompareWithVTK<GPU>(argc, argv, "CroppingComposite", cropped(composite), AgainstGPU) |
    CompareWithVTK<GPU>(argc, argv, "CroppingMIP", cropped(mip), AgainstGPU);
}
