// A program written for vtkSmartVolumeMapper: the ray cast render mode requested, an
// interactive update rate, sample distances adjusted while interacting only
// (InteractiveAdjustSampleDistances, the smart mapper's default, with
// AutoAdjustSampleDistances off), and GetLastUsedRenderMode read back after the render.
// The wavelet, composite. Compared with vtkSmartVolumeMapper itself, which casts
// with vtkFixedPointVolumeRayCastMapper in this mode.
#include "parcExampleHarness.h"

#include <vtkSmartVolumeMapper.h>

int main(int argc, char* argv[])
{
  const auto scene = [](vtkRenderer* renderer, auto* mapper) {
    mapper->SetInputData(parcexample::MakeWavelet());
    mapper->SetRequestedRenderModeToRayCast();
    mapper->SetInteractiveUpdateRate(2.0);
    mapper->SetInteractiveAdjustSampleDistances(1);
    mapper->SetAutoAdjustSampleDistances(0);
    mapper->SetSampleDistance(0.5);
    parcexample::AddVolume(renderer, mapper, parcexample::MakeWaveletProperty());
  };
  const auto castByRays = [](auto* mapper) {
    const int mode = mapper->GetLastUsedRenderMode();
    std::cout << mapper->GetClassName() << " used render mode " << mode << "\n";
    return mode == vtkSmartVolumeMapper::RayCastRenderMode;
  };
  return parcexample::CompareWithVTK<vtkSmartVolumeMapper>(
    argc, argv, "SmartVolumeMapper", scene, parcexample::AgainstFixedPoint, castByRays);
}
