// RayContext: the per-ray state the ray functions (parcRayFunctions.h) share over a
// render's constants: the ray's lattice, the block of samples taken last, opacity,
// colour, gradients, hits, events and counts. Its shading is defined in parcRayShading.h, the
// composite function's staged block in parcCompositeBlock.h. Internal to the casters.
#ifndef parc_RayContext_h
#define parc_RayContext_h

#include "parcRayCaster.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <type_traits>

namespace parc::casting
{

/// Appends an event, out of the sample loops (only several volumes keep events).
PARC_NOINLINE inline void AppendEvent(
  std::vector<RayEvent>& events, double t, const float rgb[3], float a, bool premultiplied)
{
  events.push_back({ t, { rgb[0], rgb[1], rgb[2] }, a, premultiplied });
}

/// Lattice samples taken together along a ray; a ray that stops early has taken at most
/// this many - 1 in vain.
constexpr int SampleBlockSize = LatticeBlock::Size;
constexpr int RegulaFalsiSteps = 2; ///< isosurface refinement steps
/// Specular powers up to this whole number are computed by repeated squaring.
constexpr double MaxIntegerSpecularPower = 1024.0;
/// Cells whose voxel differences a thread keeps for gradients (a power of two): neighbouring
/// rays of a tile cross mostly the same cells.
constexpr std::size_t DifferenceCacheCells = 512;
/// ... when the rays are closer than DenseRaySpacing voxels: then a ray also crosses the
/// cells of the tile's row of rays before it, which the cache holds too (at 1000^2 on a
/// 7 MB volume, half the loads and 6% less time shaded; a volume's cells crossed by one
/// ray each gain nothing from the larger cache and lose a little to its misses).
constexpr std::size_t DenseDifferenceCacheCells = 4096;
constexpr double DenseRaySpacing = 0.6;
static_assert((DifferenceCacheCells & (DifferenceCacheCells - 1)) == 0, "a power of two");
static_assert(
  (DenseDifferenceCacheCells & (DenseDifferenceCacheCells - 1)) == 0, "a power of two");
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
  const CellMap* Cells = nullptr;
  /// Whether the next block reads Cells. Reading it costs about a tenth of a sample and
  /// pays only where the ray crosses cells that cannot contribute: a block whose lanes all
  /// lie in cells that may turns it off, a block whose last lane lies in one that cannot
  /// turns it on. Either way the same samples and bits.
  bool ReadsMap = true;
  /// The corrected opacities of the block's lanes (RenderConstants::OpacityByValue; 0 for
  /// the lanes LaneOpacities was not given).
  alignas(16) float Opacities[LatticeBlock::Size];
  /// The lanes of a block that CompositeBlock composites, packed in ray order.
  struct LaneBatch
  {
    int Count = 0;
    int Lane[LatticeBlock::Size];
    /// The compositor's weight of each (AddBatchColors reads groups of four: past Count,
    /// zeros or an earlier batch's, whose products are not added).
    alignas(16) float Weight[LatticeBlock::Size] = {};
    /// Colour, channel by channel (BatchColors writes whole groups of four lanes; ShadeLanes
    /// reads and writes groups of four or eight: past Count, zeros or an earlier batch's).
    alignas(16) float Rgb[3][LatticeBlock::Size] = {};
    /// World gradient, axis by axis (ShadeLanes reads groups of four or eight: past Count,
    /// zeros or an earlier batch's, whose results are not used).
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
  /// How far the ray's cells move over RenderConstants::PrefetchSamples samples, in
  /// values (FieldView::OffsetAhead; when it prefetches).
  std::ptrdiff_t PrefetchOffset = 0;

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
    if (k.PrefetchSamples > 0)
    {
      this->PrefetchOffset = field.OffsetAhead(this->Lattice, this->Dt * k.PrefetchSamples);
    }
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
  /// lanes that may contribute (FieldView::SampleLattice with Cells, when ReadsMap).
  PARC_HOT_INLINE unsigned SampleBlock(long k0, int n)
  {
    const CellMap* map = this->ReadsMap ? this->Cells : nullptr;
    const unsigned sampled = this->Field.SampleLattice(
      this->Lattice, this->Dt, k0, n, this->P.Interp, this->Block, map, this->K.WideVectors,
      this->K.PrefetchSamples > 0 ? &this->PrefetchOffset : nullptr);
    if (map)
    {
      this->ReadsMap = sampled != LatticeBlock::GroupLanes(n);
    }
    else if (this->Cells)
    {
      this->ReadsMap = !this->Cells->MayContribute(this->Block, n - 1);
    }
    return sampled;
  }
  /// Counts the lanes below visited that SampleBlock left out (sampled: its result).
  void CountEmptyCells(unsigned sampled, int visited)
  {
    if (this->Cells)
    {
      const unsigned below = LatticeBlock::LowLanes(visited);
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
    this->InteriorWorldGradientAt(w, world);
    return true;
  }
  /// Whether the block's lanes i to k (i <= k) all lie in interior cells, with linear
  /// interpolation: the cells of a ray's samples run monotonically along each axis, so
  /// the first and last lanes bound them in the box of interior cells.
  PARC_HOT_INLINE bool LanesInInteriorCells(int i, int k) const
  {
    const auto interior = [this](int j) {
      const int cell[3] = { this->Block.Cell[0][j], this->Block.Cell[1][j],
        this->Block.Cell[2][j] };
      return this->Field.IsInteriorCell(cell);
    };
    return this->P.Interp == Interpolation::Linear && interior(i) && interior(k);
  }
  /// InteriorWorldGradient at w, a sample of linear interpolation in an interior cell.
  PARC_HOT_INLINE void InteriorWorldGradientAt(const SampleLocation& w, float world[4])
  {
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
  PARC_HOT_INLINE bool CompositeBlock(long k0, int n, int& visited, EventCompositor& out);
  /// Whether shaded samples interpolate the shading of their cells' quantized normals.
  bool InterpolatesNormalShading() const
  {
    return this->K.QuantizedNormals && this->P.Interp == Interpolation::Linear;
  }
#if defined(__SSE2__)
  /// Adds the weighted colours of the lanes of Batch, shaded by quantized normals
  /// (InterpolatesNormalShading), to out, as BatchColors, ShadeBatch and CompositeBlock's
  /// sums do (the same bits) without turning lanes into channels.
  PARC_HOT_INLINE void AddNormalShadedColors(EventCompositor& out);
  /// ShadeQuantized of lane j of the block, colour (red, green, blue, 0) rgb, in a register.
  PARC_HOT_INLINE __m128 ShadeByNormals(int j, __m128 rgb) const;
  /// The diffuse and specular factors (red, green, blue; the fourth lane is not one)
  /// interpolated at fractions f from the normals of a cell's corners (codes) with the
  /// render's table.
  PARC_HOT_INLINE void InterpolateNormalFactors(
    const std::uint16_t codes[8], const float f[3], __m128& diffuse, __m128& specular) const;
  /// The values of lanes i .. i + 3 of Batch (its last lane repeated past Count).
  PARC_HOT_INLINE __m128 BatchValues(int i) const;
  /// CompositeBlock of unshaded samples without events, the same bits and counts, over
  /// every lane rather than those gathered into Batch: a lane of opacity 0 changes nothing
  /// (its weight is 0 and the transparency is multiplied by 1), and its weight times its
  /// colour adds 0.
  PARC_HOT_INLINE bool CompositeUnshadedBlock(
    long k0, int n, int& visited, EventCompositor& out);
#endif
  /// The colours of the lanes of Batch (see CompositeBlock).
  PARC_HOT_INLINE void BatchColors();
  /// Adds the colours of Batch times their weights to out's colour, lane by lane.
  PARC_HOT_INLINE void AddBatchColors(EventCompositor& out) const;
  /// Shades the colours of Batch in place (see CompositeBlock).
  PARC_HOT_INLINE void ShadeBatch(long k0);
  /// Shade for the lanes of Batch together (RenderConstants::ShadeLanesTogether): the same
  /// operations in the same order, lane by lane, so the same bits.
  PARC_HOT_INLINE void ShadeLanes();
#if PARC_WIDE_VECTORS
  /// ShadeLanes eight lanes at a time, for a whole specular power (the same bits). A
  /// function of its own, compiled for wide vectors whichever copy of the block calls it.
  PARC_NOINLINE PARC_TARGET_WIDE_VECTORS void ShadeEightLanes();
#endif
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
#if PARC_WIDE_VECTORS
    if (this->K.WideVectors && this->P.Opacity.PermutesPieces())
    {
      this->P.Opacity.EvaluateEightLanes(this->Block.Values, lanes, a);
    }
    else
#endif
    {
      this->P.Opacity.EvaluateLanes(this->Block.Values, lanes, a);
    }
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
    this->K.Correction.CorrectLanes<LatticeBlock::Size>(a);
    return lanes & nonZero;
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
    return lanes & LatticeBlock::LowLanes(n);
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
  float CorrectOpacity(float a) const { return this->K.Correction.Correct(a); }
  /// ndh^SpecularPower for 0 < ndh (about 1 at most).
  float SpecularTerm(float ndh) const;
#if defined(__SSE2__)
  /// SpecularTerm lane by lane (any value for lanes whose ndh is not above 0).
  PARC_HOT_INLINE __m128 SpecularLanes(__m128 ndh) const;
#endif
  Vec3 WorldPosition(double t) const
  {
    return this->WorldRay.Origin + t * this->WorldRay.Direction;
  }
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

} // namespace parc::casting

#endif
