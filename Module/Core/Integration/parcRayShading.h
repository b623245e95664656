// The ray context's shading (parcRayContext.h): Blinn-Phong for one sample and for the
// lanes of a block (four or, with wide vectors, eight at a time), shading by quantized
// normals, positional lights and shadow visibility, over the arithmetic they share (sign
// flips, whole powers, the interpolation of quantized-normal shading factors, colour sums
// in registers). Internal to the casters.
#ifndef parc_RayShading_h
#define parc_RayShading_h

#include "parcInterpolation.h"
#include "parcRayContext.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>
#if PARC_WIDE_VECTORS
#include <immintrin.h>
#endif

namespace parc::casting
{

/// x when sign > 0, else -x, without a branch (the sign of a normal towards the eye is
/// as unpredictable as the data).
inline float FlipUnlessPositive(float x, float sign)
{
  std::uint32_t bits;
  std::memcpy(&bits, &x, sizeof(bits));
  bits ^= static_cast<std::uint32_t>(!(sign > 0.f)) << 31;
  std::memcpy(&x, &bits, sizeof(bits));
  return x;
}

/// Blinn-Phong's weights of one light, the one definition the scalar shading shares
/// (RayContext::Shade and AddPositionalLights, and the quantized normals' table;
/// ShadeLanes is its form for the lanes of a block): false when the light is behind the
/// surface (n.l <= 0), weights untouched; else the diffuse weight n.l and the specular
/// weight power(n.h) where n.h > 0, 0 elsewhere. halfDot gives n.h (computed only for a
/// light in front). T is float for the cast's samples, double for the table and
/// positional lights.
template <class T, class HalfDot, class Power>
inline bool BlinnPhongWeights(T ndl, HalfDot halfDot, Power power, T& diffuse, T& specular)
{
  if (!(ndl > T(0)))
  {
    return false;
  }
  const T ndh = halfDot();
  diffuse = ndl;
  specular = ndh > T(0) ? power(ndh) : T(0);
  return true;
}

/// power = base^n for a whole n >= 0 by repeated squaring, power holding 1 on entry. T is
/// float or a register of lanes (each lane its own power: the same products lane by lane;
/// passed by reference, so that no function without wide vectors takes or returns one).
template <class T>
PARC_HOT_INLINE void IntegerPower(const T& base, int n, T& power)
{
  T x = base;
  for (; n > 0; n >>= 1)
  {
    if (n & 1)
    {
      power *= x;
    }
    x *= x;
  }
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
  _mm_storeu_ps(diffuse, Trilinear(d, fx, fy, fz));
  _mm_storeu_ps(specular, Trilinear(s, fx, fy, fz));
#else
  for (int c = 0; c < 4; ++c)
  {
    float d[8], s[8];
    for (int n = 0; n < 8; ++n)
    {
      d[n] = table[codes[n]].Diffuse[c];
      s[n] = table[codes[n]].Specular[c];
    }
    diffuse[c] = Trilinear(d, f);
    specular[c] = Trilinear(s, f);
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
  const auto lerp = [](__m128 a, __m128 b, float t) { return Lerp(a, b, _mm_set1_ps(t)); };
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

#if defined(__SSE2__)
template <class View>
PARC_HOT_INLINE __m128 RayContext<View>::SpecularLanes(__m128 ndh) const
{
  if (this->K.IntegerSpecularPower < 0)
  {
    return PowOfUnitInterval(ndh, _mm_set1_ps(this->K.SpecularPower));
  }
  __m128 power = _mm_set1_ps(1.f);
  IntegerPower(ndh, this->K.IntegerSpecularPower, power);
  return power;
}
#endif

template <class View>
inline float RayContext<View>::SpecularTerm(float ndh) const
{
#if defined(__SSE2__)
  // SpecularLanes on one lane, so that a sample gets the bits it gets in a batch.
  return _mm_cvtss_f32(this->SpecularLanes(_mm_set1_ps(ndh)));
#else
  if (this->K.IntegerSpecularPower < 0)
  {
    return std::pow(ndh, this->K.SpecularPower);
  }
  float power = 1.f;
  IntegerPower(ndh, this->K.IntegerSpecularPower, power);
  return power;
#endif
}

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
    const auto power = [this](float ndh) { return this->SpecularTerm(ndh); };
    for (std::size_t i = 0; i < count; ++i)
    {
      const RayCaster::DirectionalLight& light = lights[i];
      float ndl, spec;
      const auto halfDot = [&] {
        return Dot(
          n, i < MaxHoistedLights ? this->HalfVectors[i] : this->HalfVector(light.ToLight));
      };
      if (BlinnPhongWeights(Dot(n, light.ToLight), halfDot, power, ndl, spec))
      {
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

#if PARC_WIDE_VECTORS
/// v.X ax + v.Y ay + v.Z az, eight lanes (ShadeLanes' order).
PARC_TARGET_WIDE_VECTORS PARC_HOT_INLINE __m256 DotEight(
  __m256 ax, __m256 ay, __m256 az, const Vec3f& v)
{
  const __m256 x = _mm256_mul_ps(ax, _mm256_set1_ps(v.X));
  const __m256 y = _mm256_mul_ps(ay, _mm256_set1_ps(v.Y));
  return _mm256_add_ps(_mm256_add_ps(x, y), _mm256_mul_ps(az, _mm256_set1_ps(v.Z)));
}

template <class View>
void RayContext<View>::ShadeEightLanes()
{
  LaneBatch& b = this->Batch;
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.f);
  const __m256 signBit = _mm256_set1_ps(-0.f);
  const RayCaster::DirectionalLight* lights = this->K.DirectionalLights.data();
  const std::size_t count = this->K.DirectionalLights.size();
  const int channels = this->K.GreyLights ? 1 : 3;
  static_assert(LatticeBlock::Size % 8 == 0, "whole groups of eight lanes in a batch");
  for (int i = 0; i < b.Count; i += 8)
  {
    const __m256 gx = _mm256_loadu_ps(b.Gradient[0] + i);
    const __m256 gy = _mm256_loadu_ps(b.Gradient[1] + i);
    const __m256 gz = _mm256_loadu_ps(b.Gradient[2] + i);
    const __m256 length = _mm256_sqrt_ps(_mm256_add_ps(
      _mm256_add_ps(_mm256_mul_ps(gx, gx), _mm256_mul_ps(gy, gy)), _mm256_mul_ps(gz, gz)));
    const __m256 valid = _mm256_cmp_ps(length, zero, _CMP_GT_OQ);
    const __m256 back = _mm256_cmp_ps(DotEight(gx, gy, gz, this->ToEye), zero, _CMP_NGT_UQ);
    const __m256 scale =
      _mm256_xor_ps(_mm256_div_ps(one, length), _mm256_and_ps(back, signBit));
    const __m256 nx = _mm256_mul_ps(scale, gx), ny = _mm256_mul_ps(scale, gy);
    const __m256 nz = _mm256_mul_ps(scale, gz);
    __m256 diffuse[3] = { zero, zero, zero }, specular[3] = { zero, zero, zero };
    for (std::size_t l = 0; l < count; ++l)
    {
      const RayCaster::DirectionalLight& light = lights[l];
      const __m256 ndl = DotEight(nx, ny, nz, light.ToLight);
      const __m256 lit = _mm256_and_ps(valid, _mm256_cmp_ps(ndl, zero, _CMP_GT_OQ));
      const __m256 ndh = DotEight(nx, ny, nz, this->HalfVectors[l]);
      __m256 power = one;
      IntegerPower(ndh, this->K.IntegerSpecularPower, power);
      const __m256 spec = _mm256_and_ps(_mm256_cmp_ps(ndh, zero, _CMP_GT_OQ), power);
      for (int c = 0; c < channels; ++c)
      {
        const __m256 d = _mm256_mul_ps(ndl, _mm256_set1_ps((&light.Diffuse.X)[c]));
        const __m256 sc = _mm256_mul_ps(spec, _mm256_set1_ps((&light.Specular.X)[c]));
        diffuse[c] = _mm256_blendv_ps(diffuse[c], _mm256_add_ps(diffuse[c], d), lit);
        specular[c] = _mm256_blendv_ps(specular[c], _mm256_add_ps(specular[c], sc), lit);
      }
    }
    for (int c = channels; c < 3; ++c) // white lights: the same as red
    {
      diffuse[c] = diffuse[0];
      specular[c] = specular[0];
    }
    for (int c = 0; c < 3; ++c)
    {
      const __m256 rgb = _mm256_loadu_ps(b.Rgb[c] + i);
      const __m256 ambient = _mm256_set1_ps(this->K.Ambient[c]);
      const __m256 shaded =
        _mm256_add_ps(_mm256_mul_ps(rgb, _mm256_add_ps(ambient, diffuse[c])), specular[c]);
      _mm256_storeu_ps(b.Rgb[c] + i, _mm256_min_ps(one, shaded));
    }
  }
}
#endif

template <class View>
PARC_HOT_INLINE void RayContext<View>::ShadeLanes()
{
  LaneBatch& b = this->Batch;
#if PARC_WIDE_VECTORS
  // Eight lanes at a time where the caster runs wide vectors; a fractional power keeps
  // PowOfUnitInterval's four.
  if (this->K.WideVectors && this->K.IntegerSpecularPower >= 0)
  {
    this->ShadeEightLanes();
    return;
  }
#endif
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
      const __m128 power = this->SpecularLanes(ndh);
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
  const auto power = [this](double ndh) {
    return static_cast<double>(this->SpecularTerm(static_cast<float>(ndh)));
  };
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
    double ndl, spec;
    const auto halfDot = [&] { return Dot(normal, Normalized(l - this->WorldRay.Direction)); };
    if (attenuation != 0.0 && BlinnPhongWeights(Dot(normal, l), halfDot, power, ndl, spec))
    {
      if (light->ShadowAttenuation > 0.0 && this->Shadows)
      {
        attenuation *= this->Visibility(
          x, l, dist, positional.Index, static_cast<float>(light->ShadowAttenuation));
      }
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

#if defined(__SSE2__)
template <class View>
PARC_HOT_INLINE __m128 RayContext<View>::ShadeByNormals(int j, __m128 rgb) const
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

template <class View>
PARC_HOT_INLINE void RayContext<View>::InterpolateNormalFactors(
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
#endif



} // namespace parc::casting

#endif
