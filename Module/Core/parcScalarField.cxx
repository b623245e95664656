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

float ScalarField::Trilinear(const int cell[3], const float fraction[3]) const
{
  const std::size_t sx = 1;
  const std::size_t sy = static_cast<std::size_t>(this->Dims[0]);
  const std::size_t sz = sy * static_cast<std::size_t>(this->Dims[1]);
  const float* v = this->Values.data() + cell[0] * sx + cell[1] * sy + cell[2] * sz;
  const float fx = fraction[0], fy = fraction[1], fz = fraction[2];
  const float c00 = Lerp(v[0], v[sx], fx);
  const float c10 = Lerp(v[sy], v[sy + sx], fx);
  const float c01 = Lerp(v[sz], v[sz + sx], fx);
  const float c11 = Lerp(v[sz + sy], v[sz + sy + sx], fx);
  return Lerp(Lerp(c00, c10, fy), Lerp(c01, c11, fy), fz);
}

float ScalarField::SampleLinear(const Vec3& p) const
{
  int cell[3];
  float fraction[3];
  for (int a = 0; a < 3; ++a)
  {
    Locate(p[a], this->Dims[a], cell[a], fraction[a]);
  }
  return this->Trilinear(cell, fraction);
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
  if (mode == Interpolation::Linear)
  {
    return this->GradientLinear(p);
  }
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

Vec3 ScalarField::GradientLinear(const Vec3& p) const
{
  // The same samples as the general central differences, locating each coordinate once.
  int cell[3];
  float fraction[3];
  for (int a = 0; a < 3; ++a)
  {
    Locate(p[a], this->Dims[a], cell[a], fraction[a]);
  }
  Vec3 g;
  for (int a = 0; a < 3; ++a)
  {
    const double lo = std::max(p[a] - 1.0, 0.0);
    const double hi = std::min(p[a] + 1.0, static_cast<double>(this->Dims[a] - 1));
    const double h = hi - lo;
    if (!(h > 0.0))
    {
      g[a] = 0.0;
      continue;
    }
    int shifted[3] = { cell[0], cell[1], cell[2] };
    float shiftedFraction[3] = { fraction[0], fraction[1], fraction[2] };
    Locate(hi, this->Dims[a], shifted[a], shiftedFraction[a]);
    const float high = this->Trilinear(shifted, shiftedFraction);
    Locate(lo, this->Dims[a], shifted[a], shiftedFraction[a]);
    const float low = this->Trilinear(shifted, shiftedFraction);
    g[a] = (high - low) / h;
  }
  return g;
}

} // namespace parc
