// PARC for VTK: transfer functions of the core.
//
// PiecewiseLinearFunction is evaluated from its nodes (no lookup table): on the piece
// holding a value, in float. The classification decides *exactly* from the nodes whether
// it is non-zero anywhere on a scalar interval (DESIGN.md section 2), and the float value
// is non-zero only where the function is: the caster and the classifier agree.
// ColorTable is a sampled colour function; colour never decides what is skipped.
#ifndef parcTransferFunction_h
#define parcTransferFunction_h

#include "parcMath.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace parc
{

/// Nodes up to which PiecewiseLinearFunction::EvaluateLanes finds each lane's piece by
/// counting, four lanes at once, the nodes at or before it.
constexpr std::size_t MaxCountedNodes = 16;
/// Nodes up to which PiecewiseLinearFunction::EvaluateEightLanes picks each lane's piece
/// out of eight-lane registers: entries 0 to n of its pieces fit in eight lanes.
constexpr std::size_t MaxPermutedNodes = 7;

class PiecewiseLinearFunction
{
public:
  /// Nodes must be sorted by x (equal x allowed: a step). clamp: outside [x0, xn] the end
  /// values hold (vtkPiecewiseFunction's Clamping on); otherwise the function is 0 there.
  void SetNodes(std::vector<double> x, std::vector<double> y, bool clamp);
  /// A constant function (no nodes).
  void SetConstant(double value);

  /// f(s) >= 0 for opacity functions. The piece holding s is found in constant time: a
  /// table of buckets over the nodes' range gives a node at or before s, then at most a few
  /// nodes are stepped over; on it f is evaluated in float (see OnPiece).
  PARC_HOT_INLINE float Evaluate(double s) const
  {
    if (s >= this->X0 && s < this->XN) // the nodes' range (NaN fails)
    {
      // The last node with x <= s: the bucket's start, or a few nodes after it.
      const int bucket = std::min(static_cast<int>((s - this->X0) * this->BucketScale), this->LastBucket);
      std::size_t i = this->BucketStart[bucket];
      while (this->X[i + 1] <= s) // X.back() > s ends the walk
      {
        ++i;
      }
      return this->OnPiece(i, s);
    }
    return this->EvaluateOutside(s);
  }
  /// Evaluate(s[j]) into out[j] for each lane j in lanes (bits 1 << j, j < 32), the same
  /// bits; the other lanes of out are left alone. s and out hold whole groups of four
  /// lanes.
  PARC_HOT_INLINE void EvaluateLanes(const float* s, unsigned lanes, float* out) const
  {
#if defined(__SSE2__)
    const std::size_t n = this->NodeThresholds.size();
    if (n > 0)
    {
      // Lane by lane, the count c of nodes at or before s: on the piece c - 1 for
      // 0 < c < n (Evaluate's range), below the range for c = 0 (also NaN), else at or
      // after its end. OnPiece for four lanes at once, from their pieces' entries.
      alignas(16) std::int32_t counts[4];
      const __m128i end = _mm_set1_epi32(static_cast<std::int32_t>(n));
      const __m128i laneBit = _mm_setr_epi32(1, 2, 4, 8);
      const __m128 left = _mm_set1_ps(static_cast<float>(this->LeftValue()));
      while (lanes != 0)
      {
        const int first = CountTrailingZeros(lanes) & ~3;
        const __m128 v = _mm_loadu_ps(s + first);
        __m128i c = _mm_setzero_si128();
        for (const float x : this->NodeThresholds)
        {
          c = _mm_sub_epi32(c, _mm_castps_si128(_mm_cmpge_ps(v, _mm_set1_ps(x))));
        }
        _mm_store_si128(reinterpret_cast<__m128i*>(counts), c);
        __m128 x = _mm_loadu_ps(this->Pieces.data() + 4 * counts[0]);
        __m128 y = _mm_loadu_ps(this->Pieces.data() + 4 * counts[1]);
        __m128 slope = _mm_loadu_ps(this->Pieces.data() + 4 * counts[2]);
        __m128 unused = _mm_loadu_ps(this->Pieces.data() + 4 * counts[3]);
        _MM_TRANSPOSE4_PS(x, y, slope, unused);
        const __m128 f = _mm_add_ps(y, _mm_mul_ps(_mm_sub_ps(v, x), slope));
        const __m128 below = _mm_castsi128_ps(_mm_cmpeq_epi32(c, _mm_setzero_si128()));
        // max(f, 0) is 0 for a NaN f, like OnPiece.
        const __m128 onPiece = _mm_max_ps(f, _mm_setzero_ps());
        const __m128 value = Select(below, left, onPiece);
        const unsigned group = (lanes >> first) & 0xFu;
        lanes &= ~(0xFu << first);
        // The group's lanes asked for take their values, the others keep theirs.
        const __m128i asked = _mm_and_si128(_mm_set1_epi32(static_cast<int>(group)), laneBit);
        const __m128 write = _mm_castsi128_ps(_mm_cmpeq_epi32(asked, laneBit));
        const __m128 kept = _mm_loadu_ps(out + first);
        _mm_storeu_ps(out + first, Select(write, value, kept));
        // At or after the last node (rare): Evaluate's end values.
        unsigned ends =
          group & static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(c, end))));
        for (; ends != 0; ends &= ends - 1)
        {
          const int j = first + CountTrailingZeros(ends);
          out[j] = this->Evaluate(s[j]);
        }
      }
      return;
    }
