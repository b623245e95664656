// PARC for VTK: the polygon models of the PC supercells (paper sections 3 and 4).
//
// Depth model: the outer faces of the union of PC supercells, i.e. the faces between a PC
// supercell and an empty one or the outside. Colour model for a major axis: every face of
// every PC supercell except those shared with a PC supercell of the same plane (slab of
// supercells across the axis), each carrying its plane index (0 = the first plane holding a
// PC supercell, counted along +axis; a view along -axis only reverses the numbering).
// Both are closed surfaces made of axis-aligned quads in voxel-index coordinates, wound
// counter-clockwise seen from outside.
#ifndef parcPolygonModel_h
#define parcPolygonModel_h

#include "parcSupercellGrid.h"

#include <cstdint>
#include <vector>

namespace parc
{

struct PolygonModel
{
  std::vector<Vec3> Vertices; ///< 4 per quad, voxel-index coordinates
  std::vector<int> Planes;    ///< per quad (colour model only)
  int MajorAxis = -1;         ///< colour model: 0, 1 or 2; depth model: -1
  int FirstPlane = 0;         ///< supercell index along MajorAxis of plane 0
  int PlaneCount = 0;         ///< colour model: planes from the first to the last PC one
  double PlanesLow = 0.0;     ///< colour model: index coordinate where plane 0 begins
  double PlanesHigh = 0.0;    ///< colour model: index coordinate where the last plane ends

  std::size_t GetNumberOfQuads() const { return this->Vertices.size() / 4; }
  /// Memory held by the model, in bytes.
  std::size_t GetMemorySize() const
  {
    return this->Vertices.capacity() * sizeof(Vec3) + this->Planes.capacity() * sizeof(int);
  }
  /// Total area in voxel-index units.
  double GetArea() const;
};

/// The paper's Table 4 for one grid and model.
struct ModelStatistics
{
  std::uint64_t Cells = 0;
  std::uint64_t Supercells = 0;
  std::uint64_t ContributingSupercells = 0;
  double ContributingPercent = 0.0;
  std::uint64_t Polygons = 0;
};

/// Outer faces of the PC union; merge joins coplanar neighbouring faces into rectangles.
void BuildDepthModel(const SupercellGrid& grid, bool merge, PolygonModel& model);
/// Per-plane faces along axis (0, 1, 2); merge joins coplanar neighbouring faces of the same
/// plane into rectangles.
void BuildColorModel(const SupercellGrid& grid, int axis, bool merge, PolygonModel& model);
/// For a colour model: +1 (-1) when every ray, given by the corners of the convex set of its
/// start points and the directions at the image corners (voxel-index coordinates), runs
/// along +axis (-axis) and starts before all planes. Such rays enter each plane's PC region
/// through a face towards the eye, so the plane pass may leave out the faces across the
/// axis that face along the rays. 0 otherwise (every face is needed).
int RayAxisSign(const PolygonModel& model, const std::vector<Vec3>& starts,
  const std::vector<Vec3>& directions);

ModelStatistics ComputeStatistics(const SupercellGrid& grid, const PolygonModel& model);

} // namespace parc

#endif
