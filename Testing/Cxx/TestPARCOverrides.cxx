// The object-factory drop-in: with vtkPARCOverrides enabled, vtkGPUVolumeRayCastMapper::New()
// is a vtkPARCGPUVolumeRayCastMapper whose float ray-cast images equal vtkPARCVolumeMapper's
// bit for bit (composite and maximum intensity, cropping, a clipping plane, image sample
// distance 2); a vtkSmartVolumeMapper made then renders through PARC in its GPU and default
// modes and says so (GetLastUsedRenderMode); vtkPARCOverrides::GetPARCMapper reaches the
// statistics; the drop-in's GetColorImage is what it shows (the final colour window and
// level applied). Disabled, New() gives VTK's OpenGL mapper again, and a mapper made while
// enabled keeps rendering through PARC.
#include "parcTestScene.h"
#include "vtkPARCGPUVolumeRayCastMapper.h"
#include "vtkPARCOverrides.h"

#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPlane.h>
#include <vtkRendererCollection.h>
#include <vtkSmartVolumeMapper.h>
#include <vtkUnsignedCharArray.h>

#include <iostream>
#include <string>

namespace
{
/// Renders mapper alone in window's renderer (replacing the volume's mapper).
void RenderWith(vtkRenderWindow* window, vtkVolume* volume, vtkVolumeMapper* mapper)
{
  volume->SetMapper(mapper);
  window->Render();
}

/// The mean of each channel of mapper's GetColorImage (RGBA bytes), or -1s without one.
std::vector<double> MeanColor(vtkGPUVolumeRayCastMapper* mapper)
{
  vtkNew<vtkImageData> image;
  mapper->GetColorImage(image);
  auto* bytes = vtkUnsignedCharArray::SafeDownCast(image->GetPointData()->GetScalars());
  std::vector<double> mean(4, -1.0);
  if (!bytes || bytes->GetNumberOfComponents() != 4 || bytes->GetNumberOfTuples() == 0)
  {
    return mean;
  }
  std::fill(mean.begin(), mean.end(), 0.0);
  for (vtkIdType i = 0; i < bytes->GetNumberOfValues(); ++i)
  {
    mean[i % 4] += bytes->GetValue(i) / static_cast<double>(bytes->GetNumberOfTuples());
  }
  return mean;
}

bool Fail(const std::string& message)
{
  std::cerr << message << "\n";
  return false;
}

/// Configures a GPU-API mapper and a PARC mapper alike.
template <class Mapper>
void Configure(Mapper* mapper, vtkImageData* image, int blend, vtkPlane* plane)
{
  mapper->SetInputData(image);
  mapper->SetBlendMode(blend);
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetSampleDistance(0.7f); // the GPU mapper's distances are floats
  mapper->SetImageSampleDistance(2.0);
  const double* b = image->GetBounds(); // the left two thirds along x
  mapper->CroppingOn();
  mapper->SetCroppingRegionPlanes(b[0], b[0] + 0.66 * (b[1] - b[0]), b[2], b[3], b[4], b[5]);
  mapper->RemoveAllClippingPlanes();
  mapper->AddClippingPlane(plane);
}
}

