// PARC for VTK: the supercell classification walked along each ray on the CPU, a segment
// source without a GL pass (what the depth pass projects, found by a 3-D DDA instead).
//
// Each ray gets one segment, from where it may first meet a PC supercell to where it may
// last, found by walking from its front and from its back. The walk goes through blocks of
// BlockSize^3 supercells: an empty block (no PC supercell in it or next to it) is crossed
// together with the empty blocks within its reach in one step; in a block of PC supercells
// only the ray meets one where it enters; the supercells of any other block are walked one
// by one. The sampler and the walk round differently, so a ray that passes within a
// tolerance of a PC supercell's closed box from a supercell that is not PC (possible only
// next to one, which the near flags mark) counts as meeting it there: the segment holds
// every interval the segment oracle gives (tested). A ray needs no pixel, so shadow rays
// use the same source.
#ifndef parcSupercellWalk_h
#define parcSupercellWalk_h

#include "parcSegmentSource.h"
#include "parcSupercellGrid.h"

#include <cstdint>
#include <vector>

namespace parc
{

class SupercellWalk final : public SegmentSource
{
public:
  /// Supercells along each axis of a block of the first level of the walk.
  static constexpr int BlockSize = 4;
  /// The largest reach of a block (see Reach).
  static constexpr int MaxReach = 16;

  /// Derives the walk's flags from grid's classification (in parallel); grid must outlive
  /// the walk's use and keep this classification while it is used. worldToIndex maps the
  /// rays' coordinates to voxel-index coordinates.
  void Set(const SupercellGrid* grid, const Matrix4& worldToIndex);
  /// Whether Set has been called since the last Clear.
  bool IsSet() const { return this->Grid != nullptr; }
  /// Frees the flags; the walk is unset.
  void Clear();
  void SetWorldToIndex(const Matrix4& worldToIndex) { this->WorldToIndex = worldToIndex; }

  void Segments(const RayQuery& query, std::vector<Segment>& out) const override;
  /// The segments of the line o + t d (voxel-index coordinates) within [t0, t1].
  void IndexSegments(
    const Vec3& o, const Vec3& d, double t0, double t1, std::vector<Segment>& out) const;

  /// Memory held by the near flags and the block states, in bytes.
  std::size_t GetMemorySize() const;

private:
  enum BlockState : std::uint8_t
  {
    Empty = 0, ///< no PC supercell in it or next to it
    Full = 1,  ///< PC supercells only
    Mixed = 2
  };
  struct Line; // one ray's walk (parcSupercellWalk.cxx)

  void BuildNear();
  void BuildBlocks();
  void BuildReach();
  bool IsNear(std::size_t index) const
  {
    return ((this->Near[index >> 6] >> (index & 63)) & 1) != 0;
  }
  std::size_t BlockIndex(const int block[3]) const
  {
    return block[0] +
      static_cast<std::size_t>(this->BlockCounts[0]) *
      (block[1] + static_cast<std::size_t>(this->BlockCounts[1]) * block[2]);
  }
  /// The first (or, with last, the last) parameter hit of [t0, t1] where line may meet a
  /// PC supercell; false when there is none.
  bool FirstHit(const Line& line, bool last, double t0, double t1, double& hit) const;
  /// The first (or, with last, the last) parameter t of [tIn, tOut] where line may meet a
  /// PC supercell of block, walking its supercells one by one from that end; false when
  /// there is none.
  bool EndInBlock(const Line& line, bool last, const int block[3], double tIn, double tOut,
    double& t) const;
  /// Whether the ray, in supercell s (not PC, next to one) over [tIn, tOut], comes within
  /// the tolerance of a PC neighbour; first receives the first parameter where it does.
  bool Approach(const Line& line, const int s[3], double tIn, double tOut, double& first) const;

  const SupercellGrid* Grid = nullptr;
  Matrix4 WorldToIndex;
  /// Per supercell (the grid's layout and bit order): PC or next to a PC supercell.
  std::vector<std::uint64_t> Near;
  int BlockCounts[3] = { 0, 0, 0 };
  std::vector<std::uint8_t> Blocks; ///< BlockState per block, x fastest
  /// Per block, its reach r: an empty block's neighbours within r - 1 of it along every
  /// axis are empty, so that a ray crosses them in one step (1 for the other blocks).
  std::vector<std::uint8_t> Reach;
};

} // namespace parc

#endif
