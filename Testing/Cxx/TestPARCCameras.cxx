// Cameras and transforms: (left) perspective camera inside the volume; (middle) parallel
// projection of a volume with non-uniform spacing, a direction matrix, an orientation, a
// scale and a user matrix, lit by a positional spot light; (right) opaque geometry crossing
// the volume: rays end at the sphere's depth.
#include "parcTestScene.h"

#include <vtkActor.h>
#include <vtkLight.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRendererCollection.h>
#include <vtkSphereSource.h>
#include <vtkVolumeCollection.h>

#include <iostream>

int TestPARCCameras(int argc, char* argv[])
{
  vtkNew<vtkRenderWindow> window;
  window->SetSize(450, 150);
  window->SetMultiSamples(0);
  auto image = parctest::MakeBlobs();
  auto property = parctest::MakeProperty(true);

  // Camera inside the volume, looking at the blobs.
  const double left[4] = { 0.0, 0.0, 1.0 / 3, 1.0 };
  auto inside = parctest::AddVolume(window, left, image, property, vtkVolumeMapper::COMPOSITE_BLEND);
  vtkRenderer* insideRenderer = vtkRenderer::SafeDownCast(window->GetRenderers()->GetItemAsObject(0));
  vtkCamera* camera = insideRenderer->GetActiveCamera();
  camera->SetPosition(0.0, -20.0, 2.0);
  camera->SetFocalPoint(0.0, 10.0, 0.0);
  camera->SetViewUp(0.0, 0.0, 1.0);
  camera->SetViewAngle(70.0);
  insideRenderer->ResetCameraClippingRange();

  // Transformed volume, parallel projection, positional spot light.
  auto transformed = parctest::MakeBlobs();
  transformed->SetSpacing(1.6, 1.3, 1.0);
  vtkNew<vtkMatrix3x3> direction;
  direction->SetElement(0, 0, 0.0);
  direction->SetElement(0, 1, -1.0);
  direction->SetElement(1, 0, 1.0);
  direction->SetElement(1, 1, 0.0);
  transformed->SetDirectionMatrix(direction);
  const double middle[4] = { 1.0 / 3, 0.0, 2.0 / 3, 1.0 };
  auto moved = parctest::AddVolume(window, middle, transformed, property, vtkVolumeMapper::COMPOSITE_BLEND);
  vtkRenderer* movedRenderer = vtkRenderer::SafeDownCast(window->GetRenderers()->GetItemAsObject(1));
  vtkVolume* volume = vtkVolume::SafeDownCast(movedRenderer->GetVolumes()->GetItemAsObject(0));
  volume->SetOrientation(10.0, 25.0, -15.0);
  volume->SetScale(1.0, 0.8, 1.2);
  volume->SetPosition(5.0, 0.0, -3.0);
  vtkNew<vtkMatrix4x4> user;
  user->SetElement(0, 1, 0.2); // a shear
  volume->SetUserMatrix(user);
  movedRenderer->GetActiveCamera()->ParallelProjectionOn();
  movedRenderer->ResetCamera();
  vtkNew<vtkLight> spot;
  spot->SetLightTypeToSceneLight();
  spot->SetPositional(true);
  spot->SetPosition(60.0, 60.0, 80.0);
  spot->SetFocalPoint(0.0, 0.0, 0.0);
  spot->SetConeAngle(30.0);
  spot->SetColor(1.0, 0.9, 0.8);
  movedRenderer->AddLight(spot);

  // Opaque geometry crossing the volume.
  const double right[4] = { 2.0 / 3, 0.0, 1.0, 1.0 };
  auto withGeometry = parctest::AddVolume(window, right, image, property, vtkVolumeMapper::COMPOSITE_BLEND);
  vtkRenderer* geometryRenderer = vtkRenderer::SafeDownCast(window->GetRenderers()->GetItemAsObject(2));
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(-6.0, 0.0, 0.0);
  sphere->SetRadius(12.0);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(24);
  vtkNew<vtkPolyDataMapper> sphereMapper;
  sphereMapper->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(sphereMapper);
  actor->GetProperty()->SetColor(0.3, 0.8, 0.4);
  geometryRenderer->AddActor(actor);
  geometryRenderer->ResetCameraClippingRange();

  window->Render();
  for (vtkPARCVolumeMapper* m : { inside.Get(), moved.Get(), withGeometry.Get() })
  {
    if (m->GetLastRayCount() <= 0 || parctest::MaxAlpha(m) <= 0.0)
    {
      std::cerr << "a volume drew nothing\n";
      return EXIT_FAILURE;
    }
  }
  // The sphere hides part of the volume: fewer samples than without it.
  const vtkIdType withSphere = withGeometry->GetLastSampleCount();
  actor->VisibilityOff();
  window->Render();
  const vtkIdType withoutSphere = withGeometry->GetLastSampleCount();
  actor->VisibilityOn();
  window->Render();
  if (withSphere >= withoutSphere)
  {
    std::cerr << "rays did not stop at the opaque sphere: " << withSphere << " samples with it, "
              << withoutSphere << " without\n";
    return EXIT_FAILURE;
  }
  return parctest::MatchesBaseline(window, argc, argv) ? EXIT_SUCCESS : EXIT_FAILURE;
}
