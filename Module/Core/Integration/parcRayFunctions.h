// The ray functions (composite, maximum and minimum intensity, per component, average,
// additive, isosurface, absorption) over a RayContext, and Run, which walks a ray's
// lattice ranges through one of them. Internal to the casters.
#ifndef parc_RayFunctions_h
#define parc_RayFunctions_h

#include "parcCompositeBlock.h"

namespace parc::casting
{

/// Writes colour * opacity, or exact zeros when the opacity is zero.
inline void Premultiply(const float rgb[3], float a, float rgba[4])
{
  if (!(a > 0.f))
  {
    rgba[0] = rgba[1] = rgba[2] = rgba[3] = 0.f;
    return;
  }
  for (int c = 0; c < 3; ++c)
  {
    rgba[c] = rgb[c] * a;
  }
  rgba[3] = a;
}

// Each ray function: bool operator()(long k0, int n, bool follows, int& visited) visits
// lattice samples k0 .. k0 + n - 1, taken into the context's block (follows: k0 - 1 was
// visited just before); false stops the ray after the first `visited` of them. Finish(rgba)
// writes the result.

template <class Context>
struct CompositeFunction
{
  static constexpr bool WholeRay = false;
  Context& C;
  EventCompositor Out;
  /// Other volumes' events to composite between the samples (null: none).
  MergedEvents* Merge = nullptr;

  PARC_HOT_INLINE bool operator()(long k0, int n, bool, int& visited)
  {
    return this->Merge ? this->Interleaved(k0, n, visited) : this->Block(k0, n, visited);
  }
  /// The block of samples k0 .. k0 + n - 1 in parts between the events of Merge, each
  /// event composited before the first sample that comes after it; stops at Merge->End.
  PARC_HOT_INLINE bool Interleaved(long k0, int n, int& visited)
  {
    const double termination = this->C.P.TerminationOpacity;
    for (int done = 0; done < n;)
    {
      const long k = k0 + done;
      if (!this->Merge->AddBefore(k, this->Out, termination) || k >= this->Merge->End)
      {
        visited = done;
        return false;
      }
      const int part = static_cast<int>(std::min<long>(n - done, this->Merge->NextPosition() - k));
      int partVisited = part;
      if (!this->Block(k, part, partVisited))
      {
        visited = done + partVisited;
        return false;
      }
      done += part;
    }
    return true;
  }
  PARC_HOT_INLINE bool Block(long k0, int n, int& visited)
  {
    if (this->C.K.ColorByValue)
    {
      return this->C.CompositeBlock(k0, n, visited, this->Out);
    }
    return this->C.ContributingSamples(k0, n, visited,
      [this](int j, double t, float a, const Vec3f& g, bool haveGradient) {
        float rgb[3];
        this->C.SampleColor(j, t, 0.0, rgb);
        if (this->C.P.Shade)
        {
          this->C.ShadeSample(rgb, t, j, g, haveGradient);
        }
        return this->C.Over(this->Out, t, rgb, a);
      });
  }
  void Finish(float rgba[4]) const { this->Out.Finish(rgba); }
};

/// Maximum (Sign = 1) or minimum (Sign = -1) intensity.
template <class Context, int Sign>
struct ExtremeFunction
{
  static constexpr bool WholeRay = true;
  Context& C;
  float Extreme = 0.f;
  bool Found = false;
  double ExtremeAt = 0.0; ///< the first sample with the extreme value

