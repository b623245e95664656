// The composite ray function's block of samples in stages (RayContext::CompositeBlock):
// opacities, the lanes composited before the ray may stop, their colours and shading, then
// the weighted sums. Internal to the casters.
#ifndef parc_CompositeBlock_h
#define parc_CompositeBlock_h

#include "parcRayShading.h"

#include <algorithm>
#include <cstdint>

namespace parc::casting
{

template <class View>
PARC_HOT_INLINE bool RayContext<View>::CompositeBlock(
  long k0, int n, int& visited, EventCompositor& out)
{
#if defined(__SSE2__)
  if (!this->P.Shade && !this->Events)
  {
    return this->CompositeUnshadedBlock(k0, n, visited, out);
  }
#endif
  const unsigned sampled = this->SampleBlock(k0, n);
  const unsigned lanes = this->LaneOpacities(this->MayContribute(n) & sampled);
  LaneBatch& b = this->Batch;
  b.Count = 0;
  bool stops = false;
  // EventCompositor::AddSample lane by lane: the weights now, the colours below.
  EventCompositor left = out;
  for (unsigned m = lanes; m != 0; m &= m - 1)
  {
    const int j = CountTrailingZeros(m);
    b.Weight[b.Count] = left.Absorb(this->Opacities[j]);
    b.Lane[b.Count++] = j;
    if (!left.Below(this->P.TerminationOpacity))
    {
      stops = true;
      visited = j + 1;
      break;
    }
  }
  this->Stats.ContributingSamples += static_cast<std::uint64_t>(b.Count);
  this->CountEmptyCells(sampled, stops ? visited : n);
  if (b.Count > 0)
  {
    this->RecordHit((k0 + b.Lane[0]) * this->Dt); // the first is the nearest
  }
#if defined(__SSE2__)
  if (!this->Events && this->InterpolatesNormalShading())
  {
    this->AddNormalShadedColors(out);
  }
  else
#endif
  {
    this->BatchColors();
    if (this->P.Shade)
    {
      this->ShadeBatch(k0);
    }
    this->AddBatchColors(out);
  }
  out.Alpha = left.Alpha;
  out.Transparency = left.Transparency;
  if (this->Events)
  {
    for (int i = 0; i < b.Count; ++i)
    {
      const float rgb[3] = { b.Rgb[0][i], b.Rgb[1][i], b.Rgb[2][i] };
      AppendEvent(*this->Events, (k0 + b.Lane[i]) * this->Dt, rgb,
        this->Opacities[b.Lane[i]], false);
    }
  }
  return !stops;
}

#if defined(__SSE2__)
template <class View>
PARC_HOT_INLINE void RayContext<View>::AddNormalShadedColors(EventCompositor& out)
{
  const LaneBatch& b = this->Batch;
  __m128 sum = ColourSums(out);
  for (int i = 0; i < b.Count; i += 4)
  {
    __m128 c[4];
    this->P.Color.LookupFour(this->BatchValues(i), c);
    for (int l = 0; l < std::min(4, b.Count - i); ++l)
    {
      const __m128 rgb = this->ShadeByNormals(b.Lane[i + l], c[l]);
      sum = _mm_add_ps(sum, _mm_mul_ps(_mm_set1_ps(b.Weight[i + l]), rgb));
    }
  }
  SetColourSums(out, sum);
}

template <class View>
PARC_HOT_INLINE __m128 RayContext<View>::BatchValues(int i) const
{
  const LaneBatch& b = this->Batch;
  const auto value = [&](int l) { return this->Value(b.Lane[std::min(i + l, b.Count - 1)]); };
  return _mm_setr_ps(value(0), value(1), value(2), value(3));
}

template <class View>
PARC_HOT_INLINE bool RayContext<View>::CompositeUnshadedBlock(
  long k0, int n, int& visited, EventCompositor& out)
{
  const unsigned sampled = this->SampleBlock(k0, n);
  const unsigned lanes = this->LaneOpacities(this->MayContribute(n) & sampled);
  if (lanes == 0)
  {
    this->CountEmptyCells(sampled, n);
    return true;
  }
  alignas(16) float weight[LatticeBlock::Size];
  EventCompositor left = out;
  int end = n; // the lanes composited: those before end
  bool stops = false;
  for (int j = 0; j < n; ++j)
  {
    weight[j] = left.Absorb(this->Opacities[j]);
    if (!left.Below(this->P.TerminationOpacity))
    {
      stops = true;
      end = j + 1;
      break;
    }
  }
  const unsigned composited = lanes & LatticeBlock::LowLanes(end);
  this->Stats.ContributingSamples += static_cast<std::uint64_t>(PopCount(composited));
  this->CountEmptyCells(sampled, end);
  this->RecordHit((k0 + CountTrailingZeros(composited)) * this->Dt);
  __m128 sum = ColourSums(out);
  for (int first = 0; first < end; first += LatticeBlock::Lanes)
  {
    if (((composited >> first) & LatticeBlock::GroupBits) == 0)
    {
      continue;
    }
    __m128 c[4];
    this->P.Color.LookupFour(_mm_loadu_ps(this->Block.Values + first), c);
    for (int l = 0; l < std::min(4, end - first); ++l)
    {
      sum = _mm_add_ps(sum, _mm_mul_ps(_mm_set1_ps(weight[first + l]), c[l]));
    }
  }
  SetColourSums(out, sum);
  out.Alpha = left.Alpha;
  out.Transparency = left.Transparency;
  if (stops)
  {
    visited = end;
  }
  return !stops;
}
#endif

template <class View>
PARC_HOT_INLINE void RayContext<View>::BatchColors()
{
  LaneBatch& b = this->Batch;
#if defined(__SSE2__)
  for (int i = 0; i < b.Count; i += 4)
  {
    // Four lanes' (red, green, blue, 0), turned into channels of four lanes.
    __m128 c[4];
    this->P.Color.LookupFour(this->BatchValues(i), c);
    _MM_TRANSPOSE4_PS(c[0], c[1], c[2], c[3]);
    for (int ch = 0; ch < 3; ++ch)
    {
      _mm_store_ps(b.Rgb[ch] + i, c[ch]);
    }
  }
#else
  for (int i = 0; i < b.Count; ++i)
  {
    float rgb[3];
    this->P.Color.Lookup(this->Value(b.Lane[i]), rgb);
    for (int ch = 0; ch < 3; ++ch)
    {
      b.Rgb[ch][i] = rgb[ch];
    }
  }
#endif
}

template <class View>
PARC_HOT_INLINE void RayContext<View>::AddBatchColors(EventCompositor& out) const
{
  const LaneBatch& b = this->Batch;
#if defined(__SSE2__)
  // Four lanes' weighted colours at once, turned into (red, green, blue, 0) per lane and
  // added in lane order: per channel the products and sums of the lane-by-lane loop.
  __m128 sum = ColourSums(out);
  for (int i = 0; i < b.Count; i += 4)
  {
    const __m128 w = _mm_load_ps(b.Weight + i);
    __m128 c[4] = { _mm_mul_ps(w, _mm_load_ps(b.Rgb[0] + i)),
      _mm_mul_ps(w, _mm_load_ps(b.Rgb[1] + i)), _mm_mul_ps(w, _mm_load_ps(b.Rgb[2] + i)),
      _mm_setzero_ps() };
    _MM_TRANSPOSE4_PS(c[0], c[1], c[2], c[3]);
    for (int l = 0; l < std::min(4, b.Count - i); ++l)
    {
      sum = _mm_add_ps(sum, c[l]);
    }
  }
  SetColourSums(out, sum);
#else
  for (int i = 0; i < b.Count; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      out.Rgb[c] += b.Weight[i] * b.Rgb[c][i];
    }
  }
#endif
}

