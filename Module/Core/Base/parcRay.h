// PARC for VTK: rays, the global sample lattice and ray segments.
//
// A ray is x(t) = Origin + t * Direction in world coordinates, Direction of unit length, so
// t is a world distance. Its samples lie on the *global lattice* t_k = k * dt (DESIGN.md
// section 2): t_0 = 0 is the eye (perspective) or the plane through the camera position
// normal to the view direction (parallel), and the lattice never depends on the segment
// being cast. That is what makes every segment source give bit-identical images.
#ifndef parcRay_h
#define parcRay_h

#include "parcMath.h"

#include <vector>

namespace parc
{

struct Ray
{
  Vec3 Origin;    ///< world coordinates
  Vec3 Direction; ///< world, unit length
  double TMin = 0.0;    ///< ray parameter where the ray may start (near clipping plane)
  double TMax = 0.0;    ///< ray parameter where it must end (far plane or opaque geometry)
};

/// A ray-parameter interval [TNear, TFar] that may hold contributing samples.
struct Segment
{
  double TNear;
  double TFar;
};

/// An inclusive range of lattice indices [First, Last].
struct LatticeRange
{
  long First;
  long Last;
};

/// A clipping plane (vtkAbstractMapper::SetClippingPlanes): the half-space
/// dot(Normal, x - Origin) >= 0 is kept, the side the normal points to, as in VTK's mappers.
struct ClipPlane
{
  Vec3 Origin;
  Vec3 Normal;
};

/// vtkVolumeMapper's cropping: planes x0 < x1, y0 < y1, z0 < z1 cut the volume into 27
/// regions, region (i, j, k) (each 0, 1, 2 from low to high along its axis) being bit
/// i + 3 j + 9 k of RegionFlags; only the regions whose bit is set are rendered.
struct Cropping
{
  bool Enabled = false;
  double Planes[6] = { 0, 0, 0, 0, 0, 0 }; ///< x0, x1, y0, y1, z0, z1 (the ray's coordinates)
  int RegionFlags = 0;
};

/// Clips the line o + t d (any coordinates) to the box [lo, hi]; [t0, t1] is narrowed in
/// place. Returns false when nothing is left.
bool ClipToBox(const Vec3& o, const Vec3& d, const Vec3& lo, const Vec3& hi, double& t0,
  double& t1);

/// Narrows [t0, t1] of ray to the part kept by every plane; false when nothing is left.
bool ClipToPlanes(const Ray& ray, const std::vector<ClipPlane>& planes, double& t0, double& t1);

/// The closed intervals of [t0, t1] of the line o + t d (in the cropping's coordinates)
/// inside rendered regions, in order and merged, into out.
void CroppedIntervals(const Vec3& o, const Vec3& d, const Cropping& cropping, double t0,
  double t1, std::vector<Segment>& out);

/// Keeps of ranges (sorted, disjoint) only the lattice indices k with k dt in one of the
/// intervals (sorted, disjoint).
void IntersectLatticeRanges(
  std::vector<LatticeRange>& ranges, const std::vector<Segment>& intervals, double dt);

/// The number of lattice samples k dt in [tEnter, tExit].
long LatticeSampleCount(double tEnter, double tExit, double dt);

/// The lattice indices to visit for segments already clipped to [tEnter, tExit]: each
/// segment [a, b] becomes [floor(a/dt) - 1, ceil(b/dt) + 1] (one lattice step of slack on
/// each side, so a crossing between the last sample before a segment and its first sample
/// is never missed), clamped to [ceil(tEnter/dt), floor(tExit/dt)], sorted and merged.
void SegmentsToLatticeRanges(const std::vector<Segment>& segments, double tEnter, double tExit,
  double dt, std::vector<LatticeRange>& ranges);

} // namespace parc

#endif
