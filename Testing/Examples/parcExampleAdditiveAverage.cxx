// Additive and average-intensity blending, which VTK defines as grey intensity images:
// the wavelet summed along each ray, averaged, and averaged over the values from 100 up
// (vtkVolumeMapper::SetAverageIPScalarRange). Compared with vtkGPUVolumeRayCastMapper; VTK's
// FixedPoint mapper has neither mode.
#include "parcExampleHarness.h"

#include <vtkGPUVolumeRayCastMapper.h>

namespace
{
auto IntensityScene(int blendMode, double lowest)
{
  return [=](vtkRenderer* renderer, auto* mapper) {
    mapper->SetInputData(parcexample::MakeWavelet());
    mapper->SetBlendMode(blendMode);
    mapper->SetAverageIPScalarRange(lowest, 255);
    parcexample::SampleAlike(mapper);
    auto property = parcexample::MakeWaveletProperty();
    // The grey level is the sum or average of the opacity function's values along the ray:
    // a small ramp keeps a sum of about 200 samples in range.
    vtkNew<vtkPiecewiseFunction> opacity;
    opacity->AddPoint(0, 0.0);
    opacity->AddPoint(254, blendMode == vtkVolumeMapper::ADDITIVE_BLEND ? 0.008 : 1.0);
    property->SetScalarOpacity(opacity);
    parcexample::AddVolume(renderer, mapper, property);
  };
}
}

int main(int argc, char* argv[])
{
  using GPU = vtkGPUVolumeRayCastMapper;
  using parcexample::AgainstGPU;
  using parcexample::CompareWithVTK;
  const int additive = vtkVolumeMapper::ADDITIVE_BLEND;
  const int average = vtkVolumeMapper::AVERAGE_INTENSITY_BLEND;
  return CompareWithVTK<GPU>(argc, argv, "Additive", IntensityScene(additive, 0), AgainstGPU) |
    CompareWithVTK<GPU>(argc, argv, "Average", IntensityScene(average, 0), AgainstGPU) |
    CompareWithVTK<GPU>(argc, argv, "AverageFrom100", IntensityScene(average, 100), AgainstGPU);
}
