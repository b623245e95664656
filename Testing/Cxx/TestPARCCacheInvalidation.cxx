// Cache invalidation: after a render in an accelerated mode, any one input changes (data
// values in place, the scalars replaced, the array selection by name or by index, the
// transfer function, blend mode, iso values, interpolation, shading, supercell size, volume
// matrix, window size, sample distance, projection, an opaque prop, the lights, a clipping
// plane, cropping, the render window); the next image must be bit-identical to a fresh mapper's without acceleration.
#include "parcTestScene.h"

#include <vtkActor.h>
#include <vtkLight.h>
#include <vtkPlane.h>
#include <vtkPlaneCollection.h>
#include <vtkPolyDataMapper.h>
#include <vtkRendererCollection.h>
#include <vtkSphereSource.h>
#include <vtkTransform.h>

#include <functional>
#include <iostream>
#include <vector>

namespace
{
/// An image with point arrays "density" (the blobs, the active scalars), "inverted" and
/// "shifted" (the blobs moved along x).
vtkSmartPointer<vtkImageData> MakeImage()
{
  vtkSmartPointer<vtkImageData> image = parctest::MakeBlobs(32);
  vtkSmartPointer<vtkImageData> inverted = parctest::MakeBlobs(32, true);
  vtkDataArray* a = inverted->GetPointData()->GetScalars();
  a->SetName("inverted");
  image->GetPointData()->AddArray(a);
  vtkNew<vtkUnsignedCharArray> shifted;
  shifted->SetName("shifted");
  vtkDataArray* density = image->GetPointData()->GetScalars();
  shifted->SetNumberOfTuples(density->GetNumberOfTuples());
  for (vtkIdType i = 0; i < density->GetNumberOfTuples(); ++i)
  {
    shifted->SetValue(i, static_cast<unsigned char>(density->GetTuple1((i + 5) % density->GetNumberOfTuples())));
  }
  image->GetPointData()->AddArray(shifted);
  return image;
}

/// One scene in a window the test owns (the test reuses its windows: an X server serves a
/// limited number of connections), with a spare window for the render-window case.
struct Scene
{
  vtkRenderWindow* Window;
  vtkRenderWindow* Spare;
  vtkNew<vtkRenderer> Renderer;
  vtkSmartPointer<vtkImageData> Image = MakeImage();
  vtkSmartPointer<vtkVolumeProperty> Property = parctest::MakeProperty(false);
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkPARCVolumeMapper> Mapper;
  bool MovedToSpare = false; ///< the render window case

  Scene(vtkRenderWindow* window, vtkRenderWindow* spare)
    : Window(window)
    , Spare(spare)
  {
    for (vtkRenderWindow* w : { window, spare })
    {
      if (w)
      {
        w->GetRenderers()->RemoveAllItems();
        w->SetSize(64, 56);
      }
    }
    this->Window->AddRenderer(this->Renderer);
    this->Mapper->SetInputData(this->Image);
    this->Volume->SetMapper(this->Mapper);
    this->Volume->SetProperty(this->Property);
    this->Renderer->AddVolume(this->Volume);
    this->Renderer->ResetCamera();
    this->Renderer->GetActiveCamera()->Azimuth(30);
    this->Renderer->GetActiveCamera()->Elevation(20);
    this->Renderer->ResetCameraClippingRange();
  }
  ~Scene()
  {
    for (vtkRenderWindow* w : { this->Window, this->Spare })
    {
      if (w)
      {
        w->GetRenderers()->RemoveAllItems();
      }
    }
  }
  vtkRenderWindow* Current() { return this->MovedToSpare ? this->Spare : this->Window; }

  /// The image of a fresh mapper with the same settings, unaccelerated, in the same view.
  std::vector<float> FreshImage()
  {
    vtkNew<vtkPARCVolumeMapper> fresh;
    fresh->SetInputData(this->Mapper->GetInput());
    fresh->SetBlendMode(this->Mapper->GetBlendMode());
    fresh->SetScalarMode(this->Mapper->GetScalarMode());
    if (this->Mapper->GetArrayAccessMode() == VTK_GET_ARRAY_BY_ID)
    {
      fresh->SelectScalarArray(this->Mapper->GetArrayId());
    }
    else
    {
      fresh->SelectScalarArray(this->Mapper->GetArrayName());
    }
    fresh->SetSampleDistance(this->Mapper->GetSampleDistance());
    fresh->SetClippingPlanes(this->Mapper->GetClippingPlanes());
    fresh->SetCropping(this->Mapper->GetCropping());
    fresh->SetCroppingRegionPlanes(this->Mapper->GetCroppingRegionPlanes());
    fresh->SetCroppingRegionFlags(this->Mapper->GetCroppingRegionFlags());
    fresh->SetAccelerationModeToNone();
    this->Volume->SetMapper(fresh);
    this->Current()->Render();
    this->Volume->SetMapper(this->Mapper);
    return parctest::RayImage(fresh);
  }
};

struct Change
{
  const char* Name;
  std::function<void(Scene&)> Setup; ///< before the first render (may be empty)
  std::function<void(Scene&)> Apply;
};
}

