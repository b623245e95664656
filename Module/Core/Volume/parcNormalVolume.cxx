#include "parcNormalVolume.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <cmath>

namespace parc
{

namespace
{
constexpr double GridLast = NormalVolume::Resolution - 1;

/// The grid cell of an octahedral coordinate in [-1, 1].
int ToGrid(double x)
{
  const int u = static_cast<int>(std::lround((0.5 * x + 0.5) * GridLast));
  return std::min(std::max(u, 0), NormalVolume::Resolution - 1);
}

double FromGrid(int u)
{
  return 2.0 * u / GridLast - 1.0;
}

double SignNotZero(double x)
{
  return x < 0.0 ? -1.0 : 1.0;
}

/// The central-difference gradient of view at voxel (i, j, k), one-sided on the faces.
template <class View>
Vec3 VoxelGradient(const View& view, int i, int j, int k)
{
  const int* dims = view.GetDimensions();
  const int at[3] = { i, j, k };
  Vec3 g;
  for (int a = 0; a < 3; ++a)
  {
    int lo[3] = { i, j, k }, hi[3] = { i, j, k };
    lo[a] = std::max(at[a] - 1, 0);
    hi[a] = std::min(at[a] + 1, dims[a] - 1);
    const int h = hi[a] - lo[a];
    g[a] = h > 0 ? (static_cast<double>(view.Value(hi[0], hi[1], hi[2])) -
                     static_cast<double>(view.Value(lo[0], lo[1], lo[2]))) /
        h
                 : 0.0;
  }
  return g;
}
}

std::uint16_t NormalVolume::Encode(const Vec3& d)
{
  const double l1 = std::abs(d.X) + std::abs(d.Y) + std::abs(d.Z);
  if (!(l1 > 0.0) || !std::isfinite(l1))
  {
    return ZeroNormal;
  }
  double x = d.X / l1, y = d.Y / l1;
  if (d.Z < 0.0) // the lower half folds over the diagonals
  {
    const double fx = (1.0 - std::abs(y)) * SignNotZero(x);
    const double fy = (1.0 - std::abs(x)) * SignNotZero(y);
    x = fx;
    y = fy;
  }
  return static_cast<std::uint16_t>(1 + ToGrid(x) + Resolution * ToGrid(y));
}

Vec3 NormalVolume::Decode(std::uint16_t code)
{
  if (code == ZeroNormal || code >= Count)
  {
    return { 0.0, 0.0, 0.0 };
  }
  const int index = code - 1;
  double x = FromGrid(index % Resolution), y = FromGrid(index / Resolution);
  const double z = 1.0 - std::abs(x) - std::abs(y);
  if (z < 0.0)
  {
    const double ux = (1.0 - std::abs(y)) * SignNotZero(x);
    const double uy = (1.0 - std::abs(x)) * SignNotZero(y);
    x = ux;
    y = uy;
  }
  return Normalized(Vec3{ x, y, z });
}

void NormalVolume::Build(const ScalarField& field)
{
  const int* dims = field.GetDimensions();
  std::copy_n(dims, 3, this->Dims);
  this->Step[1] = dims[0];
  this->Step[2] = static_cast<std::ptrdiff_t>(dims[0]) * dims[1];
  this->Codes.assign(field.GetNumberOfValues(), ZeroNormal);
  std::uint16_t* codes = this->Codes.data();
  const std::ptrdiff_t slice = this->Step[2];
  field.Dispatch([&](const auto& view) {
    vtkSMPTools::For(0, dims[2], [&](vtkIdType k0, vtkIdType k1) {
      for (int k = static_cast<int>(k0); k < k1; ++k)
      {
        std::uint16_t* out = codes + slice * k;
        for (int j = 0; j < dims[1]; ++j)
        {
          for (int i = 0; i < dims[0]; ++i)
          {
            *out++ = Encode(VoxelGradient(view, i, j, k));
          }
        }
      }
    });
  });
}

void NormalVolume::Clear()
{
  std::vector<std::uint16_t>().swap(this->Codes);
  std::fill_n(this->Dims, 3, 0);
}

} // namespace parc
