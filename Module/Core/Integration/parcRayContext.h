// RayContext: the per-ray state the ray functions (parcRayFunctions.h) share over a
// render's constants: the ray's lattice, the block of samples taken last, opacity,
// colour, gradients and shading, hits, events and counts. Internal to the casters.
#ifndef parc_RayContext_h
#define parc_RayContext_h

#include "parcRayShading.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

namespace parc::casting
{

/// Lattice samples taken together along a ray; a ray that stops early has taken at most
/// this many - 1 in vain.
constexpr int SampleBlockSize = LatticeBlock::Size;
constexpr int RegulaFalsiSteps = 2; ///< isosurface refinement steps
/// Specular powers up to this whole number are computed by repeated squaring.
constexpr double MaxIntegerSpecularPower = 1024.0;
/// Cells whose voxel differences a thread keeps for gradients (a power of two): the rays
/// of a tile cross mostly the same cells.
constexpr std::size_t DifferenceCacheCells = 512;
static_assert((DifferenceCacheCells & (DifferenceCacheCells - 1)) == 0, "a power of two");
/// The block lane of a gradient at a point that is not a lattice sample (an isosurface
/// crossing).
constexpr int NotALatticeSample = -1;
/// Directional lights whose half vectors are computed once per ray.
constexpr std::size_t MaxHoistedLights = 8;
/// Iso values up to which the isosurface function finds a block's crossings by counting,
/// lane by lane, the values above each sample (RenderConstants::IsoThresholds).
constexpr std::size_t MaxThresholdIsoValues = 8;

/// Per-ray state shared by the ray functions, over the per-render constants.
template <class View>
struct RayContext
{
  const View& Field;
  const CastParameters& P;
  const RayCaster::RenderConstants& K;
  const Ray& WorldRay;
  /// The ray's sample points in index coordinates (the ray o + t d of the constructor).
  RayLattice Lattice;
  double Dt;
  CastStatistics& Stats;
  double FirstHit = std::numeric_limits<double>::infinity();
  /// Where the ray enters the field (inside the clipping planes).
  double EntryT = 0.0;
  /// Where the ray's events go (several volumes), or null.
  std::vector<RayEvent>* Events = nullptr;
  /// The label functions of the sample SampleOpacity took last (label maps), or null.
  const LabelFunctions* SampleLabel = nullptr;
  /// The block of lattice samples taken last.
  LatticeBlock Block;
  /// RayCaster::ContributingCells for composite rays, else null.
  const std::uint8_t* Cells = nullptr;
  /// The corrected opacities of the block's lanes (RenderConstants::OpacityByValue; 0 for
  /// the lanes LaneOpacities was not given).
  alignas(16) float Opacities[LatticeBlock::Size];
  /// The lanes of a block that CompositeBlock composites, packed in ray order.
  struct LaneBatch
  {
    int Count = 0;
    int Lane[LatticeBlock::Size];
    float Weight[LatticeBlock::Size]; ///< the compositor's weight of each
    /// Colour, channel by channel (BatchColors writes whole groups of four lanes).
    alignas(16) float Rgb[3][LatticeBlock::Size];
    /// World gradient, axis by axis (zeros past Count: ShadeLanes reads groups of four).
    alignas(16) float Gradient[3][LatticeBlock::Size] = {};
  } Batch;
  /// One cell's voxel differences: the cache of a ray whose thread shares none.
  CellDifferences OwnDifferences;
  /// The cells whose differences are kept, direct-mapped by cell (one slot, OwnDifferences,
  /// unless the thread shares its cache).
  CellDifferences* DifferenceSlots = &OwnDifferences;
  std::uint64_t DifferenceMask = 0;
  /// Unit vector from the samples to the eye (parallel light rays: the same for all).
  Vec3f ToEye;
  /// Half vectors of the first directional lights for this ray (Blinn-Phong).
  std::array<Vec3f, MaxHoistedLights> HalfVectors;
  /// What shadows the shaded contributions (null: nothing), and the thread's scratch for
  /// shadow rays.
  const Occluders* Shadows = nullptr;
  ShadowScratch* ShadowSpace = nullptr;

  /// shading: whether the ray's contributions are shaded (a shadow ray's are not).
  RayContext(const View& field, const CastParameters& p, const RayCaster::RenderConstants& k,
    const Ray& ray, const Vec3& indexOrigin, const Vec3& indexDirection, CastStatistics& stats,
    bool shading)
    : Field(field)
    , P(p)
    , K(k)
    , WorldRay(ray)
    , Lattice(indexOrigin, indexDirection, field.GetDimensions())
    , Dt(p.SampleDistance)
    , Stats(stats)
    , ToEye(-ray.Direction)
  {
    const std::size_t n = std::min(k.DirectionalLights.size(), MaxHoistedLights);
    for (std::size_t i = 0; shading && p.Shade && i < n; ++i)
    {
      this->HalfVectors[i] = this->HalfVector(k.DirectionalLights[i].ToLight);
    }
  }
  Vec3f HalfVector(const Vec3f& toLight) const
  {
    const Vec3 d = this->WorldRay.Direction;
    return Vec3f(Normalized(Vec3(toLight.X - d.X, toLight.Y - d.Y, toLight.Z - d.Z)));
  }

