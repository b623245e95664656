// Exactness of PARC through the mapper: for every blend mode, camera case and supercell
// size, the float ray-cast image with acceleration is bit-identical to the one without,
// and takes fewer samples.
#include "parcTestScene.h"

#include <vtkLight.h>

#include <vtkActor.h>
#include <vtkPolyDataMapper.h>
#include <vtkRendererCollection.h>
#include <vtkVolumeCollection.h>
#include <vtkSphereSource.h>

#include <cstdlib>
#include <cstring>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace
{
struct CameraCase
{
  const char* Name;
  std::function<void(vtkCamera*)> Set;
  bool Geometry; ///< an opaque sphere in the scene
};
}

int TestPARCAccelerationExact(int argc, char* argv[])
{
  (void)argc;
  (void)argv;
  const int modes[] = { vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER,
    vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER, vtkPARCVolumeMapper::ACCELERATION_BOTH,
    vtkPARCVolumeMapper::ACCELERATION_SUPERCELL_WALK, vtkPARCVolumeMapper::ACCELERATION_AUTO };
  const int blends[] = { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
    vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, vtkVolumeMapper::AVERAGE_INTENSITY_BLEND,
    vtkVolumeMapper::ADDITIVE_BLEND, vtkVolumeMapper::ISOSURFACE_BLEND };
  const double sizes[][3] = { { 1, 1, 1 }, { 4, 4, 4 }, { 2.5, 3, 1.7 }, { 0.5, 0.75, 0.6 } };
  const CameraCase cameras[] = {
    { "perspective", [](vtkCamera*) {}, false },
    { "parallel", [](vtkCamera* c) { c->ParallelProjectionOn(); }, false },
    { "opaque sphere", [](vtkCamera*) {}, true },
    { "eye on a face", // the eye on the volume's face z = -31.5, looking in
      [](vtkCamera* c) {
        c->SetPosition(0.3, 0.2, -31.5);
        c->SetFocalPoint(0.3, 0.2, 0.0);
        c->SetViewUp(0, 1, 0);
      },
      false },
    { "eye inside a PC blob",
      [](vtkCamera* c) {
        c->SetPosition(-9, 0, 4);
        c->SetFocalPoint(20, 5, -3);
        c->SetViewUp(0, 0, 1);
      },
      false },
    { "parallel, view plane inside",
      [](vtkCamera* c) {
        c->ParallelProjectionOn();
        c->SetPosition(-9, 0, 4);
        c->SetFocalPoint(20, 5, -3);
        c->SetViewUp(0, 0, 1);
        c->SetParallelScale(20);
      },
      false },
  };
  vtkSmartPointer<vtkImageData> blobs = parctest::MakeBlobs(40);
  vtkSmartPointer<vtkImageData> inverted = parctest::MakeBlobs(40, true);
  vtkSmartPointer<vtkVolumeProperty> property = parctest::MakeProperty(true);
  property->GetIsoSurfaceValues()->SetValue(1, 60.0);

  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(72, 64);
  const double vp[4] = { 0, 0, 1, 1 };
  int failures = 0, cases = 0;
  for (int blend : blends)
  {
    vtkImageData* image = blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND ? inverted : blobs;
    for (const CameraCase& cam : cameras)
    {
      window->GetRenderers()->RemoveAllItems();
      vtkSmartPointer<vtkPARCVolumeMapper> mapper =
        parctest::AddVolume(window, vp, image, property, blend);
      mapper->SetAverageIPScalarRange(60, 255);
      vtkRenderer* ren = window->GetRenderers()->GetFirstRenderer();
      if (cam.Geometry)
      {
        vtkNew<vtkSphereSource> sphere;
        sphere->SetRadius(12);
        sphere->SetCenter(-5, 0, 0);
        vtkNew<vtkPolyDataMapper> pm;
        pm->SetInputConnection(sphere->GetOutputPort());
        vtkNew<vtkActor> actor;
        actor->SetMapper(pm);
        ren->AddActor(actor);
      }
      cam.Set(ren->GetActiveCamera());
      ren->ResetCameraClippingRange();
      mapper->SetAccelerationModeToNone();
      window->Render();
      const std::vector<float> reference = parctest::RayImage(mapper);
      const vtkIdType referenceSamples = mapper->GetLastSampleCount();
      for (const auto& size : sizes)
      {
        mapper->SetSupercellSize(size[0], size[1], size[2]);
        for (int mode : modes)
        {
          mapper->SetAccelerationMode(mode);
          window->Render();
          ++cases;
          const std::vector<float> fast = parctest::RayImage(mapper);
          const bool same = fast.size() == reference.size() &&
            std::memcmp(fast.data(), reference.data(), fast.size() * sizeof(float)) == 0;
          // Auto may cast unaccelerated when it predicts that to be fastest; the other
          // modes always run their passes.
          const bool accelerated =
            mapper->GetLastAccelerationMode() != vtkPARCVolumeMapper::ACCELERATION_NONE ||
            mode == vtkPARCVolumeMapper::ACCELERATION_AUTO;
          if (!same || !accelerated || mapper->GetLastSampleCount() > referenceSamples)
          {
            std::size_t differ = 0;
            for (std::size_t i = 0; i < fast.size() && i < reference.size(); ++i)
            {
              differ += fast[i] != reference[i];
            }
            std::cerr << "FAIL blend " << blend << ", " << cam.Name << ", supercell " << size[0]
                      << "x" << size[1] << "x" << size[2] << ", mode "
                      << vtkPARCVolumeMapper::GetAccelerationModeAsString(mode) << ": "
                      << differ << " values differ, used "
                      << vtkPARCVolumeMapper::GetAccelerationModeAsString(mapper->GetLastAccelerationMode())
                      << ", samples " << mapper->GetLastSampleCount() << " vs " << referenceSamples
                      << "\n";
            ++failures;
          }
        }
      }
    }
  }
  // Only what changed is redone: a camera move reclassifies nothing and uploads nothing; a
  // transfer-function change reclassifies once and keeps the data's cell-range pyramid.
  {
    window->GetRenderers()->RemoveAllItems();
    vtkSmartPointer<vtkPARCVolumeMapper> mapper =
      parctest::AddVolume(window, vp, blobs, property, vtkVolumeMapper::COMPOSITE_BLEND);
    mapper->SetAccelerationModeToDepthBuffer();
    window->Render();
    const vtkIdType classifications = mapper->GetClassificationCount();
    const vtkIdType uploads = mapper->GetModelUploadCount();
    window->GetRenderers()->GetFirstRenderer()->GetActiveCamera()->Azimuth(20);
    window->Render();
    window->Render();
    if (mapper->GetClassificationCount() != classifications || mapper->GetModelUploadCount() != uploads ||
      mapper->GetPyramidBuildCount() != 1 || classifications != 1 || uploads != 1)
    {
      std::cerr << "FAIL: a camera move redid work: classifications " << classifications << " -> "
                << mapper->GetClassificationCount() << ", uploads " << uploads << " -> "
                << mapper->GetModelUploadCount() << "\n";
      ++failures;
    }
    property->GetScalarOpacity()->AddPoint(200, 0.9);
    window->Render();
    if (mapper->GetClassificationCount() != 2 || mapper->GetModelUploadCount() != 2 ||
      mapper->GetPyramidBuildCount() != 1)
    {
      std::cerr << "FAIL: a transfer-function change should reclassify once\n";
      ++failures;
    }
    // A settled mode holds nothing for the passes it does not use, and no CPU copy of a
    // model; acceleration none holds no pass memory at all.
    {
      auto memory = [&](int mode) {
        mapper->SetAccelerationMode(mode);
        window->Render();
        std::ostringstream lines;
        mapper->PrintMemory(lines);
        return lines.str();
      };
      auto holds = [](const std::string& lines, const std::string& what) {
        return lines.find("Memory, " + what + " (bytes): 0\n") == std::string::npos;
      };
      const std::string both = memory(vtkPARCVolumeMapper::ACCELERATION_BOTH);
      const vtkIdType bothBytes = mapper->GetMemorySize();
      const std::string depthOnly = memory(vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER);
      const vtkIdType depthBytes = mapper->GetMemorySize();
      const std::string none = memory(vtkPARCVolumeMapper::ACCELERATION_NONE);
      const bool ok = holds(both, "bit-plane buffer") && holds(both, "depth buffer") &&
        !holds(both, "depth model") && !holds(both, "colour models") &&
        !holds(depthOnly, "bit-plane buffer") && holds(depthOnly, "depth buffer") &&
        holds(depthOnly, "OpenGL models and targets") && depthBytes < bothBytes &&
        !holds(none, "depth buffer") && !holds(none, "bit-plane buffer") &&
        !holds(none, "OpenGL models and targets");
      if (!ok)
      {
        std::cerr << "FAIL: memory of unused passes or model copies kept:\n"
                  << both << "--\n" << depthOnly << "--\n" << none;
        ++failures;
      }
      // What the GL implementation keeps for the passes is measured (on llvmpipe, its copies
      // and its own memory are in the process), and goes with the window's graphics
      // resources, as does what it keeps for the displayed image.
      const std::string drawn = memory(vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER);
      mapper->ReleaseGraphicsResources(window);
      std::ostringstream released;
      mapper->PrintMemory(released);
      const std::string passes = "OpenGL implementation, beyond them (measured)";
      if (!holds(drawn, passes) || holds(released.str(), passes) ||
        holds(released.str(), "OpenGL implementation, display (measured)"))
      {
        std::cerr << "FAIL: the GL implementation's memory not measured or not released:\n"
                  << drawn << "--\n" << released.str();
        ++failures;
      }
    }
    // The mapper keeps no vertices once its model is uploaded; the same volume in a second
    // window (another GL context) gets the model built again, and the image stays exact.
    const vtkIdType builds = mapper->GetModelBuildCount();
    vtkRenderer* first = window->GetRenderers()->GetFirstRenderer();
    vtkNew<vtkRenderWindow> second;
    second->SetOffScreenRendering(1);
    second->SetSize(72, 64);
    vtkNew<vtkRenderer> ren2;
    ren2->AddVolume(vtkVolume::SafeDownCast(first->GetVolumes()->GetItemAsObject(0)));
    ren2->SetActiveCamera(first->GetActiveCamera());
    second->AddRenderer(ren2);
    mapper->SetAccelerationModeToNone();
    second->Render();
    const std::vector<float> reference = parctest::RayImage(mapper);
    mapper->SetAccelerationModeToDepthBuffer();
    second->Render();
    const std::vector<float> fast = parctest::RayImage(mapper);
    if (reference.empty() || fast != reference || mapper->GetModelBuildCount() != builds + 1 ||
      mapper->GetLastAccelerationMode() != vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER)
    {
      std::cerr << "FAIL: a second window: model builds " << builds << " -> "
                << mapper->GetModelBuildCount() << ", image "
                << (fast == reference ? "identical" : "differs") << "\n";
      ++failures;
    }
    ren2->RemoveAllViewProps();
  }
  // A mapper that outlives its window (taken off its volume first, so the window never
  // releases its GL resources) is destroyed without touching the dead context.
  {
    vtkSmartPointer<vtkPARCVolumeMapper> survivor;
    {
      vtkNew<vtkRenderWindow> shortLived;
      shortLived->SetOffScreenRendering(1);
      shortLived->SetSize(32, 32);
      survivor = parctest::AddVolume(shortLived, vp, blobs, property, vtkVolumeMapper::COMPOSITE_BLEND);
      survivor->SetAccelerationModeToDepthBuffer();
      shortLived->Render();
      vtkRenderer* ren = shortLived->GetRenderers()->GetFirstRenderer();
      vtkVolume::SafeDownCast(ren->GetVolumes()->GetItemAsObject(0))->SetMapper(nullptr);
    }
  }
  // A copy of the scalars in bricks (BrickedCopy; 129^3 voxels are 2 x 2 x 2 bricks) gives
  // the same images in every mode, shaded or not, with shadows; GetMemorySize counts it, and
  // it is freed when turned off.
  {
    window->GetRenderers()->RemoveAllItems();
    vtkSmartPointer<vtkImageData> large = parctest::MakeBlobs(129);
    for (int blend : { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::ISOSURFACE_BLEND })
    {
      for (bool shade : { false, true })
      {
        window->GetRenderers()->RemoveAllItems();
        vtkSmartPointer<vtkPARCVolumeMapper> mapper =
          parctest::AddVolume(window, vp, large, parctest::MakeProperty(shade), blend);
        window->GetRenderers()->GetFirstRenderer()->SetUseShadows(blend ==
          vtkVolumeMapper::ISOSURFACE_BLEND);
        mapper->SetAccelerationModeToNone();
        window->Render();
        const std::vector<float> reference = parctest::RayImage(mapper);
        mapper->BrickedCopyOn();
        for (int mode : modes)
        {
          mapper->SetAccelerationMode(mode);
          window->Render();
          ++cases;
          if (parctest::RayImage(mapper) != reference)
          {
            std::cerr << "FAIL: the bricked copy changed the image: blend " << blend
                      << ", shade " << shade << ", mode "
                      << vtkPARCVolumeMapper::GetAccelerationModeAsString(mode) << "\n";
            ++failures;
          }
        }
        mapper->SetAccelerationModeToNone();
        window->Render();
        std::ostringstream with;
        mapper->PrintMemory(with);
        const vtkIdType withBytes = mapper->GetMemorySize();
        const int brickBytes = 8 * 67 * 67 * 67; // uint8 values
        mapper->BrickedCopyOff();
        window->Render();
        std::ostringstream freed;
        mapper->PrintMemory(freed);
        const vtkIdType freedBytes = withBytes - mapper->GetMemorySize();
        if (with.str().find("bricked copy (bytes): " + std::to_string(brickBytes)) ==
            std::string::npos ||
          freed.str().find("bricked copy (bytes): 0\n") == std::string::npos ||
          parctest::RayImage(mapper) != reference || std::abs(freedBytes - brickBytes) > 65536)
        {
          std::cerr << "FAIL: the bricked copy's memory not counted or not freed:\n"
                    << with.str() << "--\n" << freed.str();
          ++failures;
        }
      }
    }
  }
  std::cout << cases << " accelerated renders compared, " << failures << " failures\n";
  // Shadows: shadowed images are bit-identical in every mode, for a light inside the
  // volume, one on a face, a directional one and two at once; only with the renderer's
  // shadows on; the light passes are cached across camera moves.
  {
    window->GetRenderers()->RemoveAllItems();
    vtkSmartPointer<vtkPARCVolumeMapper> mapper =
      parctest::AddVolume(window, vp, blobs, property, vtkVolumeMapper::ISOSURFACE_BLEND);
    vtkRenderer* ren = window->GetRenderers()->GetFirstRenderer();
    const double* bounds = mapper->GetBounds();
    int narrowed[2] = { 0, 0 }; ///< light sets whose shadow rays took fewer samples with
                                ///< depth PARC, with colour PARC (the lights' own kinds)
    const double lightSets[][2][4] = { // x, y, z, positional (0: direction towards the light)
      { { 3, 2, 1, 1 }, { 0, 0, 0, -1 } },
      { { 0.5, 0.25, bounds[4], 1 }, { 0, 0, 0, -1 } },
      { { 1, 2, 0.5, 0 }, { 0, 0, 0, -1 } },
      { { -2, 3, 30, 1 }, { 1, -1, 0.2, 0 } } };
    for (int blend : { vtkVolumeMapper::ISOSURFACE_BLEND, vtkVolumeMapper::COMPOSITE_BLEND })
    {
      mapper->SetBlendMode(blend);
      for (const auto& set : lightSets)
      {
        ren->RemoveAllLights();
        for (const auto& l : set)
        {
          if (l[3] < 0)
          {
            continue;
          }
          vtkNew<vtkLight> light;
          light->SetLightTypeToSceneLight();
          light->SetPositional(l[3] > 0);
          light->SetConeAngle(180);
          light->SetPosition(l[0], l[1], l[2]);
          light->SetFocalPoint(0, 0, 0);
          ren->AddLight(light);
        }
        ren->SetUseShadows(0);
        mapper->SetAccelerationModeToNone();
        window->Render();
        const std::vector<float> unshadowed = parctest::RayImage(mapper);
        const bool off = mapper->GetLastShadowRayCount() == 0;
        ren->SetUseShadows(1);
        window->Render();
        const std::vector<float> reference = parctest::RayImage(mapper);
        const vtkIdType shadowRays = mapper->GetLastShadowRayCount();
        const vtkIdType shadowSamples = mapper->GetLastShadowSampleCount();
        ++cases;
        if (!off || shadowRays == 0 || reference == unshadowed)
        {
          std::cerr << "FAIL shadows (blend " << blend << ", light " << set[0][0]
                    << "): shadow rays without shadows on, or none with them\n";
          ++failures;
        }
        for (int mode : modes)
        {
          mapper->SetAccelerationMode(mode);
          window->Render();
          ++cases;
          const std::vector<float> fast = parctest::RayImage(mapper);
          const bool single = mode == vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER ||
            mode == vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER;
          narrowed[mode == vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER] +=
            single && mapper->GetLastShadowSampleCount() < shadowSamples;
          if (fast != reference || mapper->GetLastShadowRayCount() != shadowRays ||
            (single && mapper->GetLastShadowSampleCount() > shadowSamples))
          {
            std::cerr << "FAIL shadows (blend " << blend << ", light " << set[0][0] << ", "
                      << vtkPARCVolumeMapper::GetAccelerationModeAsString(mode)
                      << "): not bit-identical or shadow samples not fewer ("
                      << mapper->GetLastShadowSampleCount() << " vs " << shadowSamples << ")\n";
            ++failures;
          }
        }
        ren->GetActiveCamera()->Azimuth(10);
        window->Render();
        ren->GetActiveCamera()->Azimuth(-10);
        if (mapper->GetLastLightProjectionTime() != 0.0)
        {
          std::cerr << "FAIL shadows: a camera move ran the light passes again\n";
          ++failures;
        }
      }
    }
    if (narrowed[0] < 4 || narrowed[1] < 4)
    {
      std::cerr << "FAIL shadows: the light passes narrowed the shadow rays of only "
                << narrowed[0] << " (depth) and " << narrowed[1] << " (colour) of 8 scenes\n";
      ++failures;
    }
    std::cout << "shadow rays narrowed in " << narrowed[0] << " (depth) and " << narrowed[1]
              << " (colour) of 8 scenes\n";
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
