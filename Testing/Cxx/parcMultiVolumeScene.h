// The paper's Figure 12 scene through vtkPARCMultiVolume (an isosurface inside a translucent
// cloud, two volumes on two input ports), and the test both the analytic pair and the iron
// protein run: a regression image, and bit-identical ray-cast images in every acceleration
// mode for overlapping, disjoint and transformed volumes, with the eye outside or inside.
#ifndef parcMultiVolumeScene_h
#define parcMultiVolumeScene_h

#include "parcTestScene.h"
#include "vtkPARCMultiVolume.h"

#include <vtkImageReader2.h>
#include <vtkRendererCollection.h>
#include <vtkTransform.h>

#include <cstring>
#include <iostream>
#include <string>

namespace parctest
{
/// Two volumes and what to render of them: an isosurface of Surface, a cloud of Cloud.
struct MultiVolumeScene
{
  vtkSmartPointer<vtkImageData> Surface, Cloud;
  double IsoValue = 0.0;
  vtkSmartPointer<vtkPiecewiseFunction> CloudOpacity;
  vtkSmartPointer<vtkColorTransferFunction> CloudColor;
};

/// The analytic stand-in for the iron protein: two lobes (the isosurface) inside a
/// lumpy shell of density (the cloud).
inline MultiVolumeScene AnalyticPair()
{
  MultiVolumeScene scene;
  scene.Surface = MakeVolume(48, [](double x, double y, double z) {
    const double a = std::exp(-((x - 8) * (x - 8) + y * y + z * z) / 60.0);
    const double b = std::exp(-((x + 8) * (x + 8) + (y - 4) * (y - 4) + z * z) / 40.0);
    return std::max(a, b);
  });
  scene.Cloud = MakeVolume(44, [](double x, double y, double z) {
    const double r = std::sqrt(x * x + y * y + z * z);
    return std::exp(-(r - 18) * (r - 18) / 40.0) * (0.6 + 0.4 * std::sin(0.3 * x) * std::cos(0.25 * y));
  });
  scene.IsoValue = 120.0;
  scene.CloudOpacity = vtkSmartPointer<vtkPiecewiseFunction>::New();
  scene.CloudOpacity->AddPoint(0, 0.0);
  scene.CloudOpacity->AddPoint(40, 0.0);
  scene.CloudOpacity->AddPoint(120, 0.04);
  scene.CloudOpacity->AddPoint(255, 0.2);
  scene.CloudColor = vtkSmartPointer<vtkColorTransferFunction>::New();
  scene.CloudColor->AddRGBPoint(40, 0.2, 0.3, 0.9);
  scene.CloudColor->AddRGBPoint(255, 0.6, 0.8, 1.0);
  return scene;
}

/// A raw uint8 cube of n^3 voxels, spacing 1, origin at -(n - 1) / 2 (centres aligned).
inline vtkSmartPointer<vtkImageData> ReadCube(const std::string& path, int n)
{
  vtkNew<vtkImageReader2> reader;
  reader->SetFileName(path.c_str());
  reader->SetDataScalarTypeToUnsignedChar();
  reader->SetNumberOfScalarComponents(1);
  reader->SetFileDimensionality(3);
  reader->SetDataExtent(0, n - 1, 0, n - 1, 0, n - 1);
  const double o = -0.5 * (n - 1);
  reader->SetDataOrigin(o, o, o);
  reader->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->ShallowCopy(reader->GetOutput());
  return image;
}

/// Figure 12: poship as an isosurface (iso value 120) inside neghip as a cloud.
inline MultiVolumeScene IronProtein(const std::string& data)
{
  MultiVolumeScene scene = AnalyticPair(); // its cloud transfer function
  scene.Surface = ReadCube(data + "/poship_66x66x66_uint8.raw", 66);
  scene.Cloud = ReadCube(data + "/neghip_64x64x64_uint8.raw", 64);
  return scene;
}

/// Renders the scene as one vtkPARCMultiVolume; runs the checks; compares the image.
inline int RunMultiVolumeTest(const MultiVolumeScene& scene, int argc, char* argv[])
{
  vtkNew<vtkPARCVolumeMapper> mapper;
  mapper->SetInputDataObject(0, scene.Surface);
  mapper->SetInputDataObject(1, scene.Cloud);
  mapper->SetInputBlendMode(0, vtkVolumeMapper::ISOSURFACE_BLEND);
  mapper->SetInputBlendMode(1, vtkVolumeMapper::COMPOSITE_BLEND);
  mapper->SetSampleDistance(0.25);

  vtkNew<vtkVolumeProperty> surfaceProperty;
  vtkNew<vtkPiecewiseFunction> opaque;
  opaque->AddPoint(0, 1.0);
  opaque->AddPoint(255, 1.0);
  vtkNew<vtkColorTransferFunction> red;
  red->AddRGBPoint(0, 1.0, 0.35, 0.2);
  red->AddRGBPoint(255, 1.0, 0.35, 0.2);
  surfaceProperty->SetScalarOpacity(opaque);
  surfaceProperty->SetColor(red);
  surfaceProperty->ShadeOn();
  surfaceProperty->SetInterpolationTypeToLinear();
  surfaceProperty->GetIsoSurfaceValues()->SetValue(0, scene.IsoValue);
  vtkNew<vtkVolumeProperty> cloudProperty;
  cloudProperty->SetScalarOpacity(scene.CloudOpacity);
  cloudProperty->SetColor(scene.CloudColor);
  cloudProperty->SetInterpolationTypeToLinear();

  vtkNew<vtkVolume> surface, cloud;
  surface->SetProperty(surfaceProperty);
  cloud->SetProperty(cloudProperty);
  vtkNew<vtkPARCMultiVolume> multi;
  multi->SetMapper(mapper);
  multi->SetVolume(surface, 0);
  multi->SetVolume(cloud, 1);

  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.1, 0.1, 0.15);
  renderer->AddVolume(multi);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->AddRenderer(renderer);
  vtkCamera* camera = renderer->GetActiveCamera();
  auto outside = [&]() {
    camera->SetFocalPoint(0, 0, 0);
    camera->SetPosition(0, 0, 1);
    camera->SetViewUp(0, 1, 0);
    camera->ParallelProjectionOff();
    renderer->ResetCamera();
    camera->Azimuth(30);
    camera->Elevation(20);
    camera->OrthogonalizeViewUp();
    renderer->ResetCameraClippingRange();
  };

