// Slice blending (vtkVolumeMapper::SetBlendModeToSlice): the wavelet's values on an oblique
// plane, the property's SliceFunction, coloured by its transfer functions, unshaded and
// shaded. Compared with vtkGPUVolumeRayCastMapper; VTK's FixedPoint mapper has no slices.
#include "parcExampleHarness.h"

#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkPlane.h>

namespace
{
auto SliceScene(bool shade)
{
  return [=](vtkRenderer* renderer, auto* mapper) {
    mapper->SetInputData(parcexample::MakeWavelet());
    mapper->SetBlendModeToSlice();
    parcexample::SampleAlike(mapper);
    auto property = parcexample::MakeWaveletProperty();
    vtkNew<vtkPlane> plane;
    plane->SetOrigin(0.0, 0.0, 3.3); // the volume's centre is at the world origin
    plane->SetNormal(0.2, 0.3, 1.0);
    property->SetSliceFunction(plane);
    property->SetShade(shade);
    parcexample::AddVolume(renderer, mapper, property);
  };
}
}

int main(int argc, char* argv[])
{
  using GPU = vtkGPUVolumeRayCastMapper;
  using parcexample::AgainstGPU;
  using parcexample::CompareWithVTK;
  return CompareWithVTK<GPU>(argc, argv, "Slice", SliceScene(false), AgainstGPU) |
    CompareWithVTK<GPU>(argc, argv, "SliceShaded", SliceScene(true), AgainstGPU);
}
