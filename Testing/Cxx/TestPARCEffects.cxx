// Only the effects a scene calls for: gradients, shadow rays and light passes,
// the view's passes and the rebuilds each have a counter, and switching the effect off (or
// leaving its inputs unchanged) makes that counter 0, while switching it on makes it
// positive, so that every check can fail.
#include "parcTestScene.h"
#include "vtkPARCMultiVolume.h"

#include <vtkLight.h>
#include <vtkRendererCollection.h>
#include <vtkTransform.h>

#include <iostream>
#include <string>

namespace
{
int Failures = 0;

void Expect(bool ok, const std::string& what)
{
  if (!ok)
  {
    std::cerr << "FAIL: " << what << "\n";
    ++Failures;
  }
}

/// Gradients only when shading or a non-constant, enabled gradient opacity needs them.
void CheckGradients(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper, vtkVolumeProperty* property)
{
  property->ShadeOff();
  window->Render();
  Expect(mapper->GetLastContributingSampleCount() > 0, "the scene shows something");
  Expect(mapper->GetLastGradientCount() == 0, "no gradient unshaded");
  property->GetGradientOpacity(); // VTK makes a constant function of 1 here
  window->Render();
  Expect(mapper->GetLastGradientCount() == 0, "no gradient for a constant gradient opacity");
  vtkNew<vtkPiecewiseFunction> ramp;
  ramp->AddPoint(0.0, 0.2);
  ramp->AddPoint(30.0, 1.0);
  property->SetGradientOpacity(ramp);
  window->Render();
  Expect(mapper->GetLastGradientCount() > 0, "gradients for a gradient-opacity ramp");
  property->DisableGradientOpacityOn();
  window->Render();
  Expect(mapper->GetLastGradientCount() == 0, "no gradient with the gradient opacity disabled");
  property->ShadeOn();
  window->Render();
  Expect(mapper->GetLastGradientCount() > 0, "gradients for shading");
}

/// Shadow rays and light passes only for shadow-casting lights, shaded contributions and a
/// renderer with shadows on; light passes only when a light moves.
void CheckShadows(vtkRenderWindow* window, vtkRenderer* renderer, vtkPARCVolumeMapper* mapper,
  vtkVolumeProperty* property)
{
  vtkNew<vtkLight> light;
  light->SetLightTypeToSceneLight();
  light->SetPositional(1);
  light->SetConeAngle(180.0);
  light->SetPosition(60, 80, 40);
  light->SetShadowAttenuation(0.0);
  renderer->RemoveAllLights(); // the headlight made by earlier renders casts shadows too
  renderer->AddLight(light);
  renderer->SetUseShadows(1);
  property->ShadeOn();
  const auto expectNone = [&](const std::string& why) {
    window->Render();
    Expect(mapper->GetLastShadowRayCount() == 0 && mapper->GetLastLightFrustumCount() == 0,
      "no shadow ray and no light pass " + why);
  };
  expectNone("for a light that casts no shadow");
  light->SetShadowAttenuation(1.0);
  window->Render();
  Expect(mapper->GetLastShadowRayCount() > 0 && mapper->GetLastLightFrustumCount() > 0,
    "shadow rays and light passes for a shadow-casting light");
  renderer->GetActiveCamera()->Azimuth(10);
  window->Render();
  Expect(mapper->GetLastShadowRayCount() > 0 && mapper->GetLastLightFrustumCount() == 0,
    "shadow rays but no light pass after a camera move");
  light->SetPosition(-60, 80, 40);
  renderer->SetUseShadows(0);
  expectNone("with the renderer's shadows off");
  // ShadowMode On casts them without the renderer's switch, and the same image as with it.
  mapper->SetShadowModeToOn();
  window->Render();
  const std::vector<float> forced = parctest::RayImage(mapper);
  Expect(mapper->GetLastShadowRayCount() > 0, "shadow rays with ShadowMode On");
  renderer->SetUseShadows(1);
  mapper->SetShadowModeToOff();
  expectNone("with ShadowMode Off");
  mapper->SetShadowModeToFromRenderer();
  window->Render();
  Expect(parctest::RayImage(mapper) == forced,
    "ShadowMode On gives the image the renderer's shadows give");
  property->ShadeOff();
  light->SetPosition(60, -80, 40);
  expectNone("without shading");
  property->ShadeOn();
  renderer->RemoveLight(light);
  renderer->SetUseShadows(0);
}

/// No work is done again when nothing changed.
void CheckRebuilds(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper)
{
  window->Render();
  const vtkIdType counts[4] = { mapper->GetPyramidBuildCount(), mapper->GetClassificationCount(),
    mapper->GetModelBuildCount(), mapper->GetModelUploadCount() };
  window->Render();
  const vtkIdType again[4] = { mapper->GetPyramidBuildCount(), mapper->GetClassificationCount(),
    mapper->GetModelBuildCount(), mapper->GetModelUploadCount() };
  Expect(std::equal(counts, counts + 4, again) && counts[1] > 0,
    "no pyramid, classification, model build or upload without a change");
}

/// No pass for a volume of a multi-volume outside the view; the image stays exact.
void CheckPassesOutsideTheView(vtkRenderWindow* window)
{
  vtkSmartPointer<vtkImageData> image = parctest::MakeBlobs(32);
  vtkSmartPointer<vtkVolumeProperty> property = parctest::MakeProperty(false);
  vtkNew<vtkPARCVolumeMapper> single, both;
  single->SetInputData(image);
  both->SetInputDataObject(0, image);
  both->SetInputDataObject(1, image);
  vtkNew<vtkVolume> alone, first, second;
  alone->SetMapper(single);
  for (vtkVolume* v : { alone.Get(), first.Get(), second.Get() })
  {
    v->SetProperty(property);
  }
  vtkNew<vtkPARCMultiVolume> multi;
  multi->SetMapper(both);
  multi->SetVolume(first, 0);
  multi->SetVolume(second, 1);
  vtkNew<vtkTransform> away;
  second->SetUserTransform(away);

  vtkNew<vtkRenderer> renderer;
  window->AddRenderer(renderer);
  const auto aimAtTheFirst = [&]() { // the same camera every time
    vtkCamera* camera = renderer->GetActiveCamera();
    camera->SetFocalPoint(0, 0, 0);
    camera->SetPosition(0, 50, 160);
    camera->SetViewUp(0, 1, 0);
    renderer->ResetCameraClippingRange();
  };
  const auto render = [&](vtkVolume* shown, vtkPARCVolumeMapper* mapper, int mode) {
    renderer->RemoveAllViewProps();
    renderer->AddVolume(shown);
    mapper->SetAccelerationMode(mode);
    aimAtTheFirst();
    window->Render();
    return parctest::RayImage(mapper);
  };
  render(alone, single, vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER);
  const vtkIdType polygonsAlone = single->GetLastPolygonCount();
  for (double shift : { 20.0, 400.0 }) // in view, partly overlapping; far to the side
  {
    away->Identity();
    away->Translate(shift, 0, 0);
    const std::vector<float> reference =
      render(multi, both, vtkPARCVolumeMapper::ACCELERATION_NONE);
    const std::vector<float> fast = render(multi, both, vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER);
    std::size_t differ = fast.size() == reference.size() ? 0 : reference.size();
    for (std::size_t i = 0; i < fast.size() && fast.size() == reference.size(); ++i)
    {
      differ += fast[i] != reference[i];
    }
    Expect(!reference.empty() && differ == 0, "exact with the second volume shifted by " +
        std::to_string(shift) + ": " + std::to_string(differ) + " values differ of " +
        std::to_string(reference.size()));
    const vtkIdType polygons = both->GetLastPolygonCount();
    Expect(shift < 100.0 ? polygons > polygonsAlone : polygons == polygonsAlone,
      "polygons " + std::to_string(polygons) + " with the second volume shifted by " +
        std::to_string(shift) + ", " + std::to_string(polygonsAlone) + " for the first alone");
  }
  window->RemoveRenderer(renderer);
}
}

int TestPARCEffects(int, char*[])
{
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(64, 56);
  vtkSmartPointer<vtkImageData> image = parctest::MakeBlobs(32);
  vtkSmartPointer<vtkVolumeProperty> property = parctest::MakeProperty(false);
  const double viewport[4] = { 0, 0, 1, 1 };
  vtkSmartPointer<vtkPARCVolumeMapper> mapper =
    parctest::AddVolume(window, viewport, image, property, vtkVolumeMapper::COMPOSITE_BLEND);
  mapper->SetAccelerationModeToDepthBuffer();
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();

  CheckGradients(window, mapper, property);
  CheckShadows(window, renderer, mapper, property);
  CheckRebuilds(window, mapper);
  window->RemoveRenderer(renderer);
  CheckPassesOutsideTheView(window);
  std::cout << Failures << " failures\n";
  return Failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
