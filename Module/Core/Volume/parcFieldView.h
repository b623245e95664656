// PARC for VTK: FieldView<T>, the typed, non-owning view of a scalar field's values that the
// ray caster's hot loops sample (values converted to float as they are loaded; nearest and
// trilinear samples, lattice blocks, gradients). ScalarField::Dispatch hands one out.
#ifndef parcFieldView_h
#define parcFieldView_h

#include "parcCellMap.h"
#include "parcInterpolation.h"
#include "parcMath.h"
#include "parcRayLattice.h"
#include "parcTypedLoads.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace parc
{

enum class Interpolation
{
  Nearest,
  Linear
};

/// Lanes of a block between two whose cells FieldView::PrefetchAhead prefetches (two
/// voxels at half a voxel: every second lane gained no more at 429 MB, every eighth less).
constexpr int PrefetchLaneStep = 4;

/// A hint to the processor to fetch the cache line holding p (nothing where the compiler
/// has no such hint). Always inlined: GCC 12 finds a function that only prefetches free of
/// side effects and drops the calls to it that it has not inlined by then, as it did to
/// every call in PrefetchAhead (the test parc_core.PrefetchInstructions).
PARC_HOT_INLINE void PrefetchLine(const void* p)
{
#if defined(__GNUC__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}

/// The voxel differences v(c + e_a) - v(c - e_a) at the 8 corners c of the cell a ray's
/// gradient was taken in last, per axis a: the next gradient in that cell reuses them.
struct CellDifferences
{
  std::ptrdiff_t Offset = -1; ///< the cell's first voxel, or -1
  /// Values[corner][axis]; the fourth entry is 0 (the axes are interpolated together).
  alignas(16) float Values[8][4];
};

/// The layout of a field's copy in bricks (ScalarField::SetBricked): cubes of Cells^3
/// cells, each stored whole with the voxels its cells' gradients read (Side^3 voxels: one
/// layer before the cube along each axis, two after), x fastest within a brick, the bricks
/// in x, y, z order. A cell's 8 corners and their neighbours lie in one brick, with x
/// neighbours next to each other, and voxels near each other in space lie near each other
/// in memory whichever way a ray goes through them. Voxels outside the field (in the first
/// and last bricks) repeat its nearest one.
struct BrickGrid
{
  static constexpr int CellShift = 6;
  static constexpr int Cells = 1 << CellShift; ///< cells along each axis of a brick
  static constexpr int Side = Cells + 3;       ///< voxels along each axis of a brick
  static constexpr std::ptrdiff_t Voxels = std::ptrdiff_t(Side) * Side * Side;
  /// A brick's first voxel along an axis: the one before its first cell.
  static constexpr int First(int brick) { return brick * Cells - 1; }
  /// From a brick's first voxel to its first cell's first voxel.
  static constexpr std::ptrdiff_t Apron = 1 + Side + std::ptrdiff_t(Side) * Side;

  BrickGrid() = default; ///< no bricks
  explicit BrickGrid(const int dims[3])
  {
    for (int a = 0; a < 3; ++a)
    {
      const int cells = std::max(dims[a] - 1, 1);
      this->Count[a] = (cells + Cells - 1) / Cells;
    }
    this->Step[0] = Voxels;
    this->Step[1] = Voxels * this->Count[0];
    this->Step[2] = this->Step[1] * this->Count[1];
  }
  std::size_t NumberOfValues() const
  {
    return static_cast<std::size_t>(this->Step[2]) * static_cast<std::size_t>(this->Count[2]);
  }
  /// Where the copy holds cell (i, j, k)'s first voxel.
  std::ptrdiff_t CellOffset(const int cell[3]) const
  {
    std::ptrdiff_t offset = Apron, scale = 1;
    for (int a = 0; a < 3; ++a)
    {
      offset += (cell[a] >> CellShift) * this->Step[a] + (cell[a] & (Cells - 1)) * scale;
      scale *= Side;
    }
    return offset;
  }

  int Count[3] = { 0, 0, 0 };           ///< bricks along x, y, z
  std::ptrdiff_t Step[3] = { 0, 0, 0 }; ///< elements from a brick to the next along x, y, z
};

/// Typed, non-owning read access to a field's values (see the file comment).
template <typename T>
class FieldView
{
  /// How a block holds corner values before interpolating them: 8- and 16-bit integers
  /// as 32-bit ones (converted to float 4 lanes at a time, exactly), others as floats.
  using LaneValue =
    std::conditional_t<std::is_integral<T>::value && sizeof(T) <= 2, std::int32_t, float>;
#if defined(__SSE2__)
  using Loads = TypedLoads<T>;
#endif

public:
  /// bricks (optional): the same values in a BrickGrid of dims, which SampleLattice and the
  /// gradients at its locations read instead of data.
  FieldView(const T* data, const int dims[3], std::ptrdiff_t stride, const T* bricks = nullptr)
    : Data(data)
    , Bricks(bricks)
    , Grid(bricks ? BrickGrid(dims) : BrickGrid())
  {
    for (int a = 0; a < 3; ++a)
    {
      this->Dims[a] = dims[a];
      this->Last[a] = dims[a] - 1;
      this->LastCell[a] = dims[a] - 2;
    }
    this->Step[0] = stride;
    this->Step[1] = stride * dims[0];
    this->Step[2] = this->Step[1] * dims[1];
    this->StepsFitIn32Bits = true;
    for (std::ptrdiff_t step : this->Step)
    {
      this->StepsFitIn32Bits &= step >= 0 && step <= std::numeric_limits<std::uint32_t>::max();
    }
    SetCorners(this->Step, this->Corner);
    this->LastCellOffset = 0;
    for (int a = 0; a < 3; ++a)
    {
      this->LastCellOffset += std::max(this->LastCell[a], 0) * this->Step[a];
    }
    this->BrickStepsFitIn32Bits = this->Grid.Step[2] <= std::numeric_limits<std::uint32_t>::max();
    this->SetRead();
  }

  const int* GetDimensions() const { return this->Dims; }
  /// The view of the values `elements` further in memory, with the same layout: another
  /// component of the same multi-component array.
  FieldView Shifted(std::ptrdiff_t elements) const
  {
    FieldView view = *this;
    view.Data += elements;
    view.Bricks = nullptr; // the bricks hold this view's values only
    view.SetRead();
    return view;
  }
  /// The first value of row (j, k), voxels (0 .. nx-1, j, k) being GetXStep() elements
  /// apart: for loops over whole rows in the values' own type.
  const T* Row(int j, int k) const { return this->Data + j * this->Step[1] + k * this->Step[2]; }
  std::ptrdiff_t GetXStep() const { return this->Step[0]; }
  float Value(int i, int j, int k) const
  {
    return static_cast<float>(this->Data[i * this->Step[0] + j * this->Step[1] + k * this->Step[2]]);
  }

  /// The range of the 8 corner values of cell (i, j, k).
  void CellRange(int i, int j, int k, float& lo, float& hi) const
  {
    const int cell[3] = { i, j, k };
    float c[8];
    this->LoadCorners(this->CellPointer(cell), c);
    const auto range = std::minmax({ c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7] });
    lo = range.first;
    hi = range.second;
  }

  /// Trilinear interpolation at index coordinates p (clamped to the box).
  float SampleLinear(const Vec3& p) const
  {
    int cell[3];
    float f[3];
    this->Locate(p, cell, f);
    return this->InterpolateCell(cell, f);
  }
  /// The samples at the points lattice.Point(k dt) for k = k0 .. k0 + count - 1 (count <=
  /// LatticeBlock::Size) into block; lanes up to the next multiple of LatticeBlock::Lanes
  /// hold the samples after them. Each is the same arithmetic as Sample of that point and
  /// its location that of Locate. No branch depends on the data, and each step works on
  /// several lanes at once.
  /// cells (optional, linear interpolation of a field whose x neighbours are next to each
  /// other): the cells that may contribute, covering the field's. Only the groups of
  /// LatticeBlock::Lanes lanes where some lane's cell may contribute are sampled (the
  /// values of the others are 0). Returns the lanes sampled whose cell may contribute, as
  /// bits 1 << j (all n lanes without cells).
  /// wide: the caller runs in code compiled for wide vectors (RayCaster's
  /// RenderConstants::WideVectors); the lanes are then located by a plain loop, which the
  /// compiler makes eight lanes wide there (SSE2's four are faster in the baseline code).
  /// ahead (optional): the voxels the lanes' cells moved by this offset read are
  /// prefetched (OffsetAhead, PrefetchAhead; values read in place only).
  PARC_HOT_INLINE unsigned SampleLattice(const RayLattice& lattice, double dt, long k0,
    int count, Interpolation mode, LatticeBlock& block, const CellMap* cells = nullptr,
    bool wide = false, const std::ptrdiff_t* ahead = nullptr) const
  {
    const int n = LatticeBlock::GroupedCount(count);
    const unsigned all = LatticeBlock::GroupLanes(count);
    if (mode == Interpolation::Nearest)
    {
      for (int j = 0; j < n; ++j)
      {
        block.Values[j] =
          this->SampleNearest(lattice.Point((static_cast<double>(k0) + j) * dt));
      }
      return all;
    }
    alignas(16) float u[LatticeBlock::Size];
    for (int j = 0; j < n; ++j)
    {
      u[j] = lattice.Offset((static_cast<double>(k0) + j) * dt); // k0 + j exactly, as a double
    }
    for (int a = 0; a < 3; ++a)
    {
      LocateLanes(lattice.Origin[a], lattice.Direction[a], u, n, this->Last[a],
        this->LastCell[a], block.Cell[a], block.Fractions[a], wide);
    }
    this->CellOffsets(block, n);
    if (ahead && !this->Bricks)
    {
      this->PrefetchAhead(block, n, *ahead);
    }
    unsigned lanes = all;
    if (cells)
    {
      lanes = cells->Lanes(block, n);
    }
    for (int j = 0; j < n; j += LatticeBlock::Lanes)
    {
      if (((lanes >> j) & LatticeBlock::GroupBits) != 0)
      {
        this->SampleGroup(block, j);
      }
      else
      {
        std::fill_n(block.Values + j, LatticeBlock::Lanes, 0.f);
      }
    }
    return lanes;
  }
  /// The offset, in values, by which a ray's cells move over the ray parameter `ahead`:
  /// its whole steps along each axis over that distance, each at most the field's width
  /// (no overflow, whatever the spacing or sample distance). Computed once a ray, for
  /// PrefetchAhead.
  std::ptrdiff_t OffsetAhead(const RayLattice& lattice, double ahead) const
  {
    std::ptrdiff_t offset = 0;
    for (int a = 0; a < 3; ++a)
    {
      const double width = this->Dims[a];
      const double cells = std::nearbyint(ahead * lattice.Direction[a]);
      const double moved = cells > width ? width : (cells > -width ? cells : -width);
      offset += static_cast<std::ptrdiff_t>(moved) * this->Step[a];
    }
    return offset;
  }
  /// Prefetches the cache lines that the samples ahead of every PrefetchLaneStep-th lane of
  /// block (located, n lanes) will read: the cell each lane's moves to by the offset ahead
  /// (OffsetAhead; clamped to the field), its row and slice and the next ones. Approximate
  /// (a cell may be one off), and only a hint: a ray through a field many times the
  /// processor's cache waits on its cache lines, which its steps of a row or a slice leave
  /// the processor no pattern to fetch early by. Every lane's corners lie in the field's
  /// values (y and z have two voxels or more).
  PARC_HOT_INLINE void PrefetchAhead(
    const LatticeBlock& block, int n, std::ptrdiff_t ahead) const
  {
    const std::ptrdiff_t row = this->Step[1], slice = this->Step[2];
    for (int j = 0; j < n; j += PrefetchLaneStep)
    {
      const std::ptrdiff_t offset =
        std::clamp<std::ptrdiff_t>(block.Offset[j] + ahead, 0, this->LastCellOffset);
      const T* v = this->Data + offset;
      PrefetchLine(v);
      PrefetchLine(v + row);
      PrefetchLine(v + slice);
      PrefetchLine(v + row + slice);
    }
  }
  /// The value of the nearest voxel to p (ties round up; clamped to the box).
  float SampleNearest(const Vec3& p) const
  {
    int idx[3];
    NearestVoxel(p, this->Dims, idx);
    return this->Value(idx[0], idx[1], idx[2]);
  }
  float Sample(const Vec3& p, Interpolation mode) const
  {
    return mode == Interpolation::Linear ? this->SampleLinear(p) : this->SampleNearest(p);
  }
  /// Central-difference gradient of the interpolated field at p (offsets of one voxel), in
  /// scalar units per voxel index; one-sided where p is within one voxel of a box face.
  Vec3 Gradient(const Vec3& p, Interpolation mode) const
  {
    CellDifferences differences;
    return this->Gradient(p, mode, differences);
  }
  /// The same, reusing (and updating) the differences of the cell of the last gradient.
  /// located (optional, linear interpolation only) is p's location, from SampleLattice: it
  /// is not computed again.
  Vec3 Gradient(const Vec3& p, Interpolation mode, CellDifferences& differences,
    const SampleLocation* located = nullptr) const
  {
    return mode == Interpolation::Linear ? this->GradientLinear(p, differences, located)
                                         : this->GradientNearest(p);
  }
  /// Where p (clamped to the box) lies, as Sample locates it.
  SampleLocation LocationOf(const Vec3& p) const
  {
    SampleLocation w;
    this->Locate(p, w.Cell, w.Fractions);
    w.Offset = this->Bricks ? this->Grid.CellOffset(w.Cell) : this->CellOffset(w.Cell);
    return w;
  }
  /// Whether central differences in every point of cell need no voxel outside the box.
  PARC_HOT_INLINE bool IsInteriorCell(const int cell[3]) const
  {
    bool interior = true;
    for (int a = 0; a < 3; ++a)
    {
      interior &= (cell[a] >= 1) & (cell[a] + 3 <= this->Dims[a]); // no branch
    }
    return interior;
  }
  /// The linear-interpolation gradient at a located point of an interior cell, in float:
  /// the same bits as Gradient. Inside, f(p + e_a) - f(p - e_a) is the trilinear
  /// interpolation, in p's own cell, of the voxel differences v(c + e_a) - v(c - e_a) at
  /// its 8 corners.
  PARC_HOT_INLINE Vec3f InteriorGradient(
    const SampleLocation& w, CellDifferences& differences) const
  {
#if defined(__SSE2__)
    alignas(16) float g[4];
    _mm_store_ps(g, this->InteriorGradientVector(w, differences));
#else
    this->EnsureDifferences(w, differences);
    const float(*d)[4] = differences.Values;
    float g[3];
    for (int a = 0; a < 3; ++a)
    {
      const float c[8] = { d[0][a], d[1][a], d[2][a], d[3][a], d[4][a], d[5][a], d[6][a],
        d[7][a] };
      g[a] = 0.5f * Trilinear(c, w.Fractions);
    }
#endif
    return { g[0], g[1], g[2] };
  }
#if defined(__SSE2__)
  /// InteriorGradient as the lanes of a register (x, y, z, 0): the same bits. The three
  /// axes are interpolated at once, with the same operations lane by lane.
  PARC_HOT_INLINE __m128 InteriorGradientVector(
    const SampleLocation& w, CellDifferences& differences) const
  {
    this->EnsureDifferences(w, differences);
    __m128 c[8];
    for (int n = 0; n < 8; ++n)
    {
      c[n] = _mm_load_ps(differences.Values[n]);
    }
    const __m128 fx = _mm_set1_ps(w.Fractions[0]), fy = _mm_set1_ps(w.Fractions[1]);
    const __m128 fz = _mm_set1_ps(w.Fractions[2]);
    return _mm_mul_ps(_mm_set1_ps(0.5f), Trilinear(c, fx, fy, fz));
  }
#endif

private:
  /// Loads differences for w's cell unless they hold it already.
  PARC_HOT_INLINE void EnsureDifferences(
    const SampleLocation& w, CellDifferences& differences) const
  {
    if (w.Offset != differences.Offset)
    {
      this->LoadDifferences(this->Read.Values + w.Offset, differences.Values);
      differences.Offset = w.Offset;
    }
  }
  /// The cell along one axis and the fraction inside it, for x clamped to [0, last]
  /// (last = lastCell + 1, the number of cells).
  static PARC_HOT_INLINE void LocateAxis(double x, double last, int lastCell, int& i, float& f)
  {
    x = x > 0.0 ? x : 0.0; // also NaN
    x = x < last ? x : last;
    i = static_cast<int>(x);
    i = i < lastCell ? i : lastCell;
    f = static_cast<float>(x - i);
  }
  // The lanes of a LatticeBlock, with SSE2 where there is SSE2: the same IEEE operations
  // in the same order as the scalar code (LocateAxis, Interpolate), so the same bits.

  /// LocateAxis for the coordinates o + u[j] d (in float) of the lanes. The last cell
  /// holds [lastCell, last], so min(floor(x), lastCell) = floor(min(x, lastCell)).
  /// plain: the plain loop (the same operations) even where there is SSE2.
  static PARC_HOT_INLINE void LocateLanes(float o, float d, const float* u, int n,
    double last, int lastCell, int* cell, float* f, bool plain)
  {
    // Coordinates in float are exact in LocateAxis's double (last and lastCell are whole
    // numbers of cells, exact in float): the same cells and fractions.
    const float lastF = static_cast<float>(last), lastCellF = static_cast<float>(lastCell);
#if defined(__SSE2__)
    if (!plain)
    {
      LocateFourLanes(o, d, u, n, lastF, lastCellF, cell, f);
      return;
    }
#else
    static_cast<void>(plain);
#endif
    for (int j = 0; j < n; ++j)
    {
      float x = o + u[j] * d;
      x = x > 0.f ? x : 0.f; // also NaN
      x = x < lastF ? x : lastF;
      const int i = static_cast<int>(x < lastCellF ? x : lastCellF);
      cell[j] = i;
      f[j] = x - static_cast<float>(i);
    }
  }
#if defined(__SSE2__)
  /// LocateLanes' loop four lanes at a time.
  static PARC_HOT_INLINE void LocateFourLanes(float o, float d, const float* u, int n,
    float lastF, float lastCellF, int* cell, float* f)
  {
    const __m128 vo = _mm_set1_ps(o), vd = _mm_set1_ps(d), vlast = _mm_set1_ps(lastF);
    const __m128 vcell = _mm_set1_ps(lastCellF), zero = _mm_setzero_ps();
    for (int j = 0; j < n; j += 4)
    {
      __m128 x = _mm_add_ps(vo, _mm_mul_ps(_mm_load_ps(u + j), vd));
      x = _mm_max_ps(x, zero); // x > 0 ? x : 0, also for NaN
      x = _mm_min_ps(x, vlast); // x < last ? x : last
      const __m128i i = _mm_cvttps_epi32(_mm_min_ps(x, vcell));
      _mm_storeu_si128(reinterpret_cast<__m128i*>(cell + j), i);
      _mm_storeu_ps(f + j, _mm_sub_ps(x, _mm_cvtepi32_ps(i)));
    }
    static_assert(LatticeBlock::Lanes == 4, "four lanes to an SSE register");
  }
#endif
  /// The offsets of the located cells of block's lanes j < n (a multiple of
  /// LatticeBlock::Lanes) from the first voxel of the values SampleGroup reads (the bricks
  /// when there are bricks).
  PARC_HOT_INLINE void CellOffsets(LatticeBlock& block, int n) const
  {
    if (this->Bricks)
    {
      this->BrickOffsets(block, n);
      return;
    }
#if defined(__SSE2__)
    if (this->StepsFitIn32Bits)
    {
      const Steps32 steps(this->Step);
      for (int j = 0; j < n; j += 4)
      {
        __m128i low, high;
        steps.Sums(block.CellLanes(0, j), block.CellLanes(1, j), block.CellLanes(2, j), low, high);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(block.Offset + j), low);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(block.Offset + j + 2), high);
      }
      return;
    }
#endif
    for (int j = 0; j < n; ++j)
    {
      block.Offset[j] = block.Cell[0][j] * this->Step[0] + block.Cell[1][j] * this->Step[1] +
        block.Cell[2][j] * this->Step[2];
    }
  }
