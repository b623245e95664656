// PARC for VTK: small fixed-size vector and matrix helpers of the core.
#ifndef parcMath_h
#define parcMath_h

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

/// Marks the small per-sample functions the caster's loops must inline.
/// Marks rare work kept out of those loops, so that they stay small.
#if defined(__GNUC__)
#define PARC_HOT_INLINE inline __attribute__((always_inline))
#define PARC_NOINLINE __attribute__((noinline))
#else
#define PARC_HOT_INLINE inline
#define PARC_NOINLINE
#endif

/// Marks a function compiled for AVX2 (and without FMA: no multiplication and addition is
/// fused, so every operation rounds as in the baseline code). PARC_WIDE_VECTORS is 1 where
/// the compiler can do so and the processor can be asked at run time (HasWideVectors).
#if defined(__GNUC__) && defined(__x86_64__)
#define PARC_WIDE_VECTORS 1
#define PARC_TARGET_WIDE_VECTORS __attribute__((target("avx2")))
#else
#define PARC_WIDE_VECTORS 0
#define PARC_TARGET_WIDE_VECTORS
#endif

namespace parc
{

/// Whether this processor (and its operating system) runs the functions marked
/// PARC_TARGET_WIDE_VECTORS.
inline bool HasWideVectors()
{
#if PARC_WIDE_VECTORS
  return __builtin_cpu_supports("avx2");
#else
  return false;
#endif
}

/// A 3-vector of doubles: world coordinates, voxel-index coordinates or directions.
struct Vec3
{
  double X = 0.0, Y = 0.0, Z = 0.0;

  constexpr Vec3() = default;
  constexpr Vec3(double x, double y, double z)
    : X(x)
    , Y(y)
    , Z(z)
  {
  }
  double operator[](int i) const { return i == 0 ? X : (i == 1 ? Y : Z); }
  double& operator[](int i) { return i == 0 ? X : (i == 1 ? Y : Z); }
};

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return { a.X + b.X, a.Y + b.Y, a.Z + b.Z }; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return { a.X - b.X, a.Y - b.Y, a.Z - b.Z }; }
inline Vec3 operator-(const Vec3& a) { return { -a.X, -a.Y, -a.Z }; }
inline Vec3 operator*(double s, const Vec3& a) { return { s * a.X, s * a.Y, s * a.Z }; }
inline double Dot(const Vec3& a, const Vec3& b) { return a.X * b.X + a.Y * b.Y + a.Z * b.Z; }
inline Vec3 Cross(const Vec3& a, const Vec3& b)
{
  return { a.Y * b.Z - a.Z * b.Y, a.Z * b.X - a.X * b.Z, a.X * b.Y - a.Y * b.X };
}
inline double Length(const Vec3& a) { return std::sqrt(Dot(a, a)); }
/// The unit vector along a; the zero vector stays zero.
inline Vec3 Normalized(const Vec3& a)
{
  const double len = Length(a);
  return len > 0.0 ? (1.0 / len) * a : a;
}

/// A 3-vector of floats: the caster's per-sample shading arithmetic (gradients, normals,
/// light and half vectors).
struct Vec3f
{
  float X = 0.f, Y = 0.f, Z = 0.f;

  constexpr Vec3f() = default;
  constexpr Vec3f(float x, float y, float z)
    : X(x)
    , Y(y)
    , Z(z)
  {
  }
  explicit Vec3f(const Vec3& v)
    : X(static_cast<float>(v.X))
    , Y(static_cast<float>(v.Y))
    , Z(static_cast<float>(v.Z))
  {
  }
};

inline Vec3f operator+(const Vec3f& a, const Vec3f& b)
{
  return { a.X + b.X, a.Y + b.Y, a.Z + b.Z };
}
inline Vec3f operator*(float s, const Vec3f& a)
{
  return { s * a.X, s * a.Y, s * a.Z };
}
inline float Dot(const Vec3f& a, const Vec3f& b) { return a.X * b.X + a.Y * b.Y + a.Z * b.Z; }
inline float Length(const Vec3f& a) { return std::sqrt(Dot(a, a)); }

/// A 4x4 row-major matrix of doubles acting on column vectors (VTK's convention).
struct Matrix4
{
  std::array<double, 16> M{ 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1 };

