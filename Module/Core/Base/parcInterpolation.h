// PARC for VTK: the one trilinear interpolation of the core, in float, for a value and for
// four lanes at once: samples, gradients (of voxel differences) and quantized-normal
// shading factors all interpolate through it, so that they round alike.
#ifndef parcInterpolation_h
#define parcInterpolation_h

#include "parcMath.h" // For PARC_HOT_INLINE

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace parc
{

/// a + t (b - a).
PARC_HOT_INLINE float Lerp(float a, float b, float t)
{
  return a + t * (b - a);
}

/// The trilinear interpolation of 8 corner values c (corner n at x offset n & 1, y
/// (n >> 1) & 1, z (n >> 2) & 1) at fractions f: along x, then y, then z.
PARC_HOT_INLINE float Trilinear(const float c[8], const float f[3])
{
  const float c00 = Lerp(c[0], c[1], f[0]);
  const float c10 = Lerp(c[2], c[3], f[0]);
  const float c01 = Lerp(c[4], c[5], f[0]);
  const float c11 = Lerp(c[6], c[7], f[0]);
  return Lerp(Lerp(c00, c10, f[1]), Lerp(c01, c11, f[1]), f[2]);
}

#if defined(__SSE2__)
/// Lerp lane by lane.
PARC_HOT_INLINE __m128 Lerp(__m128 a, __m128 b, __m128 t)
{
  return _mm_add_ps(a, _mm_mul_ps(t, _mm_sub_ps(b, a)));
}

/// Trilinear lane by lane: the same operations in the same order, so the same bits in
/// each lane as Trilinear of that lane's corners and fractions.
PARC_HOT_INLINE __m128 Trilinear(const __m128 c[8], __m128 fx, __m128 fy, __m128 fz)
{
  const __m128 c00 = Lerp(c[0], c[1], fx);
  const __m128 c10 = Lerp(c[2], c[3], fx);
  const __m128 c01 = Lerp(c[4], c[5], fx);
  const __m128 c11 = Lerp(c[6], c[7], fx);
  return Lerp(Lerp(c00, c10, fy), Lerp(c01, c11, fy), fz);
}
#endif

} // namespace parc

#endif