  PARC_HOT_INLINE bool operator()(long k0, int n, bool, int&)
  {
    this->C.SampleBlock(k0, n);
    this->Scan(this->C, k0, n);
    return true;
  }
  /// Takes the extreme of the n samples from k0 in c's block.
  void Scan(const Context& c, long k0, int n)
  {
    for (int j = 0; j < n; ++j)
    {
      const float s = c.Value(j);
      if (!this->Found || Sign * s > Sign * this->Extreme)
      {
        this->Extreme = s;
        this->Found = true;
        this->ExtremeAt = (k0 + j) * c.Dt;
      }
    }
  }
  double Position() const { return this->ExtremeAt; } ///< where the result lies on the ray
  void Finish(float rgba[4]) const
  {
    float rgb[3] = { 0.f, 0.f, 0.f };
    float a = 0.f;
    if (this->Found)
    {
      a = this->C.P.Opacity.Evaluate(this->Extreme);
      // The colour of the extreme sample: from the colour function, or for dependent
      // components from the other components there (as VTK's mappers colour it).
      this->C.DefaultColor(NotALatticeSample, this->ExtremeAt, this->Extreme, rgb);
      this->C.Stats.ContributingSamples += (a > 0.f) ? 1 : 0;
    }
    Premultiply(rgb, a, rgba);
  }
};

/// The contexts of the independent components of non-zero weight, C's (component 0's)
/// first when its weight is not 0 (see the file comment of parcRayCaster.h).
template <class Context>
struct ComponentContexts
{
  std::array<Context*, MaxComponents> Parts;
  int Count = 0;
};

/// Composite over independent components: C keeps the statistics, events and result.
template <class Context>
struct ComponentCompositeFunction
{
  static constexpr bool WholeRay = false;
  Context& C;
  const ComponentContexts<Context>& Components;
  EventCompositor Out;

  PARC_HOT_INLINE bool operator()(long k0, int n, bool, int& visited)
  {
    unsigned partLanes[MaxComponents];
    unsigned lanes = 0;
    for (int c = 0; c < this->Components.Count; ++c)
    {
      this->Components.Parts[c]->SampleBlock(k0, n);
      partLanes[c] = this->Components.Parts[c]->MayContribute(n);
      lanes |= partLanes[c];
    }
    for (; lanes != 0; lanes &= lanes - 1)
    {
      const int j = CountTrailingZeros(lanes);
      const double t = (k0 + j) * this->C.Dt;
      float rgb[3] = { 0.f, 0.f, 0.f };
      float sum = 0.f, squares = 0.f;
      for (int c = 0; c < this->Components.Count; ++c)
      {
        if (partLanes[c] & (1u << j))
        {
          this->AddComponent(*this->Components.Parts[c], j, t, rgb, sum, squares);
        }
      }
      if (sum == 0.f)
      {
        continue;
      }
      ++this->C.Stats.ContributingSamples;
      this->C.RecordHit(t);
      if (!this->C.OverPremultiplied(this->Out, t, rgb, squares / sum))
      {
        visited = j + 1;
        return false;
      }
    }
    return true;
  }
  /// Adds component part's weighted opacity a at sample j (t) to sum, a^2 to squares and
  /// a times its shaded colour to rgb.
  static void AddComponent(
    Context& part, int j, double t, float rgb[3], float& sum, float& squares)
  {
    float a;
    Vec3f g;
    bool haveGradient = false;
    if (!part.SampleOpacity(j, t, a, g, haveGradient))
    {
      return;
    }
    a *= part.K.ComponentWeight;
    float color[3];
    part.SampleColor(j, t, 0.0, color);
    if (part.P.Shade)
    {
      part.ShadeSample(color, t, j, g, haveGradient);
    }
    for (int c = 0; c < 3; ++c)
    {
      rgb[c] += a * color[c];
    }
    sum += a;
    squares += a * a;
  }
  void Finish(float rgba[4]) const { this->Out.Finish(rgba); }
};

/// Maximum (Sign = 1) or minimum (Sign = -1) intensity of independent components: each
/// component's own extreme, combined in Finish.
template <class Context, int Sign>
struct ComponentExtremeFunction
{
  static constexpr bool WholeRay = true;
  Context& C;
  const ComponentContexts<Context>& Components;
  static_assert(MaxComponents == 4, "one initializer per component below");
  std::array<ExtremeFunction<Context, Sign>, MaxComponents> Extremes;

