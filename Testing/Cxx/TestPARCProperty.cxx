// Property test of exactness: random small volumes, transfer functions, blend modes,
// supercell sizes (also 2^L), volume transforms (direction matrices and user matrices with
// shear, origins up to 1e10, spacings from 1e-4 to 1e4) and cameras (parallel scales and
// view angles over many orders of magnitude, the eye outside or inside); every acceleration
// mode must give the float image of acceleration none bit for bit. Case i uses seed
// base + i; a failure prints its seed. PARC_PROPERTY_SEED sets the base (default 20261123)
// and PARC_PROPERTY_CASES the number of cases (default 400), to reproduce one case:
//   PARC_PROPERTY_SEED=<seed> PARC_PROPERTY_CASES=1 parcCxxTests TestPARCProperty
#include "parcTestScene.h"

#include <vtkFloatArray.h>
#include <vtkMatrix3x3.h>
#include <vtkMatrix4x4.h>
#include <vtkRendererCollection.h>

#include <cstdlib>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using Rng = std::mt19937_64;

double Uniform(Rng& rng, double lo, double hi)
{
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

/// 10^u for u uniform in [lo, hi].
double LogUniform(Rng& rng, double lo, double hi)
{
  return std::pow(10.0, Uniform(rng, lo, hi));
}

/// A smooth random field of a few Gaussian bumps (so that some cells are empty and some
/// dense), as unsigned char or float.
vtkSmartPointer<vtkImageData> RandomVolume(Rng& rng, std::string& what)
{
  auto image = vtkSmartPointer<vtkImageData>::New();
  const int dims[3] = { static_cast<int>(Uniform(rng, 4, 15)), static_cast<int>(Uniform(rng, 4, 15)),
    static_cast<int>(Uniform(rng, 4, 15)) };
  image->SetDimensions(dims);
  const bool floating = Uniform(rng, 0, 1) < 0.4;
  image->AllocateScalars(floating ? VTK_FLOAT : VTK_UNSIGNED_CHAR, 1);
  struct Bump
  {
    double C[3], R, H;
  };
  std::vector<Bump> bumps(static_cast<std::size_t>(Uniform(rng, 1, 4)));
  for (Bump& b : bumps)
  {
    for (int a = 0; a < 3; ++a)
    {
      b.C[a] = Uniform(rng, 0, dims[a] - 1);
    }
    b.R = Uniform(rng, 1.0, 5.0);
    b.H = Uniform(rng, 0.3, 1.0);
  }
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  vtkIdType id = 0;
  for (int k = 0; k < dims[2]; ++k)
  {
    for (int j = 0; j < dims[1]; ++j)
    {
      for (int i = 0; i < dims[0]; ++i)
      {
        double v = 0.0;
        for (const Bump& b : bumps)
        {
          const double d2 = (i - b.C[0]) * (i - b.C[0]) + (j - b.C[1]) * (j - b.C[1]) +
            (k - b.C[2]) * (k - b.C[2]);
          v = std::max(v, b.H * std::exp(-d2 / (b.R * b.R)));
        }
        scalars->SetTuple1(id++, floating ? 1000.0 * v - 200.0 : std::floor(255.0 * v));
      }
    }
  }
  std::ostringstream s;
  s << dims[0] << "x" << dims[1] << "x" << dims[2] << (floating ? " float" : " uchar");
  what += s.str();
  return image;
}

/// A random invertible 3x3 matrix: a rotation, then a shear and anisotropic scale (the
/// condition number stays moderate).
void RandomLinear(Rng& rng, double m[9], bool shear)
{
  double q[3] = { Uniform(rng, -1, 1), Uniform(rng, -1, 1), Uniform(rng, -1, 1) };
  const double w = Uniform(rng, -1, 1);
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + w * w);
  const double x = q[0] / n, y = q[1] / n, z = q[2] / n, s = w / n;
  const double r[9] = { 1 - 2 * (y * y + z * z), 2 * (x * y - s * z), 2 * (x * z + s * y),
    2 * (x * y + s * z), 1 - 2 * (x * x + z * z), 2 * (y * z - s * x), 2 * (x * z - s * y),
    2 * (y * z + s * x), 1 - 2 * (x * x + y * y) };
  double a[9] = { 1, 0, 0, 0, 1, 0, 0, 0, 1 };
  if (shear)
  {
    a[1] = Uniform(rng, -0.8, 0.8);
    a[2] = Uniform(rng, -0.8, 0.8);
    a[5] = Uniform(rng, -0.8, 0.8);
    a[0] = Uniform(rng, 0.5, 2.0);
    a[4] = Uniform(rng, 0.5, 2.0);
    a[8] = Uniform(rng, 0.5, 2.0);
  }
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      m[3 * i + j] = r[3 * i] * a[j] + r[3 * i + 1] * a[3 + j] + r[3 * i + 2] * a[6 + j];
    }
  }
}

