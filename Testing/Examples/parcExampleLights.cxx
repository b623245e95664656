// Shading with a program's own coloured lights: the fuzzy sphere of a blob, shaded
// (diffuse 0.9) under a warm headlight and a blue scene light from the upper front.
// Compared with vtkGPUVolumeRayCastMapper, where VTK's two mappers agree. The ambient and
// specular coefficients are 0, and the light falls on the side the camera sees, because
// with lights of a program's own VTK 9.1's GPU mapper
// - takes the ambient term from the lights' ambient colours (black by default), where
//   vtkFixedPointVolumeRayCastMapper and this mapper take the ambient coefficient times the
//   sample's colour;
// - draws Phong highlights, this mapper Blinn-Phong ones;
// - lights two-sided by |n.l|, where this mapper turns the normal towards the eye, as VTK's
//   surfaces do.
// The lights' specular colours are tested in the core and Python tests.
#include "parcExampleHarness.h"

#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkLight.h>

int main(int argc, char* argv[])
{
  const auto scene = [](vtkRenderer* renderer, auto* mapper) {
    mapper->SetInputData(parcexample::MakeBlob(0, 0, 0, 12));
    parcexample::SampleAlike(mapper);
    vtkNew<vtkPiecewiseFunction> shell; // a fuzzy sphere about 36 voxels across
    shell->AddPoint(0, 0.0);
    shell->AddPoint(30, 0.0);
    shell->AddPoint(80, 0.5);
    vtkNew<vtkColorTransferFunction> ivory;
    ivory->AddRGBPoint(0, 0.9, 0.85, 0.75);
    ivory->AddRGBPoint(254, 0.9, 0.85, 0.75);
    vtkNew<vtkVolumeProperty> property;
    property->SetScalarOpacity(shell);
    property->SetColor(ivory);
    property->SetInterpolationTypeToLinear();
    property->ShadeOn();
    property->SetAmbient(0.0);
    property->SetDiffuse(0.9);
    property->SetSpecular(0.0);
    parcexample::AddVolume(renderer, mapper, property);

    vtkNew<vtkLight> headlight;
    headlight->SetLightTypeToHeadlight();
    headlight->SetColor(1.0, 0.85, 0.7);
    headlight->SetIntensity(0.5);
    vtkNew<vtkLight> blue;
    blue->SetLightTypeToSceneLight();
    blue->SetPosition(60, 80, 100);
    blue->SetFocalPoint(0, 0, 0);
    blue->SetColor(0.3, 0.5, 1.0);
    blue->SetIntensity(0.8);
    renderer->AddLight(headlight);
    renderer->AddLight(blue);
  };
  return parcexample::CompareWithVTK<vtkGPUVolumeRayCastMapper>(
    argc, argv, "Lights", scene, parcexample::AgainstGPU);
}
