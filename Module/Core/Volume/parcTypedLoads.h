// PARC for VTK: TypedLoads<T>, the loads of a field's values of type T into SSE registers
// that FieldView's hot loops use: neighbouring values loaded together as the bits of one
// integer and widened or split apart exactly (8- and 16-bit integers), four lanes at once.
#ifndef parcTypedLoads_h
#define parcTypedLoads_h

#include "parcMath.h" // For PARC_HOT_INLINE

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>

namespace parc
{

/// Loads of values of type T (see the file comment); x86 byte order.
template <typename T>
struct TypedLoads
{
  /// Whether a cell's two x neighbours fit one 32-bit load (8- and 16-bit integers), so
  /// that FieldView::LoadGroupCorners may load them together when they are next to each other.
  static constexpr bool PairedCorners = std::is_integral<T>::value && sizeof(T) <= 2;
  /// Two neighbouring values as the bits of one integer (the first lowest, x86).
  using Pair = std::conditional_t<sizeof(T) == 1, std::uint16_t, std::uint32_t>;
  /// The corners of 8-bit values whose x neighbours are next to each other: the pairs
  /// of corners of rows y = 0 and 1 (z = 0), then of y = 0 and 1 (z = 1), each into the
  /// 16-bit words of one register (row after row, lane after lane), then split apart into
  /// even and odd corners: the same values.
  static PARC_HOT_INLINE void BytePairs(const T* data, const std::ptrdiff_t* offsets,
    const std::ptrdiff_t corner[8], __m128 c[8])
  {
    const T* base[4] = { data + offsets[0], data + offsets[1], data + offsets[2],
      data + offsets[3] };
    auto pair = [&](int l, int m) {
      std::uint16_t p;
      std::memcpy(&p, base[l] + corner[m], sizeof(p));
      return static_cast<int>(p);
    };
    __m128i rows[2];
    for (int z = 0; z < 2; ++z)
    {
      const int m = 4 * z;
      __m128i w = _mm_cvtsi32_si128(pair(0, m));
      w = _mm_insert_epi16(w, pair(1, m), 1);
      w = _mm_insert_epi16(w, pair(2, m), 2);
      w = _mm_insert_epi16(w, pair(3, m), 3);
      w = _mm_insert_epi16(w, pair(0, m + 2), 4);
      w = _mm_insert_epi16(w, pair(1, m + 2), 5);
      w = _mm_insert_epi16(w, pair(2, m + 2), 6);
      w = _mm_insert_epi16(w, pair(3, m + 2), 7);
      rows[z] = w;
    }
    const __m128i zero = _mm_setzero_si128();
    for (int z = 0; z < 2; ++z)
    {
      // The even corner's bits low (x86), as 16-bit words.
      __m128i even, odd;
      if (std::is_signed<T>::value)
      {
        even = _mm_srai_epi16(_mm_slli_epi16(rows[z], 8), 8);
        odd = _mm_srai_epi16(rows[z], 8);
      }
      else
      {
        even = _mm_and_si128(rows[z], _mm_set1_epi16(0xFF));
        odd = _mm_srli_epi16(rows[z], 8);
      }
      // Words to 32 bits (signed: the word in both halves, shifted down).
      auto low = [&](__m128i v) {
        return std::is_signed<T>::value ? _mm_srai_epi32(_mm_unpacklo_epi16(v, v), 16)
                                        : _mm_unpacklo_epi16(v, zero);
      };
      auto high = [&](__m128i v) {
        return std::is_signed<T>::value ? _mm_srai_epi32(_mm_unpackhi_epi16(v, v), 16)
                                        : _mm_unpackhi_epi16(v, zero);
      };
      c[4 * z] = _mm_cvtepi32_ps(low(even));
      c[4 * z + 1] = _mm_cvtepi32_ps(low(odd));
      c[4 * z + 2] = _mm_cvtepi32_ps(high(even));
      c[4 * z + 3] = _mm_cvtepi32_ps(high(odd));
    }
  }
  /// The corners of 16-bit (or 8-bit) values whose x neighbours are next to each other,
  /// four lanes at once: each pair of corners (x offsets 0 and 1) in one load, split
  /// apart.
  static PARC_HOT_INLINE void CornerPairs(const T* data, const std::ptrdiff_t* offsets,
    const std::ptrdiff_t corner[8], __m128 c[8])
  {
    constexpr int bits = 8 * sizeof(T);
    constexpr bool sign = std::is_signed<T>::value;
    for (int m = 0; m < 8; m += 2)
    {
      Pair p[4];
      for (int l = 0; l < 4; ++l)
      {
        std::memcpy(p + l, data + offsets[l] + corner[m], sizeof(Pair));
      }
      // The even corner's bits low (x86).
      const __m128i pair = _mm_setr_epi32(static_cast<std::int32_t>(p[0]),
        static_cast<std::int32_t>(p[1]), static_cast<std::int32_t>(p[2]),
        static_cast<std::int32_t>(p[3]));
      const __m128i low = _mm_slli_epi32(pair, 32 - bits);
      const __m128i high = _mm_slli_epi32(pair, 32 - 2 * bits);
      c[m] = _mm_cvtepi32_ps(
        sign ? _mm_srai_epi32(low, 32 - bits) : _mm_srli_epi32(low, 32 - bits));
      c[m + 1] = _mm_cvtepi32_ps(
        sign ? _mm_srai_epi32(high, 32 - bits) : _mm_srli_epi32(high, 32 - bits));
    }
  }
  /// Four values as the bits of one integer (the first lowest).
  using Four = std::conditional_t<sizeof(T) == 1, std::uint32_t, std::uint64_t>;
  static PARC_HOT_INLINE Four LoadFour(const T* p)
  {
    Four bits;
    std::memcpy(&bits, p, sizeof(bits));
    return bits;
  }
  /// Two values at a, then two at b, as the bits of one integer.
  static PARC_HOT_INLINE Four LoadPairs(const T* a, const T* b)
  {
    Pair low, high;
    std::memcpy(&low, a, sizeof(low));
    std::memcpy(&high, b, sizeof(high));
    return static_cast<Four>(low) | (static_cast<Four>(high) << (8 * sizeof(Pair)));
  }
  /// Four values (Four's bits) as 32-bit integers, exactly.
  static PARC_HOT_INLINE __m128i WidenFour(Four bits)
  {
    constexpr int shift = 32 - 8 * static_cast<int>(sizeof(T));
    // Each value repeated to fill its 32-bit lane (bytes twice, then 16 bits twice), so
    // that its top bits are the value, shifted down with or without its sign.
    __m128i x;
    if constexpr (sizeof(T) == 1)
    {
      x = _mm_cvtsi32_si128(static_cast<int>(bits));
      x = _mm_unpacklo_epi8(x, x);
    }
    else
    {
      x = _mm_set_epi64x(0, static_cast<long long>(bits));
    }
    x = _mm_unpacklo_epi16(x, x);
    return std::is_signed<T>::value ? _mm_srai_epi32(x, shift) : _mm_srli_epi32(x, shift);
  }
  /// Lanes 1 and 2 of a, then of b (x = 0, 1 of two rows read from x = -1).
  static PARC_HOT_INLINE __m128i MiddlePairs(__m128i a, __m128i b)
  {
    return _mm_castps_si128(
      _mm_shuffle_ps(_mm_castsi128_ps(a), _mm_castsi128_ps(b), _MM_SHUFFLE(2, 1, 2, 1)));
  }
};

} // namespace parc
#endif

#endif
