#include "parcRayCaster.h"
#include "parcRayFunctions.h"
#include "parcTileCasting.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace parc
{
using namespace casting;

namespace
{
/// The ray-parameter interval of the ray (origin o, direction d in voxel-index
/// coordinates) inside the field's box, the owned box (unless owned is false: shadow
/// rays), [ray.TMin, ray.TMax] and the clipping planes.
bool ClipToField(const ScalarField& field, const CastParameters& p, const Vec3& o,
  const Vec3& d, const Ray& ray, double& tEnter, double& tExit, bool owned = true)
{
  const int* dims = field.GetDimensions();
  Vec3 lo, hi;
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = owned ? std::max(0.0, p.OwnedLo[a]) : 0.0;
    hi[a] = owned ? std::min(dims[a] - 1.0, p.OwnedHi[a]) : dims[a] - 1.0;
    if (!(lo[a] <= hi[a]))
    {
      return false; // owns nothing
    }
  }
  tEnter = ray.TMin;
  tExit = ray.TMax;
  return ClipToBox(o, d, lo, hi, tEnter, tExit) && ClipToPlanes(ray, p.ClipPlanes, tEnter, tExit);
}
}

namespace
{
/// Whether shaded samples can use the quantized normals (see CastParameters::Shading).
bool QuantizedNormalsApply(const ScalarField& field, const CastParameters& p)
{
  return p.Shade && p.Shading == ShadingModel::QuantizedNormals && p.Normals &&
    std::equal(field.GetDimensions(), field.GetDimensions() + 3, p.Normals->GetDimensions()) &&
    LightsAllowQuantizedNormals(p);
}

/// Lattice samples ahead of a block whose voxels its ray prefetches (a block and a half of
/// 32 lanes, 24 voxels at half a voxel; at 1445 MB 96 samples ahead gained as much, 24 5%
/// less).
constexpr int PrefetchAheadSamples = 48;

/// Whether the rays prefetch voxels (CastParameters::PrefetchMinBytes): unshaded, no
/// gradient, linear interpolation of values read in place, and cells in both y and z (a
/// cell's corners lie one row and one slice on).
bool PrefetchApplies(
  const ScalarField& field, const CastParameters& p, const RayCaster::RenderConstants& k)
{
  const int* dims = field.GetDimensions();
  const std::size_t bytes =
    field.GetNumberOfValues() * field.ValueSize() * static_cast<std::size_t>(field.GetStride());
  return !p.Shade && !k.GradientNeeded && p.Interp == Interpolation::Linear &&
    !field.IsBricked() && dims[1] > 1 && dims[2] > 1 && bytes >= p.PrefetchMinBytes;
}

/// The shading factors of every normal code: Blinn-Phong of the directional lights, as
/// RayContext::Shade computes it, for the world direction of the code's voxel-index
/// normal, turned towards the eye and seen from p.ShadingViewDirection.
std::vector<RayCaster::ShadingFactors> NormalShadingTable(
  const CastParameters& p, const Matrix4& worldToIndex)
{
  std::vector<RayCaster::ShadingFactors> table(NormalVolume::Count);
  const Vec3 toEye = p.ShadingViewDirection;
  struct LightDirections
  {
    Vec3 ToLight, Half;
  };
  std::vector<LightDirections> directions;
  for (const Light& light : p.Lights)
  {
    const Vec3 toLight = Normalized(light.Position - light.FocalPoint);
    directions.push_back({ toLight, Normalized(toLight + toEye) });
  }
  const auto power = [&p](double ndh) { return std::pow(ndh, p.SpecularPower); };
  for (std::size_t code = 0; code < table.size(); ++code)
  {
    RayCaster::ShadingFactors& f = table[code];
    std::fill_n(f.Diffuse, 4, 0.f);
    std::fill_n(f.Specular, 4, 0.f);
    const Vec3 g = NormalVolume::Decode(static_cast<std::uint16_t>(code));
    // The world gradient is the transpose of the world-to-index matrix times g.
    Vec3 n;
    for (int r = 0; r < 3; ++r)
    {
      n[r] = worldToIndex(0, r) * g.X + worldToIndex(1, r) * g.Y + worldToIndex(2, r) * g.Z;
    }
    if (!(Length(n) > 0.0))
    {
      continue;
    }
    n = Normalized(n);
    n = Dot(n, toEye) > 0.0 ? n : -n;
    double diffuse[3] = { 0.0, 0.0, 0.0 }, specular[3] = { 0.0, 0.0, 0.0 };
    for (std::size_t i = 0; i < p.Lights.size(); ++i)
    {
      const Light& light = p.Lights[i];
      double ndl, spec;
      const auto halfDot = [&] { return Dot(n, directions[i].Half); };
      if (casting::BlinnPhongWeights(Dot(n, directions[i].ToLight), halfDot, power, ndl, spec))
      {
        for (int c = 0; c < 3; ++c)
        {
          diffuse[c] += p.Diffuse * light.Color[c] * ndl;
          specular[c] += p.Specular * light.SpecularColor[c] * spec;
        }
      }
    }
    for (int c = 0; c < 3; ++c)
    {
      f.Diffuse[c] = static_cast<float>(diffuse[c]);
      f.Specular[c] = static_cast<float>(specular[c]);
    }
  }
  return table;
}

/// The (diffuse, specular) pairs of table's factors when each is the same for red, green
/// and blue; else empty (see RenderConstants::GreyNormalShading).
std::vector<float> GreyFactors(const std::vector<RayCaster::ShadingFactors>& table)
{
#if defined(__SSE2__)
  std::vector<float> pairs;
  pairs.reserve(2 * table.size());
  for (const RayCaster::ShadingFactors& f : table)
  {
    if (!(f.Diffuse[0] == f.Diffuse[1] && f.Diffuse[0] == f.Diffuse[2] &&
          f.Specular[0] == f.Specular[1] && f.Specular[0] == f.Specular[2]))
    {
      return {};
    }
    pairs.push_back(f.Diffuse[0]);
    pairs.push_back(f.Specular[0]);
  }
  return pairs;
#else
  static_cast<void>(table);
  return {}; // InterpolateGreyFactors needs SSE
#endif
}
}

