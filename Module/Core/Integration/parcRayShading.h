// The casters' shading arithmetic shared by the ray context (parcRayContext.h): sign flips,
// whole powers, the interpolation of quantized-normal shading factors and the colour sums
// in registers. Internal to the casters.
#ifndef parc_RayShading_h
#define parc_RayShading_h

#include "parcRayCaster.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

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


/// x^n for a whole n >= 0 by repeated squaring.
inline float IntegerPower(float x, int n)
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
PARC_NOINLINE inline void AppendEvent(
  std::vector<RayEvent>& events, double t, const float rgb[3], float a, bool premultiplied)
{
  events.push_back({ t, { rgb[0], rgb[1], rgb[2] }, a, premultiplied });
}

} // namespace parc::casting

#endif
