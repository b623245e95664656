// Procedural volumes and scene helpers shared by the image tests (nothing is read from disk).
#ifndef parcTestScene_h
#define parcTestScene_h

#include "vtkPARCVolumeMapper.h"

#include <vtkCamera.h>
#include <vtkColorTransferFunction.h>
#include <vtkContourValues.h>
#include <vtkDataArray.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPointData.h>
#include <vtkRegressionTestImage.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace parctest
{
/// An n^3 uint8 volume over [-31.5, 31.5]^3 with values 255 * f(x, y, z) (f clamped to [0, 1]).
inline vtkSmartPointer<vtkImageData> MakeVolume(
  int n, const std::function<double(double, double, double)>& f)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(n, n, n);
  const double h = 63.0 / (n - 1);
  image->SetSpacing(h, h, h);
  image->SetOrigin(-31.5, -31.5, -31.5);
  vtkNew<vtkUnsignedCharArray> scalars;
  scalars->SetNumberOfTuples(static_cast<vtkIdType>(n) * n * n);
  vtkIdType id = 0;
  for (int k = 0; k < n; ++k)
  {
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        const double v = f(i * h - 31.5, j * h - 31.5, k * h - 31.5);
        scalars->SetValue(id++, static_cast<unsigned char>(255.0 * std::min(std::max(v, 0.0), 1.0)));
      }
    }
  }
  image->GetPointData()->SetScalars(scalars);
  return image;
}

/// Two Gaussian blobs and a thin shell, as unsigned char, n^3 voxels over [-31.5, 31.5]^3
/// (inverted: 255 minus that, for minimum intensity projections).
inline vtkSmartPointer<vtkImageData> MakeBlobs(int n = 48, bool inverted = false)
{
  auto image = MakeVolume(n, [inverted](double x, double y, double z) {
    const double a = std::exp(-((x + 9) * (x + 9) + y * y + (z - 4) * (z - 4)) / 90.0);
    const double b = std::exp(-((x - 11) * (x - 11) + (y - 6) * (y - 6) + (z + 5) * (z + 5)) / 50.0);
    const double r = std::sqrt(x * x + y * y + z * z);
    const double shell = std::exp(-(r - 26) * (r - 26) / 3.0);
    const double v = std::max(std::max(a, 0.9 * b), 0.45 * shell);
    return inverted ? 1.0 - v : v;
  });
  image->GetPointData()->GetScalars()->SetName("density");
  return image;
}

/// A colourful property: translucent shell, denser blobs.
inline vtkSmartPointer<vtkVolumeProperty> MakeProperty(bool shade)
{
  auto property = vtkSmartPointer<vtkVolumeProperty>::New();
  vtkNew<vtkPiecewiseFunction> opacity;
  opacity->AddPoint(0, 0.0);
  opacity->AddPoint(40, 0.0);
  opacity->AddPoint(110, 0.05);
  opacity->AddPoint(160, 0.3);
  opacity->AddPoint(255, 0.8);
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(0, 0.0, 0.0, 0.0);
  color->AddRGBPoint(60, 0.2, 0.4, 1.0);
  color->AddRGBPoint(140, 1.0, 0.6, 0.2);
  color->AddRGBPoint(255, 1.0, 1.0, 0.9);
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetInterpolationTypeToLinear();
  property->SetShade(shade);
  property->GetIsoSurfaceValues()->SetValue(0, 150.0);
  return property;
}

/// The tests' oblique view of what renderer shows: from vtkCamera's default orientation
/// (so a reused renderer gets the same view), reset to the props, turned 35 degrees in
/// azimuth and 25 in elevation.
inline void SetObliqueView(vtkRenderer* renderer)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetPosition(0, 0, 1);
  camera->SetFocalPoint(0, 0, 0);
  camera->SetViewUp(0, 1, 0);
  renderer->ResetCamera();
  camera->Azimuth(35);
  camera->Elevation(25);
  camera->OrthogonalizeViewUp();
  renderer->ResetCameraClippingRange();
}

/// A renderer in window w at viewport vp with one PARC volume of image.
inline vtkSmartPointer<vtkPARCVolumeMapper> AddVolume(vtkRenderWindow* window, const double vp[4],
  vtkImageData* image, vtkVolumeProperty* property, int blend)
{
  vtkNew<vtkRenderer> renderer;
  renderer->SetViewport(vp[0], vp[1], vp[2], vp[3]);
  renderer->SetBackground(0.1, 0.1, 0.15);
  auto mapper = vtkSmartPointer<vtkPARCVolumeMapper>::New();
  mapper->SetInputData(image);
  mapper->SetBlendMode(blend);
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  renderer->AddVolume(volume);
  SetObliqueView(renderer);
  window->AddRenderer(renderer);
  return mapper;
}

/// The mapper's last float ray-cast image (RGBA, 4 floats a pixel; empty if none).
inline std::vector<float> RayImage(vtkPARCVolumeMapper* mapper)
{
  vtkNew<vtkImageData> image;
  mapper->GetLastRayCastImage(image);
  vtkFloatArray* rgba = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  return rgba ? std::vector<float>(rgba->GetPointer(0),
                  rgba->GetPointer(0) + 4 * rgba->GetNumberOfTuples())
              : std::vector<float>();
}

/// The largest alpha of the mapper's last float ray-cast image (-1 if empty).
inline double MaxAlpha(vtkPARCVolumeMapper* mapper)
{
  vtkNew<vtkImageData> image;
  mapper->GetLastRayCastImage(image);
  vtkFloatArray* rgba = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  if (!rgba || rgba->GetNumberOfTuples() == 0)
  {
    return -1.0;
  }
  double hi = 0.0;
  for (vtkIdType i = 0; i < rgba->GetNumberOfTuples(); ++i)
  {
    hi = std::max(hi, static_cast<double>(rgba->GetComponent(i, 3)));
  }
  return hi;
}

/// Compares the window with the test's baseline (vtkRegressionTestImage, options in argv);
/// with -I, lets the user interact first. True when the image passes.
inline bool MatchesBaseline(vtkRenderWindow* window, int argc, char* argv[])
{
  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    vtkNew<vtkRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(window);
    interactor->Start();
  }
  return result == vtkRegressionTester::PASSED;
}
}

#endif