bool RayCaster::Prepare(const Volume& volume)
{
  const ScalarField* field = volume.Field;
  const CastParameters* parameters = volume.Parameters;
  this->Field = field;
  this->Params = parameters;
  this->WorldToIndex = volume.WorldToIndex;
  if (!field || !parameters || !(parameters->SampleDistance > 0.0) ||
    !(parameters->OpacityUnitDistance > 0.0))
  {
    return false;
  }
  this->FieldCentre = volume.Centre();
  const int* dims = field->GetDimensions();
  const int shifts = parameters->ColorShiftCount;
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2 || !(shifts == 0 || shifts == 1 || shifts == 3))
  {
    return false;
  }
  const auto& labels = parameters->Labels;
  const auto byLabel = [](const LabelFunctions& a, const LabelFunctions& b) {
    return a.Label < b.Label;
  };
  if (!labels.empty() &&
    (!parameters->Mask || !TraitsOf(parameters->Blend).AppliesLabels ||
      !std::is_sorted(labels.begin(), labels.end(), byLabel) || !(labels[0].Label > 0)))
  {
    return false; // a label map, for composite blending
  }
  const BlendMode blend = parameters->Blend;
  if (blend == BlendMode::Slice && !HasUsableSlicePlane(*parameters))
  {
    return false;
  }
  if (const ScalarField* mask = parameters->Mask)
  {
    // A mask of the field's dimensions, for the ray functions that apply it (a slice takes
    // one and ignores it).
    if (!std::equal(dims, dims + 3, mask->GetDimensions()) ||
      !TraitsOf(blend).TakesMask)
    {
      return false;
    }
  }
  RenderConstants& k = this->Constants;
  const auto perUnit =
    static_cast<float>(parameters->SampleDistance / parameters->OpacityUnitDistance);
  k.Correction.SetExponent(TraitsOf(blend).CorrectsOpacity ? perUnit : 1.f);
  k.OpacityScale = TraitsOf(blend).ScalesOpacity ? perUnit : 1.f;
  k.ComponentWeight = static_cast<float>(parameters->ComponentWeight);
  double constant = 1.0;
  k.GradientOpacityConstant =
    parameters->UseGradientOpacity && parameters->GradientOpacity.IsConstant(constant);
  k.GradientOpacityValue = static_cast<float>(constant);
  k.WideVectors = parameters->WideVectors && HasWideVectors();
  k.OpacityByValue = labels.empty() && !parameters->Mask &&
    (!parameters->UseGradientOpacity || k.GradientOpacityConstant);
  const double intensityWidth = parameters->IntensityRange[1] - parameters->IntensityRange[0];
  k.IntensityScale = intensityWidth > 0.0 ? 1.0 / intensityWidth : 0.0;
  // Zero opacity below every function's first non-zero value (labels included) and above
  // every last one.
  double firstNonZero = parameters->Opacity.FirstNonZero();
  double lastNonZero = parameters->Opacity.LastNonZero();
  bool labelGradients = false;
  for (const LabelFunctions& label : labels)
  {
    firstNonZero = std::min(firstNonZero, label.Opacity.FirstNonZero());
    lastNonZero = std::max(lastNonZero, label.Opacity.LastNonZero());
    labelGradients = labelGradients || label.UseGradientOpacity;
  }
  k.ZeroOpacityBelow = FloatAtMost(firstNonZero);
  k.ZeroOpacityAbove = -FloatAtMost(-lastNonZero);
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      k.GradientToWorld[3 * r + c] = static_cast<float>(volume.WorldToIndex(c, r));
      k.GradientToWorldColumns[c][r] = k.GradientToWorld[3 * r + c];
    }
  }
  const double power = parameters->SpecularPower;
  k.IntegerSpecularPower =
    (power >= 0.0 && power <= MaxIntegerSpecularPower && power == std::floor(power))
    ? static_cast<int>(power)
    : -1;
  k.SpecularPower = static_cast<float>(power);
  k.DirectionalLights.clear();
  k.PositionalLights.clear();
  for (std::size_t i = 0; i < parameters->Lights.size(); ++i)
  {
    const Light& light = parameters->Lights[i];
    if (light.Positional)
    {
      k.PositionalLights.push_back({ &light, Normalized(light.FocalPoint - light.Position),
        std::cos(light.ConeAngle * (M_PI / 180.0)), i });
    }
    else
    {
      const Vec3 toLight = Normalized(light.Position - light.FocalPoint);
      k.DirectionalLights.push_back({ Vec3f(toLight), Vec3f(parameters->Diffuse * light.Color),
        Vec3f(parameters->Specular * light.SpecularColor), i, toLight,
        static_cast<float>(light.ShadowAttenuation) });
    }
  }
  k.SortedIsoValues = UsedIsoValues(*parameters);
  k.IsoThresholds.clear();
  if (k.SortedIsoValues.size() <= MaxThresholdIsoValues)
  {
    for (const double v : k.SortedIsoValues)
    {
      k.IsoThresholds.push_back(FloatAtLeast(v));
    }
  }
  // One table, or none; the tables of an earlier render are freed.
  k.QuantizedNormals = QuantizedNormalsApply(*field, *parameters);
  std::vector<ShadingFactors> factors = k.QuantizedNormals
    ? NormalShadingTable(*parameters, volume.WorldToIndex)
    : std::vector<ShadingFactors>();
  k.GreyNormalShading = GreyFactors(factors);
  k.NormalShading =
    k.GreyNormalShading.empty() ? std::move(factors) : std::vector<ShadingFactors>();
  k.GradientNeeded = (parameters->Shade && !k.QuantizedNormals) ||
    (parameters->UseGradientOpacity && !k.GradientOpacityConstant) || labelGradients;
  k.ColorByValue = k.OpacityByValue && parameters->ColorShiftCount == 0;
  k.PrefetchSamples = PrefetchApplies(*field, *parameters, k) ? PrefetchAheadSamples : 0;
  for (int c = 0; c < 3; ++c)
  {
    k.Ambient[c] = static_cast<float>(parameters->Ambient * parameters->AmbientLight[c]);
  }
  k.GreyLights = std::all_of(k.DirectionalLights.begin(), k.DirectionalLights.end(),
    [](const DirectionalLight& light) {
      return light.Diffuse.X == light.Diffuse.Y && light.Diffuse.X == light.Diffuse.Z &&
        light.Specular.X == light.Specular.Y && light.Specular.X == light.Specular.Z;
    });
  k.ShadeLanesTogether = parameters->Shade && !k.QuantizedNormals &&
    k.PositionalLights.empty() && k.DirectionalLights.size() <= MaxHoistedLights &&
    std::none_of(k.DirectionalLights.begin(), k.DirectionalLights.end(),
      [](const DirectionalLight& light) { return light.ShadowAttenuation > 0.f; });
  return true;
}