  ComponentExtremeFunction(Context& c, const ComponentContexts<Context>& components)
    : C(c)
    , Components(components)
    , Extremes{ { { c }, { c }, { c }, { c } } }
  {
  }
  PARC_HOT_INLINE bool operator()(long k0, int n, bool, int&)
  {
    for (int c = 0; c < this->Components.Count; ++c)
    {
      this->Components.Parts[c]->SampleBlock(k0, n);
      this->Extremes[c].Scan(*this->Components.Parts[c], k0, n);
    }
    return true;
  }
  /// Where the result lies on the ray: the first component extreme.
  double Position() const
  {
    double t = std::numeric_limits<double>::infinity();
    for (int c = 0; c < this->Components.Count; ++c)
    {
      t = std::min(t, this->Extremes[c].Position());
    }
    return t;
  }
  void Finish(float rgba[4]) const
  {
    std::fill_n(rgba, 4, 0.f);
    for (int c = 0; c < this->Components.Count; ++c)
    {
      const Context& part = *this->Components.Parts[c];
      const ExtremeFunction<Context, Sign>& e = this->Extremes[c];
      const float a = e.Found ? part.P.Opacity.Evaluate(e.Extreme) * part.K.ComponentWeight : 0.f;
      if (a > 0.f)
      {
        float rgb[3];
        part.P.Color.Lookup(e.Extreme, rgb);
        for (int k = 0; k < 3; ++k)
        {
          rgba[k] += a * rgb[k];
        }
        rgba[3] += a;
        ++this->C.Stats.ContributingSamples;
      }
    }
    for (int k = 0; k < 4; ++k)
    {
      rgba[k] = std::min(rgba[k], 1.f);
    }
  }
};

/// The grey level of an intensity result: clamped to [0, 1], opaque.
inline void GreyIntensity(double intensity, float rgba[4])
{
  const float grey = static_cast<float>(std::min(std::max(intensity, 0.0), 1.0));
  rgba[0] = rgba[1] = rgba[2] = grey;
  rgba[3] = 1.f;
}

/// VTK's average intensity: the mean, over the samples whose value lies in AverageRange,
/// of the value (normalised to IntensityRange) times its opacity (uncorrected, as VTK's GPU
/// mapper takes it); a grey, opaque result where the ray has such samples, nothing
/// elsewhere.
template <class Context>
struct AverageFunction
{
  static constexpr bool WholeRay = true;
  Context& C;
  double Sum = 0.0;
  std::uint64_t Count = 0;
  double FirstAt = 0.0; ///< the first averaged sample

  PARC_HOT_INLINE bool operator()(long k0, int n, bool, int&)
  {
    this->C.SampleBlock(k0, n);
    for (int j = 0; j < n; ++j)
    {
      const float s = this->C.Value(j);
      if (s >= this->C.P.AverageRange[0] && s <= this->C.P.AverageRange[1])
      {
        if (this->Count == 0)
        {
          this->FirstAt = (k0 + j) * this->C.Dt;
        }
        const float a = this->C.CorrectOpacity(this->C.P.Opacity.Evaluate(s));
        this->Sum += a * this->C.NormalizedIntensity(s);
        ++this->Count;
        ++this->C.Stats.ContributingSamples;
      }
    }
    return true;
  }
  double Position() const { return this->FirstAt; } ///< where the result lies on the ray
  void Finish(float rgba[4]) const
  {
    rgba[0] = rgba[1] = rgba[2] = rgba[3] = 0.f;
    if (this->Count > 0)
    {
      GreyIntensity(this->Sum / static_cast<double>(this->Count), rgba);
    }
  }
};

/// VTK's additive intensity: the sum over the samples of the value (normalised to
/// IntensityRange) times its opacity scaled by dt / unit distance (OpacityScale), as an
/// opaque grey wherever the ray meets the field (black where nothing contributes, as VTK's
/// GPU mapper draws it; such a ray is cast even where acceleration finds nothing to
/// sample, see CastsEveryRay).
template <class Context>
struct AdditiveFunction
{
  static constexpr bool WholeRay = true;
  Context& C;
  double Sum = 0.0;
  bool Contributed = false;

