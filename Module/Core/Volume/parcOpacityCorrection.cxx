#include "parcOpacityCorrection.h"

#include <cmath>
#include <vector>

namespace parc
{
namespace
{
/// Exponents from this on take no series: the terms of a larger one alternate in sign, and
/// their sum in float loses more than the power's accuracy.
constexpr double SeriesExponentLimit = 1.0;
/// The terms summed for the truncation's bound, at most.
constexpr int TailTerms = 4096;
/// Each try at the series' bound is this factor of the one before, from MaxSeriesBound.
constexpr double BoundStep = 0.96;
constexpr double MaxSeriesBound = 0.5;
constexpr double MinSeriesBound = 1e-3;

/// b_1 .. b_n of 1 - (1 - a)^e = sum_k b_k a^k.
std::vector<double> SeriesCoefficients(double e, int n)
{
  std::vector<double> b(static_cast<std::size_t>(n));
  b[0] = e;
  for (int k = 1; k < n; ++k)
  {
    b[k] = b[k - 1] * (k - e) / (k + 1);
  }
  return b;
}

/// A bound on |1 - (1 - a)^e - sum_k float(b_k) a^k| for 0 <= a <= bound, the sum of the
/// n terms of b: its tail (summed until its terms fall away) and its coefficients'
/// rounding to float.
double SeriesError(double e, const std::vector<double>& b, double bound)
{
  const auto n = static_cast<int>(b.size());
  double error = 0.0;
  double power = 1.0; // bound^k
  for (int k = 1; k <= n; ++k)
  {
    power *= bound;
    error += std::abs(b[k - 1] - static_cast<float>(b[k - 1])) * power;
  }
  double term = std::abs(b[n - 1]) * power; // |b_k| bound^k, k = n
  for (int k = n; k < TailTerms && term > 0.0; ++k)
  {
    term *= bound * std::abs(k - e) / (k + 1);
    error += term;
    // Past k = e the terms fall by at least the factor bound <= 1/2: the rest is below term.
    if (k > e && term < 1e-3 * OpacityCorrection::SeriesTruncation)
    {
      break;
    }
  }
  return error;
}
} // namespace

void OpacityCorrection::SetExponent(float e)
{
  this->Exponent = e;
  this->Roots = 0;
  for (int m = 1; m <= MaxRoots; ++m)
  {
    if (e == std::ldexp(1.f, -m))
    {
      this->Roots = m;
    }
  }
  this->SeriesBound = 0.f;
  this->Coefficients.fill(0.f);
  if (this->Roots > 0 || !(e >= 0.f && e < SeriesExponentLimit))
  {
    return;
  }
  const std::vector<double> b = SeriesCoefficients(e, SeriesDegree);
  for (int k = 0; k < SeriesDegree; ++k)
  {
    this->Coefficients[k] = static_cast<float>(b[k]);
  }
  for (double bound = MaxSeriesBound; bound >= MinSeriesBound; bound *= BoundStep)
  {
    if (SeriesError(e, b, bound) <= SeriesTruncation)
    {
      this->SeriesBound = FloatAtMost(bound);
      return;
    }
  }
}

} // namespace parc