bool RayCaster::SetComponents(std::vector<Component> components)
{
  this->Components.clear();
  const CastParameters* p = this->Params;
  if (components.empty())
  {
    return true;
  }
  if (!p || components.size() >= MaxComponents || !TraitsOf(p->Blend).CombinesComponents)
  {
    return false;
  }
  const int* dims = this->Field->GetDimensions();
  for (const Component& c : components)
  {
    const CastParameters* q = c.Caster ? c.Caster->Params : nullptr;
    if (!q || !std::equal(dims, dims + 3, c.Caster->Field->GetDimensions()) ||
      c.Caster->Field->GetScalarType() != this->Field->GetScalarType() ||
      q->Blend != p->Blend || q->SampleDistance != p->SampleDistance ||
      c.Caster->WorldToIndex.M != this->WorldToIndex.M ||
      q->ClipPlanes.size() != p->ClipPlanes.size() || q->Crop.Enabled != p->Crop.Enabled)
    {
      return false;
    }
  }
  this->Components = std::move(components);
  return true;
}

bool RayCaster::ReadsContributingCells() const
{
  if (!this->Params || !this->Field)
  {
    return false; // not prepared
  }
  const CastParameters& p = *this->Params;
  return TraitsOf(p.Blend).SkipsEmptyCells && this->Components.empty() &&
    p.Interp == Interpolation::Linear && this->Field->GetStride() == 1;
}