  int failures = 0;
  // The bounds hold both volumes.
  const double* bounds = multi->GetBounds();
  const double* cloudBounds = scene.Cloud->GetBounds();
  if (!(bounds[0] <= cloudBounds[0] && bounds[1] >= cloudBounds[1]))
  {
    std::cerr << "FAIL: the multi-volume's bounds miss the cloud\n";
    ++failures;
  }

  // Every acceleration mode gives the unaccelerated bits.
  window->SetSize(96, 80);
  const int modes[] = { vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER,
    vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER, vtkPARCVolumeMapper::ACCELERATION_BOTH,
    vtkPARCVolumeMapper::ACCELERATION_SUPERCELL_WALK, vtkPARCVolumeMapper::ACCELERATION_AUTO };
  struct Placement
  {
    const char* Name;
    std::function<void(vtkTransform*)> Set;
  };
  const Placement placements[] = {
    { "aligned", [](vtkTransform*) {} },
    { "rotated, partly overlapping",
      [](vtkTransform* t) {
        t->Translate(14, -6, 3);
        t->RotateZ(30);
        t->RotateX(-20);
      } },
    { "apart", [](vtkTransform* t) { t->Translate(70, 0, 0); } },
  };
  struct View
  {
    const char* Name;
    std::function<void()> Set;
  };
  const View views[] = {
    { "perspective", outside },
    { "parallel",
      [&]() {
        outside();
        camera->ParallelProjectionOn();
      } },
    { "eye inside the cloud",
      [&]() {
        camera->SetPosition(-4, 22, 6);
        camera->SetFocalPoint(6, -10, 0);
        camera->SetViewUp(0, 0, 1);
        camera->ParallelProjectionOff();
        camera->SetViewAngle(70);
        renderer->ResetCameraClippingRange();
      } },
  };
  int cases = 0;
  for (const Placement& placement : placements)
  {
    vtkNew<vtkTransform> transform;
    placement.Set(transform);
    cloud->SetUserTransform(transform);
    for (const View& view : views)
    {
      view.Set();
      camera->SetViewAngle(view.Name == views[2].Name ? 70 : 30);
      mapper->SetAccelerationModeToNone();
      window->Render();
      const std::vector<float> reference = RayImage(mapper);
      const vtkIdType referenceSamples = mapper->GetLastSampleCount();
      if (MaxAlpha(mapper) <= 0.0 || reference.empty())
      {
        std::cerr << "FAIL " << placement.Name << ", " << view.Name << ": nothing drawn\n";
        ++failures;
      }
      for (int mode : modes)
      {
        mapper->SetAccelerationMode(mode);
        window->Render();
        ++cases;
        const std::vector<float> fast = RayImage(mapper);
        const bool same = fast.size() == reference.size() &&
          std::memcmp(fast.data(), reference.data(), fast.size() * sizeof(float)) == 0;
        if (!same || mapper->GetLastSampleCount() > referenceSamples)
        {
          std::size_t differ = 0;
          for (std::size_t i = 0; i < fast.size() && i < reference.size(); ++i)
          {
            differ += fast[i] != reference[i];
          }
          std::cerr << "FAIL " << placement.Name << ", " << view.Name << ", mode "
                    << vtkPARCVolumeMapper::GetAccelerationModeAsString(mode) << ": " << differ
                    << " values differ; samples " << mapper->GetLastSampleCount() << " vs "
                    << referenceSamples << "\n";
          ++failures;
        }
      }
    }
  }
  std::cout << cases << " multi-volume cases, " << failures << " failures\n";

  // The regression image: Auto, both volumes aligned, from outside.
  cloud->SetUserTransform(nullptr);
  window->SetSize(300, 300);
  outside();
  camera->SetViewAngle(30);
  camera->Zoom(1.5);
  renderer->ResetCameraClippingRange();
  mapper->SetAccelerationModeToAuto();
  window->Render();
  mapper->PrintStatistics(std::cout);
  const bool matches = MatchesBaseline(window, argc, argv);
  return failures == 0 && matches ? EXIT_SUCCESS : EXIT_FAILURE;
}
}

#endif