  void RecordHit(double t)
  {
    if (t < this->FirstHit)
    {
      this->FirstHit = t;
    }
  }
  /// Composites a sample's or crossing's colour rgb and opacity a at t behind out (and
  /// records it as an event, when events are kept); false once the ray may stop.
  bool Over(EventCompositor& out, double t, const float rgb[3], float a)
  {
    if (this->Events)
    {
      AppendEvent(*this->Events, t, rgb, a, false);
    }
    out.AddSample(rgb, a);
    return out.Below(this->P.TerminationOpacity);
  }
  /// Over for a premultiplied colour rgb.
  bool OverPremultiplied(EventCompositor& out, double t, const float rgb[3], float a)
  {
    if (this->Events)
    {
      AppendEvent(*this->Events, t, rgb, a, true);
    }
    out.AddPremultiplied(rgb, a);
    return out.Below(this->P.TerminationOpacity);
  }

  Vec3 IndexPosition(double t) const { return this->Lattice.Point(t); }
  /// Takes lattice samples k0 .. k0 + n - 1 (n <= SampleBlockSize) into Block; returns the
  /// lanes that may contribute (FieldView::SampleLattice with Cells).
  PARC_HOT_INLINE unsigned SampleBlock(long k0, int n)
  {
    return this->Field.SampleLattice(this->Lattice, this->Dt, k0, n,
      this->P.Interp, this->Block, this->Cells);
  }
  /// Counts the lanes below visited that SampleBlock left out (sampled: its result).
  void CountEmptyCells(unsigned sampled, int visited)
  {
    if (this->Cells)
    {
      const unsigned below = (1u << visited) - 1u;
      this->Stats.EmptyCellSamples += static_cast<std::uint64_t>(PopCount(below & ~sampled));
    }
  }
  float Value(int j) const { return this->Block.Values[j]; }
  /// The slot that holds, or will hold, the differences of the cell at offset.
  CellDifferences& DifferencesOf(std::ptrdiff_t offset)
  {
    const std::uint64_t hash = static_cast<std::uint64_t>(offset) * 0x9E3779B97F4A7C15ull;
    return this->DifferenceSlots[(hash >> 32) & this->DifferenceMask];
  }
  /// The world-space gradient at ray parameter t, sample j of the block (or
  /// NotALatticeSample).
  PARC_NOINLINE Vec3f WorldGradient(double t, int j)
  {
    ++this->Stats.GradientEvaluations;
    const Vec3f g = this->IndexGradient(t, j);
    const float* m = this->K.GradientToWorld;
    return { m[0] * g.X + m[1] * g.Y + m[2] * g.Z, m[3] * g.X + m[4] * g.Y + m[5] * g.Z,
      m[6] * g.X + m[7] * g.Y + m[8] * g.Z };
  }
#if defined(__SSE2__)
  /// WorldGradient of sample j of the block into world (x, y, z, 0), in registers, when it
  /// has linear interpolation and an interior cell (the same bits and counts); false, world
  /// untouched, otherwise.
  PARC_HOT_INLINE bool InteriorWorldGradient(int j, float world[4])
  {
    if (this->P.Interp != Interpolation::Linear)
    {
      return false;
    }
    const SampleLocation w = this->Block.Location(j);
    if (!this->Field.IsInteriorCell(w.Cell))
    {
      return false;
    }
    ++this->Stats.GradientEvaluations;
    CellDifferences& slot = this->DifferencesOf(w.Offset);
    this->Stats.DifferenceLoads += (slot.Offset != w.Offset);
    const __m128 g = this->Field.InteriorGradientVector(w, slot);
    // GradientToWorld's columns times g's coordinates, summed in WorldGradient's order.
    const auto column = [&](int c) { return _mm_load_ps(this->K.GradientToWorldColumns[c]); };
    const __m128 x = _mm_mul_ps(column(0), _mm_shuffle_ps(g, g, 0x00));
    const __m128 y = _mm_mul_ps(column(1), _mm_shuffle_ps(g, g, 0x55));
    const __m128 z = _mm_mul_ps(column(2), _mm_shuffle_ps(g, g, 0xAA));
    _mm_store_ps(world, _mm_add_ps(_mm_add_ps(x, y), z));
    return true;
  }
#endif
  /// The voxel-index gradient at ray parameter t, sample j of the block (or
  /// NotALatticeSample).
  Vec3f IndexGradient(double t, int j)
  {
    if (this->P.Interp != Interpolation::Linear)
    {
      return Vec3f(
        this->Field.Gradient(this->IndexPosition(t), this->P.Interp, this->OwnDifferences));
    }
    const SampleLocation w = j != NotALatticeSample
      ? this->Block.Location(j)
      : this->Field.LocationOf(this->IndexPosition(t));
    if (this->Field.IsInteriorCell(w.Cell))
    {
      CellDifferences& slot = this->DifferencesOf(w.Offset);
      this->Stats.DifferenceLoads += (slot.Offset != w.Offset);
      return this->Field.InteriorGradient(w, slot);
    }
    // Near a face: one-sided differences, no cell differences.
    return Vec3f(
      this->Field.Gradient(this->IndexPosition(t), this->P.Interp, this->OwnDifferences, &w));
  }
  /// Scales opacity a by the gradient opacity of gradient g (computed only when needed);
  /// false when the result is 0.
  bool ApplyGradientOpacity(float& a, int j, double t, Vec3f& g, bool& haveGradient)
  {
    if (!this->P.UseGradientOpacity)
    {
      return true;
    }
    if (this->K.GradientOpacityConstant)
    {
      a *= this->K.GradientOpacityValue;
    }
    else
    {
      a *= this->P.GradientOpacity.Evaluate(Length(this->GradientOnce(t, j, g, haveGradient)));
    }
    return a != 0.f;
  }
  /// g, the world gradient at sample j (t), computed unless haveGradient already says so.
  const Vec3f& GradientOnce(double t, int j, Vec3f& g, bool& haveGradient)
  {
    if (!haveGradient)
    {
      g = this->WorldGradient(t, j);
      haveGradient = true;
    }
    return g;
  }
  /// The corrected opacity a of sample j of the block, at t (with gradient opacity; g holds
  /// the gradient when haveGradient), counted and recorded as a hit; false when a is 0.
  bool ContributingOpacity(int j, double t, float& a, Vec3f& g, bool& haveGradient)
  {
    if (!this->SampleOpacity(j, t, a, g, haveGradient))
    {
      return false;
    }
    this->CountContribution(t);
    return true;
  }
  /// Counts a contributing sample at t and records it as a hit.
  void CountContribution(double t)
  {
    ++this->Stats.ContributingSamples;
    this->RecordHit(t);
  }
  /// ContributingOpacity without counting or recording the sample.
  bool SampleOpacity(int j, double t, float& a, Vec3f& g, bool& haveGradient)
  {
    if (!this->P.Labels.empty())
    {
      return this->LabelOpacity(j, t, a, g, haveGradient);
    }
    a = this->P.Opacity.Evaluate(this->Value(j));
    if (a == 0.f || this->Masked(t) || !this->ApplyGradientOpacity(a, j, t, g, haveGradient))
    {
      return false;
    }
    a = this->CorrectOpacity(a);
    return true;
  }
  /// Takes lattice samples k0 .. k0 + n - 1 into the block and calls
  /// visit(j, t, a, g, haveGradient) for each contributing one in order (a its corrected
  /// opacity; g its gradient when haveGradient); when visit returns false the walk stops
  /// after sample j (visited = j + 1) and false is returned.
  template <class Visit>
  PARC_HOT_INLINE bool ContributingSamples(long k0, int n, int& visited, Visit&& visit)
  {
    const unsigned sampled = this->SampleBlock(k0, n);
    const bool byValue = this->K.OpacityByValue;
    unsigned lanes = this->MayContribute(n) & sampled;
    if (byValue)
    {
      lanes = this->LaneOpacities(lanes);
    }
    for (; lanes != 0; lanes &= lanes - 1)
    {
      const int j = CountTrailingZeros(lanes);
      const double t = (k0 + j) * this->Dt;
      float a;
      Vec3f g;
      bool haveGradient = false;
      if (byValue)
      {
        a = this->Opacities[j];
        this->CountContribution(t);
      }
      else if (!this->ContributingOpacity(j, t, a, g, haveGradient))
      {
        continue;
      }
      if (!visit(j, t, a, g, haveGradient))
      {
        visited = j + 1;
        this->CountEmptyCells(sampled, visited);
        return false;
      }
    }
    this->CountEmptyCells(sampled, n);
    return true;
  }
  /// The composite ray function over lattice samples k0 .. k0 + n - 1 into out (and the
  /// events, when kept), in stages over the block's lanes (RenderConstants::ColorByValue):
  /// the opacities, the lanes composited before the ray may stop with their weights (the
  /// compositor's own arithmetic, so that no colour, gradient or shading is computed for a
  /// lane that is not), their colours, their shading, then the weighted colours in ray
  /// order (unshaded samples without events: CompositeUnshadedBlock). The same bits, events
  /// and counts as ContributingSamples with SampleColor, ShadeSample and Over; returns false
  /// (visited set) when the ray stops.
  PARC_HOT_INLINE bool CompositeBlock(long k0, int n, int& visited, EventCompositor& out)
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
      for (int i = 0; i < b.Count; ++i)
      {
        for (int c = 0; c < 3; ++c)
        {
          out.Rgb[c] += b.Weight[i] * b.Rgb[c][i];
        }
      }
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
  /// Whether shaded samples interpolate the shading of their cells' quantized normals.
  bool InterpolatesNormalShading() const
  {
    return this->K.QuantizedNormals && this->P.Interp == Interpolation::Linear;
  }
#if defined(__SSE2__)
  /// Adds the weighted colours of the lanes of Batch, shaded by quantized normals
  /// (InterpolatesNormalShading), to out, as BatchColors, ShadeBatch and CompositeBlock's
  /// sums do (the same bits) without turning lanes into channels.
  PARC_HOT_INLINE void AddNormalShadedColors(EventCompositor& out)
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
  /// ShadeQuantized of lane j of the block, colour (red, green, blue, 0) rgb, in a register.
  PARC_HOT_INLINE __m128 ShadeByNormals(int j, __m128 rgb) const
  {
    const LatticeBlock& block = this->Block;
    const int cell[3] = { block.Cell[0][j], block.Cell[1][j], block.Cell[2][j] };
    const float f[3] = { block.Fractions[0][j], block.Fractions[1][j], block.Fractions[2][j] };
    std::uint16_t codes[8];
    this->P.Normals->CellCorners(cell, codes);
    __m128 diffuse, specular;
    this->InterpolateNormalFactors(codes, f, diffuse, specular);
    const __m128 ambient = _mm_load_ps(this->K.Ambient); // red, green, blue, 0
    const __m128 lit = _mm_add_ps(_mm_mul_ps(rgb, _mm_add_ps(ambient, diffuse)), specular);
    return _mm_min_ps(_mm_set1_ps(1.f), lit); // std::min(lit, 1.f), NaN kept
  }
  /// The diffuse and specular factors (red, green, blue; the fourth lane is not one)
  /// interpolated at fractions f from the normals of a cell's corners (codes) with the
  /// render's table.
  PARC_HOT_INLINE void InterpolateNormalFactors(
    const std::uint16_t codes[8], const float f[3], __m128& diffuse, __m128& specular) const
  {
    if (!this->K.GreyNormalShading.empty())
    {
      const __m128 pair = InterpolateGreyFactors(this->K.GreyNormalShading.data(), codes, f);
      diffuse = _mm_shuffle_ps(pair, pair, 0x00);
      specular = _mm_shuffle_ps(pair, pair, 0x55);
      return;
    }
    alignas(16) float d[4], s[4];
    InterpolateFactors(this->K.NormalShading.data(), codes, f, d, s);
    diffuse = _mm_load_ps(d);
    specular = _mm_load_ps(s);
  }
  /// The values of lanes i .. i + 3 of Batch (its last lane repeated past Count).
  PARC_HOT_INLINE __m128 BatchValues(int i) const
  {
    const LaneBatch& b = this->Batch;
    const auto value = [&](int l) { return this->Value(b.Lane[std::min(i + l, b.Count - 1)]); };
    return _mm_setr_ps(value(0), value(1), value(2), value(3));
  }
  /// CompositeBlock of unshaded samples without events, the same bits and counts, over
  /// every lane rather than those gathered into Batch: a lane of opacity 0 changes nothing
  /// (its weight is 0 and the transparency is multiplied by 1), and its weight times its
  /// colour adds 0.
  PARC_HOT_INLINE bool CompositeUnshadedBlock(
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
    const unsigned composited = lanes & ((1u << end) - 1u);
    this->Stats.ContributingSamples += static_cast<std::uint64_t>(PopCount(composited));
    this->CountEmptyCells(sampled, end);
    this->RecordHit((k0 + CountTrailingZeros(composited)) * this->Dt);
    __m128 sum = ColourSums(out);
    for (int first = 0; first < end; first += LatticeBlock::Lanes)
    {
      if (((composited >> first) & ((1u << LatticeBlock::Lanes) - 1u)) == 0)
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
  /// The colours of the lanes of Batch (see CompositeBlock).
  PARC_HOT_INLINE void BatchColors()
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
  /// Shades the colours of Batch in place (see CompositeBlock).
  PARC_HOT_INLINE void ShadeBatch(long k0)
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
  /// Shade for the lanes of Batch together (RenderConstants::ShadeLanesTogether): the same
  /// operations in the same order, lane by lane, so the same bits.
  void ShadeLanes();
  /// The opacities of the given lanes (bits 1 << j) into Opacities, corrected; returns the
  /// lanes whose opacity is not 0 before the correction.
  PARC_HOT_INLINE unsigned LaneOpacities(unsigned lanes)
  {
    if (lanes == 0)
    {
      return 0;
    }
    float* a = this->Opacities;
    std::fill_n(a, LatticeBlock::Size, 0.f);
    this->P.Opacity.EvaluateLanes(this->Block.Values, lanes, a);
    if (this->K.GradientOpacityConstant)
    {
      for (int j = 0; j < LatticeBlock::Size; ++j)
      {
        a[j] *= this->K.GradientOpacityValue;
      }
    }
    unsigned nonZero = 0;
#if defined(__SSE2__)
    for (int j = 0; j < LatticeBlock::Size; j += 4)
    {
      const __m128 zero = _mm_setzero_ps();
      nonZero |= static_cast<unsigned>(_mm_movemask_ps(_mm_cmpneq_ps(_mm_loadu_ps(a + j), zero)))
        << j;
    }
#else
    for (int j = 0; j < LatticeBlock::Size; ++j)
    {
      nonZero |= static_cast<unsigned>(a[j] != 0.f) << j;
    }
#endif
    this->CorrectOpacities(a);
    return lanes & nonZero;
  }
  /// CorrectOpacity for every lane of a.
  PARC_HOT_INLINE void CorrectOpacities(float* a) const
  {
    const float exponent = this->K.OpacityExponent;
    if (exponent == 1.f)
    {
      return;
    }
#if defined(__SSE2__)
    if (const int roots = this->K.OpacityRoots)
    {
      const __m128 one = _mm_set1_ps(1.f);
      for (int j = 0; j < LatticeBlock::Size; j += 4)
      {
        const __m128 v = _mm_loadu_ps(a + j);
        __m128 root = _mm_sub_ps(one, v);
        for (int r = 0; r < roots; ++r)
        {
          root = _mm_sqrt_ps(root);
        }
        const __m128 opaque = _mm_cmpge_ps(v, one);
        const __m128 corrected = _mm_sub_ps(one, root);
        _mm_storeu_ps(a + j, Select(opaque, v, corrected));
      }
      return;
    }
#endif
    for (int j = 0; j < LatticeBlock::Size; ++j)
    {
      a[j] = this->CorrectOpacity(a[j]);
    }
  }
  /// The lanes j < n of the block whose opacity may be non-zero, as bits 1 << j: the
  /// others are 0 without evaluating the opacity function.
  PARC_HOT_INLINE unsigned MayContribute(int n) const
  {
    const float below = this->K.ZeroOpacityBelow, above = this->K.ZeroOpacityAbove;
    unsigned lanes = 0;
#if defined(__SSE2__)
    const __m128 low = _mm_set1_ps(below), high = _mm_set1_ps(above);
    for (int j = 0; j < n; j += LatticeBlock::Lanes) // the lanes SampleBlock computed
    {
      const __m128 s = _mm_loadu_ps(this->Block.Values + j);
      const __m128 inside = _mm_and_ps(_mm_cmpgt_ps(s, low), _mm_cmplt_ps(s, high));
      lanes |= static_cast<unsigned>(_mm_movemask_ps(inside)) << j;
    }
    static_assert(LatticeBlock::Lanes == 4, "four lanes to an SSE register");
    return lanes & ((1u << n) - 1u);
#else
    for (int j = 0; j < n; ++j)
    {
      const float s = this->Block.Values[j];
      lanes |= static_cast<unsigned>(s > below && s < above) << j;
    }
    return lanes;
#endif
  }
  /// SampleOpacity with a label map (see CastParameters::Labels); keeps the sample's label
  /// functions in SampleLabel.
  bool LabelOpacity(int j, double t, float& a, Vec3f& g, bool& haveGradient)
  {
    this->SampleLabel = this->LabelAt(t);
    const float s = this->Value(j);
    a = this->P.Opacity.Evaluate(s);
    if (a != 0.f)
    {
      this->ApplyGradientOpacity(a, j, t, g, haveGradient);
    }
    if (const LabelFunctions* label = this->SampleLabel)
    {
      float own = label->Opacity.Evaluate(s);
      if (own != 0.f && label->UseGradientOpacity)
      {
        own *= label->GradientOpacity.Evaluate(Length(this->GradientOnce(t, j, g, haveGradient)));
      }
      const float f = this->P.MaskBlendFactor;
      a = (1.f - f) * a + f * own;
    }
    if (a == 0.f)
    {
      return false;
    }
    a = this->CorrectOpacity(a);
    return true;
  }
  /// The functions of the label at ray parameter t, or null for the default ones.
  const LabelFunctions* LabelAt(double t) const
  {
    const float value = this->P.Mask->SampleNearest(this->IndexPosition(t));
    const int label = static_cast<int>(std::lround(value));
    const auto& labels = this->P.Labels;
    const auto it = std::lower_bound(labels.begin(), labels.end(), label,
      [](const LabelFunctions& l, int v) { return l.Label < v; });
    return it != labels.end() && it->Label == label ? &*it : nullptr;
  }
  /// Whether the mask hides ray parameter t (see CastParameters::Mask).
  bool Masked(double t) const
  {
    return this->P.Mask && this->P.Labels.empty() &&
      this->P.Mask->SampleNearest(this->IndexPosition(t)) == 0.f;
  }
  /// The colour of sample j of the block at t (or of a crossing of value s at t, j =
  /// NotALatticeSample): see CastParameters::ColorShiftCount.
  void SampleColor(int j, double t, double s, float rgb[3]) const
  {
    this->DefaultColor(j, t, s, rgb);
    if (const LabelFunctions* label = this->SampleLabel)
    {
      float own[3];
      label->Color.Lookup(j != NotALatticeSample ? this->Value(j) : s, own);
      const float f = this->P.MaskBlendFactor;
      for (int c = 0; c < 3; ++c)
      {
        rgb[c] = (1.f - f) * rgb[c] + f * own[c];
      }
    }
  }
  /// SampleColor from the default functions.
  void DefaultColor(int j, double t, double s, float rgb[3]) const
  {
    if (this->P.ColorShiftCount == 0)
    {
      this->P.Color.Lookup(j != NotALatticeSample ? this->Value(j) : s, rgb);
      return;
    }
    const Vec3 x = this->IndexPosition(t);
    if (this->P.ColorShiftCount == 1)
    {
      const float value = this->Field.Shifted(this->P.ColorShifts[0]).Sample(x, this->P.Interp);
      this->P.Color.Lookup(value, rgb);
      return;
    }
    for (int c = 0; c < 3; ++c)
    {
      const float v = this->Field.Shifted(this->P.ColorShifts[c]).Sample(x, this->P.Interp);
      rgb[c] = std::min(std::max(v * this->P.DirectColorScale, 0.f), 1.f);
    }
  }
  /// s normalised to the intensity range (additive and average intensity).
  double NormalizedIntensity(float s) const
  {
    return (s - this->P.IntensityRange[0]) * this->K.IntensityScale;
  }
  float CorrectOpacity(float a) const
  {
    const float exponent = this->K.OpacityExponent;
    if (exponent == 1.f || a >= 1.f)
    {
      return a;
    }
    float transparency = 1.f - a;
    if (const int roots = this->K.OpacityRoots) // see RenderConstants::OpacityRoots
    {
      for (int r = 0; r < roots; ++r)
      {
        transparency = std::sqrt(transparency);
      }
      return 1.f - transparency;
    }
    return 1.f - std::pow(transparency, exponent);
  }
  float SpecularTerm(float ndh) const
  {
    return this->K.IntegerSpecularPower >= 0
      ? IntegerPower(ndh, this->K.IntegerSpecularPower)
      : std::pow(ndh, static_cast<float>(this->P.SpecularPower));
  }
  Vec3 WorldPosition(double t) const { return this->WorldRay.Origin + t * this->WorldRay.Direction; }
  /// The factor of the terms of light `index` at world point x, for a light whose shadow
  /// attenuation is attenuation: 1 - attenuation (1 - T), T the transmittance from x
  /// towards the light along direction toLight, up to tLight. 1 without occluders.
  float Visibility(const Vec3& x, const Vec3& toLight, double tLight, std::size_t index,
    float attenuation) const;
  /// Shades rgb in place at ray parameter t with world gradient g (Blinn-Phong, two-sided,
  /// in float).
  PARC_HOT_INLINE void Shade(float rgb[3], double t, const Vec3f& g) const;
  /// Shades rgb in place: sample j of the block (or the crossing at t, j =
  /// NotALatticeSample) with world gradient g when haveGradient (else computed when needed).
  PARC_HOT_INLINE void ShadeSample(
    float rgb[3], double t, int j, const Vec3f& g, bool haveGradient)
  {
    if (this->K.QuantizedNormals)
    {
      this->ShadeQuantized(rgb, t, j);
      return;
    }
    this->Shade(rgb, t, haveGradient ? g : this->WorldGradient(t, j));
  }
  /// Shades rgb in place with the quantized normals around sample j (or the crossing at t,
  /// j = NotALatticeSample): see parcNormalVolume.h.
  void ShadeQuantized(float rgb[3], double t, int j) const;
  /// Adds the positional lights' terms at ray parameter t for unit normal n.
  void AddPositionalLights(double t, const Vec3f& n, float diffuse[3], float specular[3]) const;
};

template <class View>
PARC_HOT_INLINE void RayContext<View>::Shade(float rgb[3], double t, const Vec3f& g) const
{
  float diffuse[3] = { 0.f, 0.f, 0.f };
  float specular[3] = { 0.f, 0.f, 0.f };
  const float length = Length(g);
  if (length > 0.f)
  {
    // The normal faces the eye (two-sided lighting).
    const Vec3f n = FlipUnlessPositive(1.f / length, Dot(g, this->ToEye)) * g;
    const RayCaster::DirectionalLight* lights = this->K.DirectionalLights.data();
    const std::size_t count = this->K.DirectionalLights.size();
    for (std::size_t i = 0; i < count; ++i)
    {
      const RayCaster::DirectionalLight& light = lights[i];
      float ndl = Dot(n, light.ToLight);
      if (ndl > 0.f)
      {
        const float ndh =
          Dot(n, i < MaxHoistedLights ? this->HalfVectors[i] : this->HalfVector(light.ToLight));
        float spec = ndh > 0.f ? this->SpecularTerm(ndh) : 0.f;
        if (light.ShadowAttenuation > 0.f && this->Shadows)
        {
          const float v = this->Visibility(this->WorldPosition(t), light.ShadowDirection,
            std::numeric_limits<double>::infinity(), light.Index, light.ShadowAttenuation);
          ndl *= v;
          spec *= v;
        }
        for (int c = 0; c < 3; ++c)
        {
          diffuse[c] += ndl * (&light.Diffuse.X)[c];
          specular[c] += spec * (&light.Specular.X)[c];
        }
      }
    }
    if (!this->K.PositionalLights.empty())
    {
      this->AddPositionalLights(t, n, diffuse, specular);
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = std::min(rgb[c] * (this->K.Ambient[c] + diffuse[c]) + specular[c], 1.f);
  }
}

template <class View>
void RayContext<View>::ShadeLanes()
{
  LaneBatch& b = this->Batch;
#if defined(__SSE2__)
  const __m128 zero = _mm_setzero_ps(), one = _mm_set1_ps(1.f);
  const __m128 signBit = _mm_set1_ps(-0.f);
  auto dot = [](__m128 ax, __m128 ay, __m128 az, const Vec3f& v) {
    const __m128 x = _mm_mul_ps(ax, _mm_set1_ps(v.X)), y = _mm_mul_ps(ay, _mm_set1_ps(v.Y));
    return _mm_add_ps(_mm_add_ps(x, y), _mm_mul_ps(az, _mm_set1_ps(v.Z)));
  };
  const RayCaster::DirectionalLight* lights = this->K.DirectionalLights.data();
  const std::size_t count = this->K.DirectionalLights.size();
  const int channels = this->K.GreyLights ? 1 : 3;
  for (int i = 0; i < b.Count; i += 4)
  {
    const __m128 gx = _mm_load_ps(b.Gradient[0] + i), gy = _mm_load_ps(b.Gradient[1] + i);
    const __m128 gz = _mm_load_ps(b.Gradient[2] + i);
    const __m128 length = _mm_sqrt_ps(_mm_add_ps(
      _mm_add_ps(_mm_mul_ps(gx, gx), _mm_mul_ps(gy, gy)), _mm_mul_ps(gz, gz)));
    const __m128 valid = _mm_cmpgt_ps(length, zero);
    // FlipUnlessPositive: the normal faces the eye.
    const __m128 back = _mm_cmpngt_ps(dot(gx, gy, gz, this->ToEye), zero);
    const __m128 scale = _mm_xor_ps(_mm_div_ps(one, length), _mm_and_ps(back, signBit));
    const __m128 nx = _mm_mul_ps(scale, gx), ny = _mm_mul_ps(scale, gy);
    const __m128 nz = _mm_mul_ps(scale, gz);
    __m128 diffuse[3] = { zero, zero, zero }, specular[3] = { zero, zero, zero };
    for (std::size_t l = 0; l < count; ++l)
    {
      const RayCaster::DirectionalLight& light = lights[l];
      const __m128 ndl = dot(nx, ny, nz, light.ToLight);
      const __m128 lit = _mm_and_ps(valid, _mm_cmpgt_ps(ndl, zero));
      const __m128 ndh = dot(nx, ny, nz, this->HalfVectors[l]);
      // IntegerPower, lane by lane.
      __m128 power = one, x = ndh;
      for (int e = this->K.IntegerSpecularPower; e > 0; e >>= 1)
      {
        if (e & 1)
        {
          power = _mm_mul_ps(power, x);
        }
        x = _mm_mul_ps(x, x);
      }
      const __m128 spec = _mm_and_ps(_mm_cmpgt_ps(ndh, zero), power);
      for (int c = 0; c < channels; ++c)
      {
        const __m128 d = _mm_set1_ps((&light.Diffuse.X)[c]);
        const __m128 sc = _mm_set1_ps((&light.Specular.X)[c]);
        diffuse[c] = Select(lit, _mm_add_ps(diffuse[c], _mm_mul_ps(ndl, d)), diffuse[c]);
        specular[c] = Select(lit, _mm_add_ps(specular[c], _mm_mul_ps(spec, sc)), specular[c]);
      }
    }
    for (int c = channels; c < 3; ++c) // white lights: the same as red
    {
      diffuse[c] = diffuse[0];
      specular[c] = specular[0];
    }
    for (int c = 0; c < 3; ++c)
    {
      const __m128 rgb = _mm_load_ps(b.Rgb[c] + i);
      const __m128 ambient = _mm_set1_ps(this->K.Ambient[c]);
      const __m128 shaded =
        _mm_add_ps(_mm_mul_ps(rgb, _mm_add_ps(ambient, diffuse[c])), specular[c]);
      _mm_store_ps(b.Rgb[c] + i, _mm_min_ps(one, shaded)); // std::min(shaded, 1.f)
    }
  }
#else
  for (int i = 0; i < b.Count; ++i)
  {
    // No shadows here: Shade needs no ray parameter.
    float rgb[3] = { b.Rgb[0][i], b.Rgb[1][i], b.Rgb[2][i] };
    this->Shade(rgb, 0.0, Vec3f(b.Gradient[0][i], b.Gradient[1][i], b.Gradient[2][i]));
    for (int c = 0; c < 3; ++c)
    {
      b.Rgb[c][i] = rgb[c];
    }
  }
#endif
}

template <class View>
void RayContext<View>::ShadeQuantized(float rgb[3], double t, int j) const
{
  const NormalVolume& normals = *this->P.Normals;
  alignas(16) float diffuse[4], specular[4];
  if (this->P.Interp == Interpolation::Nearest)
  {
    int voxel[3];
    NearestVoxel(this->IndexPosition(t), normals.GetDimensions(), voxel);
    const std::uint16_t code = normals.At(voxel[0], voxel[1], voxel[2]);
    if (!this->K.GreyNormalShading.empty())
    {
      const float* pair = &this->K.GreyNormalShading[2 * static_cast<std::size_t>(code)];
      std::fill_n(diffuse, 3, pair[0]);
      std::fill_n(specular, 3, pair[1]);
    }
    else
    {
      std::copy_n(this->K.NormalShading[code].Diffuse, 3, diffuse);
      std::copy_n(this->K.NormalShading[code].Specular, 3, specular);
    }
  }
  else
  {
    const SampleLocation w = j != NotALatticeSample
      ? this->Block.Location(j)
      : this->Field.LocationOf(this->IndexPosition(t));
    std::uint16_t codes[8];
    normals.CellCorners(w.Cell, codes);
#if defined(__SSE2__)
    __m128 d, s;
    this->InterpolateNormalFactors(codes, w.Fractions, d, s);
    _mm_store_ps(diffuse, d);
    _mm_store_ps(specular, s);
#else
    InterpolateFactors(this->K.NormalShading.data(), codes, w.Fractions, diffuse, specular);
#endif
  }
  for (int c = 0; c < 3; ++c)
  {
    rgb[c] = std::min(rgb[c] * (this->K.Ambient[c] + diffuse[c]) + specular[c], 1.f);
  }
}

template <class View>
void RayContext<View>::AddPositionalLights(
  double t, const Vec3f& n, float diffuse[3], float specular[3]) const
{
  const Vec3 x = this->WorldRay.Origin + t * this->WorldRay.Direction;
  const Vec3 normal(n.X, n.Y, n.Z);
  for (const RayCaster::PositionalLight& positional : this->K.PositionalLights)
  {
    const Light* light = positional.Source;
    const Vec3 toLight = light->Position - x;
    const double dist = Length(toLight);
    const Vec3 l = Normalized(toLight);
    const double denom =
      light->Attenuation.X + dist * (light->Attenuation.Y + dist * light->Attenuation.Z);
    double attenuation = denom > 0.0 ? 1.0 / denom : 1.0;
    if (light->ConeAngle < 90.0)
    {
      const double c = Dot(-l, positional.SpotDirection);
      attenuation *=
        (c < positional.CosCone) ? 0.0 : std::pow(std::max(c, 0.0), light->Exponent);
    }
    const double ndl = Dot(normal, l);
    if (ndl > 0.0 && attenuation != 0.0)
    {
      if (light->ShadowAttenuation > 0.0 && this->Shadows)
      {
        attenuation *= this->Visibility(
          x, l, dist, positional.Index, static_cast<float>(light->ShadowAttenuation));
      }
      const double ndh = Dot(normal, Normalized(l - this->WorldRay.Direction));
      const double spec = ndh > 0.0 ? this->SpecularTerm(static_cast<float>(ndh)) : 0.0;
      for (int c = 0; c < 3; ++c)
      {
        const double color = attenuation * light->Color[c];
        const double specularColor = attenuation * light->SpecularColor[c];
        diffuse[c] += static_cast<float>(this->P.Diffuse * color * ndl);
        specular[c] += static_cast<float>(this->P.Specular * specularColor * spec);
      }
    }
  }
}

template <class View>
float RayContext<View>::Visibility(const Vec3& x, const Vec3& toLight, double tLight,
  std::size_t index, float attenuation) const
{
  const Ray shadowRay{ x, toLight, 0.0, tLight };
  const float t = this->Shadows->Transmittance(shadowRay, index, *this->ShadowSpace, this->Stats);
  return 1.f - attenuation * (1.f - t);
}

} // namespace parc::casting

#endif