  double operator()(int r, int c) const { return M[4 * r + c]; }
  double& operator()(int r, int c) { return M[4 * r + c]; }

  /// Affine point transform (no perspective division).
  Vec3 TransformPoint(const Vec3& p) const
  {
    return { M[0] * p.X + M[1] * p.Y + M[2] * p.Z + M[3],
      M[4] * p.X + M[5] * p.Y + M[6] * p.Z + M[7], M[8] * p.X + M[9] * p.Y + M[10] * p.Z + M[11] };
  }
  /// Projective point transform with division by w.
  Vec3 TransformHomogeneous(const Vec3& p) const
  {
    const double w = M[12] * p.X + M[13] * p.Y + M[14] * p.Z + M[15];
    const Vec3 q = TransformPoint(p);
    return (1.0 / w) * q;
  }
  /// The linear part applied to a direction.
  Vec3 TransformVector(const Vec3& v) const
  {
    return { M[0] * v.X + M[1] * v.Y + M[2] * v.Z, M[4] * v.X + M[5] * v.Y + M[6] * v.Z,
      M[8] * v.X + M[9] * v.Y + M[10] * v.Z };
  }
  /// The transpose of the linear part applied to a vector (gradients go this way).
  Vec3 TransposeTransformVector(const Vec3& v) const
  {
    return { M[0] * v.X + M[4] * v.Y + M[8] * v.Z, M[1] * v.X + M[5] * v.Y + M[9] * v.Z,
      M[2] * v.X + M[6] * v.Y + M[10] * v.Z };
  }
};

/// The affine map m followed by a translation by offset (offset added to m's translation).
inline Matrix4 Translated(const Matrix4& m, const Vec3& offset)
{
  Matrix4 out = m;
  for (int r = 0; r < 3; ++r)
  {
    out(r, 3) += offset[r];
  }
  return out;
}

/// The inverse of m; returns false (and leaves out untouched) when m is singular.
bool Invert(const Matrix4& m, Matrix4& out);
/// a * b.
Matrix4 Multiply(const Matrix4& a, const Matrix4& b);