  PARC_HOT_INLINE bool operator()(long k0, int n, bool, int& visited)
  {
    return this->C.ContributingSamples(
      k0, n, visited, [this](int j, double, float a, const Vec3f&, bool) {
        this->Sum += a * this->C.NormalizedIntensity(this->C.Value(j));
        this->Contributed = true;
        return true;
      });
  }
  void Finish(float rgba[4]) const { GreyIntensity(this->Sum * this->C.K.OpacityScale, rgba); }
  /// Where the result lies on the ray: the first contributing sample, or where the ray
  /// enters the field.
  double Position() const { return this->Contributed ? this->C.FirstHit : this->C.EntryT; }
};

/// Isosurfaces; with Shadow, along a shadow ray: each crossing of a value v multiplies
/// Transmittance by 1 - opacity(v), and the ray stops once it is below ShadowFloor.
template <class Context, bool Shadow = false>
struct IsoSurfaceFunction
{
  static constexpr bool WholeRay = false;
  Context& C;
  const std::vector<double>& IsoValues; // sorted
  EventCompositor Out;
  float Previous = 0.f;
  float Transmittance = 1.f;
  float ShadowFloor = 0.f;

  /// The ray parameter in [t0, t1] where the field crosses v, given s0 = f(t0), s1 = f(t1).
  double Refine(double t0, double s0, double t1, double s1, double v) const
  {
    double t = t0 + (v - s0) / (s1 - s0) * (t1 - t0);
    for (int i = 0; i < RegulaFalsiSteps; ++i)
    {
      const double s = this->C.Field.Sample(this->C.IndexPosition(t), this->C.P.Interp);
      if ((s < v) == (s0 < v))
      {
        t0 = t;
        s0 = s;
      }
      else
      {
        t1 = t;
        s1 = s;
      }
      if (s1 == s0)
      {
        break;
      }
      t = t0 + (v - s0) / (s1 - s0) * (t1 - t0);
    }
    return t;
  }

  bool Composite(double t, double v)
  {
    if (this->C.Masked(t))
    {
      return true;
    }
    float a = this->C.P.Opacity.Evaluate(v);
    ++this->C.Stats.ContributingSamples;
    this->C.RecordHit(t);
    if (a == 0.f)
    {
      return true;
    }
    float rgb[3];
    this->C.SampleColor(NotALatticeSample, t, v, rgb);
    if (this->C.P.Shade)
    {
      this->C.ShadeSample(rgb, t, NotALatticeSample, Vec3f(), false);
    }
    return this->C.Over(this->Out, t, rgb, a);
  }

  /// A shadow ray crosses v between (t0, s0) and (t1, s1); false once it may stop.
  bool Block(double v, double t0, double s0, double t1, double s1)
  {
    if (this->C.P.Mask && this->C.Masked(this->Refine(t0, s0, t1, s1, v)))
    {
      return true;
    }
    this->Transmittance *= 1.f - this->C.P.Opacity.Evaluate(v);
    return this->Transmittance >= this->ShadowFloor;
  }

