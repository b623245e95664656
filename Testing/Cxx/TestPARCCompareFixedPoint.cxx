// vtkPARCVolumeMapper against vtkFixedPointVolumeRayCastMapper on a smooth volume, same
// camera, same sample distance, MIP and composite. The samplers differ (fixed-point
// arithmetic, different sample positions), so the images are compared within a stated
// tolerance: mean absolute difference below 1 of 255 per channel and 99.9% of the values
// within 24 of 255, over an image that is not blank.
#include "parcTestScene.h"

#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkRendererCollection.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolumeCollection.h>
#include <vtkWindowToImageFilter.h>

#include <cstdlib>
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

bool Compare(int blend)
{
  vtkNew<vtkRenderWindow> window;
  window->SetSize(160, 160);
  window->SetMultiSamples(0);
  window->SetOffScreenRendering(1);
  auto image = parctest::MakeBlobs(64);
  auto property = parctest::MakeProperty(false);
  const double vp[4] = { 0, 0, 1, 1 };
  auto parcMapper = parctest::AddVolume(window, vp, image, property, blend);
  parcMapper->SetSampleDistance(0.5);
  window->Render();
  auto parcImage = Grab(window);

  vtkNew<vtkFixedPointVolumeRayCastMapper> fixed;
  fixed->SetInputData(image);
  fixed->SetBlendMode(blend);
  fixed->SetAutoAdjustSampleDistances(0);
  fixed->SetLockSampleDistanceToInputSpacing(0);
  fixed->SetSampleDistance(0.5);
  fixed->SetImageSampleDistance(1.0);
  vtkRenderer* renderer = vtkRenderer::SafeDownCast(window->GetRenderers()->GetItemAsObject(0));
  vtkVolume::SafeDownCast(renderer->GetVolumes()->GetItemAsObject(0))->SetMapper(fixed);
  window->Render();
  auto fixedImage = Grab(window);

  auto* a = vtkUnsignedCharArray::SafeDownCast(parcImage->GetPointData()->GetScalars());
  auto* b = vtkUnsignedCharArray::SafeDownCast(fixedImage->GetPointData()->GetScalars());
  const vtkIdType n = a->GetNumberOfValues();
  double sum = 0.0;
  vtkIdType far = 0, bright = 0;
  for (vtkIdType i = 0; i < n; ++i)
  {
    const int d = std::abs(static_cast<int>(a->GetValue(i)) - static_cast<int>(b->GetValue(i)));
    sum += d;
    far += d > 24 ? 1 : 0;
    bright += a->GetValue(i) > 80 ? 1 : 0;
  }
  const double mean = sum / n;
  std::cout << "blend " << blend << ": mean |difference| " << mean << ", values beyond 24: " << far
            << " of " << n << ", bright values " << bright << "\n";
  return mean < 1.0 && far < n / 1000 && bright > n / 200;
}
}

int TestPARCCompareFixedPoint(int, char*[])
{
  const bool mip = Compare(vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND);
  const bool composite = Compare(vtkVolumeMapper::COMPOSITE_BLEND);
  return mip && composite ? EXIT_SUCCESS : EXIT_FAILURE;
}