#if defined(__SSE2__)
  /// Three steps below 2^32, for sums x s0 + y s1 + z s2 of four lanes of cells.
  struct Steps32
  {
    explicit Steps32(const std::ptrdiff_t step[3])
    {
      for (int a = 0; a < 3; ++a)
      {
        this->S[a] = _mm_set1_epi32(static_cast<int>(step[a]));
      }
    }
    /// The sums of lanes 0, 1 (low) and 2, 3 (high) in 64 bits: cells are not negative, so
    /// 32 x 32 -> 64-bit products of unsigned numbers, two lanes at a time (0 and 2, then
    /// 1 and 3).
    PARC_HOT_INLINE void Sums(__m128i x, __m128i y, __m128i z, __m128i& low, __m128i& high) const
    {
      const __m128i even = _mm_add_epi64(_mm_mul_epu32(x, this->S[0]),
        _mm_add_epi64(_mm_mul_epu32(y, this->S[1]), _mm_mul_epu32(z, this->S[2])));
      const __m128i odd = _mm_add_epi64(_mm_mul_epu32(_mm_srli_epi64(x, 32), this->S[0]),
        _mm_add_epi64(_mm_mul_epu32(_mm_srli_epi64(y, 32), this->S[1]),
          _mm_mul_epu32(_mm_srli_epi64(z, 32), this->S[2])));
      static_assert(sizeof(std::ptrdiff_t) == 8, "64-bit offsets");
      low = _mm_unpacklo_epi64(even, odd);
      high = _mm_unpackhi_epi64(even, odd);
    }
    __m128i S[3];
  };
