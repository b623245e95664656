// PARC for VTK: supercells and subcells (paper section 2, DESIGN.md section 2).
//
// The grid divides the volume's box [0, nx-1] x [0, ny-1] x [0, nz-1] (voxel-index
// coordinates, where cell (i, j, k) is the unit box at (i, j, k)) into supercells of
// m x n x p cells, each a positive real number. Supercell i along an axis spans
// [Boundary(i), Boundary(i + 1)], with Boundary(i) = min(i * size, cells): the last one may
// be partial. Sizes below 1 make subcells. A supercell is possibly contributing (PC) when
// it overlaps a PC cell (the range pyramid answers that). With linear interpolation a
// subcell grid (some size below 1) is tighter: a subcell is PC when the exact range of the
// trilinear interpolant on its part of a PC cell passes the rule (the interpolant is
// multilinear, so its extremes on a box are at the box's corners).
#ifndef parcSupercellGrid_h
#define parcSupercellGrid_h

#include "parcClassification.h"

#include <cstdint>
#include <vector>

namespace parc
{

class SupercellGrid
{
public:
  /// Largest number of supercells a grid may have (one byte of flags each).
  static constexpr std::size_t MaxSupercells = std::size_t(1) << 28;

  /// Sets the geometry for a volume of cellDims cells per axis (each >= 1) and supercells of
  /// size cells per axis (each > 0 and finite). Returns false, leaving the grid empty, when
  /// the sizes are invalid or would make more than MaxSupercells supercells.
  bool Configure(const int cellDims[3], const double size[3]);
  /// The number of supercells of size for cellDims cells per axis (before Configure drops
  /// an empty last one; +inf for invalid sizes).
  static double CountSupercells(const int cellDims[3], const double size[3]);
  /// Size scaled up uniformly, by the smallest factor found, until the grid has at most
  /// MaxSupercells supercells (size itself when it fits). False for invalid sizes.
  static bool FitSize(const int cellDims[3], const double size[3], double fitted[3]);

  /// One field of a volume and the rule of its ray function: a volume of independent
  /// components classifies one channel per component.
  struct Channel
  {
    const RangePyramid* Pyramid;
    const ContributionRule* Rule;
  };
  /// Classifies every supercell (in parallel): PC when it is under some channel's rule.
  /// Configure must have matched the pyramids (of fields of equal dimensions).
  void Classify(const std::vector<Channel>& channels, Interpolation interpolation);
  /// The same for one channel.
  void Classify(const RangePyramid& pyramid, const ContributionRule& rule,
    Interpolation interpolation)
  {
    this->Classify({ { &pyramid, &rule } }, interpolation);
  }

  const int* GetCounts() const { return this->Counts; }
  const int* GetCellDimensions() const { return this->CellDims; }
  const double* GetSize() const { return this->Size; }
  std::size_t GetNumberOfSupercells() const { return this->Count; }
  std::size_t GetNumberOfContributing() const { return this->ContributingCount; }
  /// Memory held by the grid's flags (one bit a supercell), in bytes.
  std::size_t GetMemorySize() const { return this->Bits.capacity() * sizeof(std::uint64_t); }

  /// The coordinate (voxel index) of the lower face of supercell i along axis; i may be
  /// Counts[axis], the upper face of the last one.
  double Boundary(int axis, int i) const
  {
    const double b = i * this->Size[axis];
    return b < this->CellDims[axis] ? b : static_cast<double>(this->CellDims[axis]);
  }
  std::size_t Index(int i, int j, int k) const
  {
    return static_cast<std::size_t>(i) +
      static_cast<std::size_t>(this->Counts[0]) *
        (j + static_cast<std::size_t>(this->Counts[1]) * k);
  }
  bool IsContributing(int i, int j, int k) const
  {
    return this->IsContributing(this->Index(i, j, k));
  }
  /// The same by Index; Stride(axis) is the step of Index along axis.
  bool IsContributing(std::size_t index) const
  {
    return ((this->Bits[index >> 6] >> (index & 63)) & 1) != 0;
  }
  /// The flags of supercells index .. index + 63 (by Index) as bits, 0 past the last.
  std::uint64_t Flags64(std::size_t index) const
  {
    const std::size_t w = index >> 6;
    const unsigned shift = index & 63;
    std::uint64_t flags = w < this->Bits.size() ? this->Bits[w] >> shift : 0;
    if (shift != 0 && w + 1 < this->Bits.size())
    {
      flags |= this->Bits[w + 1] << (64 - shift);
    }
    return flags;
  }
  std::size_t Stride(int axis) const
  {
    return axis == 0 ? 1
                     : static_cast<std::size_t>(this->Counts[0]) * (axis == 1 ? 1 : this->Counts[1]);
  }
  /// Same, false outside the grid.
  bool IsContributingOrOutside(int i, int j, int k) const
  {
    return i >= 0 && j >= 0 && k >= 0 && i < this->Counts[0] && j < this->Counts[1] &&
      k < this->Counts[2] && this->IsContributing(i, j, k);
  }

  /// The inclusive range [first, last] of supercells along axis whose closed extent comes
  /// within eps of coordinate x; false if none.
  bool Locate(int axis, double x, double eps, int& first, int& last) const;
  /// Whether a PC supercell's closed box comes within eps of p (voxel-index coordinates).
  bool TouchesContributing(const Vec3& p, double eps) const;

  /// The first and last index along axis of a supercell slab holding a PC supercell
  /// (first > last when none is PC).
  void ContributingPlanes(int axis, int& first, int& last) const;

private:
  bool ClassifySupercell(const RangePyramid& pyramid, const ContributionRule& rule,
    Interpolation interpolation, int i, int j, int k) const;
  /// Bits and ContributingCount from a byte (0 or 1) a supercell.
  void PackFlags(const std::vector<std::uint8_t>& flags);

  int CellDims[3] = { 0, 0, 0 };
  double Size[3] = { 1.0, 1.0, 1.0 };
  int Counts[3] = { 0, 0, 0 };
  std::size_t Count = 0;            ///< supercells
  std::vector<std::uint64_t> Bits; ///< the PC flags, supercell n at bit n % 64 of word n / 64
  std::size_t ContributingCount = 0;
};

} // namespace parc

#endif