  PARC_HOT_INLINE bool operator()(long k0, int n, bool follows, int& visited)
  {
    this->C.SampleBlock(k0, n);
    const float* s = this->C.Block.Values;
    for (unsigned lanes = this->CrossingLanes(n, follows); lanes != 0; lanes &= lanes - 1)
    {
      const int j = CountTrailingZeros(lanes);
      if (!this->Crossings((k0 + j) * this->C.Dt, j > 0 ? s[j - 1] : this->Previous, s[j]))
      {
        visited = j + 1;
        return false;
      }
    }
    this->Previous = s[n - 1];
    return true;
  }
  /// The lanes j < n of the block (bits 1 << j) whose sample may lie on the other side of
  /// an iso value than the sample before it (Previous for lane 0, when the block follows
  /// it): with at most MaxThresholdIsoValues values, exactly those where the number of
  /// values above each differs; with more, those where the two differ.
  PARC_HOT_INLINE unsigned CrossingLanes(int n, bool follows) const
  {
    const float* values = this->C.Block.Values;
    alignas(16) float before[LatticeBlock::Size];
    before[0] = this->Previous;
    std::copy_n(values, LatticeBlock::Size - 1, before + 1);
    const std::vector<float>& thresholds = this->C.K.IsoThresholds;
    const bool counted = this->IsoValues.size() <= MaxThresholdIsoValues;
    unsigned lanes = 0;
#if defined(__SSE2__)
    static_assert(LatticeBlock::Lanes == 4, "four lanes to an SSE register");
    for (int j = 0; j < n; j += LatticeBlock::Lanes) // the lanes SampleBlock computed
    {
      const __m128 s0 = _mm_load_ps(before + j), s1 = _mm_loadu_ps(values + j);
      __m128 differ = _mm_cmpneq_ps(s0, s1);
      if (counted)
      {
        // Minus the count of values above: each comparison is all ones (-1) or 0.
        __m128i c0 = _mm_setzero_si128(), c1 = _mm_setzero_si128();
        for (const float v : thresholds)
        {
          const __m128 threshold = _mm_set1_ps(v);
          c0 = _mm_add_epi32(c0, _mm_castps_si128(_mm_cmplt_ps(s0, threshold)));
          c1 = _mm_add_epi32(c1, _mm_castps_si128(_mm_cmplt_ps(s1, threshold)));
        }
        differ = _mm_andnot_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(c0, c1)), differ);
      }
      lanes |= static_cast<unsigned>(_mm_movemask_ps(differ)) << j;
    }
#else
    for (int j = 0; j < n; ++j)
    {
      bool differ = before[j] != values[j];
      if (counted)
      {
        int c0 = 0, c1 = 0;
        for (const float v : thresholds)
        {
          c0 += before[j] < v;
          c1 += values[j] < v;
        }
        differ = differ && c0 != c1;
      }
      lanes |= static_cast<unsigned>(differ) << j;
    }
#endif
    lanes &= LatticeBlock::LowLanes(n);
    return follows ? lanes : lanes & ~1u;
  }
  /// Composites the crossings between sample s0 and sample s1 at t1; false once the ray
  /// may stop.
  bool Crossings(double t1, float s0, float s1)
  {
    // Crossed values lie between s0 and s1; visit them in ray order.
    const double lo = std::min(s0, s1), hi = std::max(s0, s1);
    const auto first = std::lower_bound(this->IsoValues.begin(), this->IsoValues.end(), lo);
    const auto last = std::upper_bound(this->IsoValues.begin(), this->IsoValues.end(), hi);
    const double t0 = t1 - this->C.Dt;
    const bool rising = s1 > s0;
    const long n = last - first;
    for (long i = 0; i < n; ++i)
    {
      const double v = rising ? *(first + i) : *(last - 1 - i);
      if ((s0 < v) == (s1 < v))
      {
        continue;
      }
      const bool more = Shadow ? this->Block(v, t0, s0, t1, s1)
                               : this->Composite(this->Refine(t0, s0, t1, s1, v), v);
      if (!more)
      {
        return false;
      }
    }
    return true;
  }
  void Finish(float rgba[4]) const { this->Out.Finish(rgba); }
};

/// A composite volume along a shadow ray: Transmittance is the product of 1 - a' over the
/// contributing samples; the ray stops once it is below Floor.
template <class Context>
struct AbsorptionFunction
{
  static constexpr bool WholeRay = false;
  Context& C;
  float Floor;
  float Transmittance = 1.f;

  PARC_HOT_INLINE bool operator()(long k0, int n, bool, int& visited)
  {
    return this->C.ContributingSamples(
      k0, n, visited, [this](int, double, float a, const Vec3f&, bool) {
        this->Transmittance *= 1.f - a;
        return this->Transmittance >= this->Floor;
      });
  }
  void Finish(float rgba[4]) const
  {
    rgba[0] = rgba[1] = rgba[2] = 0.f;
    rgba[3] = 1.f - this->Transmittance;
  }
};