#endif
  /// CellOffsets in the bricks.
  PARC_HOT_INLINE void BrickOffsets(LatticeBlock& block, int n) const
  {
#if defined(__SSE2__)
    if (this->BrickStepsFitIn32Bits)
    {
      // BrickGrid::CellOffset: the brick's offset as in CellOffsets, from the cell's bits
      // above CellShift; the cell's in the brick from those below, in 32 bits (factors
      // below 2^16: the low and high halves of the products of the 16-bit low halves,
      // whose high halves are 0).
      const Steps32 steps(this->Grid.Step);
      const __m128i low = _mm_set1_epi32(BrickGrid::Cells - 1);
      const __m128i side = _mm_set1_epi32(BrickGrid::Side);
      const __m128i slice = _mm_set1_epi32(BrickGrid::Side * BrickGrid::Side);
      const __m128i apron = _mm_set1_epi32(static_cast<int>(BrickGrid::Apron));
      static_assert(BrickGrid::Side * BrickGrid::Side < (1 << 16), "16-bit factors");
      const auto product = [](__m128i a, __m128i b) {
        return _mm_add_epi32(_mm_mullo_epi16(a, b), _mm_slli_epi32(_mm_mulhi_epu16(a, b), 16));
      };
      const __m128i zero = _mm_setzero_si128();
      for (int j = 0; j < n; j += 4)
      {
        const __m128i cx = block.CellLanes(0, j);
        const __m128i cy = block.CellLanes(1, j);
        const __m128i cz = block.CellLanes(2, j);
        const __m128i x = _mm_srli_epi32(cx, BrickGrid::CellShift);
        const __m128i y = _mm_srli_epi32(cy, BrickGrid::CellShift);
        const __m128i z = _mm_srli_epi32(cz, BrickGrid::CellShift);
        const __m128i local = _mm_add_epi32(_mm_add_epi32(apron, _mm_and_si128(cx, low)),
          _mm_add_epi32(product(_mm_and_si128(cy, low), side),
            product(_mm_and_si128(cz, low), slice)));
        __m128i first, second; // the bricks' offsets of lanes 0, 1 and 2, 3
        steps.Sums(x, y, z, first, second);
        _mm_storeu_si128(reinterpret_cast<__m128i*>(block.Offset + j),
          _mm_add_epi64(first, _mm_unpacklo_epi32(local, zero)));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(block.Offset + j + 2),
          _mm_add_epi64(second, _mm_unpackhi_epi32(local, zero)));
      }
      return;
    }
