// PARC for VTK: where a ray's samples lie in a field's voxel-index space: the ray's lattice
// of points, a sample's cell and fractions, a block of consecutive samples.
#ifndef parcRayLattice_h
#define parcRayLattice_h

#include "parcMath.h"

#include <cmath>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace parc
{

/// The voxel nearest to index coordinates p in a box of dims voxels (ties round up;
/// clamped to the box).
inline void NearestVoxel(const Vec3& p, const int dims[3], int voxel[3])
{
  for (int a = 0; a < 3; ++a)
  {
    double x = std::floor(p[a] + 0.5);
    if (!(x > 0.0))
    {
      x = 0.0;
    }
    voxel[a] = std::min(static_cast<int>(x), dims[a] - 1);
  }
}

/// Where a sample lies: its cell, its fractions in the cell and the cell's first voxel.
struct SampleLocation
{
  int Cell[3];
  float Fractions[3];
  std::ptrdiff_t Offset;
};

/// A ray's points in index coordinates as the caster samples them: the point of ray
/// parameter t is Origin + float(t - BaseT) Direction, in float, with Origin the ray's
/// point at BaseT, where the ray passes closest to the field's centre. Coordinates and
/// steps then stay about the size of the field, small enough for float, wherever the eye
/// is; and a parameter gives the same point wherever it is computed (Point, and the lanes
/// of FieldView::SampleLattice).
struct RayLattice
{
  float Origin[3] = { 0.f, 0.f, 0.f };
  float Direction[3] = { 0.f, 0.f, 0.f };
  double BaseT = 0.0;

  /// The lattice of the ray o + t d (index coordinates) through a field of dims voxels.
  RayLattice(const Vec3& o, const Vec3& d, const int dims[3])
  {
    const Vec3 centre(0.5 * (dims[0] - 1), 0.5 * (dims[1] - 1), 0.5 * (dims[2] - 1));
    const double dd = Dot(d, d);
    this->BaseT = dd > 0.0 ? Dot(centre - o, d) / dd : 0.0;
    const Vec3 base = o + this->BaseT * d;
    for (int a = 0; a < 3; ++a)
    {
      this->Origin[a] = static_cast<float>(base[a]);
      this->Direction[a] = static_cast<float>(d[a]);
    }
  }
  /// The offset from BaseT, as the points are made from it.
  float Offset(double t) const { return static_cast<float>(t - this->BaseT); }
  Vec3 Point(double t) const
  {
    const float u = this->Offset(t);
    return { this->Origin[0] + u * this->Direction[0], this->Origin[1] + u * this->Direction[1],
      this->Origin[2] + u * this->Direction[2] };
  }
};

/// Consecutive lattice samples along a ray, taken together (FieldView::SampleLattice),
/// one lane per sample: values and, for linear interpolation, locations.
struct LatticeBlock
{
  /// Lanes of a block: 32 rather than 16 puts twice the corner loads in flight before
  /// the ray's compositing waits on them (about 10% less casting at 429 MB, 5% at 7 MB).
  static constexpr int Size = 32;
  static_assert(Size <= 32, "a block's lanes are the bits of an unsigned number");
  static constexpr int Lanes = 4; ///< lanes computed together (a multiple of 2, dividing Size)
  /// The lanes of a group of Lanes as bits (of the group's first lane shifted down).
  static constexpr unsigned GroupBits = (1u << Lanes) - 1u;
  float Values[Size];
  int Cell[3][Size];
  float Fractions[3][Size];
  /// The cells' first voxels in the values sampled (FieldView::CellOffsets: the field's
  /// own, or its copy in bricks).
  std::ptrdiff_t Offset[Size];

  /// The lanes computed for count samples: whole groups of Lanes.
  static constexpr int GroupedCount(int count) { return Lanes * ((count + Lanes - 1) / Lanes); }
  /// The same lanes as bits 1 << j.
  static constexpr unsigned GroupLanes(int count) { return LowLanes(GroupedCount(count)); }
  /// Lanes 0 .. n - 1 (n <= Size) as bits 1 << j.
  static constexpr unsigned LowLanes(int n) { return n >= 32 ? ~0u : (1u << n) - 1u; }

#if defined(__SSE2__)
  /// The cells of lanes j .. j + 3 along axis, in a register.
  PARC_HOT_INLINE __m128i CellLanes(int axis, int j) const
  {
    return _mm_loadu_si128(reinterpret_cast<const __m128i*>(this->Cell[axis] + j));
  }
#endif
  SampleLocation Location(int j) const
  {
    return { { this->Cell[0][j], this->Cell[1][j], this->Cell[2][j] },
      { this->Fractions[0][j], this->Fractions[1][j], this->Fractions[2][j] }, this->Offset[j] };
  }
};

} // namespace parc

#endif