#endif
    for (; lanes != 0; lanes &= lanes - 1)
    {
      const int j = CountTrailingZeros(lanes);
      out[j] = this->Evaluate(s[j]);
    }
  }
#if PARC_WIDE_VECTORS
  /// Whether EvaluateEightLanes applies: 2 to MaxPermutedNodes nodes.
  bool PermutesPieces() const { return !this->PieceX.empty(); }
  /// EvaluateLanes in wide vectors, eight lanes at once (PermutesPieces; s and out hold
  /// whole groups of eight lanes): the same operations on each lane, so the same bits.
  PARC_NOINLINE PARC_TARGET_WIDE_VECTORS void EvaluateEightLanes(
    const float* s, unsigned lanes, float* out) const;
#endif
  /// True when f is the same value c >= 0 everywhere (then Evaluate returns float(c)).
  bool IsConstant(double& c) const;

  /// True when f is non-zero somewhere on [lo, hi] (exact for the function as evaluated by
  /// Evaluate: never false where Evaluate gives a non-zero value).
  bool IsNonZeroOn(double lo, double hi) const;
  /// The smallest s with f(s) != 0 (-inf if f is non-zero far left, +inf if f is zero).
  double FirstNonZero() const;
  /// The largest s with f(s) != 0 (+inf if non-zero far right, -inf if f is zero).
  double LastNonZero() const;

  bool IsEmpty() const { return this->X.empty(); }
  const std::vector<double>& GetX() const { return this->X; }
  const std::vector<double>& GetY() const { return this->Y; }

