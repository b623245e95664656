// Bad input gives a clear error (or a documented result) and never a crash, a hang or a
// stale image: no input, an empty image, one voxel, one slice, zero spacing, cell scalars
// one cell thick, an unsupported scalar type, a scalar array shorter than the image, NaN/Inf
// scalars, a bricked copy of scalars thinner than a brick, no transfer function set, NaN or
// out-of-range transfer-function values (the same image in every acceleration mode),
// unusable sample distances, isosurfaces without a usable value.
#include "parcTestScene.h"

#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkPlane.h>
#include <vtkStringArray.h>
#include <vtkTestErrorObserver.h>

#include <cstring>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
struct Harness
{
  vtkNew<vtkRenderWindow> Window;
  vtkNew<vtkRenderer> Renderer;
  vtkNew<vtkPARCVolumeMapper> Mapper;
  vtkNew<vtkVolume> Volume;
  vtkNew<vtkTest::ErrorObserver> Observer;

  Harness()
  {
    this->Window->SetSize(40, 40);
    this->Window->SetOffScreenRendering(1);
    this->Window->AddRenderer(this->Renderer);
    this->Volume->SetMapper(this->Mapper);
    this->Renderer->AddVolume(this->Volume);
    this->Mapper->AddObserver(vtkCommand::ErrorEvent, this->Observer);
    this->Mapper->AddObserver(vtkCommand::WarningEvent, this->Observer);
  }

  /// Renders image; true when an error containing `expected` was reported and nothing cast.
  bool ExpectError(vtkImageData* image, const std::string& expected, const char* what)
  {
    this->Observer->Clear();
    this->Mapper->SetInputData(image);
    this->Renderer->ResetCamera();
    this->Window->Render();
    const bool ok = this->Observer->GetError() &&
      this->Observer->GetErrorMessage().find(expected) != std::string::npos &&
      this->Mapper->GetLastSampleCount() == 0 && this->Mapper->GetLastRayCount() == 0;
    std::cout << what << ": " << (ok ? "error as expected" : "UNEXPECTED") << " ("
              << this->Observer->GetErrorMessage().substr(0, 120) << ")\n";
    return ok;
  }
};

vtkSmartPointer<vtkImageData> Image(int nx, int ny, int nz)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(nx, ny, nz);
  image->AllocateScalars(VTK_UNSIGNED_CHAR, 1);
  auto* p = static_cast<unsigned char*>(image->GetScalarPointer());
  for (vtkIdType i = 0; i < image->GetNumberOfPoints(); ++i)
  {
    p[i] = static_cast<unsigned char>(i * 7);
  }
  return image;
}
}

