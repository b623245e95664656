// A program written for vtkFixedPointVolumeRayCastMapper, as such programs set it up:
// shading (ambient 0.6, diffuse 0.6, specular 0.1), a gradient opacity, cropping, spacing
// 3.2 x 3.2 x 1.5 and a rotation as the volume's user transform. Swapped to this mapper,
// it keeps FixedPoint's brightness with SetAmbientModelToLights (FixedPoint lights the
// ambient term by the lights' ambient colours, black under VTK's default lights; this
// mapper's default follows the GPU mapper, about 16 grey levels brighter here), and its
// gradient opacity measures gradients per mean voxel spacing, as FixedPoint's does.
// Compared with vtkFixedPointVolumeRayCastMapper.
#include "parcExampleHarness.h"

#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkTransform.h>

#include <type_traits>

namespace
{
/// The one more line a program swapped from FixedPoint sets (none for FixedPoint itself).
template <class Mapper>
void FollowFixedPoint(Mapper* mapper)
{
  if constexpr (std::is_same<Mapper, vtkPARCVolumeMapper>::value)
  {
    mapper->SetAmbientModelToLights();
  }
}

auto FixedPointScene()
{
  return [](vtkRenderer* renderer, auto* mapper) {
    vtkNew<vtkImageData> wavelet;
    wavelet->ShallowCopy(parcexample::MakeWavelet());
    wavelet->SetSpacing(3.2, 3.2, 1.5);
    mapper->SetInputData(wavelet);
    FollowFixedPoint(mapper);
    parcexample::SampleAlike(mapper);
    mapper->SetSampleDistance(1.0);
    const double* b = wavelet->GetBounds();
    mapper->CroppingOn();
    mapper->SetCroppingRegionPlanes(
      b[0], b[0] + 0.7 * (b[1] - b[0]), b[2], b[3], b[4], b[4] + 0.8 * (b[5] - b[4]));
    mapper->SetCroppingRegionFlagsToSubVolume();
    auto property = parcexample::MakeWaveletProperty();
    property->ShadeOn();
    property->SetAmbient(0.6);
    property->SetDiffuse(0.6);
    property->SetSpecular(0.1);
    vtkNew<vtkPiecewiseFunction> gradient;
    gradient->AddPoint(0, 0.2);
    gradient->AddPoint(4, 0.6);
    gradient->AddPoint(12, 1.0);
    property->SetGradientOpacity(gradient);
    parcexample::AddVolume(renderer, mapper, property);
    vtkNew<vtkTransform> rotation;
    rotation->RotateZ(30);
    rotation->RotateX(20);
    vtkVolume::SafeDownCast(renderer->GetVolumes()->GetLastProp())->SetUserTransform(rotation);
    renderer->ResetCamera();
    renderer->GetActiveCamera()->Zoom(1.6);
  };
}
}

int main(int argc, char* argv[])
{
  return parcexample::CompareWithVTK<vtkFixedPointVolumeRayCastMapper>(
    argc, argv, "FixedPointProgram", FixedPointScene(), parcexample::AgainstFixedPoint);
}
