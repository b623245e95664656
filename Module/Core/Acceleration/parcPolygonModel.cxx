#include "parcPolygonModel.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace parc
{

namespace
{
/// Appends the quad on the side (0 low, 1 high) along axis of the supercells whose indices
/// along the two other axes b = axis + 1, c = axis + 2 (cyclic) run over [b0, b1] x [c0, c1]
/// and whose index along axis is i; wound counter-clockwise seen from outside.
void AddQuad(const SupercellGrid& grid, int axis, int side, int i, int b0, int b1, int c0,
  int c1, PolygonModel& model)
{
  const int b = (axis + 1) % 3, c = (axis + 2) % 3;
  const double x = grid.Boundary(axis, i + side);
  const double u0 = grid.Boundary(b, b0), u1 = grid.Boundary(b, b1 + 1);
  const double v0 = grid.Boundary(c, c0), v1 = grid.Boundary(c, c1 + 1);
  const double uv[4][2] = { { u0, v0 }, { u1, v0 }, { u1, v1 }, { u0, v1 } };
  for (int n = 0; n < 4; ++n)
  {
    const int corner = side ? n : (4 - n) % 4;
    Vec3 p;
    p[axis] = x;
    p[b] = uv[corner][0];
    p[c] = uv[corner][1];
    model.Vertices.push_back(p);
  }
}

/// Covers the set entries of a row-major nu x nv mask with rectangles (greedy: widest run
/// along u first, then as many full rows along v as follow), clearing them; calls
/// emit(u0, u1, v0, v1) for each. Without merging, each entry is its own rectangle.
template <class Emit>
void CoverMask(std::vector<char>& mask, int nu, int nv, bool merge, Emit&& emit)
{
  for (int v = 0; v < nv; ++v)
  {
    const char* row = mask.data() + static_cast<std::size_t>(nu) * v;
    for (int u = 0; u < nu; ++u)
    {
      // The next set entry of the row (entries are 0 or 1).
      const void* set = std::memchr(row + u, 1, static_cast<std::size_t>(nu - u));
      if (!set)
      {
        break;
      }
      u = static_cast<int>(static_cast<const char*>(set) - row);
      int u1 = u, v1 = v;
      if (merge)
      {
        while (u1 + 1 < nu && mask[u1 + 1 + static_cast<std::size_t>(nu) * v])
        {
          ++u1;
        }
        for (bool fullRow = true; fullRow && v1 + 1 < nv;)
        {
          for (int x = u; x <= u1 && fullRow; ++x)
          {
            fullRow = mask[x + static_cast<std::size_t>(nu) * (v1 + 1)] != 0;
          }
          v1 += fullRow ? 1 : 0;
        }
      }
      for (int y = v; y <= v1; ++y)
      {
        std::fill_n(mask.begin() + u + static_cast<std::size_t>(nu) * y, u1 - u + 1, 0);
      }
      emit(u, u1, v, v1);
    }
  }
}

/// Runs build(i, part) for every slice i in [first, last] in parallel, each into a part of
/// its own, then appends the parts to model in the order of i: the model a loop over i in
/// order would make, whatever the threads.
template <class Build>
void BuildSlices(int first, int last, PolygonModel& model, Build&& build)
{
  if (first > last)
  {
    return;
  }
  std::vector<PolygonModel> parts(static_cast<std::size_t>(last - first + 1));
  vtkSMPTools::For(first, last + 1, [&](vtkIdType begin, vtkIdType end) {
    for (vtkIdType i = begin; i < end; ++i)
    {
      build(static_cast<int>(i), parts[static_cast<std::size_t>(i - first)]);
    }
  });
  for (const PolygonModel& part : parts)
  {
    model.Vertices.insert(model.Vertices.end(), part.Vertices.begin(), part.Vertices.end());
    model.Planes.insert(model.Planes.end(), part.Planes.begin(), part.Planes.end());
  }
}

/// The supercell with index i along axis and (u, v) along the two other axes (cyclic).
void Compose(int axis, int i, int u, int v, int idx[3])
{
  idx[axis] = i;
  idx[(axis + 1) % 3] = u;
  idx[(axis + 2) % 3] = v;
}
}

double PolygonModel::GetArea() const
{
  double area = 0.0;
  for (std::size_t q = 0; q + 3 < this->Vertices.size(); q += 4)
  {
    const Vec3& p = this->Vertices[q];
    area += 0.5 * Length(Cross(this->Vertices[q + 1] - p, this->Vertices[q + 2] - p));
    area += 0.5 * Length(Cross(this->Vertices[q + 2] - p, this->Vertices[q + 3] - p));
  }
  return area;
}

void BuildDepthModel(const SupercellGrid& grid, bool merge, PolygonModel& model)
{
  model = PolygonModel();
  const int* n = grid.GetCounts();
  for (int axis = 0; axis < 3; ++axis)
  {
    const int nu = n[(axis + 1) % 3], nv = n[(axis + 2) % 3];
    for (int side = 0; side < 2; ++side)
    {
      const std::size_t su = grid.Stride((axis + 1) % 3), sv = grid.Stride((axis + 2) % 3);
      BuildSlices(0, n[axis] - 1, model, [&](int i, PolygonModel& part) {
        // A face is exposed where a PC supercell's neighbour across it is empty or outside.
        const int neighbour = side ? i + 1 : i - 1;
        const bool inside = neighbour >= 0 && neighbour < n[axis];
        const std::size_t slice = static_cast<std::size_t>(i) * grid.Stride(axis);
        const std::size_t next =
          inside ? static_cast<std::size_t>(neighbour) * grid.Stride(axis) : 0;
        std::vector<char> mask(static_cast<std::size_t>(nu) * nv);
        if (axis == 0)
        {
          for (int v = 0; v < nv; ++v)
          {
            for (int u = 0; u < nu; ++u)
            {
              const std::size_t at = u * su + v * sv;
              mask[u + static_cast<std::size_t>(nu) * v] = grid.IsContributing(slice + at) &&
                !(inside && grid.IsContributing(next + at));
            }
          }
        }
        else
        {
          // Rows along x, 64 supercells at a time: x is u (axis 2) or v (axis 1).
          const int rows = axis == 2 ? nv : nu;
          const std::size_t rowStride = axis == 2 ? sv : su;
          for (int r = 0; r < rows; ++r)
          {
            for (int x0 = 0; x0 < n[0]; x0 += 64)
            {
              const std::size_t at = r * rowStride + x0;
              std::uint64_t exposed = grid.Flags64(slice + at);
              if (inside)
              {
                exposed &= ~grid.Flags64(next + at);
              }
              if (n[0] - x0 < 64)
              {
                exposed &= (std::uint64_t(1) << (n[0] - x0)) - 1;
              }
              for (; exposed != 0; exposed &= exposed - 1)
              {
                const int x = x0 + CountTrailingZeros(exposed);
                mask[axis == 2 ? x + static_cast<std::size_t>(nu) * r
                               : r + static_cast<std::size_t>(nu) * x] = 1;
              }
            }
          }
        }
        CoverMask(mask, nu, nv, merge, [&](int u0, int u1, int v0, int v1) {
          AddQuad(grid, axis, side, i, u0, u1, v0, v1, part);
        });
      });
    }
  }
}

void BuildColorModel(const SupercellGrid& grid, int axis, bool merge, PolygonModel& model)
{
  model = PolygonModel();
  model.MajorAxis = axis;
  int first, last;
  grid.ContributingPlanes(axis, first, last);
  if (first > last)
  {
    return;
  }
  model.FirstPlane = first;
  model.PlaneCount = last - first + 1;
  model.PlanesLow = grid.Boundary(axis, first);
  model.PlanesHigh = grid.Boundary(axis, last + 1);
  const int* n = grid.GetCounts();
  const int b = (axis + 1) % 3, c = (axis + 2) % 3; // in-plane axes, indices u and v
  const int nu = n[b], nv = n[c];
  auto at = [nu](int u, int v) { return u + static_cast<std::size_t>(nu) * v; };
  BuildSlices(first, last, model, [&](int i, PolygonModel& part) {
    std::vector<char> pc(static_cast<std::size_t>(nu) * nv), mask(pc.size());
    for (int v = 0; v < nv; ++v)
    {
      for (int u = 0; u < nu; ++u)
      {
        int idx[3];
        Compose(axis, i, u, v, idx);
        pc[at(u, v)] = grid.IsContributing(idx[0], idx[1], idx[2]);
      }
    }
    // Across the axis: both faces of every PC supercell (the neighbours are in other planes).
    mask = pc;
    CoverMask(mask, nu, nv, merge, [&](int u0, int u1, int v0, int v1) {
      AddQuad(grid, axis, 0, i, u0, u1, v0, v1, part);
      AddQuad(grid, axis, 1, i, u0, u1, v0, v1, part);
    });
    // Within the plane: only towards an empty supercell or the outside. A face normal to b
    // spans (c, axis), one normal to c spans (axis, b); runs along the free in-plane axis
    // merge.
    for (int side = 0; side < 2; ++side)
    {
      const int step = side ? 1 : -1;
      auto exposed = [&](int u, int v, int du, int dv) {
        int other[3];
        Compose(axis, i, u + du, v + dv, other);
        return pc[at(u, v)] && !grid.IsContributingOrOutside(other[0], other[1], other[2]);
      };
      for (int u = 0; u < nu; ++u)
      {
        for (int v = 0; v < nv; ++v)
        {
          if (exposed(u, v, step, 0))
          {
            int v1 = v;
            while (merge && v1 + 1 < nv && exposed(u, v1 + 1, step, 0))
            {
              ++v1;
            }
            AddQuad(grid, b, side, u, v, v1, i, i, part);
            v = v1;
          }
        }
      }
      for (int v = 0; v < nv; ++v)
      {
        for (int u = 0; u < nu; ++u)
        {
          if (exposed(u, v, 0, step))
          {
            int u1 = u;
            while (merge && u1 + 1 < nu && exposed(u1 + 1, v, 0, step))
            {
              ++u1;
            }
            AddQuad(grid, c, side, v, i, i, u, u1, part);
            u = u1;
          }
        }
      }
    }
    part.Planes.resize(part.GetNumberOfQuads(), i - first);
  });
}

int RayAxisSign(const PolygonModel& model, const std::vector<Vec3>& starts,
  const std::vector<Vec3>& directions)
{
  const int axis = model.MajorAxis;
  if (axis < 0 || directions.empty())
  {
    return 0;
  }
  for (const int sign : { 1, -1 })
  {
    const bool along = std::all_of(directions.begin(), directions.end(),
      [&](const Vec3& d) { return sign * d[axis] > 0.0; });
    const bool before = std::all_of(starts.begin(), starts.end(), [&](const Vec3& p) {
      return sign > 0 ? p[axis] < model.PlanesLow : p[axis] > model.PlanesHigh;
    });
    if (along && before)
    {
      return sign;
    }
  }
  return 0;
}

ModelStatistics ComputeStatistics(const SupercellGrid& grid, const PolygonModel& model)
{
  ModelStatistics s;
  const int* cells = grid.GetCellDimensions();
  s.Cells = static_cast<std::uint64_t>(cells[0]) * cells[1] * cells[2];
  s.Supercells = grid.GetNumberOfSupercells();
  s.ContributingSupercells = grid.GetNumberOfContributing();
  s.ContributingPercent =
    s.Supercells ? 100.0 * static_cast<double>(s.ContributingSupercells) / s.Supercells : 0.0;
  s.Polygons = model.GetNumberOfQuads();
  return s;
}

} // namespace parc