const CellMap* RayCaster::ContributingCells() const
{
  if (!this->Cells || !this->ReadsContributingCells())
  {
    return nullptr;
  }
  return this->Cells->Covers(this->Field->GetDimensions()) ? this->Cells : nullptr;
}

bool RayCaster::ClipRay(const Ray& ray, double& tEnter, double& tExit) const
{
  const Matrix4& w2i = this->WorldToIndex;
  return ClipToField(*this->Field, *this->Params, w2i.TransformPoint(ray.Origin),
    w2i.TransformVector(ray.Direction), ray, tEnter, tExit);
}


void RayCaster::CastRay(const RayQuery& query, const SegmentSource& source,
  std::vector<Segment>& segments, std::vector<LatticeRange>& ranges, float rgba[4],
  CastStatistics& stats, double* firstHit, std::vector<RayEvent>* events,
  ShadowScratch* shadows) const
{
  this->Field->Dispatch([&](const auto& field) {
    this->CastRayIn(
      field, query, source, segments, ranges, rgba, stats, firstHit, events, nullptr, shadows);
  });
}

void RayCaster::CastRayMerged(const RayQuery& query, const SegmentSource& source,
  std::vector<Segment>& segments, std::vector<LatticeRange>& ranges, MergedEvents& merge,
  EventCompositor& out, CastStatistics& stats, ShadowScratch* shadows) const
{
  float rgba[4];
  this->Field->Dispatch([&](const auto& field) {
    this->CastRayIn(field, query, source, segments, ranges, rgba, stats, nullptr, nullptr,
      nullptr, shadows, &merge, &out);
  });
}