#endif
    for (int j = 0; j < n; ++j)
    {
      const int cell[3] = { block.Cell[0][j], block.Cell[1][j], block.Cell[2][j] };
      block.Offset[j] = this->Grid.CellOffset(cell);
    }
  }
  /// Interpolates the located lanes of block's group from lane first into its values.
  PARC_HOT_INLINE void SampleGroup(LatticeBlock& block, int first) const
  {
    const T* data = this->Read.Values;
    const std::ptrdiff_t* corner = this->Read.Corner;
    const std::ptrdiff_t* offsets = block.Offset + first;
#if defined(__SSE2__)
    static_assert(LatticeBlock::Lanes == 4, "four lanes to an SSE register");
    __m128 c[8];
    LoadGroupCorners(data, offsets, corner, this->Read.Paired, c);
    const __m128 fx = _mm_loadu_ps(block.Fractions[0] + first);
    const __m128 fy = _mm_loadu_ps(block.Fractions[1] + first);
    const __m128 fz = _mm_loadu_ps(block.Fractions[2] + first);
    _mm_storeu_ps(block.Values + first, Trilinear(c, fx, fy, fz));
#else
    for (int l = 0; l < LatticeBlock::Lanes; ++l)
    {
      float v[8];
      for (int m = 0; m < 8; ++m)
      {
        v[m] = static_cast<float>(static_cast<LaneValue>(data[offsets[l] + corner[m]]));
      }
      const int j = first + l;
      const float f[3] = { block.Fractions[0][j], block.Fractions[1][j], block.Fractions[2][j] };
      block.Values[j] = Trilinear(v, f);
    }
#endif
  }
