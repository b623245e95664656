// A mapper in the GL contexts of several windows, and in a context other code left an
// error pending in: every frame's float ray-cast image equals the one a fresh mapper draws
// in a fresh window, bit for bit, and the PARC pass runs (no fallback to unaccelerated
// casting).
// - Rendered in one window, then in a window created after that (its first frame there).
// - Both windows created and shown first, the mapper moved from the first to the second,
//   and a new mapper rendered in the second.
// - A GL error pending when the mapper renders (left by other code), in each pass mode.
#include "parcTestScene.h"

#include <vtkOpenGLRenderWindow.h>
#include <vtkRendererCollection.h>
#include <vtk_glew.h>

#include <iostream>
#include <vector>

namespace
{
constexpr int WindowSize = 96;

/// window (a new one of WindowSize pixels with a renderer when null) showing image through
/// mapper alone, with a copy of property, in its first renderer, from the oblique view.
vtkSmartPointer<vtkRenderWindow> Show(vtkPARCVolumeMapper* mapper, vtkImageData* image,
  vtkVolumeProperty* property, vtkRenderWindow* window = nullptr)
{
  vtkSmartPointer<vtkRenderWindow> shown = window;
  if (!shown)
  {
    shown = vtkSmartPointer<vtkRenderWindow>::New();
    shown->SetSize(WindowSize, WindowSize);
    shown->AddRenderer(vtkSmartPointer<vtkRenderer>::New());
  }
  vtkRenderer* renderer = shown->GetRenderers()->GetFirstRenderer();
  mapper->SetInputData(image);
  vtkNew<vtkVolumeProperty> copy; // a new property, as a program making a new scene has
  copy->DeepCopy(property);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(copy);
  renderer->RemoveAllViewProps();
  renderer->AddVolume(volume);
  parctest::SetObliqueView(renderer);
  return shown;
}

/// The ray image a fresh mapper in a fresh window draws in mode.
std::vector<float> Reference(vtkImageData* image, vtkVolumeProperty* property, int mode)
{
  vtkNew<vtkPARCVolumeMapper> mapper;
  mapper->SetAccelerationMode(mode);
  vtkSmartPointer<vtkRenderWindow> window = Show(mapper, image, property);
  window->Render();
  return parctest::RayImage(mapper);
}

/// Checks the mapper's last frame against reference and its mode; false with a message.
bool Check(vtkPARCVolumeMapper* mapper, const std::vector<float>& reference, const char* what)
{
  const bool same = parctest::RayImage(mapper) == reference;
  const bool accelerated = mapper->GetLastAccelerationMode() == mapper->GetAccelerationMode();
  if (!same || !accelerated)
  {
    std::cerr << what << " in mode "
              << vtkPARCVolumeMapper::GetAccelerationModeAsString(mapper->GetAccelerationMode())
              << ": " << (same ? "" : "another image than a fresh mapper's; ")
              << (accelerated ? "" : "the PARC pass did not run") << "\n";
  }
  return same && accelerated;
}
}

int TestPARCWindows(int, char*[])
{
  vtkSmartPointer<vtkImageData> image = parctest::MakeBlobs(40);
  vtkSmartPointer<vtkVolumeProperty> property = parctest::MakeProperty(true);
  bool ok = true;
  for (int mode : { vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER,
         vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER })
  {
    // A window created after the first render (the reference after them: its window
    // would be the earlier one).
    vtkNew<vtkPARCVolumeMapper> mapper;
    mapper->SetAccelerationMode(mode);
    vtkSmartPointer<vtkRenderWindow> first = Show(mapper, image, property);
    first->Render();
    const std::vector<float> inFirst = parctest::RayImage(mapper);
    vtkSmartPointer<vtkRenderWindow> later = Show(mapper, image, property);
    later->Render();
    const std::vector<float> reference = Reference(image, property, mode);
    ok = !reference.empty() && ok;
    if (inFirst != reference)
    {
      std::cerr << "the first window: another image than a fresh mapper's\n";
      ok = false;
    }
    ok = Check(mapper, reference, "the first frame in a window created later") && ok;

    // Two windows shown first; the mapper moves from one to the other, then a new one.
    vtkNew<vtkPARCVolumeMapper> moved;
    moved->SetAccelerationMode(mode);
    vtkSmartPointer<vtkRenderWindow> one = Show(moved, image, property);
    vtkNew<vtkPARCVolumeMapper> other;
    other->SetAccelerationMode(mode);
    vtkSmartPointer<vtkRenderWindow> two = Show(other, image, property);
    two->Render();
    one->Render();
    Show(moved, image, property, two)->Render();
    ok = Check(moved, reference, "a mapper moved to a second window") && ok;
    vtkNew<vtkPARCVolumeMapper> fresh;
    fresh->SetAccelerationMode(mode);
    Show(fresh, image, property, two)->Render();
    ok = Check(fresh, reference, "a new mapper in the second window") && ok;

    // Another's GL error pending when the mapper renders.
    vtkOpenGLRenderWindow::SafeDownCast(two.GetPointer())->MakeCurrent();
    glEnable(GL_INVALID_ENUM); // not a capability: GL_INVALID_ENUM stays pending
    two->Render();
    ok = Check(fresh, reference, "a frame after another's GL error") && ok;
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