int TestPARCOverrides(int, char*[])
{
  vtkSmartPointer<vtkImageData> image = parctest::MakeBlobs(40);
  vtkNew<vtkRenderWindow> window;
  window->SetSize(96, 80);
  window->SetMultiSamples(0);
  const double viewport[4] = { 0, 0, 1, 1 };
  vtkSmartPointer<vtkPARCVolumeMapper> reference = parctest::AddVolume(
    window, viewport, image, parctest::MakeProperty(true), vtkVolumeMapper::COMPOSITE_BLEND);
  vtkRenderer* renderer = window->GetRenderers()->GetFirstRenderer();
  vtkVolume* volume = vtkVolume::SafeDownCast(renderer->GetVolumes()->GetItemAsObject(0));
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(image->GetCenter());
  plane->SetNormal(1, 0.3, -0.2);
  bool ok = true;

  vtkPARCOverrides::Enable();
  ok = vtkPARCOverrides::IsEnabled() || Fail("Enable did not enable the override");
  vtkSmartPointer<vtkGPUVolumeRayCastMapper> gpu =
    vtkSmartPointer<vtkGPUVolumeRayCastMapper>::Take(vtkGPUVolumeRayCastMapper::New());
  auto* dropIn = vtkPARCGPUVolumeRayCastMapper::SafeDownCast(gpu);
  if (!dropIn)
  {
    std::cerr << "vtkGPUVolumeRayCastMapper::New() made a " << gpu->GetClassName() << "\n";
    return EXIT_FAILURE;
  }
  ok = ((vtkPARCOverrides::GetPARCMapper(gpu) == dropIn->GetPARCMapper() &&
         vtkPARCOverrides::GetPARCMapper(reference) == reference) ||
    Fail("GetPARCMapper does not find the PARC mappers")) && ok;
  for (int blend : { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND })
  {
    Configure(reference.GetPointer(), image, blend, plane);
    Configure(gpu.GetPointer(), image, blend, plane);
    RenderWith(window, volume, reference);
    const std::vector<float> expected = parctest::RayImage(reference);
    const double alpha = parctest::MaxAlpha(reference);
    RenderWith(window, volume, gpu);
    const std::vector<float> got = parctest::RayImage(dropIn->GetPARCMapper());
    ok = ((!expected.empty() && got == expected && alpha > 0.1) ||
      Fail("blend " + std::to_string(blend) + ": the drop-in's image is not vtkPARCVolumeMapper's")) && ok;
  }

  // GetColorImage: the bytes shown, adjusted by the final colour window and level (0.5 and
  // 0.25 brighten the colours, not the opacity).
  const std::vector<double> plain = MeanColor(gpu);
  gpu->SetFinalColorWindow(0.5f);
  gpu->SetFinalColorLevel(0.25f);
  RenderWith(window, volume, gpu);
  const std::vector<double> bright = MeanColor(gpu);
  gpu->SetFinalColorWindow(1.f);
  gpu->SetFinalColorLevel(0.5f);
  ok = ((plain[3] > 1.0 && bright[0] > 1.3 * plain[0] && bright[3] == plain[3]) ||
         Fail("GetColorImage is not the image shown with the final colour window and level")) &&
    ok;

  // The array a program selects by name (as ParaView does), not the active scalars.
  vtkNew<vtkImageData> twoArrays;
  twoArrays->DeepCopy(image);
  vtkNew<vtkFloatArray> inverted;
  inverted->DeepCopy(parctest::MakeBlobs(40, true)->GetPointData()->GetScalars());
  inverted->SetName("inverted");
  twoArrays->GetPointData()->AddArray(inverted);
  auto select = [&](vtkVolumeMapper* mapper, const char* name) {
    mapper->SetInputData(twoArrays);
    mapper->SetScalarModeToUsePointFieldData();
    mapper->SelectScalarArray(name);
    mapper->CroppingOff();
    mapper->RemoveAllClippingPlanes();
    RenderWith(window, volume, mapper);
    return parctest::RayImage(vtkPARCOverrides::GetPARCMapper(mapper));
  };
  const std::vector<float> density = select(reference, "density");
  const std::vector<float> selected = select(reference, "inverted");
  ok = ((!selected.empty() && selected != density && select(gpu, "inverted") == selected) ||
         Fail("the drop-in does not render the array selected by name")) &&
    ok;

  // The smart mapper builds its GPU mapper through the factory.
  for (int mode : { vtkSmartVolumeMapper::GPURenderMode, vtkSmartVolumeMapper::DefaultRenderMode })
  {
    vtkNew<vtkSmartVolumeMapper> smart;
    smart->SetInputData(image);
    smart->SetRequestedRenderMode(mode);
    RenderWith(window, volume, smart);
    vtkPARCVolumeMapper* parc = vtkPARCOverrides::GetPARCMapper(smart);
    ok = ((smart->GetLastUsedRenderMode() == vtkSmartVolumeMapper::GPURenderMode && parc &&
           parc->GetLastSampleCount() > 0 && parctest::MaxAlpha(parc) > 0.1) ||
      Fail("the smart mapper in mode " + std::to_string(mode) + " did not render through PARC")) && ok;
  }
  vtkNew<vtkFixedPointVolumeRayCastMapper> fixedPoint;
  ok = (!vtkPARCOverrides::GetPARCMapper(fixedPoint) ||
    Fail("GetPARCMapper finds a PARC mapper in FixedPoint")) && ok;

  vtkPARCOverrides::Disable();
  vtkSmartPointer<vtkGPUVolumeRayCastMapper> after =
    vtkSmartPointer<vtkGPUVolumeRayCastMapper>::Take(vtkGPUVolumeRayCastMapper::New());
  ok = ((!vtkPARCOverrides::IsEnabled() && after &&
         std::string(after->GetClassName()) == "vtkOpenGLGPUVolumeRayCastMapper") ||
    Fail("Disable did not restore VTK's OpenGL GPU mapper")) && ok;
  RenderWith(window, volume, gpu);
  ok = (dropIn->GetPARCMapper()->GetLastSampleCount() > 0 ||
    Fail("a mapper made while enabled no longer renders through PARC")) && ok;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