private:
  /// f(s) on the piece from node i to node i + 1, in float from the piece's entry:
  /// max(y + (s - x) slope, 0). On a piece whose nodes are both 0 that is 0; elsewhere it
  /// is non-zero only where the exact function is, so IsNonZeroOn holds for it.
  PARC_HOT_INLINE float OnPiece(std::size_t i, double s) const
  {
    const float* e = &this->Pieces[4 * (i + 1)];
    const float f = e[1] + (static_cast<float>(s) - e[0]) * e[2];
    return f > 0.f ? f : 0.f;
  }
  /// Evaluate for s outside [X0, XN) or NaN, and for functions without nodes.
  float EvaluateOutside(double s) const;
  double LeftValue() const { return this->Clamp ? this->Y.front() : 0.0; }
  double RightValue() const { return this->Clamp ? this->Y.back() : 0.0; }

  std::vector<double> X, Y, Slope;
  /// Entry c (four floats: x, y and slope of the piece c - 1, then 0) for 0 < c < n nodes;
  /// entries 0 and n are zeros (so that four lanes load theirs whatever their counts).
  std::vector<float> Pieces;
  /// The x, y and slope of Pieces' entries 0 to 7, each as eight lanes, for 2 to
  /// MaxPermutedNodes nodes (the entries after n zeros); else empty.
  std::vector<float> PieceX, PieceY, PieceSlope;
  /// FloatAtLeast of each node's x (a float s is at or after a node exactly when it is at
  /// or after its threshold), for 2 to MaxCountedNodes nodes; else empty.
  std::vector<float> NodeThresholds;
  /// BucketStart[b]: a node at or before every s with bucket b; the last node is never one.
  std::vector<std::uint32_t> BucketStart;
  double BucketScale = 0.0;
  int LastBucket = 0;
  /// The first and last node (an empty range without nodes: Evaluate goes outside).
  double X0 = 0.0, XN = 0.0;
  bool Clamp = true;
  double Constant = 0.0;
};

/// An RGB function sampled into a table over [Lo, Hi], linearly interpolated, clamped.
/// The place in the table is found in float: u = (s - Lo) Scale, clamped to [0, n - 1].
class ColorTable
{
public:
  /// rgb holds 3 * n values for n >= 2 evenly spaced scalars from lo to hi.
  void SetTable(double lo, double hi, std::vector<float> rgb);
  PARC_HOT_INLINE void Lookup(double s, float rgb[3]) const
  {
    float u = (static_cast<float>(s) - this->LoF) * this->ScaleF;
    u = u > 0.f ? u : 0.f; // also NaN
    u = u < this->LastF ? u : this->LastF;
    const float below = u < this->LastStartF ? u : this->LastStartF;
    const int i = static_cast<int>(below);
    const float f = u - static_cast<float>(i);
    const float* a = &this->RGBA[4 * static_cast<std::size_t>(i)];
    for (int c = 0; c < 3; ++c)
    {
      rgb[c] = a[c] + f * (a[c + 4] - a[c]);
    }
  }
#if defined(__SSE2__)
  /// Lookup of the four lanes of s at once: rgb[l] holds lane l's (red, green, blue, 0),
  /// the same bits.
  PARC_HOT_INLINE void LookupFour(__m128 s, __m128 rgb[4]) const
  {
    __m128 u = _mm_mul_ps(_mm_sub_ps(s, _mm_set1_ps(this->LoF)), _mm_set1_ps(this->ScaleF));
    u = _mm_max_ps(u, _mm_setzero_ps()); // u > 0 ? u : 0, also NaN
    u = _mm_min_ps(u, _mm_set1_ps(this->LastF)); // u < last ? u : last
    const __m128i i = _mm_cvttps_epi32(_mm_min_ps(u, _mm_set1_ps(this->LastStartF)));
    alignas(16) std::int32_t entry[4];
    alignas(16) float f[4];
    _mm_store_si128(reinterpret_cast<__m128i*>(entry), i);
    _mm_store_ps(f, _mm_sub_ps(u, _mm_cvtepi32_ps(i)));
    for (int l = 0; l < 4; ++l)
    {
      const float* a = &this->RGBA[4 * static_cast<std::size_t>(entry[l])];
      const __m128 low = _mm_loadu_ps(a), high = _mm_loadu_ps(a + 4);
      rgb[l] = _mm_add_ps(low, _mm_mul_ps(_mm_set1_ps(f[l]), _mm_sub_ps(high, low)));
    }
  }
#endif

private:
  /// Four floats an entry: red, green, blue, 0.
  std::vector<float> RGBA{ 1.f, 1.f, 1.f, 0.f, 1.f, 1.f, 1.f, 0.f };
  /// The table's first scalar and its entries per scalar unit, in float; the last entry's
  /// place (n - 1) and the last place an interpolation starts from (n - 2).
  float LoF = 0.f, ScaleF = 1.f, LastF = 1.f, LastStartF = 0.f;
};

} // namespace parc

#endif
