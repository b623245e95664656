#include "parcTransferFunction.h"

#include <algorithm>
#include <cmath>

#if PARC_WIDE_VECTORS
#include <immintrin.h>
#endif

namespace parc
{

void PiecewiseLinearFunction::SetNodes(std::vector<double> x, std::vector<double> y, bool clamp)
{
  this->X = std::move(x);
  this->Y = std::move(y);
  this->Clamp = clamp;
  const std::size_t n = this->X.size();
  this->Slope.assign(n, 0.0);
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    const double dx = this->X[i + 1] - this->X[i];
    this->Slope[i] = dx > 0.0 ? (this->Y[i + 1] - this->Y[i]) / dx : 0.0;
  }
  // Buckets over [x0, xn]: s falls in bucket floor((s - x0) * scale), whose start lies at
  // least one bucket width (far more than rounding) after the node it records.
  this->NodeThresholds.clear();
  if (n >= 2 && n <= MaxCountedNodes)
  {
    for (const double x : this->X)
    {
      this->NodeThresholds.push_back(FloatAtLeast(x));
    }
  }
  this->Pieces.assign(4 * (n + 1), 0.f);
  for (std::size_t c = 1; c < n; ++c)
  {
    this->Pieces[4 * c] = static_cast<float>(this->X[c - 1]);
    this->Pieces[4 * c + 1] = static_cast<float>(this->Y[c - 1]);
    this->Pieces[4 * c + 2] = static_cast<float>(this->Slope[c - 1]);
  }
  this->PieceX.clear();
  this->PieceY.clear();
  this->PieceSlope.clear();
  if (n >= 2 && n <= MaxPermutedNodes)
  {
    for (std::size_t c = 0; c < 8; ++c)
    {
      const bool entry = c <= n;
      this->PieceX.push_back(entry ? this->Pieces[4 * c] : 0.f);
      this->PieceY.push_back(entry ? this->Pieces[4 * c + 1] : 0.f);
      this->PieceSlope.push_back(entry ? this->Pieces[4 * c + 2] : 0.f);
    }
  }
  this->X0 = n > 0 ? this->X.front() : 0.0;
  this->XN = n > 0 ? this->X.back() : 0.0;
  const std::size_t buckets = std::min<std::size_t>(std::max<std::size_t>(4 * n, 1024), 4096);
  const double width = n > 1 ? (this->X.back() - this->X.front()) / buckets : 0.0;
  this->BucketScale = width > 0.0 ? 1.0 / width : 0.0;
  this->LastBucket = static_cast<int>(buckets) - 1;
  this->BucketStart.assign(buckets, 0);
  std::size_t node = 0;
  for (std::size_t b = 1; b < buckets; ++b)
  {
    const double before = this->X.front() + (static_cast<double>(b) - 1.0) * width;
    while (node + 2 < n && this->X[node + 1] <= before)
    {
      ++node;
    }
    this->BucketStart[b] = static_cast<std::uint32_t>(node);
  }
}

void PiecewiseLinearFunction::SetConstant(double value)
{
  this->X0 = this->XN = 0.0;
  this->X.clear();
  this->Y.clear();
  this->Slope.clear();
  this->Pieces.clear();
  this->PieceX.clear();
  this->PieceY.clear();
  this->PieceSlope.clear();
  this->NodeThresholds.clear();
  this->Constant = value;
}

#if PARC_WIDE_VECTORS
void PiecewiseLinearFunction::EvaluateEightLanes(const float* s, unsigned lanes, float* out) const
{
  // EvaluateLanes' steps, on eight lanes: the count c of nodes at or before each lane's s,
  // its piece's entry c picked out of the registers, OnPiece, the value left of the nodes
  // for c = 0, Evaluate for c = n.
  const __m256i end = _mm256_set1_epi32(static_cast<std::int32_t>(this->NodeThresholds.size()));
  const __m256i laneBit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
  const __m256 left = _mm256_set1_ps(static_cast<float>(this->LeftValue()));
  const __m256 xs = _mm256_loadu_ps(this->PieceX.data());
  const __m256 ys = _mm256_loadu_ps(this->PieceY.data());
  const __m256 slopes = _mm256_loadu_ps(this->PieceSlope.data());
  while (lanes != 0)
  {
    const int first = CountTrailingZeros(lanes) & ~7;
    const __m256 v = _mm256_loadu_ps(s + first);
    __m256i c = _mm256_setzero_si256();
    for (const float x : this->NodeThresholds)
    {
      c = _mm256_sub_epi32(c, _mm256_castps_si256(_mm256_cmp_ps(v, _mm256_set1_ps(x), _CMP_GE_OQ)));
    }
    const __m256 x = _mm256_permutevar8x32_ps(xs, c);
    const __m256 y = _mm256_permutevar8x32_ps(ys, c);
    const __m256 slope = _mm256_permutevar8x32_ps(slopes, c);
    const __m256 f = _mm256_add_ps(y, _mm256_mul_ps(_mm256_sub_ps(v, x), slope));
    const __m256 below = _mm256_castsi256_ps(_mm256_cmpeq_epi32(c, _mm256_setzero_si256()));
    // max(f, 0) is 0 for a NaN f, like OnPiece.
    const __m256 value = _mm256_blendv_ps(_mm256_max_ps(f, _mm256_setzero_ps()), left, below);
    const unsigned group = (lanes >> first) & 0xFFu;
    lanes &= ~(0xFFu << first);
    if (group == 0xFFu)
    {
      _mm256_storeu_ps(out + first, value);
    }
    else // the group's lanes asked for take their values, the others keep theirs
    {
      const __m256i asked = _mm256_and_si256(_mm256_set1_epi32(static_cast<int>(group)), laneBit);
      const __m256 write = _mm256_castsi256_ps(_mm256_cmpeq_epi32(asked, laneBit));
      _mm256_storeu_ps(out + first, _mm256_blendv_ps(_mm256_loadu_ps(out + first), value, write));
    }
    // At or after the last node (rare): Evaluate's end values.
    const __m256 atEnd = _mm256_castsi256_ps(_mm256_cmpeq_epi32(c, end));
    unsigned ends = group & static_cast<unsigned>(_mm256_movemask_ps(atEnd));
    for (; ends != 0; ends &= ends - 1)
    {
      const int j = first + CountTrailingZeros(ends);
      out[j] = this->Evaluate(s[j]);
    }
  }
}
#endif

