// The paper's Figure 13 from ../shared/data: the embryo (the stand-in for the confocal
// neuron) as an isosurface standing over the voxelized floor slab of parcio::MakeFloor, two
// point lights casting shadows, both volumes through one vtkPARCMultiVolume. Checks: the
// shadowed float image is bit-identical in every acceleration mode; PARC narrows the shadow
// rays (fewer shadow cells than without acceleration, the same shadow rays); the shadows
// darken the floor; then the regression image. The data folder is the first argument; the
// test is only registered when the data are there.
#include "parcTestScene.h"
#include "parcVolumeIO.h"
#include "vtkPARCMultiVolume.h"

#include <vtkLight.h>

#include <cstring>
#include <iostream>
#include <string>

namespace
{
constexpr double EmbryoIsoValue = 80.0;

/// The Figure 13 look: an opaque shaded surface with some ambient light.
vtkSmartPointer<vtkVolumeProperty> SurfaceProperty(double iso, const double rgb[3])
{
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  parcio::SetUpSurfaceProperty(iso, rgb, property);
  property->SetAmbient(0.25);
  property->SetDiffuse(0.75);
  property->SetSpecular(0.2);
  return property;
}

/// The mean red of the float image (premultiplied by alpha), over all pixels.
double MeanRed(const std::vector<float>& rgba)
{
  double sum = 0.0;
  for (std::size_t i = 0; i < rgba.size(); i += 4)
  {
    sum += rgba[i];
  }
  return sum / std::max<std::size_t>(1, rgba.size() / 4);
}
}

int TestPARCShadowFloor(int argc, char* argv[])
{
  if (argc < 2)
  {
    std::cerr << "usage: TestPARCShadowFloor <data folder> [regression options]\n";
    return EXIT_FAILURE;
  }
  vtkNew<vtkImageData> embryo, floor;
  std::string error;
  if (!parcio::ReadVolume(std::string(argv[1]) + "/embryo_256x256x256_uint8.raw", embryo, error))
  {
    std::cerr << "FAIL: " << error << "\n";
    return EXIT_FAILURE;
  }
  parcio::MakeFloor(embryo->GetBounds(), floor);

  vtkNew<vtkPARCVolumeMapper> mapper;
  mapper->SetInputDataObject(0, embryo);
  mapper->SetInputDataObject(1, floor);
  mapper->SetInputBlendMode(0, vtkVolumeMapper::ISOSURFACE_BLEND);
  mapper->SetInputBlendMode(1, vtkVolumeMapper::ISOSURFACE_BLEND);
  mapper->SetSupercellSize(4, 4, 4); // the paper's 64^3 supercells for its neuron
  constexpr double Skin[3] = { 0.95, 0.75, 0.55 }, Grey[3] = { 0.85, 0.85, 0.8 };
  vtkNew<vtkVolume> object, ground;
  object->SetProperty(SurfaceProperty(EmbryoIsoValue, Skin));
  ground->SetProperty(SurfaceProperty(parcio::FloorIsoValue, Grey));
  vtkNew<vtkPARCMultiVolume> scene;
  scene->SetMapper(mapper);
  scene->SetVolume(object, 0);
  scene->SetVolume(ground, 1);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.1, 0.15);
  renderer->AddVolume(scene);
  renderer->SetUseShadows(1);
  constexpr double LightPositions[2][3] = { { -250, 500, 350 }, { 550, 450, 250 } };
  for (const double* position : LightPositions)
  {
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetPositional(1);
    light->SetConeAngle(180.0);
    light->SetPosition(position);
    light->SetFocalPoint(embryo->GetCenter());
    light->SetIntensity(0.5);
    light->SetShadowAttenuation(1.0);
    renderer->AddLight(light);
  }
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  renderer->ResetCamera();
  camera->Azimuth(20);
  camera->Elevation(55);
  camera->OrthogonalizeViewUp();
  camera->Zoom(1.3);
  renderer->ResetCameraClippingRange();

  int failures = 0;
  // Every mode gives the unaccelerated bits; PARC casts the same shadow rays through
  // fewer cells.
  window->SetSize(120, 100);
  mapper->SetAccelerationModeToNone();
  window->Render();
  const std::vector<float> reference = parctest::RayImage(mapper);
  const vtkIdType shadowRays = mapper->GetLastShadowRayCount();
  const vtkIdType shadowCells = mapper->GetLastShadowCellCount();
  if (shadowRays == 0)
  {
    std::cerr << "FAIL: no shadow rays\n";
    ++failures;
  }
  for (int mode : { vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER,
         vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER, vtkPARCVolumeMapper::ACCELERATION_BOTH,
         vtkPARCVolumeMapper::ACCELERATION_SUPERCELL_WALK, vtkPARCVolumeMapper::ACCELERATION_AUTO })
  {
    mapper->SetAccelerationMode(mode);
    window->Render();
    const std::vector<float> fast = parctest::RayImage(mapper);
    const char* name = vtkPARCVolumeMapper::GetAccelerationModeAsString(mode);
    if (fast.size() != reference.size() ||
      std::memcmp(fast.data(), reference.data(), fast.size() * sizeof(float)) != 0)
    {
      std::cerr << "FAIL " << name << ": the shadowed image differs from acceleration none\n";
      ++failures;
    }
    if (mapper->GetLastShadowRayCount() != shadowRays ||
      mapper->GetLastShadowCellCount() >= shadowCells)
    {
      std::cerr << "FAIL " << name << ": shadow rays " << mapper->GetLastShadowRayCount()
                << " (none: " << shadowRays << "), shadow cells "
                << mapper->GetLastShadowCellCount() << " (none: " << shadowCells << ")\n";
      ++failures;
    }
    std::cout << name << ": " << mapper->GetLastShadowRayCount() << " shadow rays, "
              << mapper->GetLastShadowCellCount() << " shadow cells (none: " << shadowCells
              << ")\n";
  }
  // The shadows are there: the same scene without them is brighter.
  renderer->SetUseShadows(0);
  window->Render();
  const double lit = MeanRed(parctest::RayImage(mapper));
  const double shadowed = MeanRed(reference);
  if (!(shadowed < 0.97 * lit) || mapper->GetLastShadowRayCount() != 0)
  {
    std::cerr << "FAIL: mean red " << shadowed << " with shadows, " << lit << " without; "
              << mapper->GetLastShadowRayCount() << " shadow rays without\n";
    ++failures;
  }
  renderer->SetUseShadows(1);

  // The regression image: Auto.
  window->SetSize(300, 300);
  mapper->SetAccelerationModeToAuto();
  window->Render();
  mapper->PrintStatistics(std::cout);
  const bool matches = parctest::MatchesBaseline(window, argc, argv);
  return failures == 0 && matches ? EXIT_SUCCESS : EXIT_FAILURE;
}