#if defined(__SSE2__)
  /// The corner values c[corner] of the cells at offsets[0 .. 3] of data, lane by lane,
  /// as floats; held in registers (no store and load again). With x neighbours next to
  /// each other (paired) each pair of corners (x offsets 0 and 1) is loaded at once and
  /// split apart four lanes at a time (TypedLoads): the same values as one load a corner.
  static PARC_HOT_INLINE void LoadGroupCorners(const T* data, const std::ptrdiff_t* offsets,
    const std::ptrdiff_t corner[8], bool paired, __m128 c[8])
  {
    if constexpr (Loads::PairedCorners)
    {
      if (paired)
      {
        if constexpr (sizeof(T) == 1)
        {
          Loads::BytePairs(data, offsets, corner, c);
        }
        else
        {
          Loads::CornerPairs(data, offsets, corner, c);
        }
        return;
      }
    }
    for (int m = 0; m < 8; ++m)
    {
      auto value = [&](int l) {
        return static_cast<float>(static_cast<LaneValue>(data[offsets[l] + corner[m]]));
      };
      c[m] = _mm_setr_ps(value(0), value(1), value(2), value(3));
    }
  }
#endif
  PARC_HOT_INLINE void Locate(const Vec3& p, int cell[3], float f[3]) const
  {
    LocateAxis(p.X, this->Last[0], this->LastCell[0], cell[0], f[0]);
    LocateAxis(p.Y, this->Last[1], this->LastCell[1], cell[1], f[1]);
    LocateAxis(p.Z, this->Last[2], this->LastCell[2], cell[2], f[2]);
  }
  std::ptrdiff_t CellOffset(const int cell[3]) const
  {
    return cell[0] * this->Step[0] + cell[1] * this->Step[1] + cell[2] * this->Step[2];
  }
  const T* CellPointer(const int cell[3]) const { return this->Data + this->CellOffset(cell); }
  PARC_HOT_INLINE void LoadCorners(const T* v, float c[8]) const
  {
    const std::ptrdiff_t* corner = this->Corner;
    for (int n = 0; n < 8; ++n)
    {
      c[n] = static_cast<float>(v[corner[n]]);
    }
  }
  float InterpolateCell(const int cell[3], const float f[3]) const
  {
    float c[8];
    this->LoadCorners(this->CellPointer(cell), c);
    return Trilinear(c, f);
  }

  Vec3 GradientLinear(
    const Vec3& p, CellDifferences& differences, const SampleLocation* located) const
  {
    const SampleLocation w = located ? *located : this->LocationOf(p);
    if (!this->IsInteriorCell(w.Cell))
    {
      return this->GradientNearFaces(p, w.Cell, w.Fractions);
    }
    const Vec3f g = this->InteriorGradient(w, differences);
    return { g.X, g.Y, g.Z };
  }
  /// The voxel differences v(c + e_a) - v(c - e_a) at the 8 corners c of the interior cell
  /// whose first voxel is v, as d[corner][axis] (corner n: x offset n & 1, y (n >> 1) & 1,
  /// z (n >> 2) & 1; d[n][3] = 0). Per axis, each difference takes one corner of the cell
  /// and one voxel outside it: 8 corner loads and 24 outer ones. 8- and 16-bit differences
  /// are taken in integers, exactly, and converted together.
  PARC_HOT_INLINE void LoadDifferences(const T* v, float d[8][4]) const
  {
#if defined(__SSE2__)
    if constexpr (Loads::PairedCorners)
    {
      if (this->Read.Paired)
      {
        this->LoadDifferencesOfRows(v, d);
        return;
      }
    }
#endif
    const std::ptrdiff_t* corner = this->Read.Corner;
    LaneValue c[8];
    for (int n = 0; n < 8; ++n)
    {
      c[n] = static_cast<LaneValue>(v[corner[n]]);
    }
    LaneValue e[8][4];
    for (int a = 0; a < 3; ++a)
    {
      const std::ptrdiff_t s = this->Read.Step[a];
      const int bit = 1 << a;
      for (int n = 0; n < 8; ++n)
      {
        if (n & bit)
        {
          continue;
        }
        // Corners n (low along a) and n | bit (high): the low one's difference is the high
        // corner minus the voxel before the cell, the high one's the voxel after the cell
        // minus the low corner.
        const T* low = v + corner[n];
        e[n][a] = c[n | bit] - static_cast<LaneValue>(low[-s]);
        e[n | bit][a] = static_cast<LaneValue>(low[2 * s]) - c[n];
      }
    }
    for (int n = 0; n < 8; ++n)
    {
      e[n][3] = 0;
#if defined(__SSE2__)
      // Built in registers: a load spanning the four separate stores would wait for them.
      if constexpr (std::is_same<LaneValue, std::int32_t>::value)
      {
        _mm_store_ps(d[n], _mm_cvtepi32_ps(_mm_setr_epi32(e[n][0], e[n][1], e[n][2], 0)));
      }
      else
      {
        _mm_store_ps(d[n], _mm_setr_ps(e[n][0], e[n][1], e[n][2], 0.f));
      }
#else
      for (int a = 0; a < 4; ++a)
      {
        d[n][a] = static_cast<float>(e[n][a]);
      }
#endif
    }
  }