float PiecewiseLinearFunction::EvaluateOutside(double s) const
{
  if (this->X.empty())
  {
    return static_cast<float>(this->Constant);
  }
  if (!(s >= this->X0)) // also NaN: treated as below the range
  {
    return static_cast<float>(this->LeftValue());
  }
  if (s > this->XN)
  {
    return static_cast<float>(this->RightValue());
  }
  // s == XN: the last node's value.
  return static_cast<float>(std::max(this->Y.back(), 0.0));
}

bool PiecewiseLinearFunction::IsConstant(double& c) const
{
  if (this->X.empty())
  {
    c = this->Constant;
    return c >= 0.0;
  }
  c = this->Y.front();
  const bool flat =
    std::all_of(this->Y.begin(), this->Y.end(), [c](double y) { return y == c; });
  return flat && this->Clamp && c >= 0.0;
}

bool PiecewiseLinearFunction::IsNonZeroOn(double lo, double hi) const
{
  if (this->X.empty())
  {
    return this->Constant > 0.0;
  }
  if (lo > hi)
  {
    return false;
  }
  const size_t n = this->X.size();
  if (lo < this->X.front() && this->LeftValue() > 0.0)
  {
    return true;
  }
  if (hi > this->X.back() && this->RightValue() > 0.0)
  {
    return true;
  }
  for (size_t i = 0; i < n; ++i)
  {
    // A node inside [lo, hi].
    if (this->X[i] >= lo && this->X[i] <= hi && this->Y[i] > 0.0)
    {
      return true;
    }
    // The open interval (x_i, x_i+1) meets [lo, hi]: the linear piece is positive on all of it
    // when one of its ends is.
    if (i + 1 < n && lo < this->X[i + 1] && hi > this->X[i] && this->X[i] < this->X[i + 1] &&
      std::max(this->Y[i], this->Y[i + 1]) > 0.0)
    {
      return true;
    }
  }
  return false;
}

double PiecewiseLinearFunction::FirstNonZero() const
{
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (this->X.empty())
  {
    return this->Constant > 0.0 ? -inf : inf;
  }
  if (this->LeftValue() > 0.0)
  {
    return -inf;
  }
  for (size_t i = 0; i < this->X.size(); ++i)
  {
    if (this->Y[i] > 0.0)
    {
      // Positive from the previous node on (exclusive), or at this node.
      return i > 0 ? this->X[i - 1] : this->X[i];
    }
  }
  return this->RightValue() > 0.0 ? this->X.back() : inf;
}

double PiecewiseLinearFunction::LastNonZero() const
{
  constexpr double inf = std::numeric_limits<double>::infinity();
  if (this->X.empty())
  {
    return this->Constant > 0.0 ? inf : -inf;
  }
  if (this->RightValue() > 0.0)
  {
    return inf;
  }
  for (size_t i = this->X.size(); i-- > 0;)
  {
    if (this->Y[i] > 0.0)
    {
      return i + 1 < this->X.size() ? this->X[i + 1] : this->X[i];
    }
  }
  return this->LeftValue() > 0.0 ? this->X.front() : -inf;
}

void ColorTable::SetTable(double lo, double hi, std::vector<float> rgb)
{
  const std::size_t n = rgb.size() / 3;
  this->RGBA.assign(4 * n, 0.f);
  for (std::size_t i = 0; i < n; ++i)
  {
    std::copy_n(&rgb[3 * i], 3, &this->RGBA[4 * i]);
  }
  hi = hi > lo ? hi : lo;
  this->LoF = static_cast<float>(lo);
  this->ScaleF = static_cast<float>(hi > lo ? (static_cast<double>(n) - 1.0) / (hi - lo) : 0.0);
  this->LastF = static_cast<float>(n - 1);
  this->LastStartF = static_cast<float>(n - 2);
}

} // namespace parc
