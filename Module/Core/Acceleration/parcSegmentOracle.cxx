#include "parcSegmentOracle.h"

#include <algorithm>
#include <cmath>

namespace parc
{

namespace
{
/// Relative tolerance of "on a boundary": double rounding of the walk, far below a voxel.
constexpr double RelativeTolerance = 1e-9;
}

SegmentOracle::SegmentOracle(const SupercellGrid& grid, const Matrix4& worldToIndex)
  : Grid(grid)
  , WorldToIndex(worldToIndex)
{
  const int* cells = grid.GetCellDimensions();
  this->Eps = RelativeTolerance * std::max({ 1, cells[0], cells[1], cells[2] });
}

bool SegmentOracle::Touches(const Vec3& o, const Vec3& d, double t, int axis,
  std::vector<int>* planes) const
{
  const Vec3 p = o + t * d;
  int first[3], last[3];
  for (int a = 0; a < 3; ++a)
  {
    if (!this->Grid.Locate(a, p[a], this->Eps, first[a], last[a]))
    {
      return false;
    }
  }
  bool touches = false;
  int idx[3];
  for (idx[2] = first[2]; idx[2] <= last[2]; ++idx[2])
  {
    for (idx[1] = first[1]; idx[1] <= last[1]; ++idx[1])
    {
      for (idx[0] = first[0]; idx[0] <= last[0]; ++idx[0])
      {
        if (this->Grid.IsContributing(idx[0], idx[1], idx[2]))
        {
          touches = true;
          if (!planes)
          {
            return true;
          }
          planes->push_back(idx[axis]);
        }
      }
    }
  }
  return touches;
}

void SegmentOracle::Intervals(const Ray& ray, double t0, double t1, std::vector<Segment>& out,
  int axis, std::vector<int>* planes) const
{
  const Vec3 o = this->WorldToIndex.TransformPoint(ray.Origin);
  const Vec3 d = this->WorldToIndex.TransformVector(ray.Direction);
  const int* cells = this->Grid.GetCellDimensions();
  const Vec3 margin{ this->Eps, this->Eps, this->Eps };
  if (!ClipToBox(o, d, Vec3() - margin, Vec3(cells[0], cells[1], cells[2]) + margin, t0, t1))
  {
    return;
  }
  // Every boundary crossing inside (t0, t1), in ray order.
  std::vector<double> events{ t0 };
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] == 0.0)
    {
      continue;
    }
    for (int i = 0; i <= this->Grid.GetCounts()[a]; ++i)
    {
      const double t = (this->Grid.Boundary(a, i) - o[a]) / d[a];
      if (t > t0 && t < t1)
      {
        events.push_back(t);
      }
    }
  }
  events.push_back(t1);
  std::sort(events.begin(), events.end());
  // The event points and the open stretches between them, each tested at one point.
  const std::size_t begin = out.size();
  auto add = [&](double a, double b) {
    if (out.size() > begin && a <= out.back().TFar)
    {
      out.back().TFar = std::max(out.back().TFar, b);
    }
    else
    {
      out.push_back({ a, b });
    }
  };
  for (std::size_t e = 0; e < events.size(); ++e)
  {
    if (this->Touches(o, d, events[e], axis, planes))
    {
      add(events[e], events[e]);
    }
    if (e + 1 < events.size() && events[e + 1] > events[e] &&
      this->Touches(o, d, 0.5 * (events[e] + events[e + 1]), axis, planes))
    {
      add(events[e], events[e + 1]);
    }
  }
  if (planes)
  {
    std::sort(planes->begin(), planes->end());
    planes->erase(std::unique(planes->begin(), planes->end()), planes->end());
  }
}

void SegmentOracle::Segments(const RayQuery& query, std::vector<Segment>& out) const
{
  this->Intervals(query.Path, query.Path.TMin, query.Path.TMax, out);
}

} // namespace parc