#if defined(__SSE2__)
  /// LoadDifferences of 8- and 16-bit values whose x neighbours are next to each other:
  /// the same differences from 12 loads instead of 32. Each of the cell's four x rows is
  /// read with its outer neighbours (x = -1 .. 2), the outer voxels along y and z two at a
  /// time; the differences of four corners are taken together and turned corner by corner.
  PARC_HOT_INLINE void LoadDifferencesOfRows(const T* v, float d[8][4]) const
  {
    const std::ptrdiff_t sy = this->Read.Step[1], sz = this->Read.Step[2];
    // row[y + 2 z]: x = -1 .. 2 of the cell's row (y, z).
    __m128i row[4];
    for (int r = 0; r < 4; ++r)
    {
      row[r] = Loads::WidenFour(Loads::LoadFour(v - 1 + (r & 1) * sy + (r >> 1) * sz));
    }
    // The corners (x = 0, 1) of rows (0, z) and (1, z), as lanes 0 1 2 3.
    const __m128i centre[2] = { Loads::MiddlePairs(row[0], row[1]), Loads::MiddlePairs(row[2], row[3]) };
    // The outer voxels (x = 0, 1) before and after the cell along y, per z, and along z,
    // per y (as lanes 0 1 2 3: y or z = 0, then 1).
    const __m128i yBefore = Loads::WidenFour(Loads::LoadPairs(v - sy, v - sy + sz));
    const __m128i yAfter = Loads::WidenFour(Loads::LoadPairs(v + 2 * sy, v + 2 * sy + sz));
    const __m128i zBefore = Loads::WidenFour(Loads::LoadPairs(v - sz, v + sy - sz));
    const __m128i zAfter = Loads::WidenFour(Loads::LoadPairs(v + 2 * sz, v + sy + 2 * sz));
    for (int z = 0; z < 2; ++z)
    {
      // Corners 4 z .. 4 z + 3: (x, y) = (0, 0), (1, 0), (0, 1), (1, 1).
      const __m128i& c = centre[z];
      const __m128i dx = _mm_sub_epi32(_mm_unpackhi_epi64(row[2 * z], row[2 * z + 1]),
        _mm_unpacklo_epi64(row[2 * z], row[2 * z + 1]));
      const __m128i yPair = z == 0 ? yBefore : _mm_srli_si128(yBefore, 8);
      const __m128i yNext = z == 0 ? yAfter : _mm_srli_si128(yAfter, 8);
      const __m128i dy = _mm_sub_epi32(_mm_unpacklo_epi64(_mm_srli_si128(c, 8), yNext),
        _mm_unpacklo_epi64(yPair, c));
      const __m128i dz = z == 0 ? _mm_sub_epi32(centre[1], zBefore)
                                : _mm_sub_epi32(zAfter, centre[0]);
      __m128 ax = _mm_cvtepi32_ps(dx), ay = _mm_cvtepi32_ps(dy), az = _mm_cvtepi32_ps(dz);
      __m128 zero = _mm_setzero_ps();
      _MM_TRANSPOSE4_PS(ax, ay, az, zero);
      _mm_store_ps(d[4 * z], ax);
      _mm_store_ps(d[4 * z + 1], ay);
      _mm_store_ps(d[4 * z + 2], az);
      _mm_store_ps(d[4 * z + 3], zero);
    }
  }