std::uint64_t RayCaster::UnacceleratedSamples(const Ray& ray) const
{
  double tEnter, tExit;
  return this->ClipRay(ray, tEnter, tExit)
    ? LatticeSampleCount(tEnter, tExit, this->Params->SampleDistance)
    : 0;
}

bool RayCaster::RangesOf(const RayQuery& query, const SegmentSource& source,
  std::vector<Segment>& segments, std::vector<LatticeRange>& ranges, Vec3& indexOrigin,
  Vec3& indexDirection, std::size_t& sourceSegments, double& tEnter, double& tExit,
  bool owned) const
{
  const Ray& ray = query.Path;
  const Matrix4& w2i = this->WorldToIndex;
  indexOrigin = w2i.TransformPoint(ray.Origin);
  indexDirection = w2i.TransformVector(ray.Direction);
  if (!ClipToField(
        *this->Field, *this->Params, indexOrigin, indexDirection, ray, tEnter, tExit, owned))
  {
    return false;
  }
  segments.clear();
  source.Segments(query, segments);
  sourceSegments = segments.size();
  const double dt = this->Params->SampleDistance;
  SegmentsToLatticeRanges(segments, tEnter, tExit, dt, ranges);
  if (this->Params->Crop.Enabled)
  {
    // The segments are spent: their storage takes the cropping's intervals.
    CroppedIntervals(indexOrigin, indexDirection, this->Params->Crop, tEnter, tExit, segments);
    IntersectLatticeRanges(ranges, segments, dt);
  }
  return true;
}

float RayCaster::Transmittance(const RayQuery& query, const SegmentSource& source,
  ShadowScratch& scratch, CastStatistics& stats) const
{
  return this->Field->Dispatch([&](const auto& field) {
    return this->TransmittanceIn(field, query, source, scratch, stats);
  });
}

template <class View>
float RayCaster::TransmittanceIn(const View& field, const RayQuery& query,
  const SegmentSource& source, ShadowScratch& scratch, CastStatistics& stats) const
{
  const CastParameters& p = *this->Params;
  if (!TraitsOf(p.Blend).CastsShadows)
  {
    return 1.f;
  }
  RayQuery shadow = query;
  shadow.Path.TMin = std::max(shadow.Path.TMin, 0.5 * p.SampleDistance); // from k = 1
  Vec3 indexOrigin, indexDirection;
  std::size_t sourceSegments = 0;
  double tEnter, tExit;
  if (!this->RangesOf(shadow, source, scratch.Segments, scratch.Ranges, indexOrigin,
        indexDirection, sourceSegments, tEnter, tExit, false) ||
    scratch.Ranges.empty())
  {
    return 1.f;
  }
  using Context = RayContext<View>;
  CastStatistics own;
  Context context(field, p, this->Constants, shadow.Path, indexOrigin, indexDirection, own, false);
  context.Cells = this->ContributingCells();
  const float floor = static_cast<float>(1.0 - p.TerminationOpacity);
  float rgba[4];
  float transmittance;
  if (p.Blend == BlendMode::Composite)
  {
    AbsorptionFunction<Context> fn{ context, floor };
    Run(fn, scratch.Ranges, rgba);
    transmittance = fn.Transmittance;
  }
  else
  {
    IsoSurfaceFunction<Context, true> fn{ context, this->Constants.SortedIsoValues, {} };
    fn.ShadowFloor = floor;
    Run(fn, scratch.Ranges, rgba);
    transmittance = fn.Transmittance;
  }
  stats.ShadowSamples += own.Samples;
  stats.ShadowCells += own.Cells;
  stats.GradientEvaluations += own.GradientEvaluations;
  stats.DifferenceLoads += own.DifferenceLoads;
  return transmittance;
}

