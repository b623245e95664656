#include "parcRay.h"

#include <algorithm>
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

void WholeRaySource::GetSegments(int, int, const Ray&, std::vector<Segment>& out) const
{
  constexpr double inf = std::numeric_limits<double>::infinity();
  out.push_back({ -inf, inf });
}

} // namespace parc
