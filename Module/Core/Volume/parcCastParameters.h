// PARC for VTK: what decides a ray's result besides the ray and the field: the ray
// function (blend mode) with its transfer functions, shading and lights. Shared by the
// classification (what may contribute) and the caster (what does).
#ifndef parcCastParameters_h
#define parcCastParameters_h

#include "parcMath.h"
#include "parcNormalVolume.h"
#include "parcRay.h"
#include "parcScalarField.h"
#include "parcTransferFunction.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <vector>

namespace parc
{

/// The isosurface ray function uses at most this many iso values (the smallest ones).
constexpr std::size_t MaxIsoValues = 64;

/// Fields of at least this many bytes have their voxels prefetched ahead of unshaded rays
/// (CastParameters::PrefetchMinBytes). Measured on a processor with a 32 MB last-level
/// cache (unshaded, the head resized, frames alternating with and without in one process):
/// 1445 MB 6-7% less casting with the depth pass at supercells of 32, 1.5% unaccelerated;
/// 877 MB none and 3.5% more; 429 MB and 181 MB 2-6% more; shaded none.
constexpr std::size_t DefaultPrefetchMinBytes = std::size_t(1) << 30;

enum class BlendMode
{
  Composite,
  MaximumIntensity,
  MinimumIntensity,
  AverageIntensity,
  Additive,
  IsoSurface,
  Slice
};

/// What the casters and the mapper need to know of a ray function, in one table
/// (TraitsOf): a new blend mode is a row here, besides its ray function, its contribution
/// rule and its VTK conversion.
struct BlendTraits
{
  /// Its own opacity can stop a ray (composite, isosurface); in a scene, for every volume.
  bool StopsRays = false;
  /// Where a volume of it comes in a scene's cast order: isosurfaces first (their opacity
  /// stops rays soonest and cheapest), the whole-ray functions next, composite last.
  int CastRank = 1;
  /// Its opacity is corrected for the sample distance, 1 - (1 - a)^(dt / unit distance)
  /// (not additive or average intensity).
  bool CorrectsOpacity = false;
  /// Its opacity is scaled by dt / unit distance instead (additive).
  bool ScalesOpacity = false;
  /// It combines independent components (composite, maximum and minimum intensity).
  bool CombinesComponents = false;
  /// A binary mask hides its samples (composite, isosurface, additive).
  bool AppliesMask = false;
  /// A mask is accepted: applied, or ignored (a slice).
  bool TakesMask = false;
  /// A label map's functions apply to its samples (composite).
  bool AppliesLabels = false;
  /// Its samples' opacity shadows what is behind them from a light (composite,
  /// isosurface): shadow rays are cast through it.
  bool CastsShadows = false;
  /// Every ray that meets the field has a result, even with nothing to sample (additive:
  /// opaque black), so that no ray may be skipped.
  bool CastsEveryRay = false;
  /// Its rays leave out the samples of cells that cannot contribute (composite, with one
  /// component and linear interpolation: RayCaster::ReadsContributingCells).
  bool SkipsEmptyCells = false;
  /// Cast last in a scene, its samples are composited as they are taken, merged with the
  /// other volumes' events (composite), rather than kept as events of their own.
  bool StreamsInScene = false;
  /// Its rays sample segments, so that PARC passes can shorten them (not a slice: one
  /// sample a ray).
  bool UsesSegments = true;
};

constexpr BlendTraits TraitsOf(BlendMode blend)
{
  BlendTraits t;
  switch (blend)
  {
    case BlendMode::Composite:
      t.StopsRays = t.CorrectsOpacity = t.CombinesComponents = true;
      t.AppliesMask = t.TakesMask = t.AppliesLabels = true;
      t.CastsShadows = t.SkipsEmptyCells = t.StreamsInScene = true;
      t.CastRank = 2;
      break;
    case BlendMode::MaximumIntensity:
    case BlendMode::MinimumIntensity:
      t.CorrectsOpacity = t.CombinesComponents = true;
      break;
    case BlendMode::AverageIntensity:
      break;
    case BlendMode::Additive:
      t.ScalesOpacity = t.AppliesMask = t.TakesMask = t.CastsEveryRay = true;
      break;
    case BlendMode::IsoSurface:
      t.StopsRays = t.CorrectsOpacity = t.AppliesMask = t.TakesMask = t.CastsShadows = true;
      t.CastRank = 0;
      break;
    case BlendMode::Slice:
      t.CorrectsOpacity = t.TakesMask = true;
      t.UsesSegments = false;
      break;
  }
  return t;
}

/// How shaded samples are lit (see CastParameters::Shading).
enum class ShadingModel
{
  Exact,
  QuantizedNormals
};

/// A light in world coordinates.
struct Light
{
  bool Positional = false;
  Vec3 Position;                     ///< positional lights
  Vec3 FocalPoint;                   ///< the light points from Position to FocalPoint
  Vec3 Color{ 1.0, 1.0, 1.0 };       ///< diffuse colour times intensity
  Vec3 SpecularColor{ 1.0, 1.0, 1.0 }; ///< specular colour times intensity
  Vec3 Attenuation{ 1.0, 0.0, 0.0 }; ///< constant, linear, quadratic (positional only)
  double ConeAngle = 180.0;          ///< degrees; >= 90 means no spot
  double Exponent = 1.0;             ///< spot exponent
  /// How much a shadow darkens what this light gives (vtkLight::ShadowAttenuation): the
  /// light's diffuse and specular terms are scaled by 1 - ShadowAttenuation (1 - T), T the
  /// transmittance towards the light. 0: the light casts no shadow and no shadow ray is
  /// cast for it.
  double ShadowAttenuation = 0.0;
};

/// The transfer functions of one label of a label map (CastParameters::Labels).
struct LabelFunctions
{
  int Label = 1; ///< > 0
  PiecewiseLinearFunction Opacity;
  ColorTable Color;
  bool UseGradientOpacity = false;
  PiecewiseLinearFunction GradientOpacity;
};

/// Everything that decides what a ray returns, except the ray and the field.
struct CastParameters
{
  BlendMode Blend = BlendMode::Composite;
  Interpolation Interp = Interpolation::Linear;
  PiecewiseLinearFunction Opacity; ///< scalar opacity, per unit distance
  ColorTable Color;
  bool UseGradientOpacity = false;
  PiecewiseLinearFunction GradientOpacity; ///< of the world-space gradient magnitude
  double OpacityUnitDistance = 1.0;        ///< world units
  double SampleDistance = 1.0;             ///< dt, world units
  double TerminationOpacity = 0.99;
  std::vector<double> IsoValues;
  /// The plane of the slice ray function (world coordinates; the normal need not be of
  /// unit length, and is not zero).
  Vec3 SliceOrigin;
  Vec3 SliceNormal{ 0.0, 0.0, 1.0 };
  double AverageRange[2] = { -1e300, 1e300 };
  /// Additive and average intensity weigh each sample's value normalised to this range,
  /// (s - IntensityRange[0]) / (IntensityRange[1] - IntensityRange[0]), as VTK's mappers
  /// normalise to the scalars' range (0 for an empty range).
  double IntensityRange[2] = { 0.0, 1.0 };
  /// Where composite samples and isosurface crossings take their colour (dependent
  /// components; opacity and gradient always come from the field): with 0 ColorShifts
  /// from Color at the field's value; with 1, from Color at the value of the component
  /// ColorShifts[0] elements away in memory; with 3, directly from those three components
  /// times DirectColorScale (RGB).
  /// A binary mask of the field's dimensions, or null: a sample or isosurface crossing
  /// contributes only where the nearest voxel of Mask is non-zero (composite, isosurface,
  /// additive). The mask must outlive the casts.
  const ScalarField* Mask = nullptr;
  /// With Labels (composite only), Mask is a label map instead, as VTK's GPU mapper reads
  /// one: the label L of a sample is its nearest voxel of Mask, rounded. Where L has
  /// functions here (sorted by Label), with f = MaskBlendFactor, the sample's opacity is
  /// (1 - f) a(s) g(|grad|) + f a_L(s) g_L(|grad|) and its colour (1 - f) rgb(s) +
  /// f rgb_L(s), the default functions a, g, rgb being the ones above (g = 1 without
  /// gradient opacity); elsewhere (L = 0, or no functions) it has the default ones.
  std::vector<LabelFunctions> Labels;
  float MaskBlendFactor = 1.f;
  int ColorShiftCount = 0;
  int ColorShifts[3] = { 0, 0, 0 };
  float DirectColorScale = 1.f;
  /// The weight of an independent component's opacity (RayCaster::SetComponents); 0 makes
  /// the component contribute nowhere.
  double ComponentWeight = 1.0;
  bool Shade = false;
  double Ambient = 0.1, Diffuse = 0.7, Specular = 0.2, SpecularPower = 10.0;
  /// The ambient light's colour, per channel: the ambient term is Ambient times it times
  /// the sample's colour. White by default; the lights' summed ambient colours (times
  /// their intensities) where a mapper's ambient comes from its lights.
  Vec3 AmbientLight{ 1.0, 1.0, 1.0 };
  std::vector<Light> Lights;
  /// Exact: Blinn-Phong of the gradient of the interpolated field at every shaded sample
  /// or crossing. QuantizedNormals: the table shading of Normals (parcNormalVolume.h),
  /// for the directional lights as seen from ShadingViewDirection; faster, less accurate.
  /// QuantizedNormals falls back to Exact without Normals of the field's dimensions, and
  /// with a positional or shadow-casting light.
  ShadingModel Shading = ShadingModel::Exact;
  const NormalVolume* Normals = nullptr; ///< must outlive the casts
  Vec3 ShadingViewDirection{ 0.0, 0.0, 1.0 }; ///< unit, towards the eye (world)
  /// Rays are cut to the part every clipping plane keeps (world coordinates, as for
  /// Volume::WorldToIndex) ...
  std::vector<ClipPlane> ClipPlanes;
  /// ... and to the rendered cropping regions (voxel-index coordinates). A sample outside
  /// them is never taken, whatever the acceleration.
  Cropping Crop;
  /// ... and to this box of voxel-index coordinates, as well as to the field's own box:
  /// the cells a renderer owns when the field also holds layers of ghost cells, the
  /// neighbouring pieces' cells that gradients and interpolation at its border read, and
  /// that shadow rays cross (they are not cut to this box).
  Vec3 OwnedLo{ -std::numeric_limits<double>::infinity(),
    -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity() };
  Vec3 OwnedHi{ std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity() };
  /// Whether the rays' loops may run compiled for AVX2 where the processor has it (x86-64
  /// with GCC or Clang; 4-10% less casting): the same operations, each rounding alike,
  /// so the same image as with false, the code of the baseline instruction set.
  bool WideVectors = true;
  /// Unshaded rays (no gradient) through a field of at least this many bytes, read in
  /// place (not bricked) with linear interpolation, prefetch the cache lines their samples
  /// will read a few blocks ahead (FieldView::SampleLattice): a hint to the processor, so
  /// the same samples and bits either way.
  std::size_t PrefetchMinBytes = DefaultPrefetchMinBytes;
};

/// Whether every light of p can shade from quantized normals: directional, casting no
/// shadow (see CastParameters::Shading).
inline bool LightsAllowQuantizedNormals(const CastParameters& p)
{
  return std::all_of(p.Lights.begin(), p.Lights.end(),
    [](const Light& light) { return !light.Positional && !(light.ShadowAttenuation > 0.0); });
}

/// Whether p's slice plane is one: a finite point and a non-zero finite normal.
inline bool HasUsableSlicePlane(const CastParameters& p)
{
  const double n2 = Dot(p.SliceNormal, p.SliceNormal);
  return std::isfinite(Dot(p.SliceOrigin, p.SliceOrigin)) && n2 > 0.0 && std::isfinite(n2);
}

/// The iso values the isosurface ray function uses, for the caster and the classification
/// alike: sorted, the smallest MaxIsoValues.
inline std::vector<double> UsedIsoValues(const CastParameters& p)
{
  std::vector<double> values = p.IsoValues;
  std::sort(values.begin(), values.end());
  values.resize(std::min(values.size(), MaxIsoValues));
  return values;
}

} // namespace parc

#endif