int TestPARCBadInput(int, char*[])
{
  Harness h;
  bool ok = true;

  // No input: the pipeline reports the missing connection; nothing is cast.
  h.Window->Render();
  ok &= h.Mapper->GetLastSampleCount() == 0;

  vtkNew<vtkImageData> empty;
  ok &= h.ExpectError(empty, "at least 2 samples", "empty image");
  ok &= h.ExpectError(Image(1, 1, 1), "at least 2 samples", "one voxel");
  ok &= h.ExpectError(Image(10, 10, 1), "at least 2 samples", "one slice");

  auto flat = Image(4, 4, 4);
  flat->SetSpacing(1.0, 0.0, 1.0);
  ok &= h.ExpectError(flat, "non-zero", "zero spacing");

  auto cells = vtkSmartPointer<vtkImageData>::New(); // one cell along z: no volume of cells
  cells->SetDimensions(4, 4, 2);
  vtkNew<vtkDoubleArray> cellScalars;
  cellScalars->SetNumberOfTuples(9);
  cellScalars->Fill(1.0);
  cells->GetCellData()->SetScalars(cellScalars);
  ok &= h.ExpectError(cells, "The image's cells", "cell scalars, one cell thick");

  auto wide = vtkSmartPointer<vtkImageData>::New();
  wide->SetDimensions(4, 4, 4);
  wide->AllocateScalars(VTK_LONG_LONG, 1);
  ok &= h.ExpectError(wide, "Unsupported scalar type", "64-bit integers");

  // NaN and Inf: a warning, then a finite image (documented replacement).
  auto nan = vtkSmartPointer<vtkImageData>::New();
  nan->SetDimensions(8, 8, 8);
  nan->AllocateScalars(VTK_FLOAT, 1);
  auto* v = static_cast<float*>(nan->GetScalarPointer());
  for (int i = 0; i < 512; ++i)
  {
    v[i] = (i % 5 == 0) ? std::numeric_limits<float>::quiet_NaN()
                        : (i % 7 == 0 ? std::numeric_limits<float>::infinity() : 0.5f * (i % 9));
  }
  h.Observer->Clear();
  h.Mapper->SetInputData(nan);
  h.Renderer->ResetCamera();
  h.Window->Render();
  const bool nanOk = !h.Observer->GetError() && h.Observer->GetWarning() &&
    h.Observer->GetWarningMessage().find("non-finite") != std::string::npos &&
    h.Mapper->GetLastSampleCount() > 0 && parctest::MaxAlpha(h.Mapper) >= 0.0 &&
    parctest::MaxAlpha(h.Mapper) <= 1.0;
  std::cout << "NaN/Inf scalars: " << (nanOk ? "replaced, image finite" : "UNEXPECTED") << "\n";
  ok &= nanOk;

  // BrickedCopy on a volume thinner than a brick: a warning, once for the same scalars, no
  // copy, and the image it renders without.
  {
    vtkSmartPointer<vtkImageData> thin = Image(200, 3, 300);
    h.Mapper->SetInputData(thin);
    h.Renderer->ResetCamera();
    h.Window->Render();
    const std::vector<float> without = parctest::RayImage(h.Mapper);
    h.Observer->Clear();
    h.Mapper->BrickedCopyOn();
    h.Window->Render();
    const bool warned = h.Observer->GetWarning() &&
      h.Observer->GetWarningMessage().find("too thin for bricks") != std::string::npos;
    h.Observer->Clear();
    h.Window->Render();
    std::ostringstream memory;
    h.Mapper->PrintMemory(memory);
    const bool thinOk = warned && !h.Observer->GetWarning() && !h.Observer->GetError() &&
      memory.str().find("bricked copy (bytes): 0\n") != std::string::npos &&
      parctest::RayImage(h.Mapper) == without;
    std::cout << "BrickedCopy on thin scalars: "
              << (thinOk ? "warned once, no copy, the same image" : "UNEXPECTED") << "\n";
    ok &= thinOk;
    h.Mapper->BrickedCopyOff();
  }

  // No transfer function set: the property's defaults render without error.
  h.Observer->Clear();
  h.Mapper->SetInputData(parctest::MakeBlobs(16));
  h.Renderer->ResetCamera();
  h.Window->Render();
  const bool defaultsOk = !h.Observer->GetError() && h.Mapper->GetLastSampleCount() > 0;
  std::cout << "default property: " << (defaultsOk ? "rendered" : "UNEXPECTED") << "\n";
  ok &= defaultsOk;

  // A scalar array shorter than the image: an error, no read past its end.
  auto shortArray = Image(8, 8, 8);
  shortArray->GetPointData()->GetScalars()->SetNumberOfTuples(100);
  ok &= h.ExpectError(shortArray, "fewer than the image's 512 points", "short scalar array");

  // Unusable sample distances and image sample distances: an error each, nothing drawn.
  for (const double d : { std::numeric_limits<double>::infinity(),
         std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::quiet_NaN() })
  {
    h.Mapper->SetSampleDistance(d);
    ok &= h.ExpectError(parctest::MakeBlobs(16), "SampleDistance", "unusable sample distance");
  }
  h.Mapper->SetSampleDistance(0.0);
  h.Mapper->SetImageSampleDistance(std::numeric_limits<double>::quiet_NaN());
  ok &= h.ExpectError(parctest::MakeBlobs(16), "ImageSampleDistance", "NaN image sample distance");
  h.Mapper->SetImageSampleDistance(1.0);

  // An isosurface without iso values, or with a NaN one: an error, nothing drawn.
  h.Mapper->SetBlendMode(vtkVolumeMapper::ISOSURFACE_BLEND);
  h.Volume->GetProperty()->GetIsoSurfaceValues()->SetNumberOfContours(0);
  ok &= h.ExpectError(parctest::MakeBlobs(16), "iso value", "isosurface without iso values");
  h.Volume->GetProperty()->GetIsoSurfaceValues()->SetValue(0, std::numeric_limits<double>::quiet_NaN());
  ok &= h.ExpectError(parctest::MakeBlobs(16), "iso value", "NaN iso value");
  h.Mapper->SetBlendMode(vtkVolumeMapper::COMPOSITE_BLEND);

  // NaN nodes and opacities outside [0, 1]: one warning, the nodes left out and the values
  // clamped, the same image in every acceleration mode, alpha at most 1.
  {
    vtkSmartPointer<vtkVolumeProperty> property = parctest::MakeProperty(false);
    vtkPiecewiseFunction* opacity = property->GetScalarOpacity();
    opacity->AddPoint(200, 4.0);
    opacity->AddPoint(std::numeric_limits<double>::quiet_NaN(), 0.5);
    opacity->AddPoint(230, std::numeric_limits<double>::quiet_NaN());
    opacity->AddPoint(20, -1.0);
    h.Volume->SetProperty(property);
    h.Mapper->SetInputData(parctest::MakeBlobs(24));
    h.Renderer->ResetCamera();
    std::vector<float> images[2];
    int warnings = 0;
    const int modes[2] = { vtkPARCVolumeMapper::ACCELERATION_NONE,
      vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER };
    for (int m = 0; m < 2; ++m)
    {
      h.Observer->Clear();
      h.Mapper->SetAccelerationMode(modes[m]);
      h.Window->Render();
      warnings += h.Observer->GetWarning() &&
        h.Observer->GetWarningMessage().find("left out and clamped") != std::string::npos;
      images[m] = parctest::RayImage(h.Mapper);
    }
    const bool tfOk = warnings == 1 && !images[0].empty() && images[0] == images[1] &&
      h.Mapper->GetLastAccelerationMode() == vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER &&
      parctest::MaxAlpha(h.Mapper) <= 1.0 && parctest::MaxAlpha(h.Mapper) > 0.0;
    std::cout << "NaN and out-of-range opacities: "
              << (tfOk ? "one warning, identical images, alpha <= 1" : "UNEXPECTED") << "\n";
    ok &= tfOk;
    h.Volume->SetProperty(parctest::MakeProperty(false));
  }

  // Slice blending without a plane, or with a plane of zero normal: an error, nothing drawn.
  h.Mapper->SetBlendMode(vtkVolumeMapper::SLICE_BLEND);
  ok &= h.ExpectError(parctest::MakeBlobs(16), "needs a vtkPlane", "slice without a plane");
  vtkNew<vtkPlane> degenerate;
  degenerate->SetNormal(0.0, 0.0, 0.0);
  h.Volume->GetProperty()->SetSliceFunction(degenerate);
  ok &= h.ExpectError(parctest::MakeBlobs(16), "needs a vtkPlane", "slice plane of zero normal");
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}