template <class View>
PARC_HOT_INLINE void RayContext<View>::ShadeBatch(long k0)
{
  LaneBatch& b = this->Batch;
  if (!this->K.ShadeLanesTogether)
  {
    for (int i = 0; i < b.Count; ++i)
    {
      float rgb[3] = { b.Rgb[0][i], b.Rgb[1][i], b.Rgb[2][i] };
      this->ShadeSample(rgb, (k0 + b.Lane[i]) * this->Dt, b.Lane[i], Vec3f(), false);
      for (int c = 0; c < 3; ++c)
      {
        b.Rgb[c][i] = rgb[c];
      }
    }
    return;
  }
#if defined(__SSE2__)
  if (b.Count > 0 && this->LanesInInteriorCells(b.Lane[0], b.Lane[b.Count - 1]))
  {
    // Every lane in an interior cell (most batches): no cell to check lane by lane.
    for (int i = 0; i < b.Count; ++i)
    {
      alignas(16) float world[4];
      this->InteriorWorldGradientAt(this->Block.Location(b.Lane[i]), world);
      for (int a = 0; a < 3; ++a)
      {
        b.Gradient[a][i] = world[a];
      }
    }
    this->ShadeLanes();
    return;
  }
#endif
  for (int i = 0; i < b.Count; ++i)
  {
#if defined(__SSE2__)
    alignas(16) float world[4];
    if (this->InteriorWorldGradient(b.Lane[i], world))
    {
      for (int a = 0; a < 3; ++a)
      {
        b.Gradient[a][i] = world[a];
      }
      continue;
    }
#endif
    const Vec3f g = this->WorldGradient((k0 + b.Lane[i]) * this->Dt, b.Lane[i]);
    b.Gradient[0][i] = g.X;
    b.Gradient[1][i] = g.Y;
    b.Gradient[2][i] = g.Z;
  }
  this->ShadeLanes();
}

} // namespace parc::casting

#endif