float Occluders::Transmittance(const Ray& shadowRay, std::size_t light, ShadowScratch& scratch,
  CastStatistics& stats) const
{
  ++stats.ShadowRays;
  const RayQuery query = RayQuery::Anywhere(shadowRay);
  float transmittance = 1.f;
  for (const Member& m : this->Members)
  {
    const SegmentSource* source =
      light < m.LightSources.size() ? m.LightSources[light] : nullptr;
    transmittance *= m.Caster->Transmittance(
      query, source ? *source : this->WholeRay, scratch, stats);
    if (transmittance == 0.f)
    {
      break;
    }
  }
  return transmittance;
}

template <class View>
void RayCaster::CastRayIn(const View& field, const RayQuery& query, const SegmentSource& source,
  std::vector<Segment>& segments, std::vector<LatticeRange>& ranges, float rgba[4],
  CastStatistics& stats, double* firstHit, std::vector<RayEvent>* events,
  std::vector<CellDifferences>* differences, ShadowScratch* shadows, MergedEvents* merge,
  EventCompositor* merged) const
{
  rgba[0] = rgba[1] = rgba[2] = rgba[3] = 0.f;
  if (merged)
  {
    *merged = EventCompositor();
  }
  if (events)
  {
    events->clear();
  }
  if (firstHit)
  {
    *firstHit = std::numeric_limits<double>::infinity();
  }
  if (this->Params->Blend == BlendMode::Slice)
  {
    this->CastSliceIn(field, query, segments, rgba, stats, firstHit, events);
    return;
  }
  Vec3 indexOrigin, indexDirection;
  std::size_t sourceSegments = 0;
  double tEnter, tExit;
  if (!this->RangesOf(query, source, segments, ranges, indexOrigin, indexDirection,
        sourceSegments, tEnter, tExit))
  {
    return;
  }
  ++stats.Rays;
  stats.Segments += sourceSegments;
  // Without acceleration the ray would take the same samples up to the same stop.
  long stop = NotStopped;
  // (a stop lies in the ranges, which lie in [ceil(tEnter / dt), floor(tExit / dt)]).
  auto countUnaccelerated = [&]() {
    const double dt = this->Params->SampleDistance;
    stats.UnacceleratedSamples += stop == NotStopped
      ? LatticeSampleCount(tEnter, tExit, dt)
      : stop - static_cast<long>(std::ceil(tEnter / dt)) + 1;
  };
  if (ranges.empty() && !this->CastsEveryRay())
  {
    countUnaccelerated();
    return;
  }
  using Context = RayContext<View>;
  Context context(
    field, *this->Params, this->Constants, query.Path, indexOrigin, indexDirection, stats, true);
  context.Events = events;
  context.EntryT = tEnter;
  context.Cells = this->ContributingCells();
  ShadowScratch ownShadowScratch;
  context.Shadows = this->Shadows;
  context.ShadowSpace = shadows ? shadows : &ownShadowScratch;
  if (differences && !differences->empty())
  {
    context.DifferenceSlots = differences->data();
    context.DifferenceMask = differences->size() - 1;
  }
  if (!this->Components.empty())
  {
    // Independent components: a context per component of non-zero weight on its field.
    context.Shadows = nullptr;
    std::array<std::optional<View>, MaxComponents> views;
    std::array<std::optional<Context>, MaxComponents> others;
    ComponentContexts<Context> parts;
    if (this->Constants.ComponentWeight > 0.f)
    {
      parts.Parts[parts.Count++] = &context;
    }
    for (std::size_t c = 0; c < this->Components.size(); ++c)
    {
      const RayCaster& caster = *this->Components[c].Caster;
      if (caster.Constants.ComponentWeight > 0.f)
      {
        views[c].emplace(field.Shifted(this->Components[c].Shift));
        others[c].emplace(*views[c], *caster.Params, caster.Constants, query.Path, indexOrigin,
          indexDirection, stats, true);
        parts.Parts[parts.Count++] = &*others[c];
      }
    }
    stop = this->Params->Blend == BlendMode::Composite
      ? Run(ComponentCompositeFunction<Context>{ context, parts, {} }, ranges, rgba)
      : this->Params->Blend == BlendMode::MaximumIntensity
      ? Run(ComponentExtremeFunction<Context, 1>(context, parts), ranges, rgba)
      : Run(ComponentExtremeFunction<Context, -1>(context, parts), ranges, rgba);
  }
  else
  {
    switch (this->Params->Blend)
    {
      case BlendMode::Composite:
      {
        CompositeFunction<Context> composite{ context, {}, merge };
        stop = Run(composite, ranges, rgba);
        if (merged)
        {
          *merged = composite.Out;
        }
        break;
      }
      case BlendMode::MaximumIntensity:
        stop = Run(ExtremeFunction<Context, 1>{ context }, ranges, rgba);
        break;
      case BlendMode::MinimumIntensity:
        stop = Run(ExtremeFunction<Context, -1>{ context }, ranges, rgba);
        break;
      case BlendMode::AverageIntensity:
        stop = Run(AverageFunction<Context>{ context }, ranges, rgba);
        break;
      case BlendMode::Additive:
        stop = Run(AdditiveFunction<Context>{ context }, ranges, rgba);
        break;
      case BlendMode::IsoSurface:
        stop = Run(IsoSurfaceFunction<Context>{ context, this->Constants.SortedIsoValues, {} },
          ranges, rgba);
        break;
      case BlendMode::Slice: // CastSliceIn
        break;
    }
  }
  countUnaccelerated();
  if (firstHit)
  {
    *firstHit = context.FirstHit;
  }
}

