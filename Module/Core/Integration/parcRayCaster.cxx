#include "parcRayCaster.h"

#include <vtkSMPThreadLocal.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <optional>
#include <type_traits>

namespace parc
{

namespace
{
constexpr int TileSize = 16;        ///< ray-image pixels per tile edge
constexpr int TileRowsPerBand = 4;  ///< tile rows cast between two progress reports
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
/// Lattice steps beyond a scene ray's stop that its composite and isosurface volumes are
/// still cast (SceneCaster::CastRay).
constexpr double StopMarginSteps = 2.0;

/// Whether a volume of this ray function can stop a ray by its own opacity.
bool CanStopRay(BlendMode blend)
{
  return blend == BlendMode::Composite || blend == BlendMode::IsoSurface;
}

/// Where a volume of this ray function comes in SceneCaster's cast order.
int CastRank(BlendMode blend)
{
  return blend == BlendMode::IsoSurface ? 0 : blend == BlendMode::Composite ? 2 : 1;
}

/// The first lattice index k of member `member` (sample distance dt) whose sample at ray
/// parameter k dt comes after an event at t of member `from` in the merge by (ray
/// parameter, member index); the lattice position is computed as the caster computes it.
long FirstSampleAfter(double t, std::size_t from, double dt, std::size_t member)
{
  const auto after = [&](long k) {
    const double tk = k * dt;
    return tk > t || (tk == t && member > from);
  };
  constexpr double Limit = 4503599627370496.0; // 2^52: lattice indices stay exact
  long k = static_cast<long>(std::max(-Limit, std::min(std::floor(t / dt), Limit)));
  while (!after(k))
  {
    ++k;
  }
  while (after(k - 1))
  {
    --k;
  }
  return k;
}

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
      const double ndl = Dot(n, directions[i].ToLight);
      if (ndl > 0.0)
      {
        const double ndh = Dot(n, directions[i].Half);
        const double spec = ndh > 0.0 ? std::pow(ndh, p.SpecularPower) : 0.0;
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
    (!parameters->Mask || parameters->Blend != BlendMode::Composite ||
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
    // A mask of the field's dimensions, for the ray functions that composite samples (a
    // slice does not apply it).
    if (!std::equal(dims, dims + 3, mask->GetDimensions()) ||
      !(blend == BlendMode::Composite || blend == BlendMode::IsoSurface ||
        blend == BlendMode::Additive || blend == BlendMode::Slice))
    {
      return false;
    }
  }
  RenderConstants& k = this->Constants;
  const auto perUnit =
    static_cast<float>(parameters->SampleDistance / parameters->OpacityUnitDistance);
  const bool uncorrected = blend == BlendMode::Additive || blend == BlendMode::AverageIntensity;
  k.OpacityExponent = uncorrected ? 1.f : perUnit;
  k.OpacityScale = blend == BlendMode::Additive ? perUnit : 1.f;
  k.ComponentWeight = static_cast<float>(parameters->ComponentWeight);
  double constant = 1.0;
  k.GradientOpacityConstant =
    parameters->UseGradientOpacity && parameters->GradientOpacity.IsConstant(constant);
  k.GradientOpacityValue = static_cast<float>(constant);
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
    k.IntegerSpecularPower >= 0 &&
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
  if (!p || components.size() >= MaxComponents ||
    !(p->Blend == BlendMode::Composite || p->Blend == BlendMode::MaximumIntensity ||
      p->Blend == BlendMode::MinimumIntensity))
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
  return p.Blend == BlendMode::Composite && this->Components.empty() &&
    p.Interp == Interpolation::Linear && this->Field->GetStride() == 1;
}

const std::uint8_t* RayCaster::ContributingCells() const
{
  if (!this->Cells || !this->ReadsContributingCells())
  {
    return nullptr;
  }
  const int* dims = this->Field->GetDimensions();
  const std::size_t voxels = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  return this->Cells->size() == (voxels + 7) / 8 ? this->Cells->data() : nullptr;
}

bool RayCaster::ClipRay(const Ray& ray, double& tEnter, double& tExit) const
{
  const Matrix4& w2i = this->WorldToIndex;
  return ClipToField(*this->Field, *this->Params, w2i.TransformPoint(ray.Origin),
    w2i.TransformVector(ray.Direction), ray, tEnter, tExit);
}

namespace
{

/// x when sign > 0, else -x, without a branch (the sign of a normal towards the eye is
/// as unpredictable as the data).
float FlipUnlessPositive(float x, float sign)
{
  std::uint32_t bits;
  std::memcpy(&bits, &x, sizeof(bits));
  bits ^= static_cast<std::uint32_t>(!(sign > 0.f)) << 31;
  std::memcpy(&x, &bits, sizeof(bits));
  return x;
}


/// x^n for a whole n >= 0 by repeated squaring.
float IntegerPower(float x, int n)
{
  float result = 1.f;
  while (n > 0)
  {
    if (n & 1)
    {
      result *= x;
    }
    x *= x;
    n >>= 1;
  }
  return result;
}

/// The trilinear interpolation at fractions f of the shading factors of 8 corner normals
/// (corner n: x offset n & 1, y (n >> 1) & 1, z (n >> 2) & 1).
PARC_HOT_INLINE void InterpolateFactors(const RayCaster::ShadingFactors* table,
  const std::uint16_t codes[8], const float f[3], float diffuse[4], float specular[4])
{
#if defined(__SSE2__)
  const __m128 fx = _mm_set1_ps(f[0]), fy = _mm_set1_ps(f[1]), fz = _mm_set1_ps(f[2]);
  __m128 d[8], s[8];
  for (int n = 0; n < 8; ++n)
  {
    d[n] = _mm_load_ps(table[codes[n]].Diffuse);
    s[n] = _mm_load_ps(table[codes[n]].Specular);
  }
  for (int n = 0; n < 8; n += 2) // along x
  {
    d[n] = _mm_add_ps(d[n], _mm_mul_ps(fx, _mm_sub_ps(d[n + 1], d[n])));
    s[n] = _mm_add_ps(s[n], _mm_mul_ps(fx, _mm_sub_ps(s[n + 1], s[n])));
  }
  for (int n = 0; n < 8; n += 4) // along y
  {
    d[n] = _mm_add_ps(d[n], _mm_mul_ps(fy, _mm_sub_ps(d[n + 2], d[n])));
    s[n] = _mm_add_ps(s[n], _mm_mul_ps(fy, _mm_sub_ps(s[n + 2], s[n])));
  }
  _mm_storeu_ps(diffuse, _mm_add_ps(d[0], _mm_mul_ps(fz, _mm_sub_ps(d[4], d[0]))));
  _mm_storeu_ps(specular, _mm_add_ps(s[0], _mm_mul_ps(fz, _mm_sub_ps(s[4], s[0]))));
#else
  for (int c = 0; c < 4; ++c)
  {
    float d[8], s[8];
    for (int n = 0; n < 8; ++n)
    {
      d[n] = table[codes[n]].Diffuse[c];
      s[n] = table[codes[n]].Specular[c];
    }
    for (int step = 1; step < 8; step *= 2) // along x, y, z
    {
      const float t = f[step == 1 ? 0 : step == 2 ? 1 : 2];
      for (int n = 0; n < 8; n += 2 * step)
      {
        d[n] = d[n] + t * (d[n + step] - d[n]);
        s[n] = s[n] + t * (s[n + step] - s[n]);
      }
    }
    diffuse[c] = d[0];
    specular[c] = s[0];
  }
#endif
}

#if defined(__SSE2__)
/// InterpolateFactors of (diffuse, specular) pairs (RenderConstants::GreyNormalShading):
/// the pair in lanes 0 and 1, the same bits as either colour channel of InterpolateFactors.
PARC_HOT_INLINE __m128 InterpolateGreyFactors(
  const float* pairs, const std::uint16_t codes[8], const float f[3])
{
  // Corners a and b side by side: (diffuse a, specular a, diffuse b, specular b).
  const auto two = [&](int a, int b) {
    const __m128 low =
      _mm_loadl_pi(_mm_setzero_ps(), reinterpret_cast<const __m64*>(pairs + 2 * codes[a]));
    return _mm_loadh_pi(low, reinterpret_cast<const __m64*>(pairs + 2 * codes[b]));
  };
  const auto lerp = [](__m128 a, __m128 b, float t) {
    return _mm_add_ps(a, _mm_mul_ps(_mm_set1_ps(t), _mm_sub_ps(b, a)));
  };
  const __m128 z0 = lerp(two(0, 2), two(1, 3), f[0]); // along x: corners 0 2 | z = 0
  const __m128 z1 = lerp(two(4, 6), two(5, 7), f[0]); // corners 4 6 | z = 1
  const __m128 y = lerp(_mm_movelh_ps(z0, z1), _mm_movehl_ps(z1, z0), f[1]); // z = 0 | 1
  return lerp(y, _mm_movehl_ps(y, y), f[2]);
}
#endif

#if defined(__SSE2__)
/// The colour sums of out as a register (red, green, blue, 0).
PARC_HOT_INLINE __m128 ColourSums(const EventCompositor& out)
{
  return _mm_setr_ps(out.Rgb[0], out.Rgb[1], out.Rgb[2], 0.f);
}
/// Sets the colour sums of out from a register of ColourSums.
PARC_HOT_INLINE void SetColourSums(EventCompositor& out, __m128 sums)
{
  alignas(16) float rgb[4];
  _mm_store_ps(rgb, sums);
  std::copy_n(rgb, 3, out.Rgb);
}
#endif

/// Appends an event, out of the sample loops (only several volumes keep events).
PARC_NOINLINE void AppendEvent(
  std::vector<RayEvent>& events, double t, const float rgb[3], float a, bool premultiplied)
{
  events.push_back({ t, { rgb[0], rgb[1], rgb[2] }, a, premultiplied });
}

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
    if (exponent == 0.5f || exponent == 0.25f)
    {
      const __m128 one = _mm_set1_ps(1.f);
      for (int j = 0; j < LatticeBlock::Size; j += 4)
      {
        const __m128 v = _mm_loadu_ps(a + j);
        __m128 root = _mm_sqrt_ps(_mm_sub_ps(one, v));
        if (exponent == 0.25f)
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
    const float transparency = 1.f - a;
    // The sample distances of half and a quarter of the unit distance by square roots.
    if (exponent == 0.5f)
    {
      return 1.f - std::sqrt(transparency);
    }
    if (exponent == 0.25f)
    {
      return 1.f - std::sqrt(std::sqrt(transparency));
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

/// Writes colour * opacity, or exact zeros when the opacity is zero.
void Premultiply(const float rgb[3], float a, float rgba[4])
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

  bool operator()(long k0, int n, bool, int& visited)
  {
    return this->Merge ? this->Interleaved(k0, n, visited) : this->Block(k0, n, visited);
  }
  /// The block of samples k0 .. k0 + n - 1 in parts between the events of Merge, each
  /// event composited before the first sample that comes after it; stops at Merge->End.
  bool Interleaved(long k0, int n, int& visited)
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
  bool Block(long k0, int n, int& visited)
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

  bool operator()(long k0, int n, bool, int&)
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
      this->C.P.Color.Lookup(this->Extreme, rgb);
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

  bool operator()(long k0, int n, bool, int& visited)
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
  bool operator()(long k0, int n, bool, int&)
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
void GreyIntensity(double intensity, float rgba[4])
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

  bool operator()(long k0, int n, bool, int&)
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

  bool operator()(long k0, int n, bool, int& visited)
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

  bool operator()(long k0, int n, bool follows, int& visited)
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
    lanes &= (1u << n) - 1u;
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

  bool operator()(long k0, int n, bool, int& visited)
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
std::uint64_t CellsCrossed(const Vec3& a, const Vec3& b)
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

/// Visits the lattice samples of ranges in order, in blocks, and counts them; returns the
/// last one visited (stopped: whether the ray function stopped the ray there).
template <class Function>
long Walk(const std::vector<LatticeRange>& ranges, Function& fn, bool& stopped)
{
  stopped = false;
  long previous = std::numeric_limits<long>::min();
  for (const LatticeRange& r : ranges)
  {
    for (long k0 = std::max(r.First, previous + 1); k0 <= r.Last;)
    {
      const int n = static_cast<int>(std::min<long>(SampleBlockSize, r.Last - k0 + 1));
      const bool follows = (k0 == previous + 1);
      int visited = n;
      const bool more = fn(k0, n, follows, visited);
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
  const long last = Walk(ranges, fn, stopped);
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

} // namespace

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
  if (p.Blend != BlendMode::Composite && p.Blend != BlendMode::IsoSurface)
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

namespace
{
/// Scratch storage of one thread's rays.
struct RayScratch
{
  std::vector<Segment> Segments;
  std::vector<LatticeRange> Ranges;
  SceneScratch Scene; ///< SceneCaster
  CastStatistics Stats;
  std::vector<CastStatistics> MemberStats; ///< per volume (SceneCaster)
  std::vector<CellDifferences> Differences; ///< of one volume's cells (RayCaster)
  ShadowScratch Shadows;
};

/// The ray of pixel (px, py), ending at the opaque geometry of depth (optional).
Ray PixelRay(const Camera& view, const float* depth, int px, int py)
{
  Ray ray = view.MakeRay(px, py);
  const std::size_t pixel = static_cast<std::size_t>(py) * view.Width + px;
  if (depth && depth[pixel] < 1.f)
  {
    ray.TMax = std::min(ray.TMax, view.DepthToParameter(ray, px, py, depth[pixel]));
  }
  return ray;
}

/// Casts the tiles of one band of rows; vtkSMPTools functor.
template <class Cast, class MayHave, class Skip>
struct TileCaster
{
  const Cast& CastOne;       ///< casts one ray: (query, scratch, rgba)
  const MayHave& MayHaveRay; ///< (px, py): false when the pixel's ray surely gets nothing
  const Skip& SkipOne;       ///< (px, py, scratch): for each pixel whose ray is not cast
  const Camera& View;
  const float* Depth;
  float* Image;
  int TilesX;
  int FirstTileRow;
  vtkSMPThreadLocal<RayScratch> Local;

  void Initialize() {}
  void operator()(vtkIdType begin, vtkIdType end)
  {
    RayScratch& scratch = this->Local.Local();
    for (vtkIdType tile = begin; tile < end; ++tile)
    {
      const int tx = static_cast<int>(tile % this->TilesX);
      const int ty = this->FirstTileRow + static_cast<int>(tile / this->TilesX);
      const int x1 = std::min((tx + 1) * TileSize, this->View.Width);
      const int y1 = std::min((ty + 1) * TileSize, this->View.Height);
      for (int py = ty * TileSize; py < y1; ++py)
      {
        for (int px = tx * TileSize; px < x1; ++px)
        {
          float* rgba = this->Image + 4 * (static_cast<std::size_t>(py) * this->View.Width + px);
          if (!this->MayHaveRay(px, py))
          {
            std::fill_n(rgba, 4, 0.f);
            this->SkipOne(px, py, scratch);
            continue;
          }
          const Ray ray = PixelRay(this->View, this->Depth, px, py);
          this->CastOne(RayQuery::AtPixel(ray, px, py), scratch, rgba);
        }
      }
    }
  }
  void Reduce() {}
};

/// Casts a whole image in bands of tile rows (see RayCaster::CastImage); reduce(scratch)
/// gathers each thread's statistics.
template <class Cast, class MayHave, class Skip, class Reduce>
bool CastTiles(const Camera& view, const float* depth, const Cast& castOne,
  const MayHave& mayHave, const Skip& skipOne, float* rgba, const Reduce& reduce,
  const std::function<bool(double)>& progress)
{
  // Every pixel of a cast band is written by its tile (zero when no ray is cast).
  const int tilesX = (view.Width + TileSize - 1) / TileSize;
  const int tilesY = (view.Height + TileSize - 1) / TileSize;
  bool completed = true;
  TileCaster<Cast, MayHave, Skip> caster{ castOne, mayHave, skipOne, view, depth, rgba, tilesX,
    0, {} };
  for (int row = 0; row < tilesY; row += TileRowsPerBand)
  {
    const int rows = std::min(TileRowsPerBand, tilesY - row);
    caster.FirstTileRow = row;
    vtkSMPTools::For(0, static_cast<vtkIdType>(tilesX) * rows, 1, caster);
    if (progress && !progress(static_cast<double>(row + rows) / tilesY))
    {
      const std::size_t castRows = std::min(view.Height, (row + rows) * TileSize);
      std::fill(rgba + 4 * castRows * view.Width,
        rgba + 4 * static_cast<std::size_t>(view.Height) * view.Width, 0.f);
      completed = false;
      break;
    }
  }
  for (auto& scratch : caster.Local)
  {
    reduce(scratch);
  }
  return completed;
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

template <class View>
bool RayCaster::CastImageIn(const View& field, const Camera& view, const float* depth,
  const SegmentSource& source, float* rgba, CastStatistics& stats,
  const std::function<bool(double)>& progress) const
{
  auto castOne = [&](const RayQuery& query, RayScratch& scratch, float* pixel) {
    if (this->Constants.GradientNeeded && scratch.Differences.empty())
    {
      scratch.Differences.resize(DifferenceCacheCells);
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
  return CastTiles(view, depth, castOne, mayHave, skipOne, rgba, reduce, progress);
}

//------------------------------------------------------------------------------
bool SceneCaster::SetMembers(std::vector<Member> members, double terminationOpacity)
{
  if (members.size() > MaxSceneVolumes)
  {
    return false;
  }
  this->Members = std::move(members);
  this->TerminationOpacity = terminationOpacity;
  this->CastOrder.resize(this->Members.size());
  std::iota(this->CastOrder.begin(), this->CastOrder.end(), std::size_t(0));
  const auto rank = [this](std::size_t v) {
    return CastRank(this->Members[v].Caster->GetParameters()->Blend);
  };
  std::stable_sort(this->CastOrder.begin(), this->CastOrder.end(),
    [&rank](std::size_t a, std::size_t b) { return rank(a) < rank(b); });
  this->Streamed = this->Members.size();
  if (!this->CastOrder.empty())
  {
    const RayCaster& last = *this->Members[this->CastOrder.back()].Caster;
    if (last.GetParameters()->Blend == BlendMode::Composite && last.GetComponents().empty() &&
      last.GetParameters()->TerminationOpacity == terminationOpacity)
    {
      this->Streamed = this->CastOrder.back();
    }
  }
  return true;
}

bool SceneCaster::Skips(std::size_t v, int px, int py) const
{
  const Member& m = this->Members[v];
  return !m.Caster->CastsEveryRay() && !m.Source->MayHaveSegments(px, py);
}

bool SceneCaster::Skips(std::size_t v, const RayQuery& query) const
{
  return query.HasPixel && this->Skips(v, query.Pixel[0], query.Pixel[1]);
}

void SceneCaster::MergeEvents(
  const std::vector<std::vector<RayEvent>>& events, double stop, MergedEvents& merged) const
{
  const std::size_t n = this->Members.size();
  const bool streams = this->Streamed < n;
  const double dt =
    streams ? this->Members[this->Streamed].Caster->GetParameters()->SampleDistance : 1.0;
  merged.Entries.clear();
  merged.Next = 0;
  merged.End = streams && stop < std::numeric_limits<double>::infinity()
    ? FirstSampleAfter(stop, this->Streamed, dt, this->Streamed)
    : std::numeric_limits<long>::max();
  // Each member's events are in ray order.
  std::size_t next[MaxSceneVolumes] = {};
  for (;;)
  {
    std::size_t best = n;
    for (std::size_t v = 0; v < n; ++v)
    {
      if (next[v] < events[v].size() &&
        (best == n || events[v][next[v]].T < events[best][next[best]].T))
      {
        best = v;
      }
    }
    if (best == n || events[best][next[best]].T > stop)
    {
      break;
    }
    const RayEvent& e = events[best][next[best]++];
    merged.Entries.push_back(
      { streams ? FirstSampleAfter(e.T, best, dt, this->Streamed) : 0, e });
  }
}

void SceneCaster::CastRay(const RayQuery& query, std::vector<Segment>& segments,
  std::vector<LatticeRange>& ranges, SceneScratch& scratch, float rgba[4],
  CastStatistics* stats, ShadowScratch* shadows) const
{
  std::vector<std::vector<RayEvent>>& events = scratch.Events;
  events.resize(this->Members.size());
  float own[4];
  double stop = std::numeric_limits<double>::infinity(); // see the header's file comment
  RayQuery clamped = query;
  // A volume that can stop the ray is cast two lattice steps beyond the stop: every sample
  // at or before it, and the sample after it that an isosurface crossing before it is
  // found with. The others give their whole-ray result.
  auto clampFor = [&](const CastParameters& p) {
    clamped.Path.TMax = CanStopRay(p.Blend)
      ? std::min(query.Path.TMax, stop + StopMarginSteps * p.SampleDistance)
      : query.Path.TMax;
  };
  for (const std::size_t v : this->CastOrder)
  {
    events[v].clear();
    if (v == this->Streamed || this->Skips(v, query))
    {
      continue;
    }
    const Member& m = this->Members[v];
    const CastParameters& p = *m.Caster->GetParameters();
    clampFor(p);
    m.Caster->CastRay(
      clamped, *m.Source, segments, ranges, own, stats[v], nullptr, &events[v], shadows);
    if (CanStopRay(p.Blend) && !events[v].empty() && !(own[3] < p.TerminationOpacity))
    {
      stop = std::min(stop, events[v].back().T);
    }
  }
  MergedEvents& merged = scratch.Merged;
  this->MergeEvents(events, stop, merged);
  EventCompositor compositor;
  if (this->Streamed < this->Members.size() && !this->Skips(this->Streamed, query))
  {
    const Member& m = this->Members[this->Streamed];
    clampFor(*m.Caster->GetParameters());
    m.Caster->CastRayMerged(
      clamped, *m.Source, segments, ranges, merged, compositor, stats[this->Streamed], shadows);
  }
  // The events after the streamed volume's samples, or all of them.
  merged.AddBefore(std::numeric_limits<long>::max(), compositor, this->TerminationOpacity);
  compositor.Finish(rgba);
}

bool SceneCaster::CastImage(const Camera& view, const float* depth, float* rgba,
  std::vector<CastStatistics>& stats, const std::function<bool(double)>& progress) const
{
  const std::size_t n = this->Members.size();
  auto castOne = [&](const RayQuery& query, RayScratch& scratch, float* pixel) {
    scratch.MemberStats.resize(n);
    this->CastRay(query, scratch.Segments, scratch.Ranges, scratch.Scene, pixel,
      scratch.MemberStats.data(), &scratch.Shadows);
  };
  auto mayHave = [&](int px, int py) {
    for (std::size_t v = 0; v < n; ++v)
    {
      if (!this->Skips(v, px, py))
      {
        return true;
      }
    }
    return false;
  };
  stats.assign(n, CastStatistics());
  auto skipOne = [](int, int, RayScratch&) {}; // Auto's fit is the single volume's
  auto reduce = [&stats](const RayScratch& scratch) {
    for (std::size_t v = 0; v < scratch.MemberStats.size(); ++v)
    {
      stats[v] += scratch.MemberStats[v];
    }
  };
  return CastTiles(view, depth, castOne, mayHave, skipOne, rgba, reduce, progress);
}

} // namespace parc
