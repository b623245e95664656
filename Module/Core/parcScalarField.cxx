#include "parcScalarField.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace parc
{

void ScalarField::ReplaceNonFinite(std::size_t& replaced)
{
  float lo = std::numeric_limits<float>::max();
  float hi = std::numeric_limits<float>::lowest();
  for (float v : this->Values)
  {
    if (std::isfinite(v))
    {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  if (lo > hi) // no finite value at all
  {
    lo = hi = 0.f;
  }
  for (float& v : this->Values)
  {
    if (!std::isfinite(v))
    {
      v = (v > 0.f) ? hi : lo;
      ++replaced;
    }
  }
  this->Range[0] = this->Values.empty() ? 0.0 : lo;
  this->Range[1] = this->Values.empty() ? 0.0 : hi;
}

namespace
{
// The cell index along one axis and the fraction inside it, for a clamped coordinate.
inline void Locate(double x, int n, int& i, float& f)
{
  if (!(x > 0.0)) // also NaN
  {
    x = 0.0;
  }
  const double last = n - 1;
  if (x >= last)
  {
    x = last;
  }
  i = static_cast<int>(x);
  if (i >= n - 1)
  {
    i = n - 2;
  }
  f = static_cast<float>(x - i);
}

inline float Lerp(float a, float b, float t) { return a + t * (b - a); }
}

float ScalarField::SampleLinear(const Vec3& p) const
{
  int i, j, k;
  float fx, fy, fz;
  Locate(p.X, this->Dims[0], i, fx);
  Locate(p.Y, this->Dims[1], j, fy);
  Locate(p.Z, this->Dims[2], k, fz);
  const std::size_t sx = 1;
  const std::size_t sy = static_cast<std::size_t>(this->Dims[0]);
  const std::size_t sz = sy * static_cast<std::size_t>(this->Dims[1]);
  const float* v = this->Values.data() + i * sx + j * sy + k * sz;
  const float c00 = Lerp(v[0], v[sx], fx);
  const float c10 = Lerp(v[sy], v[sy + sx], fx);
  const float c01 = Lerp(v[sz], v[sz + sx], fx);
  const float c11 = Lerp(v[sz + sy], v[sz + sy + sx], fx);
  return Lerp(Lerp(c00, c10, fy), Lerp(c01, c11, fy), fz);
}

float ScalarField::SampleNearest(const Vec3& p) const
{
  int idx[3];
  for (int a = 0; a < 3; ++a)
  {
    double x = std::floor(p[a] + 0.5);
    if (!(x > 0.0))
    {
      x = 0.0;
    }
    idx[a] = std::min(static_cast<int>(x), this->Dims[a] - 1);
  }
  return this->GetValue(idx[0], idx[1], idx[2]);
}

Vec3 ScalarField::Gradient(const Vec3& p, Interpolation mode) const
{
  Vec3 g;
  for (int a = 0; a < 3; ++a)
  {
    Vec3 lo = p, hi = p;
    lo[a] = std::max(p[a] - 1.0, 0.0);
    hi[a] = std::min(p[a] + 1.0, static_cast<double>(this->Dims[a] - 1));
    const double h = hi[a] - lo[a];
    g[a] = h > 0.0 ? (this->Sample(hi, mode) - this->Sample(lo, mode)) / h : 0.0;
  }
  return g;
}

} // namespace parc