/// Several windows: two mappers in window 1, a third in window 2 (both alive, rendered
/// in turn); then mapper 1 visits window 2 and comes back. Every image of every accelerated
/// mode must equal the unaccelerated one of the same mapper in the same view.
int TwoWindows()
{
  int failures = 0;
  const int modes[] = { vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER,
    vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER };
  for (int mode : modes)
  {
    vtkNew<vtkRenderWindow> first, second;
    for (vtkRenderWindow* w : { first.Get(), second.Get() })
    {
      w->SetOffScreenRendering(1);
    }
    Scene one(first, nullptr), two(second, nullptr);
    vtkNew<vtkPARCVolumeMapper> other; // a second mapper in window 1
    other->SetInputData(one.Image);
    vtkNew<vtkVolume> otherVolume;
    otherVolume->SetMapper(other);
    otherVolume->SetProperty(one.Property);
    otherVolume->SetPosition(20, 0, 0);
    one.Renderer->AddVolume(otherVolume);
    vtkPARCVolumeMapper* mappers[3] = { one.Mapper, other, two.Mapper };
    auto check = [&](const char* when) {
      // Each mapper's image with acceleration against the same render without.
      for (vtkRenderWindow* w : { one.Window, two.Window })
      {
        for (vtkPARCVolumeMapper* m : mappers)
        {
          m->SetAccelerationModeToNone();
        }
        w->Render();
        std::vector<std::vector<float>> reference;
        for (vtkPARCVolumeMapper* m : mappers)
        {
          reference.push_back(parctest::RayImage(m));
          m->SetAccelerationMode(mode);
        }
        w->Render();
        for (int i = 0; i < 3; ++i)
        {
          if (parctest::RayImage(mappers[i]) != reference[i])
          {
            std::cerr << "FAIL: two windows, " << when << ", mapper " << i << ", "
                      << vtkPARCVolumeMapper::GetAccelerationModeAsString(mode) << "\n";
            ++failures;
          }
        }
      }
    };
    check("both alive");
    // Mapper 1's volume moves to window 2 and back.
    one.Renderer->RemoveVolume(one.Volume);
    two.Renderer->AddVolume(one.Volume);
    two.Window->Render();
    two.Renderer->RemoveVolume(one.Volume);
    one.Renderer->AddVolume(one.Volume);
    check("after a visit to the other window");
    // Mapper 1's volume visits a window that is then destroyed.
    {
      vtkNew<vtkRenderWindow> temporary;
      temporary->SetOffScreenRendering(1);
      temporary->SetSize(40, 40);
      vtkNew<vtkRenderer> renderer;
      renderer->SetActiveCamera(one.Renderer->GetActiveCamera());
      temporary->AddRenderer(renderer);
      one.Renderer->RemoveVolume(one.Volume);
      renderer->AddVolume(one.Volume);
      temporary->Render();
      renderer->RemoveVolume(one.Volume);
      one.Renderer->AddVolume(one.Volume);
    }
    check("after a visit to a window since destroyed");
  }
  return failures;
}