/// The number of unit cells the segment from a to b (voxel-index coordinates) passes.
inline std::uint64_t CellsCrossed(const Vec3& a, const Vec3& b)
{
  std::uint64_t n = 1;
  for (int axis = 0; axis < 3; ++axis)
  {
    n += static_cast<std::uint64_t>(std::fabs(std::floor(b[axis]) - std::floor(a[axis])));
  }
  return n;
}

/// What Run returns for a ray its function did not stop.
constexpr long NotStopped = std::numeric_limits<long>::max();

/// One block of a ray function (its operator()), compiled for the baseline instruction
/// set ...
template <class Function>
PARC_NOINLINE bool VisitBaseline(Function& fn, long k0, int n, bool follows, int& visited)
{
  return fn(k0, n, follows, visited);
}

#if PARC_WIDE_VECTORS
/// ... and for wide vectors: every ray function's block inlines into it (PARC_HOT_INLINE),
/// so the whole sampling, compositing and shading of the block is compiled for them.
template <class Function>
PARC_NOINLINE PARC_TARGET_WIDE_VECTORS bool VisitWide(
  Function& fn, long k0, int n, bool follows, int& visited)
{
  return fn(k0, n, follows, visited);
}
#endif

/// Visits the lattice samples of ranges in order, in blocks, and counts them; returns the
/// last one visited (stopped: whether the ray function stopped the ray there). Each block
/// runs with the instructions the caster chose (RenderConstants::WideVectors): the same
/// operations either way, so the same bits.
template <class Function>
long WalkRanges(const std::vector<LatticeRange>& ranges, Function& fn, bool& stopped)
{
  stopped = false;
  long previous = std::numeric_limits<long>::min();
#if PARC_WIDE_VECTORS
  const bool wide = fn.C.K.WideVectors;
#endif
  for (const LatticeRange& r : ranges)
  {
    for (long k0 = std::max(r.First, previous + 1); k0 <= r.Last;)
    {
      const int n = static_cast<int>(std::min<long>(SampleBlockSize, r.Last - k0 + 1));
      const bool follows = (k0 == previous + 1);
      int visited = n;
#if PARC_WIDE_VECTORS
      const bool more = wide ? VisitWide(fn, k0, n, follows, visited)
                             : VisitBaseline(fn, k0, n, follows, visited);
#else
      const bool more = VisitBaseline(fn, k0, n, follows, visited);
#endif
      fn.C.Stats.Samples += static_cast<std::uint64_t>(visited);
      previous = k0 + visited - 1;
      if (!more)
      {
        stopped = true;
        return previous;
      }
      k0 += n;
    }
  }
  return previous;
}

/// Casts fn over ranges into rgba (and a whole-ray result into the events, when kept) and
/// counts the cells the visited stretches crossed; returns the lattice index of the sample
/// where fn stopped the ray, or NotStopped.
template <class Function>
long Run(Function&& fn, const std::vector<LatticeRange>& ranges, float rgba[4])
{
  bool stopped;
  const long last = WalkRanges(ranges, fn, stopped);
  fn.Finish(rgba);
  const auto& c = fn.C;
  if constexpr (std::decay_t<Function>::WholeRay)
  {
    if (c.Events && rgba[3] > 0.f)
    {
      AppendEvent(*c.Events, fn.Position(), rgba, rgba[3], true);
    }
  }
  for (const LatticeRange& r : ranges)
  {
    if (r.First > last)
    {
      break;
    }
    c.Stats.Cells +=
      CellsCrossed(c.IndexPosition(r.First * c.Dt), c.IndexPosition(std::min(r.Last, last) * c.Dt));
  }
  return stopped ? last : NotStopped;
}

} // namespace parc::casting

#endif
