#include "parcRayCaster.h"

#include <vtkSMPThreadLocal.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace parc
{

namespace
{
constexpr int TileSize = 16;        ///< ray-image pixels per tile edge
constexpr int TileRowsPerBand = 4;  ///< tile rows cast between two progress reports
constexpr int RegulaFalsiSteps = 2; ///< isosurface refinement steps
/// Specular powers up to this whole number are computed by repeated squaring.
constexpr double MaxIntegerSpecularPower = 1024.0;
/// Directional lights whose half vectors are computed once per ray.
constexpr std::size_t MaxHoistedLights = 8;

/// The ray-parameter interval of the ray (origin o, direction d in voxel-index
/// coordinates) inside the field's box and [ray.TMin, ray.TMax].
bool ClipToField(const ScalarField& field, const Vec3& o, const Vec3& d, const Ray& ray,
  double& tEnter, double& tExit)
{
  const int* dims = field.GetDimensions();
  tEnter = ray.TMin;
  tExit = ray.TMax;
  return ClipToBox(o, d, { 0.0, 0.0, 0.0 }, { dims[0] - 1.0, dims[1] - 1.0, dims[2] - 1.0 },
    tEnter, tExit);
}
}

CastStatistics& CastStatistics::operator+=(const CastStatistics& o)
{
  this->Rays += o.Rays;
  this->Segments += o.Segments;
  this->Samples += o.Samples;
  this->ContributingSamples += o.ContributingSamples;
  this->GradientEvaluations += o.GradientEvaluations;
  this->Cells += o.Cells;
  return *this;
}

Ray ViewGeometry::MakeRay(int px, int py) const
{
  const double x = (2.0 * px + 1.0) / this->Width - 1.0;
  const double y = (2.0 * py + 1.0) / this->Height - 1.0;
  const Vec3 nearPoint = this->NDCToWorld.TransformHomogeneous({ x, y, -1.0 });
  const Vec3 farPoint = this->NDCToWorld.TransformHomogeneous({ x, y, 1.0 });
  Ray ray;
  ray.Direction = Normalized(farPoint - nearPoint);
  if (this->Parallel)
  {
    // The lattice starts on the plane through the camera position normal to the rays.
    ray.Origin = nearPoint - Dot(nearPoint - this->Eye, ray.Direction) * ray.Direction;
  }
  else
  {
    ray.Origin = this->Eye;
  }
  ray.TMin = Dot(nearPoint - ray.Origin, ray.Direction);
  ray.TMax = Dot(farPoint - ray.Origin, ray.Direction);
  return ray;
}

double ViewGeometry::DepthToParameter(const Ray& ray, int px, int py, double z) const
{
  const double x = (2.0 * px + 1.0) / this->Width - 1.0;
  const double y = (2.0 * py + 1.0) / this->Height - 1.0;
  const Vec3 p = this->NDCToWorld.TransformHomogeneous({ x, y, 2.0 * z - 1.0 });
  return Dot(p - ray.Origin, ray.Direction);
}

void ViewGeometry::RayBounds(
  const Matrix4& transform, std::vector<Vec3>& starts, std::vector<Vec3>& directions) const
{
  starts.clear();
  directions.clear();
  if (!this->Parallel)
  {
    starts.push_back(transform.TransformPoint(this->Eye));
  }
  for (const double x : { -1.0, 1.0 })
  {
    for (const double y : { -1.0, 1.0 })
    {
      const Vec3 nearPoint = this->NDCToWorld.TransformHomogeneous({ x, y, -1.0 });
      const Vec3 farPoint = this->NDCToWorld.TransformHomogeneous({ x, y, 1.0 });
      starts.push_back(transform.TransformPoint(nearPoint));
      directions.push_back(transform.TransformVector(farPoint - nearPoint));
    }
  }
}

bool RayCaster::Prepare(const ScalarField* field, const CastParameters* parameters)
{
  this->Field = field;
  this->Params = parameters;
  if (!field || !parameters || !(parameters->SampleDistance > 0.0) ||
    !(parameters->OpacityUnitDistance > 0.0))
  {
    return false;
  }
  const int* dims = field->GetDimensions();
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
  {
    return false;
  }
  this->OpacityExponent =
    static_cast<float>(parameters->SampleDistance / parameters->OpacityUnitDistance);
  double constant = 1.0;
  this->GradientOpacityConstant =
    parameters->UseGradientOpacity && parameters->GradientOpacity.IsConstant(constant);
  this->GradientOpacityValue = static_cast<float>(constant);
  this->GradientNeeded = parameters->Shade ||
    (parameters->UseGradientOpacity && !this->GradientOpacityConstant);
  const double power = parameters->SpecularPower;
  this->IntegerSpecularPower = (power >= 0.0 && power <= MaxIntegerSpecularPower &&
                                 power == std::floor(power))
    ? static_cast<int>(power)
    : -1;
  this->DirectionalLights.clear();
  this->PositionalLights.clear();
  for (const Light& light : parameters->Lights)
  {
    if (light.Positional)
    {
      this->PositionalLights.push_back(&light);
    }
    else
    {
      this->DirectionalLights.push_back({ Normalized(light.Position - light.FocalPoint), light.Color });
    }
  }
  this->SkipEmptyCells = parameters->SkipEmptyCells &&
    parameters->Interp == Interpolation::Linear &&
    (parameters->Blend == BlendMode::Composite || parameters->Blend == BlendMode::Additive);
  if (this->SkipEmptyCells)
  {
    this->Rule.Set(*parameters, field->GetRange());
  }
  this->SortedIsoValues = parameters->IsoValues;
  std::sort(this->SortedIsoValues.begin(), this->SortedIsoValues.end());
  if (this->SortedIsoValues.size() > MaxIsoValues)
  {
    this->SortedIsoValues.resize(MaxIsoValues);
  }
  return true;
}

bool RayCaster::ClipRay(const Ray& ray, double& tEnter, double& tExit) const
{
  const Matrix4& w2i = this->Params->WorldToIndex;
  return ClipToField(*this->Field, w2i.TransformPoint(ray.Origin),
    w2i.TransformVector(ray.Direction), ray, tEnter, tExit);
}

namespace
{

/// x^n for a whole n >= 0 by repeated squaring.
double IntegerPower(double x, int n)
{
  double result = 1.0;
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

/// Per-ray constants shared by the ray functions.
template <class View>
struct RayContext
{
  const View& Field;
  const CastParameters& P;
  const Ray& WorldRay;
  Vec3 IndexOrigin;
  Vec3 IndexDirection;
  double Dt;
  float OpacityExponent;
  bool GradientOpacityConstant;
  float GradientOpacityValue;
  int IntegerSpecularPower;
  bool SkipEmptyCells;
  const ContributionRule& Rule;
  const std::vector<RayCaster::DirectionalLight>& DirectionalLights;
  const std::vector<const Light*>& PositionalLights;
  CastStatistics& Stats;
  double FirstHit = std::numeric_limits<double>::infinity();
  /// The corners of the cell the last lattice sample was in.
  CellCorners Corners;
  /// The voxel differences of the cell the last gradient was taken in.
  CellDifferences Differences;
  /// Half vectors of the first directional lights for this ray (Blinn-Phong).
  std::array<Vec3, MaxHoistedLights> HalfVectors;

  void Begin()
  {
    const std::size_t n = std::min(this->DirectionalLights.size(), MaxHoistedLights);
    for (std::size_t i = 0; this->P.Shade && i < n; ++i)
    {
      this->HalfVectors[i] = this->HalfVector(this->DirectionalLights[i].ToLight);
    }
  }
  Vec3 HalfVector(const Vec3& toLight) const
  {
    return Normalized(toLight - this->WorldRay.Direction);
  }

  void RecordHit(double t)
  {
    if (t < this->FirstHit)
    {
      this->FirstHit = t;
    }
  }

  Vec3 IndexPosition(double t) const { return this->IndexOrigin + t * this->IndexDirection; }
  PARC_HOT_INLINE float SampleAt(double t)
  {
    ++this->Stats.Samples;
    return this->Field.Sample(this->IndexPosition(t), this->P.Interp, this->Corners);
  }
  /// The sample at t in s, or false (s unset) for a sample in a cell that cannot contribute
  /// when the caster skips such cells: its opacity would be exactly 0.
  PARC_HOT_INLINE bool ContributingSampleAt(double t, float& s)
  {
    if (!this->SkipEmptyCells)
    {
      s = this->SampleAt(t);
      return true;
    }
    ++this->Stats.Samples;
    float f[3];
    if (this->Field.LocateCell(this->IndexPosition(t), this->Corners, f))
    {
      const float* c = this->Corners.Values;
      const auto range = std::minmax({ c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7] });
      this->Corners.Contributing = this->Rule.IsPossiblyContributing(range.first, range.second);
    }
    if (!this->Corners.Contributing)
    {
      return false;
    }
    s = View::Interpolate(this->Corners.Values, f);
    return true;
  }
  /// The world-space gradient at ray parameter t.
  Vec3 WorldGradient(double t)
  {
    ++this->Stats.GradientEvaluations;
    const Vec3 g = this->Field.Gradient(this->IndexPosition(t), this->P.Interp, this->Differences);
    return this->P.WorldToIndex.TransposeTransformVector(g);
  }
  /// Scales opacity a by the gradient opacity of gradient g (computed only when needed);
  /// false when the result is 0.
  bool ApplyGradientOpacity(float& a, double t, Vec3& g, bool& haveGradient)
  {
    if (!this->P.UseGradientOpacity)
    {
      return true;
    }
    if (this->GradientOpacityConstant)
    {
      a *= this->GradientOpacityValue;
    }
    else
    {
      if (!haveGradient)
      {
        g = this->WorldGradient(t);
        haveGradient = true;
      }
      a *= this->P.GradientOpacity.Evaluate(Length(g));
    }
    return a != 0.f;
  }
  /// The sample s at t and its corrected opacity a (with gradient opacity; g holds the
  /// gradient when haveGradient), counted and recorded as a hit; false when a is 0.
  bool ContributingOpacity(double t, float& s, float& a, Vec3& g, bool& haveGradient)
  {
    if (!this->ContributingSampleAt(t, s))
    {
      return false;
    }
    a = this->P.Opacity.Evaluate(s);
    if (a == 0.f || !this->ApplyGradientOpacity(a, t, g, haveGradient))
    {
      return false;
    }
    a = this->CorrectOpacity(a);
    ++this->Stats.ContributingSamples;
    this->RecordHit(t);
    return true;
  }
  float CorrectOpacity(float a) const
  {
    if (this->OpacityExponent == 1.f || a >= 1.f)
    {
      return a;
    }
    const float transparency = 1.f - a;
    // The sample distances of half and a quarter of the unit distance by square roots.
    if (this->OpacityExponent == 0.5f)
    {
      return 1.f - std::sqrt(transparency);
    }
    if (this->OpacityExponent == 0.25f)
    {
      return 1.f - std::sqrt(std::sqrt(transparency));
    }
    return 1.f - std::pow(transparency, this->OpacityExponent);
  }
  double SpecularTerm(double ndh) const
  {
    return this->IntegerSpecularPower >= 0 ? IntegerPower(ndh, this->IntegerSpecularPower)
                                           : std::pow(ndh, this->P.SpecularPower);
  }
  /// Shades rgb in place at ray parameter t with world gradient g (Blinn-Phong, two-sided).
  void Shade(float rgb[3], double t, const Vec3& g) const;
};

template <class View>
void RayContext<View>::Shade(float rgb[3], double t, const Vec3& g) const
{
  const double len = Length(g);
  double diffuse[3] = { 0.0, 0.0, 0.0 };
  double specular[3] = { 0.0, 0.0, 0.0 };
  auto add = [&](const Vec3& color, double attenuation, double ndl, double ndh) {
    const double spec = ndh > 0.0 ? this->SpecularTerm(ndh) : 0.0;
    for (int c = 0; c < 3; ++c)
    {
      diffuse[c] += attenuation * color[c] * ndl;
      specular[c] += attenuation * color[c] * spec;
    }
  };
  if (len > 0.0)
  {
    const Vec3 toEye = -this->WorldRay.Direction;
    Vec3 n = (-1.0 / len) * g;
    if (Dot(n, toEye) < 0.0)
    {
      n = -n;
    }
    for (std::size_t i = 0; i < this->DirectionalLights.size(); ++i)
    {
      const RayCaster::DirectionalLight& light = this->DirectionalLights[i];
      const double ndl = Dot(n, light.ToLight);
      if (ndl > 0.0)
      {
        const Vec3 h = i < MaxHoistedLights ? this->HalfVectors[i] : this->HalfVector(light.ToLight);
        add(light.Color, 1.0, ndl, Dot(n, h));
      }
    }
    for (const Light* light : this->PositionalLights)
    {
      const Vec3 x = this->WorldRay.Origin + t * this->WorldRay.Direction;
      const Vec3 toLight = light->Position - x;
      const double dist = Length(toLight);
      const Vec3 l = Normalized(toLight);
      const double denom =
        light->Attenuation.X + dist * (light->Attenuation.Y + dist * light->Attenuation.Z);
      double attenuation = denom > 0.0 ? 1.0 / denom : 1.0;
      if (light->ConeAngle < 90.0)
      {
        const Vec3 spot = Normalized(light->FocalPoint - light->Position);
        const double c = Dot(-l, spot);
        attenuation *= (c < std::cos(light->ConeAngle * (M_PI / 180.0)))
          ? 0.0
          : std::pow(std::max(c, 0.0), light->Exponent);
      }
      const double ndl = Dot(n, l);
      if (ndl > 0.0 && attenuation != 0.0)
      {
        add(light->Color, attenuation, ndl, Dot(n, Normalized(l + toEye)));
      }
    }
  }
  for (int c = 0; c < 3; ++c)
  {
    const double v =
      rgb[c] * (this->P.Ambient + this->P.Diffuse * diffuse[c]) + this->P.Specular * specular[c];
    rgb[c] = static_cast<float>(std::min(v, 1.0));
  }
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

// Each ray function: bool operator()(long k, bool previousSampled) visits lattice sample
// k (false stops the ray) and Finish(rgba) writes the result.

template <class Context>
struct CompositeFunction
{
  Context& C;
  float Rgb[3] = { 0.f, 0.f, 0.f };
  float Alpha = 0.f;

  bool operator()(long k, bool)
  {
    const double t = k * this->C.Dt;
    float s, a;
    Vec3 g;
    bool haveGradient = false;
    if (!this->C.ContributingOpacity(t, s, a, g, haveGradient))
    {
      return true;
    }
    float rgb[3];
    this->C.P.Color.Lookup(s, rgb);
    if (this->C.P.Shade)
    {
      this->C.Shade(rgb, t, haveGradient ? g : this->C.WorldGradient(t));
    }
    const float w = (1.f - this->Alpha) * a;
    for (int c = 0; c < 3; ++c)
    {
      this->Rgb[c] += w * rgb[c];
    }
    this->Alpha += w;
    return this->Alpha < this->C.P.TerminationOpacity;
  }
  void Finish(float rgba[4]) const
  {
    for (int c = 0; c < 3; ++c)
    {
      rgba[c] = this->Rgb[c];
    }
    rgba[3] = this->Alpha;
  }
};

/// Maximum (Sign = 1) or minimum (Sign = -1) intensity.
template <class Context, int Sign>
struct ExtremeFunction
{
  Context& C;
  float Extreme = 0.f;
  bool Found = false;

  bool operator()(long k, bool)
  {
    const float s = this->C.SampleAt(k * this->C.Dt);
    if (!this->Found || Sign * s > Sign * this->Extreme)
    {
      this->Extreme = s;
      this->Found = true;
    }
    return true;
  }
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

template <class Context>
struct AverageFunction
{
  Context& C;
  double Sum = 0.0;
  std::uint64_t Count = 0;

  bool operator()(long k, bool)
  {
    const float s = this->C.SampleAt(k * this->C.Dt);
    if (s >= this->C.P.AverageRange[0] && s <= this->C.P.AverageRange[1])
    {
      this->Sum += s;
      ++this->Count;
      ++this->C.Stats.ContributingSamples;
    }
    return true;
  }
  void Finish(float rgba[4]) const
  {
    float rgb[3] = { 0.f, 0.f, 0.f };
    float a = 0.f;
    if (this->Count > 0)
    {
      const double mean = this->Sum / static_cast<double>(this->Count);
      a = this->C.P.Opacity.Evaluate(mean);
      this->C.P.Color.Lookup(mean, rgb);
    }
    Premultiply(rgb, a, rgba);
  }
};

template <class Context>
struct AdditiveFunction
{
  Context& C;
  float Rgb[3] = { 0.f, 0.f, 0.f };
  float Alpha = 0.f;

  bool operator()(long k, bool)
  {
    float s, a;
    Vec3 g;
    bool haveGradient = false;
    if (!this->C.ContributingOpacity(k * this->C.Dt, s, a, g, haveGradient))
    {
      return true;
    }
    float rgb[3];
    this->C.P.Color.Lookup(s, rgb);
    for (int c = 0; c < 3; ++c)
    {
      this->Rgb[c] += a * rgb[c];
    }
    this->Alpha += a;
    return true;
  }
  void Finish(float rgba[4]) const
  {
    for (int c = 0; c < 3; ++c)
    {
      rgba[c] = std::min(this->Rgb[c], 1.f);
    }
    rgba[3] = std::min(this->Alpha, 1.f);
  }
};

template <class Context>
struct IsoSurfaceFunction
{
  Context& C;
  const std::vector<double>& IsoValues; // sorted
  float Rgb[3] = { 0.f, 0.f, 0.f };
  float Alpha = 0.f;
  float Previous = 0.f;

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
    float a = this->C.P.Opacity.Evaluate(v);
    ++this->C.Stats.ContributingSamples;
    this->C.RecordHit(t);
    if (a == 0.f)
    {
      return true;
    }
    float rgb[3];
    this->C.P.Color.Lookup(v, rgb);
    if (this->C.P.Shade)
    {
      this->C.Shade(rgb, t, this->C.WorldGradient(t));
    }
    const float w = (1.f - this->Alpha) * a;
    for (int c = 0; c < 3; ++c)
    {
      this->Rgb[c] += w * rgb[c];
    }
    this->Alpha += w;
    return this->Alpha < this->C.P.TerminationOpacity;
  }

  bool operator()(long k, bool previousSampled)
  {
    const double t1 = k * this->C.Dt;
    const float s1 = this->C.SampleAt(t1);
    const float s0 = this->Previous;
    this->Previous = s1;
    if (!previousSampled || s0 == s1)
    {
      return true;
    }
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
      if (!this->Composite(this->Refine(t0, s0, t1, s1, v), v))
      {
        return false;
      }
    }
    return true;
  }
  void Finish(float rgba[4]) const
  {
    for (int c = 0; c < 3; ++c)
    {
      rgba[c] = this->Rgb[c];
    }
    rgba[3] = this->Alpha;
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

/// Visits the lattice samples of ranges in order; returns the last one visited.
template <class Function>
long Walk(const std::vector<LatticeRange>& ranges, Function& fn)
{
  long previous = std::numeric_limits<long>::min();
  for (const LatticeRange& r : ranges)
  {
    for (long k = std::max(r.First, previous + 1); k <= r.Last; ++k)
    {
      const bool follows = (k == previous + 1);
      previous = k;
      if (!fn(k, follows))
      {
        return k;
      }
    }
  }
  return previous;
}

/// Casts fn over ranges into rgba and counts the cells the visited stretches crossed.
template <class Function>
void Run(Function&& fn, const std::vector<LatticeRange>& ranges, float rgba[4])
{
  const long last = Walk(ranges, fn);
  fn.Finish(rgba);
  const auto& c = fn.C;
  for (const LatticeRange& r : ranges)
  {
    if (r.First > last)
    {
      break;
    }
    c.Stats.Cells +=
      CellsCrossed(c.IndexPosition(r.First * c.Dt), c.IndexPosition(std::min(r.Last, last) * c.Dt));
  }
}

} // namespace

void RayCaster::CastRay(const Ray& ray, int px, int py, const SegmentSource& source,
  std::vector<Segment>& segments, std::vector<LatticeRange>& ranges, float rgba[4],
  CastStatistics& stats, double* firstHit) const
{
  this->Field->Dispatch([&](const auto& field) {
    this->CastRayIn(field, ray, px, py, source, segments, ranges, rgba, stats, firstHit);
  });
}

template <class View>
void RayCaster::CastRayIn(const View& field, const Ray& ray, int px, int py,
  const SegmentSource& source, std::vector<Segment>& segments, std::vector<LatticeRange>& ranges,
  float rgba[4], CastStatistics& stats, double* firstHit) const
{
  rgba[0] = rgba[1] = rgba[2] = rgba[3] = 0.f;
  if (firstHit)
  {
    *firstHit = std::numeric_limits<double>::infinity();
  }
  const Matrix4& w2i = this->Params->WorldToIndex;
  const Vec3 indexOrigin = w2i.TransformPoint(ray.Origin);
  const Vec3 indexDirection = w2i.TransformVector(ray.Direction);
  double tEnter, tExit;
  if (!ClipToField(*this->Field, indexOrigin, indexDirection, ray, tEnter, tExit))
  {
    return;
  }
  ++stats.Rays;
  segments.clear();
  source.GetSegments(px, py, ray, segments);
  stats.Segments += segments.size();
  const double dt = this->Params->SampleDistance;
  SegmentsToLatticeRanges(segments, tEnter, tExit, dt, ranges);
  if (ranges.empty())
  {
    return;
  }
  using Context = RayContext<View>;
  Context context{ field, *this->Params, ray, indexOrigin, indexDirection, dt,
    this->OpacityExponent, this->GradientOpacityConstant, this->GradientOpacityValue,
    this->IntegerSpecularPower, this->SkipEmptyCells, this->Rule, this->DirectionalLights,
    this->PositionalLights, stats, std::numeric_limits<double>::infinity(), {}, {}, {} };
  context.Begin();
  switch (this->Params->Blend)
  {
    case BlendMode::Composite:
      Run(CompositeFunction<Context>{ context }, ranges, rgba);
      break;
    case BlendMode::MaximumIntensity:
      Run(ExtremeFunction<Context, 1>{ context }, ranges, rgba);
      break;
    case BlendMode::MinimumIntensity:
      Run(ExtremeFunction<Context, -1>{ context }, ranges, rgba);
      break;
    case BlendMode::AverageIntensity:
      Run(AverageFunction<Context>{ context }, ranges, rgba);
      break;
    case BlendMode::Additive:
      Run(AdditiveFunction<Context>{ context }, ranges, rgba);
      break;
    case BlendMode::IsoSurface:
      Run(IsoSurfaceFunction<Context>{ context, this->SortedIsoValues }, ranges, rgba);
      break;
  }
  if (firstHit)
  {
    *firstHit = context.FirstHit;
  }
}

namespace
{
/// Casts the tiles of one band of rows; vtkSMPTools functor.
template <class Cast>
struct TileCaster
{
  const Cast& CastOne; ///< casts one ray: (ray, px, py, scratch, rgba)
  const ViewGeometry& View;
  const float* Depth;
  const SegmentSource& Source;
  float* Image;
  int TilesX;
  int FirstTileRow;

  struct Scratch
  {
    std::vector<Segment> Segments;
    std::vector<LatticeRange> Ranges;
    CastStatistics Stats;
  };
  vtkSMPThreadLocal<Scratch> Local;

  void Initialize() {}
  void operator()(vtkIdType begin, vtkIdType end)
  {
    Scratch& scratch = this->Local.Local();
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
          const std::size_t pixel = static_cast<std::size_t>(py) * this->View.Width + px;
          if (!this->Source.MayHaveSegments(px, py))
          {
            std::fill_n(this->Image + 4 * pixel, 4, 0.f);
            continue;
          }
          Ray ray = this->View.MakeRay(px, py);
          if (this->Depth && this->Depth[pixel] < 1.f)
          {
            ray.TMax =
              std::min(ray.TMax, this->View.DepthToParameter(ray, px, py, this->Depth[pixel]));
          }
          this->CastOne(ray, px, py, scratch, this->Image + 4 * pixel);
        }
      }
    }
  }
  void Reduce() {}
};
}

bool RayCaster::CastImage(const ViewGeometry& view, const float* depth,
  const SegmentSource& source, float* rgba, CastStatistics& stats,
  const std::function<bool(double)>& progress) const
{
  return this->Field->Dispatch([&](const auto& field) {
    return this->CastImageIn(field, view, depth, source, rgba, stats, progress);
  });
}

template <class View>
bool RayCaster::CastImageIn(const View& field, const ViewGeometry& view, const float* depth,
  const SegmentSource& source, float* rgba, CastStatistics& stats,
  const std::function<bool(double)>& progress) const
{
  // Every pixel of a cast band is written by its tile (zero when no ray is cast).
  const int tilesX = (view.Width + TileSize - 1) / TileSize;
  const int tilesY = (view.Height + TileSize - 1) / TileSize;
  bool completed = true;
  auto castOne = [&](const Ray& ray, int px, int py, auto& scratch, float* pixel) {
    this->CastRayIn(field, ray, px, py, source, scratch.Segments, scratch.Ranges, pixel,
      scratch.Stats, nullptr);
  };
  TileCaster<decltype(castOne)> caster{ castOne, view, depth, source, rgba, tilesX, 0, {} };
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
    stats += scratch.Stats;
  }
  return completed;
}

} // namespace parc
