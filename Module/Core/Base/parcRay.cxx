#include "parcRay.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace parc
{

bool ClipToBox(const Vec3& o, const Vec3& d, const Vec3& lo, const Vec3& hi, double& t0,
  double& t1)
{
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.0)
    {
      if (o[a] < lo[a] || o[a] > hi[a])
      {
        return false;
      }
      continue;
    }
    const double inv = 1.0 / d[a];
    double ta = (lo[a] - o[a]) * inv;
    double tb = (hi[a] - o[a]) * inv;
    if (ta > tb)
    {
      std::swap(ta, tb);
    }
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1;
}

long LatticeSampleCount(double tEnter, double tExit, double dt)
{
  const double count = std::floor(tExit / dt) - std::ceil(tEnter / dt) + 1.0;
  return count > 0.0 ? static_cast<long>(count) : 0;
}

void SegmentsToLatticeRanges(const std::vector<Segment>& segments, double tEnter, double tExit,
  double dt, std::vector<LatticeRange>& ranges)
{
  ranges.clear();
  const double kEnter = std::ceil(tEnter / dt);
  const double kExit = std::floor(tExit / dt);
  if (!(kEnter <= kExit))
  {
    return;
  }
  for (const Segment& s : segments)
  {
    const double a = std::max(s.TNear, tEnter);
    const double b = std::min(s.TFar, tExit);
    if (!(a <= b))
    {
      continue;
    }
    const double first = std::max(kEnter, std::floor(a / dt) - 1.0);
    const double last = std::min(kExit, std::ceil(b / dt) + 1.0);
    if (first <= last)
    {
      ranges.push_back({ static_cast<long>(first), static_cast<long>(last) });
    }
  }
  if (ranges.size() > 1)
  {
    std::sort(ranges.begin(), ranges.end(),
      [](const LatticeRange& x, const LatticeRange& y) { return x.First < y.First; });
    size_t out = 0;
    for (size_t i = 1; i < ranges.size(); ++i)
    {
      if (ranges[i].First <= ranges[out].Last + 1)
      {
        ranges[out].Last = std::max(ranges[out].Last, ranges[i].Last);
      }
      else
      {
        ranges[++out] = ranges[i];
      }
    }
    ranges.resize(out + 1);
  }
}

bool ClipToPlanes(const Ray& ray, const std::vector<ClipPlane>& planes, double& t0, double& t1)
{
  for (const ClipPlane& plane : planes)
  {
    // dot(n, o + t d - p) >= 0  <=>  dot(n, d) t >= dot(n, p - o).
    const double slope = Dot(plane.Normal, ray.Direction);
    const double offset = Dot(plane.Normal, plane.Origin - ray.Origin);
    if (slope > 0.0)
    {
      t0 = std::max(t0, offset / slope);
    }
    else if (slope < 0.0)
    {
      t1 = std::min(t1, offset / slope);
    }
    else if (offset > 0.0)
    {
      return false; // parallel to the plane, on the clipped side
    }
  }
  return t0 <= t1;
}

namespace
{
/// The cropping region index (0, 1, 2) of coordinate x between planes lo and hi.
int CropSlab(double x, double lo, double hi)
{
  return x < lo ? 0 : (x <= hi ? 1 : 2);
}
}

void CroppedIntervals(const Vec3& o, const Vec3& d, const Cropping& cropping, double t0,
  double t1, std::vector<Segment>& out)
{
  out.clear();
  if (!(t0 <= t1))
  {
    return;
  }
  // The parameters where the line crosses a cropping plane split [t0, t1] into pieces,
  // each inside one region: its midpoint tells which.
  // At most the two ends and one crossing per plane, kept in order as they are found: no
  // allocation per ray.
  std::array<double, 8> cuts{ t0, t1 };
  std::size_t count = 2;
  for (int a = 0; a < 3; ++a)
  {
    for (int side = 0; side < 2 && d[a] != 0.0; ++side)
    {
      const double t = (cropping.Planes[2 * a + side] - o[a]) / d[a];
      if (t > t0 && t < t1)
      {
        std::size_t at = count++;
        for (; cuts[at - 1] > t; --at) // t0 is first and smallest: the walk stops there
        {
          cuts[at] = cuts[at - 1];
        }
        cuts[at] = t;
      }
    }
  }
  for (std::size_t i = 0; i + 1 < count; ++i)
  {
    const double a = cuts[i], b = cuts[i + 1];
    const double m = a == b ? a : 0.5 * (a + b);
    int region = 0;
    for (int axis = 2; axis >= 0; --axis)
    {
      const double x = o[axis] + m * d[axis];
      region = 3 * region + CropSlab(x, cropping.Planes[2 * axis], cropping.Planes[2 * axis + 1]);
    }
    if (!(cropping.RegionFlags & (1 << region)))
    {
      continue;
    }
    if (!out.empty() && out.back().TFar >= a)
    {
      out.back().TFar = b;
    }
    else
    {
      out.push_back({ a, b });
    }
  }
}

void IntersectLatticeRanges(
  std::vector<LatticeRange>& ranges, const std::vector<Segment>& intervals, double dt)
{
  std::vector<LatticeRange> kept;
  std::size_t r = 0;
  for (const Segment& s : intervals)
  {
    const double first = std::ceil(s.TNear / dt), last = std::floor(s.TFar / dt);
    if (!(first <= last))
    {
      continue;
    }
    const long k0 = static_cast<long>(first), k1 = static_cast<long>(last);
    while (r < ranges.size() && ranges[r].Last < k0)
    {
      ++r;
    }
    for (std::size_t i = r; i < ranges.size() && ranges[i].First <= k1; ++i)
    {
      kept.push_back({ std::max(ranges[i].First, k0), std::min(ranges[i].Last, k1) });
    }
  }
  ranges.swap(kept);
}

} // namespace parc