template <class View>
void RayCaster::CastSliceIn(const View& field, const RayQuery& query,
  std::vector<Segment>& intervals, float rgba[4], CastStatistics& stats, double* firstHit,
  std::vector<RayEvent>* events) const
{
  const CastParameters& p = *this->Params;
  const Ray& ray = query.Path;
  const Vec3 indexOrigin = this->WorldToIndex.TransformPoint(ray.Origin);
  const Vec3 indexDirection = this->WorldToIndex.TransformVector(ray.Direction);
  double tEnter, tExit;
  if (!ClipToField(*this->Field, p, indexOrigin, indexDirection, ray, tEnter, tExit))
  {
    return;
  }
  ++stats.Rays;
  const double facing = Dot(ray.Direction, p.SliceNormal);
  if (facing == 0.0) // along the plane: no crossing (or no single one)
  {
    return;
  }
  const double t = Dot(p.SliceOrigin - ray.Origin, p.SliceNormal) / facing;
  if (!(t >= tEnter && t <= tExit))
  {
    return;
  }
  if (p.Crop.Enabled)
  {
    CroppedIntervals(indexOrigin, indexDirection, p.Crop, tEnter, tExit, intervals);
    if (std::none_of(intervals.begin(), intervals.end(),
          [t](const Segment& s) { return s.TNear <= t && t <= s.TFar; }))
    {
      return;
    }
  }
  RayContext<View> context(
    field, p, this->Constants, ray, indexOrigin, indexDirection, stats, true);
  ++stats.Samples;
  ++stats.UnacceleratedSamples;
  const float s = field.Sample(context.IndexPosition(t), p.Interp);
  const float a = p.Opacity.Evaluate(s);
  if (a == 0.f)
  {
    return;
  }
  context.CountContribution(t);
  float rgb[3];
  context.SampleColor(NotALatticeSample, t, s, rgb);
  if (p.Shade)
  {
    context.ShadeSample(rgb, t, NotALatticeSample, Vec3f(), false);
  }
  for (int c = 0; c < 3; ++c)
  {
    rgba[c] = a * rgb[c];
  }
  rgba[3] = a;
  if (events)
  {
    AppendEvent(*events, t, rgb, a, false);
  }
  if (firstHit)
  {
    *firstHit = t;
  }
}

