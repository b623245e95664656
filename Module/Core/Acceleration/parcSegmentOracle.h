// PARC for VTK: the exact CPU answer to "where may this ray meet the volume?".
//
// For a ray and a parameter range, the oracle walks the supercell grid (every crossing of
// a supercell boundary, in ray order) and returns the closed intervals where the ray
// touches a PC supercell (closed boxes: a ray along a face, an edge or through a corner
// touches every supercell sharing it), their near/far, and the planes whose PC supercells
// it touches. It is the ground truth the GL passes are tested against, and a segment
// source of its own: casting with it takes the fewest samples any PARC pass can, for this
// supercell size.
#ifndef parcSegmentOracle_h
#define parcSegmentOracle_h

#include "parcSegmentSource.h"
#include "parcSupercellGrid.h"

#include <vector>

namespace parc
{

class SegmentOracle : public SegmentSource
{
public:
  /// grid must outlive the oracle; worldToIndex maps world to voxel-index coordinates.
  SegmentOracle(const SupercellGrid& grid, const Matrix4& worldToIndex);

  /// The sorted, disjoint, closed intervals of [t0, t1] where the ray touches a PC
  /// supercell. If planes is given, it receives the sorted indices along axis of the PC
  /// supercells touched (supercell indices, not renumbered).
  void Intervals(const Ray& ray, double t0, double t1, std::vector<Segment>& out,
    int axis = 0, std::vector<int>* planes = nullptr) const;

  /// Same over [TMin, TMax] of the query's ray.
  void Segments(const RayQuery& query, std::vector<Segment>& out) const override;

  /// Tolerance (voxel-index units) within which a point counts as on a boundary.
  double GetTolerance() const { return this->Eps; }

private:
  /// Whether the point of parameter t touches a PC supercell; adds their planes.
  bool Touches(const Vec3& o, const Vec3& d, double t, int axis, std::vector<int>* planes) const;

  const SupercellGrid& Grid;
  Matrix4 WorldToIndex;
  double Eps;
};

} // namespace parc

#endif
