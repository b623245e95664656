// PARC for VTK: CellMap, which cells of a field may contribute, as the caster reads it
// for each sample: a byte a node of 4x4x4 cells (the range pyramid's lowest level, packed:
// RangePyramid::MapCells) and, for each of the 256 bytes, whether its range meets the ray
// function's rule. A transfer-function edit changes only the table.
#ifndef parcCellMap_h
#define parcCellMap_h

#include "parcMath.h"
#include "parcRayLattice.h"

#include <cstddef>
#include <cstdint>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace parc
{

class CellMap
{
public:
  static constexpr int CodeCount = 256;
  /// A node's cells along each axis: 1 << NodeShift.
  static constexpr int NodeShift = 2;
  static constexpr int NodeCells = 1 << NodeShift;
  /// 1 for the codes whose cells may contribute, 0 for the others.
  std::uint8_t Contributes[CodeCount] = {};

  /// Maps the nodes to codes (node (i, j, k), cells NodeCells i to NodeCells (i + 1) - 1
  /// along x and so on, at i + nodeDims[0] (j + nodeDims[1] k)). Nodes beyond 32-bit
  /// indices leave the map empty: the caster then samples every cell.
  void SetNodes(const std::uint8_t* codes, const int nodeDims[3])
  {
    this->NodeCodes = nullptr;
    const double nodes = static_cast<double>(nodeDims[0]) * nodeDims[1] * nodeDims[2];
    if (nodes > std::numeric_limits<std::int32_t>::max())
    {
      return;
    }
    this->NodeCodes = codes;
    for (int a = 0; a < 3; ++a)
    {
      this->NodeDims[a] = nodeDims[a];
    }
    this->RowStep = nodeDims[0];
    this->PlaneStep = nodeDims[0] * nodeDims[1];
  }
  bool IsEmpty() const { return this->NodeCodes == nullptr; }
  /// Whether the map covers the cells of a field of dims voxels.
  bool Covers(const int dims[3]) const
  {
    bool covers = !this->IsEmpty();
    for (int a = 0; a < 3; ++a)
    {
      covers &= this->NodeDims[a] == (dims[a] - 1 + NodeCells - 1) >> NodeShift; // ceil
    }
    return covers;
  }
  /// Whether cell (i, j, k) (the voxel index of its first corner) may contribute.
  bool MayContribute(int i, int j, int k) const
  {
    return this->Contributes[this->NodeCodes[this->Node(i, j, k)]] != 0;
  }
  /// Whether the cell of lane j of block may contribute.
  bool MayContribute(const LatticeBlock& block, int j) const
  {
    return this->MayContribute(block.Cell[0][j], block.Cell[1][j], block.Cell[2][j]);
  }
  /// The lanes j < n (a multiple of LatticeBlock::Lanes) of block whose cell may
  /// contribute, as bits 1 << j.
  PARC_HOT_INLINE unsigned Lanes(const LatticeBlock& block, int n) const
  {
    alignas(16) std::int32_t node[LatticeBlock::Size];
#if defined(__SSE2__)
    static_assert(LatticeBlock::Lanes == 4, "four lanes to an SSE register");
    const __m128i row = _mm_set1_epi32(this->RowStep), plane = _mm_set1_epi32(this->PlaneStep);
    for (int j = 0; j < n; j += 4)
    {
      const __m128i x = _mm_srai_epi32(block.CellLanes(0, j), NodeShift);
      const __m128i y = _mm_srai_epi32(block.CellLanes(1, j), NodeShift);
      const __m128i z = _mm_srai_epi32(block.CellLanes(2, j), NodeShift);
      _mm_store_si128(reinterpret_cast<__m128i*>(node + j),
        _mm_add_epi32(x, _mm_add_epi32(MultiplyLow(y, row), MultiplyLow(z, plane))));
    }
#else
    for (int j = 0; j < n; ++j)
    {
      node[j] = this->Node(block.Cell[0][j], block.Cell[1][j], block.Cell[2][j]);
    }
#endif
    unsigned lanes = 0;
    for (int j = 0; j < n; ++j)
    {
      lanes |= static_cast<unsigned>(this->Contributes[this->NodeCodes[node[j]]]) << j;
    }
    return lanes;
  }

private:
  std::int32_t Node(int i, int j, int k) const
  {
    return (i >> NodeShift) + (j >> NodeShift) * this->RowStep +
      (k >> NodeShift) * this->PlaneStep;
  }
#if defined(__SSE2__)
  /// The low 32 bits of the products of a's and b's lanes (SSE2 multiplies two at a time).
  static PARC_HOT_INLINE __m128i MultiplyLow(__m128i a, __m128i b)
  {
    const __m128i even = _mm_mul_epu32(a, b);
    const __m128i odd = _mm_mul_epu32(_mm_srli_epi64(a, 32), _mm_srli_epi64(b, 32));
    return _mm_unpacklo_epi32(_mm_shuffle_epi32(even, _MM_SHUFFLE(0, 0, 2, 0)),
      _mm_shuffle_epi32(odd, _MM_SHUFFLE(0, 0, 2, 0)));
  }
#endif

  const std::uint8_t* NodeCodes = nullptr; ///< null: no map
  int NodeDims[3] = { 0, 0, 0 };           ///< nodes per axis
  std::int32_t RowStep = 0, PlaneStep = 0; ///< nodes between neighbours along y, z
};

} // namespace parc

#endif
