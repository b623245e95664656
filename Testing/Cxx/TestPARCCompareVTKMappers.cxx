// vtkPARCVolumeMapper against VTK's own mappers on a smooth volume, same camera, same
// sample distance: vtkFixedPointVolumeRayCastMapper for MIP and composite, also with a
// clipping plane and with cropping (the centre subvolume, and VTK's "fence" regions), set
// alike on both; vtkGPUVolumeRayCastMapper (on llvmpipe) for average intensity and additive
// blending, the modes FixedPoint lacks, which VTK defines as grey images, and for a binary
// mask; and FixedPoint for a volume of two independent components, each with its own
// transfer functions and weight. The samplers differ (fixed-point arithmetic, other sample
// positions), so the images are compared within a stated tolerance: mean absolute
// difference below 1 of 255 per channel (2 for the GPU mapper, whose rays start at the
// box's faces) and 99.9% of the values within 24 of 255, over an image that is not blank.
#include "parcTestScene.h"

#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkGPUVolumeRayCastMapper.h>
#include <vtkPlane.h>
#include <vtkRendererCollection.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolumeCollection.h>
#include <vtkWindowToImageFilter.h>

#include <cstdlib>
#include <functional>
#include <iostream>

namespace
{
vtkSmartPointer<vtkImageData> Grab(vtkRenderWindow* window)
{
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->ReadFrontBufferOff();
  grab->Update();
  auto out = vtkSmartPointer<vtkImageData>::New();
  out->DeepCopy(grab->GetOutput());
  return out;
}

/// Sets the same clipping or cropping on a mapper.
using Configure = std::function<void(vtkVolumeMapper*)>;

/// VTK's mapper to compare with, set to cast like the PARC mapper (sample distance 0.5,
/// one ray per pixel).
vtkSmartPointer<vtkVolumeMapper> MakeReference(bool gpu)
{
  if (gpu)
  {
    auto mapper = vtkSmartPointer<vtkGPUVolumeRayCastMapper>::New();
    mapper->SetAutoAdjustSampleDistances(0);
    mapper->SetLockSampleDistanceToInputSpacing(0);
    mapper->SetSampleDistance(0.5);
    mapper->SetUseJittering(0);
    return mapper;
  }
  auto mapper = vtkSmartPointer<vtkFixedPointVolumeRayCastMapper>::New();
  mapper->SetAutoAdjustSampleDistances(0);
  mapper->SetLockSampleDistanceToInputSpacing(0);
  mapper->SetSampleDistance(0.5);
  mapper->SetImageSampleDistance(1.0);
  return mapper;
}

/// Two independent components of 64^3 voxels: the blobs, and a ball off their centre with
/// a green colour function of its own, at weight 0.7.
void MakeComponents(vtkSmartPointer<vtkImageData>& image,
  vtkSmartPointer<vtkVolumeProperty>& property)
{
  auto blobs = parctest::MakeBlobs(64);
  auto ball = parctest::MakeVolume(64, [](double x, double y, double z) {
    return 1.2 - std::sqrt((x - 6) * (x - 6) + (y + 8) * (y + 8) + z * z) / 14.0;
  });
  auto* a = vtkUnsignedCharArray::SafeDownCast(blobs->GetPointData()->GetScalars());
  auto* b = vtkUnsignedCharArray::SafeDownCast(ball->GetPointData()->GetScalars());
  vtkNew<vtkUnsignedCharArray> both;
  both->SetNumberOfComponents(2);
  both->SetNumberOfTuples(a->GetNumberOfTuples());
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    both->SetTypedComponent(i, 0, a->GetValue(i));
    both->SetTypedComponent(i, 1, b->GetValue(i));
  }
  image = blobs;
  image->GetPointData()->SetScalars(both);
  property = parctest::MakeProperty(false);
  property->IndependentComponentsOn();
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.0);
  opacity->AddPoint(150, 0.0);
  opacity->AddPoint(255, 0.4);
  vtkNew<vtkColorTransferFunction> green;
  green->AddRGBPoint(0, 0.0, 0.3, 0.0);
  green->AddRGBPoint(255, 0.3, 1.0, 0.3);
  property->SetScalarOpacity(1, opacity);
  property->SetColor(1, green);
  property->SetComponentWeight(1, 0.7);
}