/// What the cases exercised.
struct Coverage
{
  int NonBlank = 0;    ///< cases whose reference image shows something
  int Accelerated = 0; ///< accelerated renders that ran their passes
  int Renders = 0;     ///< accelerated renders
};

/// One random case; returns false (with a message naming the seed) when a mode differs.
bool RunCase(std::uint64_t seed, vtkRenderWindow* window, Coverage& coverage)
{
  Rng rng(seed);
  std::string what;
  vtkSmartPointer<vtkImageData> image = RandomVolume(rng, what);
  double spacing[3];
  double origin[3];
  for (int a = 0; a < 3; ++a)
  {
    spacing[a] = LogUniform(rng, -4, 4);
    origin[a] = (Uniform(rng, 0, 1) < 0.5 ? 1 : -1) * LogUniform(rng, -2, 10);
  }
  // Anisotropy within a factor 30 keeps the image readable; the magnitude spans 1e-4..1e4.
  for (int a = 1; a < 3; ++a)
  {
    spacing[a] = spacing[0] * LogUniform(rng, -1.5, 1.5);
  }
  image->SetSpacing(spacing);
  image->SetOrigin(origin);
  if (Uniform(rng, 0, 1) < 0.5)
  {
    double d[9];
    RandomLinear(rng, d, Uniform(rng, 0, 1) < 0.5);
    image->SetDirectionMatrix(d);
  }

  vtkNew<vtkRenderer> renderer;
  window->GetRenderers()->RemoveAllItems();
  window->AddRenderer(renderer);
  vtkNew<vtkPARCVolumeMapper> mapper;
  mapper->SetInputData(image);
  const int blends[] = { vtkVolumeMapper::COMPOSITE_BLEND, vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND,
    vtkVolumeMapper::MINIMUM_INTENSITY_BLEND, vtkVolumeMapper::AVERAGE_INTENSITY_BLEND,
    vtkVolumeMapper::ADDITIVE_BLEND, vtkVolumeMapper::ISOSURFACE_BLEND };
  const int blend = blends[static_cast<int>(Uniform(rng, 0, 6)) % 6];
  mapper->SetBlendMode(blend);
  if (Uniform(rng, 0, 1) < 0.3) // 2^L cells: the pyramid-level classification
  {
    const double s = Uniform(rng, 0, 1) < 0.5 ? 2.0 : 4.0;
    mapper->SetSupercellSize(s, s, s);
  }
  else
  {
    mapper->SetSupercellSize(Uniform(rng, 0.5, 4), Uniform(rng, 0.5, 4), Uniform(rng, 0.5, 4));
  }

  const double* range = image->GetScalarRange();
  const double span = std::max(range[1] - range[0], 1.0);
  vtkNew<vtkPiecewiseFunction> opacity;
  const double start = range[0] + span * Uniform(rng, 0.1, 0.6);
  opacity->AddPoint(range[0], 0.0);
  opacity->AddPoint(start, 0.0);
  opacity->AddPoint(start + span * Uniform(rng, 0.05, 0.3), Uniform(rng, 0.05, 1.0));
  opacity->AddPoint(range[1], Uniform(rng, 0.0, 1.0));
  vtkNew<vtkColorTransferFunction> color;
  color->AddRGBPoint(range[0], Uniform(rng, 0, 1), Uniform(rng, 0, 1), Uniform(rng, 0, 1));
  color->AddRGBPoint(range[1], Uniform(rng, 0, 1), Uniform(rng, 0, 1), Uniform(rng, 0, 1));
  vtkNew<vtkVolumeProperty> property;
  property->SetScalarOpacity(opacity);
  property->SetColor(color);
  property->SetShade(Uniform(rng, 0, 1) < 0.5);
  if (Uniform(rng, 0, 1) < 0.3)
  {
    property->SetInterpolationTypeToNearest();
  }
  else
  {
    property->SetInterpolationTypeToLinear();
  }
  property->SetScalarOpacityUnitDistance(spacing[0] * LogUniform(rng, -0.5, 1));
  property->GetIsoSurfaceValues()->SetValue(0, start + span * Uniform(rng, 0.0, 0.3));
  mapper->SetAverageIPScalarRange(start, range[1]);

  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);
  if (Uniform(rng, 0, 1) < 0.5)
  {
    double l[9];
    RandomLinear(rng, l, true);
    vtkNew<vtkMatrix4x4> user;
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        user->SetElement(i, j, l[3 * i + j]);
      }
      user->SetElement(i, 3, origin[i] * Uniform(rng, -0.5, 0.5));
    }
    volume->SetUserMatrix(user);
  }
  renderer->AddVolume(volume);

  // The camera looks at a point near the largest value (so that even a narrow view sees
  // something) from a random direction, at a distance from inside the volume to far away.
  const double* b = volume->GetBounds();
  vtkDataArray* scalars = image->GetPointData()->GetScalars();
  vtkIdType brightest = 0;
  for (vtkIdType i = 1; i < scalars->GetNumberOfTuples(); ++i)
  {
    brightest = scalars->GetTuple1(i) > scalars->GetTuple1(brightest) ? i : brightest;
  }
  double physical[3], centre[4];
  image->GetPoint(brightest, physical);
  volume->GetMatrix()->MultiplyPoint(
    std::vector<double>{ physical[0], physical[1], physical[2], 1.0 }.data(), centre);
  const double diagonal = std::sqrt((b[1] - b[0]) * (b[1] - b[0]) + (b[3] - b[2]) * (b[3] - b[2]) +
    (b[5] - b[4]) * (b[5] - b[4]));
  double dir[3] = { Uniform(rng, -1, 1), Uniform(rng, -1, 1), Uniform(rng, -1, 1) };
  const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]) + 1e-9;
  const double distance = diagonal * LogUniform(rng, -1.3, 1);
  vtkCamera* camera = renderer->GetActiveCamera();
  double focal[3], position[3];
  for (int a = 0; a < 3; ++a)
  {
    focal[a] = centre[a] + diagonal * Uniform(rng, -0.01, 0.01);
    position[a] = focal[a] + distance * dir[a] / len;
  }
  camera->SetFocalPoint(focal);
  camera->SetPosition(position);
  camera->SetViewUp(Uniform(rng, -1, 1), Uniform(rng, -1, 1), 1.0);
  camera->OrthogonalizeViewUp();
  const bool parallel = Uniform(rng, 0, 1) < 0.4;
  camera->SetParallelProjection(parallel);
  camera->SetParallelScale(diagonal * LogUniform(rng, -6, 1));
  camera->SetViewAngle(LogUniform(rng, -3, 2.1));
  renderer->ResetCameraClippingRange();

  std::vector<float> reference;
  const int modes[] = { vtkPARCVolumeMapper::ACCELERATION_NONE,
    vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER, vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER,
    vtkPARCVolumeMapper::ACCELERATION_BOTH, vtkPARCVolumeMapper::ACCELERATION_SUPERCELL_WALK };
  bool ok = true;
  for (int mode : modes)
  {
    mapper->SetAccelerationMode(mode);
    window->Render();
    const std::vector<float> result = parctest::RayImage(mapper);
    if (mode == vtkPARCVolumeMapper::ACCELERATION_NONE)
    {
      reference = result;
      bool shows = false;
      for (std::size_t i = 3; i < result.size() && !shows; i += 4)
      {
        shows = result[i] > 0.f;
      }
      coverage.NonBlank += shows ? 1 : 0;
      continue;
    }
    ++coverage.Renders;
    coverage.Accelerated += mapper->GetLastAccelerationMode() == mode ? 1 : 0;
    if (result != reference)
    {
      std::size_t differ = 0;
      for (std::size_t i = 0; i < result.size() && i < reference.size(); ++i)
      {
        differ += result[i] != reference[i];
      }
      std::cerr << "FAIL seed " << seed << ": " << what << ", blend " << blend << ", "
                << (parallel ? "parallel" : "perspective") << ", mode "
                << vtkPARCVolumeMapper::GetAccelerationModeAsString(mode) << " (used "
                << vtkPARCVolumeMapper::GetAccelerationModeAsString(mapper->GetLastAccelerationMode())
                << "): " << differ << " values differ\n";
      ok = false;
    }
  }
  return ok;
}