bool RayCaster::CastImage(const Camera& view, const float* depth,
  const SegmentSource& source, float* rgba, CastStatistics& stats,
  const std::function<bool(double)>& progress) const
{
  return this->Field->Dispatch([&](const auto& field) {
    return this->CastImageIn(field, view, depth, source, rgba, stats, progress);
  });
}

std::size_t RayCaster::DifferenceCacheCellsFor(const Camera& view) const
{
  // The rays' spacing in voxels at the field's centre.
  const double spacing =
    Length(this->WorldToIndex.TransformVector(view.PixelStepAt(this->FieldCentre)));
  return spacing < DenseRaySpacing ? DenseDifferenceCacheCells : DifferenceCacheCells;
}

template <class View>
bool RayCaster::CastImageIn(const View& field, const Camera& view, const float* depth,
  const SegmentSource& source, float* rgba, CastStatistics& stats,
  const std::function<bool(double)>& progress) const
{
  const std::size_t cacheCells =
    this->Constants.GradientNeeded ? this->DifferenceCacheCellsFor(view) : 0;
  auto castOne = [&](const RayQuery& query, RayScratch& scratch, float* pixel) {
    if (scratch.Differences.size() != cacheCells)
    {
      scratch.Differences.resize(cacheCells);
    }
    if (!RayCostFit::TimesColumn(query.Pixel[0]))
    {
      this->CastRayIn(field, query, source, scratch.Segments, scratch.Ranges, pixel,
        scratch.Stats, nullptr, nullptr, &scratch.Differences, &scratch.Shadows);
      return;
    }
    CastStatistics& s = scratch.Stats;
    const std::uint64_t samples = s.Samples, contributing = s.ContributingSamples,
                        unaccelerated = s.UnacceleratedSamples;
    const auto start = std::chrono::steady_clock::now();
    this->CastRayIn(field, query, source, scratch.Segments, scratch.Ranges, pixel, s, nullptr,
      nullptr, &scratch.Differences, &scratch.Shadows);
    s.Timing.Add(static_cast<double>(s.Samples - samples),
      static_cast<double>(s.ContributingSamples - contributing),
      SecondsSince(start),
      static_cast<double>(s.UnacceleratedSamples - unaccelerated));
  };
  const bool everyRay = this->CastsEveryRay();
  auto mayHave = [&](int px, int py) { return everyRay || source.MayHaveSegments(px, py); };
  // The samples a ray not cast would have without acceleration, on the timed columns.
  auto skipOne = [&](int px, int py, RayScratch& scratch) {
    if (RayCostFit::CountsUncast(px, py))
    {
      scratch.Stats.Timing.AddUncast(
        static_cast<double>(this->UnacceleratedSamples(PixelRay(view, depth, px, py))));
    }
  };
  auto reduce = [&stats](const RayScratch& scratch) { stats += scratch.Stats; };
  // The caches of every thread that may cast (the allocator keeps what any one took).
  stats.DifferenceCacheBytes += cacheCells * sizeof(CellDifferences) *
    static_cast<std::size_t>(vtkSMPTools::GetEstimatedNumberOfThreads());
  return CastTiles(view, depth, castOne, mayHave, skipOne, rgba, reduce, progress);
}

} // namespace parc