bool Compare(int blend, const char* what, const Configure& configure, bool gpu = false,
  bool components = false)
{
  vtkNew<vtkRenderWindow> window;
  window->SetSize(160, 160);
  window->SetMultiSamples(0);
  window->SetOffScreenRendering(1);
  auto image = parctest::MakeBlobs(64);
  auto property = parctest::MakeProperty(false);
  if (components)
  {
    MakeComponents(image, property);
  }
  const double vp[4] = { 0, 0, 1, 1 };
  auto parcMapper = parctest::AddVolume(window, vp, image, property, blend);
  parcMapper->SetSampleDistance(0.5);
  configure(parcMapper);
  window->Render();
  auto parcImage = Grab(window);

  auto reference = MakeReference(gpu);
  reference->SetInputData(image);
  reference->SetBlendMode(blend);
  configure(reference);
  vtkRenderer* renderer = vtkRenderer::SafeDownCast(window->GetRenderers()->GetItemAsObject(0));
  vtkVolume::SafeDownCast(renderer->GetVolumes()->GetItemAsObject(0))->SetMapper(reference);
  window->Render();
  auto referenceImage = Grab(window);

  auto* a = vtkUnsignedCharArray::SafeDownCast(parcImage->GetPointData()->GetScalars());
  auto* b = vtkUnsignedCharArray::SafeDownCast(referenceImage->GetPointData()->GetScalars());
  const vtkIdType n = a->GetNumberOfValues();
  double sum = 0.0;
  vtkIdType far = 0, drawn = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const int d = std::abs(static_cast<int>(a->GetValue(i)) - static_cast<int>(b->GetValue(i)));
    sum += d;
    far += d > 24 ? 1 : 0;
    // Not blank: values away from the background's (the first pixel's).
    drawn += std::abs(static_cast<int>(a->GetValue(i)) - static_cast<int>(a->GetValue(i % 3))) > 16;
  }
  const double mean = sum / n;
  std::cout << (gpu ? "GPU" : "FixedPoint") << ", blend " << blend << ", " << what
            << ": mean |difference| " << mean << ", values beyond 24: " << far << " of " << n
            << ", drawn values " << drawn << "\n";
  return mean < (gpu ? 2.0 : 1.0) && far < n / 1000 && drawn > n / 200;
}
}

int TestPARCCompareVTKMappers(int, char*[])
{
  const std::pair<const char*, Configure> configurations[] = {
    { "plain", [](vtkVolumeMapper*) {} },
    { "clipping plane",
      [](vtkVolumeMapper* m) {
        vtkNew<vtkPlane> plane; // keeps x - 0.4 y >= -6, cutting through both blobs
        plane->SetOrigin(-6, 0, 0);
        plane->SetNormal(1, -0.4, 0);
        m->AddClippingPlane(plane);
      } },
    { "cropping, centre subvolume",
      [](vtkVolumeMapper* m) {
        m->CroppingOn();
        m->SetCroppingRegionPlanes(-20, 12, -15, 18, -10, 9);
        m->SetCroppingRegionFlagsToSubVolume();
      } },
    { "cropping, fence",
      [](vtkVolumeMapper* m) {
        m->CroppingOn();
        m->SetCroppingRegionPlanes(-20, 12, -15, 18, -10, 9);
        m->SetCroppingRegionFlagsToFence();
      } },
  };
  bool ok = true;
  for (const auto& c : configurations)
  {
    ok &= Compare(vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND, c.first, c.second);
    ok &= Compare(vtkVolumeMapper::COMPOSITE_BLEND, c.first, c.second);
  }
  const Configure plain = configurations[0].second;
  ok &= Compare(vtkVolumeMapper::ADDITIVE_BLEND, "plain", plain, true);
  ok &= Compare(vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, "plain", plain, true);
  ok &= Compare(vtkVolumeMapper::AVERAGE_INTENSITY_BLEND, "average of 60 and up",
    [](vtkVolumeMapper* m) { m->SetAverageIPScalarRange(60, 255); }, true);
  // A binary mask keeping the half x < 0, set alike on both.
  auto mask = parctest::MakeVolume(64, [](double x, double, double) { return x < 0 ? 1.0 : 0.0; });
  ok &= Compare(vtkVolumeMapper::COMPOSITE_BLEND, "binary mask",
    [&mask](vtkVolumeMapper* m) {
      if (auto* gpu = vtkGPUVolumeRayCastMapper::SafeDownCast(m))
      {
        gpu->SetMaskInput(mask);
        gpu->SetMaskTypeToBinary();
      }
      else if (auto* parc = vtkPARCVolumeMapper::SafeDownCast(m))
      {
        parc->SetMaskInput(mask);
        parc->SetMaskTypeToBinary();
      }
    },
    true);
  for (const int blend :
    { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND })
  {
    ok &= Compare(blend, "two independent components", plain, false, true);
  }
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