#endif
  /// Central differences of SampleLinear with the offsets clamped to the box.
  Vec3 GradientNearFaces(const Vec3& p, const int cell[3], const float f[3]) const
  {
    Vec3 g;
    for (int a = 0; a < 3; ++a)
    {
      const double lo = std::max(p[a] - 1.0, 0.0);
      const double hi = std::min(p[a] + 1.0, static_cast<double>(this->Dims[a] - 1));
      const double h = hi - lo;
      if (!(h > 0.0))
      {
        g[a] = 0.0;
        continue;
      }
      int shifted[3] = { cell[0], cell[1], cell[2] };
      float shiftedF[3] = { f[0], f[1], f[2] };
      LocateAxis(hi, this->Last[a], this->LastCell[a], shifted[a], shiftedF[a]);
      const float high = this->InterpolateCell(shifted, shiftedF);
      LocateAxis(lo, this->Last[a], this->LastCell[a], shifted[a], shiftedF[a]);
      const float low = this->InterpolateCell(shifted, shiftedF);
      g[a] = (high - low) / h;
    }
    return g;
  }
  Vec3 GradientNearest(const Vec3& p) const
  {
    Vec3 g;
    for (int a = 0; a < 3; ++a)
    {
      Vec3 lo = p, hi = p;
      lo[a] = std::max(p[a] - 1.0, 0.0);
      hi[a] = std::min(p[a] + 1.0, static_cast<double>(this->Dims[a] - 1));
      const double h = hi[a] - lo[a];
      g[a] = h > 0.0 ? (this->SampleNearest(hi) - this->SampleNearest(lo)) / h : 0.0;
    }
    return g;
  }

  /// The corner offsets of a layout whose neighbours are step[a] apart along axis a
  /// (corner n: x offset n & 1, y (n >> 1) & 1, z (n >> 2) & 1).
  static void SetCorners(const std::ptrdiff_t step[3], std::ptrdiff_t corner[8])
  {
    for (int n = 0; n < 8; ++n)
    {
      corner[n] = ((n & 1) ? step[0] : 0) + ((n & 2) ? step[1] : 0) + ((n & 4) ? step[2] : 0);
    }
  }

  /// Read: the bricks when there are bricks, else the values.
  void SetRead()
  {
    if (this->Bricks)
    {
      const std::ptrdiff_t inBrick[3] = { 1, BrickGrid::Side, BrickGrid::Side * BrickGrid::Side };
      this->Read.Values = this->Bricks;
      std::copy_n(inBrick, 3, this->Read.Step);
      SetCorners(inBrick, this->Read.Corner);
    }
    else
    {
      this->Read.Values = this->Data;
      std::copy_n(this->Step, 3, this->Read.Step);
      std::copy_n(this->Corner, 8, this->Read.Corner);
    }
    this->Read.Paired = this->Read.Step[0] == 1;
  }

  const T* Data;
  const T* Bricks; ///< the same values in Grid, or null
  std::ptrdiff_t Step[3]; ///< elements between neighbours along x, y, z
  /// Whether every step is a 32-bit unsigned number (cell offsets four lanes at a time).
  bool StepsFitIn32Bits = false;
  /// The offsets of a cell's 8 corners from its first voxel (corner n: x offset n & 1,
  /// y (n >> 1) & 1, z (n >> 2) & 1).
  std::ptrdiff_t Corner[8];
  BrickGrid Grid; ///< the layout of Bricks
  /// Whether Grid's offsets are 32-bit unsigned numbers (BrickOffsets four lanes at a time).
  bool BrickStepsFitIn32Bits = false;
  /// The values SampleLattice and the gradients at its locations read: the field's own,
  /// or its bricks (Step and Corner within a brick).
  struct Layout
  {
    const T* Values;
    std::ptrdiff_t Step[3];
    std::ptrdiff_t Corner[8];
    bool Paired; ///< x neighbours next to each other (Step[0] = 1)
  } Read;
  int Dims[3];
  double Last[3]; ///< the last index coordinate along x, y, z
  int LastCell[3]; ///< the last cell index along x, y, z
  std::ptrdiff_t LastCellOffset; ///< the last cell's first voxel (each index at least 0)
};

} // namespace parc

#endif