std::uint64_t FromEnvironment(const char* name, std::uint64_t fallback)
{
  const char* value = std::getenv(name);
  return value && *value ? std::strtoull(value, nullptr, 10) : fallback;
}
}

int TestPARCProperty(int, char*[])
{
  const std::uint64_t base = FromEnvironment("PARC_PROPERTY_SEED", 20261123);
  const std::uint64_t cases = FromEnvironment("PARC_PROPERTY_CASES", 400);
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetSize(48, 40);
  int failures = 0;
  Coverage coverage;
  for (std::uint64_t i = 0; i < cases; ++i)
  {
    failures += RunCase(base + i, window, coverage) ? 0 : 1;
  }
  std::cout << cases << " random cases from seed " << base << ", " << failures << " failing; "
            << coverage.NonBlank << " show something, " << coverage.Accelerated << " of "
            << coverage.Renders << " accelerated renders ran their passes\n";
  // A test that exercises nothing proves nothing: most cases must show something and run
  // the passes.
  const bool covered = 2 * coverage.NonBlank >= static_cast<int>(cases) &&
    2 * coverage.Accelerated >= coverage.Renders;
  if (!covered)
  {
    std::cerr << "FAIL: the random cases exercise too little\n";
  }
  return failures == 0 && covered ? EXIT_SUCCESS : EXIT_FAILURE;
}
