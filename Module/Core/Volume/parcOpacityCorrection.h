// PARC for VTK: the correction of a sample's opacity for the sample distance.
#ifndef parcOpacityCorrection_h
#define parcOpacityCorrection_h

#include "parcMath.h"

#include <array>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace parc
{

/// VTK's correction of a sample's opacity a for the sample distance dt, as its GPU mapper
/// makes it: 1 - (1 - a)^e with the exponent e = dt / unit distance. An opacity of 0 stays
/// 0 and one of 1 (or more) stays as it is. The means are fixed per exponent, each lane's
/// by its own opacity alone, so that a sample gets the same bits alone (Correct) and in a
/// block (CorrectLanes):
/// - e = 2^-m, 1 <= m <= MaxRoots (sample distances of a half, a quarter, ... of the unit
///   distance, as half a voxel of a volume whose spacing is a power of two): m square
///   roots of 1 - a;
/// - otherwise, for e < 1 (shorter sample distances than the unit distance) and a at most
///   SeriesBound (most samples of a translucent volume): the binomial series
///   sum_k b_k a^k to the degree SeriesDegree, its truncation there below SeriesTruncation;
/// - otherwise 1 - PowOfUnitInterval(1 - a, e).
/// Each is within 1.2e-7 of 1 - (1 - a)^e or of 1 - t^e for the float t = 1 - a (checked
/// against std::pow in double).
class OpacityCorrection
{
public:
  static constexpr int MaxRoots = 8;
  static constexpr int SeriesDegree = 8;
  static constexpr double SeriesTruncation = 1e-8;

  /// The exponent e >= 0 (1: no correction).
  void SetExponent(float e);
  bool IsIdentity() const { return this->Exponent == 1.f; }
  /// m when the exponent is 2^-m (square roots), else 0.
  int GetRoots() const { return this->Roots; }
  /// The largest opacity the series corrects (0: the exponent takes no series).
  float GetSeriesBound() const { return this->SeriesBound; }

  /// The corrected opacity of a (a >= 0, not NaN).
  float Correct(float a) const
  {
    if (this->IsIdentity())
    {
      return a;
    }
#if defined(__SSE2__)
    return _mm_cvtss_f32(this->CorrectFour(_mm_set1_ps(a)));
#else
    return a >= 1.f ? a : 1.f - std::pow(1.f - a, this->Exponent);
#endif
  }
  /// Correct for each of the N opacities of a (N a multiple of 4).
  template <int N>
  PARC_HOT_INLINE void CorrectLanes(float* a) const
  {
    static_assert(N % 4 == 0, "whole groups of four lanes");
    if (this->IsIdentity())
    {
      return;
    }
#if defined(__SSE2__)
    if (this->Roots > 0 || this->SeriesBound == 0.f)
    {
      for (int j = 0; j < N; j += 4)
      {
        _mm_storeu_ps(a + j, this->CorrectFour(_mm_loadu_ps(a + j)));
      }
      return;
    }
    constexpr int groups = N / 4;
    __m128 series[groups];
    this->Series<groups>(a, series);
    for (int g = 0; g < groups; ++g)
    {
      _mm_storeu_ps(a + 4 * g, this->Finish(_mm_loadu_ps(a + 4 * g), series[g]));
    }
#else
    for (int j = 0; j < N; ++j)
    {
      a[j] = this->Correct(a[j]);
    }
#endif
  }

private:
#if defined(__SSE2__)
  /// Correct for four opacities.
  PARC_HOT_INLINE __m128 CorrectFour(__m128 a) const
  {
    const __m128 one = _mm_set1_ps(1.f);
    if (this->Roots > 0)
    {
      __m128 t = _mm_sub_ps(one, a);
      for (int r = 0; r < this->Roots; ++r)
      {
        t = _mm_sqrt_ps(t);
      }
      return Select(_mm_cmpge_ps(a, one), a, _mm_sub_ps(one, t));
    }
    if (this->SeriesBound == 0.f) // no series: the power for every lane above 0
    {
      return this->Finish(a, _mm_setzero_ps());
    }
    alignas(16) float opacities[4];
    _mm_store_ps(opacities, a);
    __m128 series;
    this->Series<1>(opacities, &series);
    return this->Finish(a, series);
  }
  /// The corrected opacities of a from the series' values: theirs up to SeriesBound, the
  /// power's above it, a itself at 1 or more.
  PARC_HOT_INLINE __m128 Finish(__m128 a, __m128 series) const
  {
    const __m128 one = _mm_set1_ps(1.f);
    __m128 corrected = series;
    const __m128 beyond = _mm_cmpgt_ps(a, _mm_set1_ps(this->SeriesBound));
    if (_mm_movemask_ps(beyond) != 0)
    {
      const __m128 power = PowOfUnitInterval(_mm_sub_ps(one, a), _mm_set1_ps(this->Exponent));
      corrected = Select(beyond, _mm_sub_ps(one, power), corrected);
    }
    return Select(_mm_cmpge_ps(a, one), a, corrected);
  }
  /// sum_k b_k a^k, k = 1 .. SeriesDegree, by Horner's rule, for the G groups of four
  /// opacities of a: each step for every group in turn (independent chains side by side;
  /// the opacities read again at each step rather than held in registers), each lane the
  /// same operations whatever G.
  template <int G>
  PARC_HOT_INLINE void Series(const float* a, __m128 series[G]) const
  {
    for (int g = 0; g < G; ++g)
    {
      series[g] = _mm_set1_ps(this->Coefficients[SeriesDegree - 1]);
    }
    for (int k = SeriesDegree - 2; k >= 0; --k)
    {
      const __m128 c = _mm_set1_ps(this->Coefficients[k]);
      for (int g = 0; g < G; ++g)
      {
        series[g] = _mm_add_ps(_mm_mul_ps(series[g], _mm_loadu_ps(a + 4 * g)), c);
      }
    }
    for (int g = 0; g < G; ++g)
    {
      series[g] = _mm_mul_ps(series[g], _mm_loadu_ps(a + 4 * g));
    }
  }
#endif

  float Exponent = 1.f;
  int Roots = 0;
  float SeriesBound = 0.f;
  /// b_1 .. b_SeriesDegree: b_1 = e, b_(k+1) = b_k (k - e) / (k + 1).
  std::array<float, SeriesDegree> Coefficients{};
};

} // namespace parc

#endif