/// The smallest float at least v: a float s is below v exactly when s is below it.
inline float FloatAtLeast(double v)
{
  const float f = static_cast<float>(v);
  return static_cast<double>(f) < v ? std::nextafter(f, std::numeric_limits<float>::infinity())
                                    : f;
}
/// The largest float not above x.
inline float FloatAtMost(double x)
{
  const float f = static_cast<float>(x);
  return static_cast<double>(f) > x ? std::nextafter(f, -std::numeric_limits<float>::infinity())
                                    : f;
}
/// The index of the lowest set bit of x != 0 (an unsigned integer of up to 64 bits).
template <typename Bits>
PARC_HOT_INLINE int CountTrailingZeros(Bits x)
{
  static_assert(std::is_unsigned<Bits>::value && sizeof(Bits) <= 8, "unsigned, up to 64 bits");
#if defined(__GNUC__)
  return sizeof(Bits) > sizeof(unsigned) ? __builtin_ctzll(x)
                                         : __builtin_ctz(static_cast<unsigned>(x));
#else
  int n = 0;
  for (; !(x & 1u); x >>= 1)
  {
    ++n;
  }
  return n;
#endif
}
#if defined(__SSE2__)
/// mask ? a : b, lane by lane (mask lanes all ones or all zeros).
PARC_HOT_INLINE __m128 Select(__m128 mask, __m128 a, __m128 b)
{
  return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b));
}
/// 2^y for y in [-126, 126], lane by lane: 2^n 2^f with n the nearest integer and
/// f in [-1/2, 1/2] from its Taylor polynomial of degree 7 (truncation below 1e-8).
/// Exactly 1 at y = 0.
PARC_HOT_INLINE __m128 Exp2InRange(__m128 y)
{
  const __m128i n = _mm_cvtps_epi32(y); // nearest (the default rounding mode)
  const __m128 f = _mm_sub_ps(y, _mm_cvtepi32_ps(n));
  // ln(2)^k / k!, k = 7 down to 1.
  constexpr float c[] = { 1.5252734e-5f, 1.5403530e-4f, 1.3333558e-3f, 9.6181291e-3f,
    5.5504109e-2f, 2.4022651e-1f, 6.9314718e-1f };
  __m128 p = _mm_set1_ps(c[0]);
  for (int i = 1; i < 7; ++i)
  {
    p = _mm_add_ps(_mm_mul_ps(p, f), _mm_set1_ps(c[i]));
  }
  p = _mm_add_ps(_mm_mul_ps(p, f), _mm_set1_ps(1.f));
  const __m128 twoToN =
    _mm_castsi128_ps(_mm_slli_epi32(_mm_add_epi32(n, _mm_set1_epi32(127)), 23));
  return _mm_mul_ps(p, twoToN);
}
/// log2(x) for positive normal x, lane by lane: k + log2(m), x = m 2^k, m in
/// [sqrt(1/2), sqrt(2)), log2(m) from the series of atanh((m - 1) / (m + 1)) to its fifth term
/// (truncation below 1e-9). Exactly 0 at x = 1.
PARC_HOT_INLINE __m128 Log2OfNormal(__m128 x)
{
  const __m128i bits = _mm_castps_si128(x);
  const __m128i exponent = _mm_sub_epi32(_mm_srli_epi32(bits, 23), _mm_set1_epi32(127));
  const __m128 one = _mm_set1_ps(1.f);
  __m128 m = _mm_castsi128_ps(_mm_or_si128(
    _mm_and_si128(bits, _mm_set1_epi32(0x007fffff)), _mm_castps_si128(one))); // [1, 2)
  const __m128 above = _mm_cmpgt_ps(m, _mm_set1_ps(1.41421356f));
  m = Select(above, _mm_mul_ps(m, _mm_set1_ps(0.5f)), m);
  // The lanes above are all ones, -1 as integers: their exponent goes up by one.
  const __m128 k = _mm_cvtepi32_ps(_mm_sub_epi32(exponent, _mm_castps_si128(above)));
  const __m128 s = _mm_div_ps(_mm_sub_ps(m, one), _mm_add_ps(m, one));
  const __m128 s2 = _mm_mul_ps(s, s);
  // 2 / ((2i + 1) ln 2), i = 4 down to 0.
  constexpr float c[] = { 0.32059890f, 0.41219858f, 0.57707802f, 0.96179669f, 2.8853901f };
  __m128 p = _mm_set1_ps(c[0]);
  for (int i = 1; i < 5; ++i)
  {
    p = _mm_add_ps(_mm_mul_ps(p, s2), _mm_set1_ps(c[i]));
  }
  return _mm_add_ps(k, _mm_mul_ps(p, s));
}
/// x^e, lane by lane, for x in (0, 1] (or a little above: a normal's dot product) and
/// e >= 0, x below 2^-126 taken as 2^-126: 2^(e log2 x). 1 - x^e (a corrected opacity) is
/// within 1.2e-7 of 1 - std::pow(x, e), and x^e within 2e-6 of it relatively where it is
/// above 2^-24; exactly 1 where x is 1 or e is 0. Four powers for less than the cost of one
/// call to std::pow, each lane computed alike, so a single value broadcast to the lanes
/// gets the bits a block's lane gets.
PARC_HOT_INLINE __m128 PowOfUnitInterval(__m128 x, __m128 e)
{
  const __m128 smallest = _mm_set1_ps(std::numeric_limits<float>::min());
  const __m128 y = _mm_mul_ps(e, Log2OfNormal(_mm_max_ps(x, smallest)));
  return Exp2InRange(_mm_min_ps(_mm_max_ps(y, _mm_set1_ps(-126.f)), _mm_set1_ps(126.f)));
}
#endif
/// The number of set bits of x (32 bits).
PARC_HOT_INLINE int PopCount(std::uint32_t x)
{
#if defined(__POPCNT__)
  return __builtin_popcount(x);
#else
  // Bits summed in pairs, nibbles, bytes, then the bytes (no call to a library routine,
  // which __builtin_popcount becomes without the instruction).
  x = x - ((x >> 1) & 0x55555555u);
  x = (x & 0x33333333u) + ((x >> 2) & 0x33333333u);
  x = (x + (x >> 4)) & 0x0F0F0F0Fu;
  return static_cast<int>((x * 0x01010101u) >> 24);
#endif
}

} // namespace parc

#endif