int TestPARCCacheInvalidation(int, char*[])
{
  const std::vector<Change> changes = {
    { "data values in place", nullptr,
      [](Scene& s) {
        vtkDataArray* a = s.Image->GetPointData()->GetScalars();
        for (vtkIdType i = 0; i < a->GetNumberOfTuples(); i += 3)
        {
          a->SetTuple1(i, 255.0 - a->GetTuple1(i));
        }
        a->Modified();
      } },
    { "scalars replaced", nullptr,
      [](Scene& s) {
        vtkNew<vtkUnsignedCharArray> copy;
        copy->DeepCopy(s.Image->GetPointData()->GetArray("shifted"));
        s.Image->GetPointData()->SetScalars(copy);
      } },
    { "array selected by name", nullptr,
      [](Scene& s) {
        s.Mapper->SetScalarModeToUsePointFieldData();
        s.Mapper->SelectScalarArray("shifted");
      } },
    { "array selected by index",
      [](Scene& s) {
        s.Mapper->SetScalarModeToUsePointFieldData();
        s.Mapper->SelectScalarArray(0);
      },
      [](Scene& s) { s.Mapper->SelectScalarArray(2); } },
    { "scalar mode", 
      [](Scene& s) {
        s.Mapper->SetScalarModeToUsePointFieldData();
        s.Mapper->SelectScalarArray("shifted");
      },
      [](Scene& s) { s.Mapper->SetScalarModeToDefault(); } },
    { "transfer function", nullptr,
      [](Scene& s) { s.Property->GetScalarOpacity()->AddPoint(90, 0.6); } },
    { "blend mode", nullptr,
      [](Scene& s) { s.Mapper->SetBlendMode(vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND); } },
    { "iso values",
      [](Scene& s) { s.Mapper->SetBlendMode(vtkVolumeMapper::ISOSURFACE_BLEND); },
      [](Scene& s) { s.Property->GetIsoSurfaceValues()->SetValue(0, 90.0); } },
    { "interpolation", nullptr, [](Scene& s) { s.Property->SetInterpolationTypeToNearest(); } },
    { "shading", nullptr, [](Scene& s) { s.Property->ShadeOn(); } },
    { "supercell size", nullptr, [](Scene& s) { s.Mapper->SetSupercellSize(3, 1.5, 2); } },
    { "volume matrix", nullptr,
      [](Scene& s) {
        s.Volume->RotateZ(25);
        s.Volume->SetScale(1.0, 1.3, 0.8);
      } },
    { "window size", nullptr, [](Scene& s) { s.Window->SetSize(80, 48); } },
    { "sample distance", nullptr, [](Scene& s) { s.Mapper->SetSampleDistance(0.9); } },
    { "projection", nullptr,
      [](Scene& s) { s.Renderer->GetActiveCamera()->ParallelProjectionOn(); } },
    { "opaque prop", nullptr,
      [](Scene& s) {
        vtkNew<vtkSphereSource> sphere;
        sphere->SetRadius(10);
        vtkNew<vtkPolyDataMapper> pm;
        pm->SetInputConnection(sphere->GetOutputPort());
        vtkNew<vtkActor> actor;
        actor->SetMapper(pm);
        s.Renderer->AddActor(actor);
      } },
    { "lights", [](Scene& s) { s.Property->ShadeOn(); },
      [](Scene& s) {
        vtkNew<vtkLight> light;
        light->SetPosition(40, -30, 10);
        light->SetFocalPoint(0, 0, 0);
        light->SetColor(1.0, 0.5, 0.3);
        s.Renderer->AddLight(light);
      } },
    { "clipping plane", nullptr,
      [](Scene& s) {
        vtkNew<vtkPlane> plane;
        plane->SetOrigin(-4, 2, 0);
        plane->SetNormal(0.8, -0.3, 0.5);
        s.Mapper->AddClippingPlane(plane);
      } },
    { "cropping", nullptr,
      [](Scene& s) {
        s.Mapper->CroppingOn();
        s.Mapper->SetCroppingRegionPlanes(-20, 12, -15, 18, -10, 9);
        s.Mapper->SetCroppingRegionFlagsToCross();
      } },
    { "cropping regions",
      [](Scene& s) {
        s.Mapper->CroppingOn();
        s.Mapper->SetCroppingRegionPlanes(-20, 12, -15, 18, -10, 9);
      },
      [](Scene& s) { s.Mapper->SetCroppingRegionFlagsToInvertedFence(); } },
    { "render window", nullptr,
      [](Scene& s) {
        vtkNew<vtkRenderer> renderer;
        renderer->SetActiveCamera(s.Renderer->GetActiveCamera());
        s.Renderer->RemoveVolume(s.Volume);
        renderer->AddVolume(s.Volume);
        s.Spare->AddRenderer(renderer);
        s.MovedToSpare = true;
      } },
  };
  const int modes[] = { vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER,
    vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER, vtkPARCVolumeMapper::ACCELERATION_AUTO };
  vtkNew<vtkRenderWindow> window, spare;
  for (vtkRenderWindow* w : { window.Get(), spare.Get() })
  {
    w->SetOffScreenRendering(1);
  }
  int failures = 0, cases = 0;
  for (int mode : modes)
  {
    for (const Change& change : changes)
    {
      Scene s(window, spare);
      s.Mapper->SetAccelerationMode(mode);
      if (change.Setup)
      {
        change.Setup(s);
      }
      for (int i = 0; i < 5; ++i) // Auto's trials too
      {
        s.Window->Render();
      }
      change.Apply(s);
      s.Current()->Render();
      const std::vector<float> image = parctest::RayImage(s.Mapper);
      const std::vector<float> fresh = s.FreshImage();
      ++cases;
      if (image.empty() || image != fresh)
      {
        std::cerr << "FAIL: " << change.Name << ", "
                  << vtkPARCVolumeMapper::GetAccelerationModeAsString(mode) << " (used "
                  << vtkPARCVolumeMapper::GetAccelerationModeAsString(
                       s.Mapper->GetLastAccelerationMode())
                  << "): the image differs from a fresh mapper's\n";
        ++failures;
      }
    }
  }
  failures += TwoWindows();
  std::cout << cases << " changes compared with a fresh mapper, " << failures << " failures\n";
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
