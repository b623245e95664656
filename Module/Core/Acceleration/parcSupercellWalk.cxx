#include "parcSupercellWalk.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace parc
{

namespace
{
/// The tolerance of "comes near a box", relative to the largest coordinate of a walk (the
/// box's extent or the ray's origin): far above double rounding, far below a voxel.
constexpr double RelativeTolerance = 1e-9;
constexpr double Infinity = std::numeric_limits<double>::infinity();

bool TestBit(const std::vector<std::uint64_t>& bits, std::size_t n)
{
  return ((bits[n >> 6] >> (n & 63)) & 1) != 0;
}
}

/// One ray's walk: the line in voxel-index coordinates.
struct SupercellWalk::Line
{
  Vec3 O, D;
  double Inverse[3];
  double Eps; ///< voxel-index tolerance

  /// The same line walked the other way: the point of parameter s is this line's point of
  /// parameter -s, and every crossing parameter is the negated one, bit for bit.
  Line Reversed() const
  {
    return { this->O, -this->D, { -this->Inverse[0], -this->Inverse[1], -this->Inverse[2] },
      this->Eps };
  }

  /// What a visit of WalkBoxes returns besides a reach: stop the walk, or go on to the next
  /// box.
  static constexpr int Stop = -1;
  static constexpr int NextBox = 0;

  /// Visits, in ray order, the boxes of a grid whose faces along axis a lie at face(a, i)
  /// and whose box i holds [i size[a], (i + 1) size[a]] up to rounding, within the index
  /// range [lo, hi) per axis, over [t0, t1] (a 3-D DDA): visit(index, tIn, tOut) for each,
  /// until it returns Stop. A visit that returns a reach r > 0 has the walk leave the cube
  /// of boxes within r of this one (along every axis) in one step, where the ray first
  /// does, without visiting them.
  template <class Face, class Visit>
  void WalkBoxes(double t0, double t1, const int lo[3], const int hi[3], const double size[3],
    Face&& face, Visit&& visit) const
  {
    int index[3], step[3];
    double next[3];
    const auto nextFace = [&](int a) {
      return step[a] == 0 ? Infinity
                          : (face(a, index[a] + (step[a] > 0)) - this->O[a]) * this->Inverse[a];
    };
    const auto boxAt = [&](double x, int a) {
      const double i = std::floor(x / size[a]);
      return i < lo[a] ? lo[a] : (i >= hi[a] ? hi[a] - 1 : static_cast<int>(i));
    };
    const Vec3 start = this->O + t0 * this->D;
    for (int a = 0; a < 3; ++a)
    {
      index[a] = boxAt(start[a], a);
      step[a] = this->D[a] > 0.0 ? 1 : (this->D[a] < 0.0 ? -1 : 0);
      next[a] = nextFace(a);
    }
    double t = t0;
    for (;;)
    {
      const int a = next[0] < next[1] ? (next[0] < next[2] ? 0 : 2) : (next[1] < next[2] ? 1 : 2);
      const int reach = visit(index, t, std::max(t, std::min(next[a], t1)));
      if (reach == Stop)
      {
        return;
      }
      if (reach == NextBox)
      {
        if (!(next[a] < t1))
        {
          return;
        }
        index[a] += step[a];
        if (index[a] < lo[a] || index[a] >= hi[a])
        {
          return;
        }
        t = std::max(t, next[a]);
        next[a] = nextFace(a);
        continue;
      }
      // Leave the cube of boxes within reach of this one where the ray first does.
      int m = 0;
      double leave = Infinity;
      for (int c = 0; c < 3; ++c)
      {
        if (step[c] != 0)
        {
          const double tc =
            (face(c, index[c] + step[c] * reach + (step[c] > 0)) - this->O[c]) * this->Inverse[c];
          if (tc < leave)
          {
            leave = tc;
            m = c;
          }
        }
      }
      if (!(leave < t1))
      {
        return;
      }
      t = std::max(t, leave);
      const Vec3 p = this->O + t * this->D;
      for (int c = 0; c < 3; ++c)
      {
        if (c != m)
        {
          index[c] = std::min(index[c] + reach, std::max(index[c] - reach, boxAt(p[c], c)));
        }
      }
      index[m] += step[m] * (reach + 1);
      if (index[m] < lo[m] || index[m] >= hi[m])
      {
        return;
      }
      for (int c = 0; c < 3; ++c)
      {
        next[c] = nextFace(c);
      }
    }
  }
};

void SupercellWalk::Set(const SupercellGrid* grid, const Matrix4& worldToIndex)
{
  this->Grid = grid;
  this->WorldToIndex = worldToIndex;
  this->BuildNear();
  this->BuildBlocks();
}

void SupercellWalk::Clear()
{
  this->Grid = nullptr;
  this->Near = std::vector<std::uint64_t>();
  this->Blocks = std::vector<std::uint8_t>();
  this->Reach = std::vector<std::uint8_t>();
}

std::size_t SupercellWalk::GetMemorySize() const
{
  return this->Near.capacity() * sizeof(std::uint64_t) + this->Blocks.capacity() +
    this->Reach.capacity();
}

void SupercellWalk::BuildNear()
{
  // The PC flags dilated by one supercell along each axis in turn: PC or next to a PC
  // supercell across a face, an edge or a corner. Each word of bits is made by one thread.
  const SupercellGrid& grid = *this->Grid;
  const std::size_t count = grid.GetNumberOfSupercells();
  std::vector<std::uint64_t> bits((count + 63) / 64, 0);
  for (std::size_t n = 0; n < count; ++n)
  {
    bits[n >> 6] |= static_cast<std::uint64_t>(grid.IsContributing(n)) << (n & 63);
  }
  std::vector<std::uint64_t> dilated(bits.size(), 0);
  for (int axis = 0; axis < 3; ++axis)
  {
    const std::size_t stride = grid.Stride(axis);
    const std::size_t length = static_cast<std::size_t>(grid.GetCounts()[axis]);
    vtkSMPTools::For(0, static_cast<vtkIdType>(bits.size()), [&](vtkIdType w0, vtkIdType w1) {
      for (std::size_t w = static_cast<std::size_t>(w0); w < static_cast<std::size_t>(w1); ++w)
      {
        std::uint64_t word = 0;
        for (std::size_t b = 0; b < 64 && 64 * w + b < count; ++b)
        {
          const std::size_t n = 64 * w + b;
          const std::size_t c = (n / stride) % length;
          const bool set = TestBit(bits, n) || (c > 0 && TestBit(bits, n - stride)) ||
            (c + 1 < length && TestBit(bits, n + stride));
          word |= static_cast<std::uint64_t>(set) << b;
        }
        dilated[w] = word;
      }
    });
    bits.swap(dilated);
  }
  this->Near = std::move(bits);
}

void SupercellWalk::BuildBlocks()
{
  const SupercellGrid& grid = *this->Grid;
  const int* counts = grid.GetCounts();
  for (int a = 0; a < 3; ++a)
  {
    this->BlockCounts[a] = (counts[a] + BlockSize - 1) / BlockSize;
  }
  const int bx = this->BlockCounts[0], by = this->BlockCounts[1];
  this->Blocks.assign(static_cast<std::size_t>(bx) * by * this->BlockCounts[2], Empty);
  vtkSMPTools::For(0, this->BlockCounts[2], [&](vtkIdType k0, vtkIdType k1) {
    for (int bk = static_cast<int>(k0); bk < k1; ++bk)
    {
      for (int bj = 0; bj < by; ++bj)
      {
        for (int bi = 0; bi < bx; ++bi)
        {
          const int block[3] = { bi, bj, bk };
          int lo[3], hi[3];
          for (int a = 0; a < 3; ++a)
          {
            lo[a] = block[a] * BlockSize;
            hi[a] = std::min(lo[a] + BlockSize, counts[a]);
          }
          bool near = false, full = true;
          for (int k = lo[2]; k < hi[2]; ++k)
          {
            for (int j = lo[1]; j < hi[1]; ++j)
            {
              for (int i = lo[0]; i < hi[0]; ++i)
              {
                const std::size_t n = grid.Index(i, j, k);
                near = near || this->IsNear(n);
                full = full && grid.IsContributing(n);
              }
            }
          }
          this->Blocks[this->BlockIndex(block)] =
            full ? Full : (near ? Mixed : Empty);
        }
      }
    }
  });
  this->BuildReach();
}

void SupercellWalk::BuildReach()
{
  // Reach r of an empty block: every block within r - 1 blocks of this one (in each axis;
  // outside the grid counts) is empty too. Grown one block a round; 1 for the others.
  const int* counts = this->BlockCounts;
  const auto empty = [this](std::size_t b) { return this->Blocks[b] == Empty; };
  this->Reach.assign(this->Blocks.size(), 1);
  std::vector<std::uint8_t> grown(this->Reach.size());
  for (int round = 1; round < MaxReach; ++round)
  {
    bool changed = false;
    for (int k = 0; k < counts[2]; ++k)
    {
      for (int j = 0; j < counts[1]; ++j)
      {
        for (int i = 0; i < counts[0]; ++i)
        {
          const int block[3] = { i, j, k };
          const std::size_t b = this->BlockIndex(block);
          bool grows = empty(b) && this->Reach[b] == round;
          for (int n = 0; grows && n < 27; ++n)
          {
            const int other[3] = { i + n % 3 - 1, j + (n / 3) % 3 - 1, k + n / 9 - 1 };
            if (other[0] >= 0 && other[1] >= 0 && other[2] >= 0 && other[0] < counts[0] &&
              other[1] < counts[1] && other[2] < counts[2])
            {
              const std::size_t c = this->BlockIndex(other);
              grows = this->Reach[c] >= round && empty(c);
            }
          }
          grown[b] = static_cast<std::uint8_t>(this->Reach[b] + (grows ? 1 : 0));
          changed = changed || grows;
        }
      }
    }
    this->Reach.swap(grown);
    if (!changed)
    {
      break;
    }
  }
}

void SupercellWalk::Segments(const RayQuery& query, std::vector<Segment>& out) const
{
  const Ray& ray = query.Path;
  this->IndexSegments(this->WorldToIndex.TransformPoint(ray.Origin),
    this->WorldToIndex.TransformVector(ray.Direction), ray.TMin, ray.TMax, out);
}

void SupercellWalk::IndexSegments(
  const Vec3& o, const Vec3& d, double t0, double t1, std::vector<Segment>& out) const
{
  if (!this->Grid || this->Grid->GetNumberOfContributing() == 0)
  {
    return;
  }
  const int* cells = this->Grid->GetCellDimensions();
  const double extent = std::max({ 1.0 * cells[0], 1.0 * cells[1], 1.0 * cells[2],
    std::abs(o.X), std::abs(o.Y), std::abs(o.Z) });
  const double eps = RelativeTolerance * extent;
  const Vec3 margin{ eps, eps, eps };
  if (!ClipToBox(o, d, Vec3() - margin, Vec3(cells[0], cells[1], cells[2]) + margin, t0, t1))
  {
    return;
  }
  const Line line{ o, d, { 1.0 / d.X, 1.0 / d.Y, 1.0 / d.Z }, eps };
  double near, far;
  if (this->FirstHit(line, false, t0, t1, near) && this->FirstHit(line, true, near, t1, far))
  {
    out.push_back({ near, std::max(near, far) });
  }
}

bool SupercellWalk::FirstHit(
  const Line& forward, bool last, double t0, double t1, double& hit) const
{
  // Walked backwards, the line's parameters are negated (Line::Reversed).
  const Line line = last ? forward.Reversed() : forward;
  const SupercellGrid& grid = *this->Grid;
  const double* size = grid.GetSize();
  const double blockSize[3] = { BlockSize * size[0], BlockSize * size[1], BlockSize * size[2] };
  const int lo[3] = { 0, 0, 0 };
  bool found = false;
  line.WalkBoxes(last ? -t1 : t0, last ? -t0 : t1, lo, this->BlockCounts, blockSize,
    [&grid](int a, int i) { return grid.Boundary(a, i * BlockSize); },
    [&](const int block[3], double s, double sOut) {
      const std::size_t b = this->BlockIndex(block);
      switch (this->Blocks[b])
      {
        case Empty:
          return this->Reach[b] - 1; // the empty blocks around it
        case Full:
          hit = last ? -s : s;
          found = true;
          return Line::Stop;
        default:
          found = this->EndInBlock(forward, last, block, last ? -sOut : s, last ? -s : sOut, hit);
          return found ? Line::Stop : Line::NextBox;
      }
    });
  return found;
}

bool SupercellWalk::EndInBlock(const Line& forward, bool last, const int block[3], double tIn,
  double tOut, double& t) const
{
  const SupercellGrid& grid = *this->Grid;
  const int* counts = grid.GetCounts();
  int lo[3], hi[3];
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = block[a] * BlockSize;
    hi[a] = std::min(lo[a] + BlockSize, counts[a]);
  }
  // Walked backwards, the line's parameters are negated (Line::Reversed).
  const Line line = last ? forward.Reversed() : forward;
  const double s0 = last ? -tOut : tIn, s1 = last ? -tIn : tOut;
  bool found = false;
  line.WalkBoxes(s0, s1, lo, hi, grid.GetSize(),
    [&grid](int a, int i) { return grid.Boundary(a, i); },
    [&](const int s[3], double a0, double a1) {
      const std::size_t n = grid.Index(s[0], s[1], s[2]);
      if (grid.IsContributing(n) || (this->IsNear(n) && this->Approach(line, s, a0, a1, a0)))
      {
        t = last ? -a0 : a0;
        found = true;
      }
      return found ? Line::Stop : Line::NextBox;
    });
  return found;
}

bool SupercellWalk::Approach(
  const Line& line, const int s[3], double tIn, double tOut, double& first) const
{
  const SupercellGrid& grid = *this->Grid;
  const int* counts = grid.GetCounts();
  const Vec3 pIn = line.O + tIn * line.D, pOut = line.O + tOut * line.D;
  // Per axis: the faces of s the ray comes within the tolerance of, and the offsets of the
  // neighbours across them.
  double faces[3][2];
  int lowest[3], highest[3];
  for (int a = 0; a < 3; ++a)
  {
    faces[a][0] = grid.Boundary(a, s[a]);
    faces[a][1] = grid.Boundary(a, s[a] + 1);
    lowest[a] = s[a] > 0 && std::min(pIn[a], pOut[a]) <= faces[a][0] + line.Eps ? -1 : 0;
    highest[a] =
      s[a] + 1 < counts[a] && std::max(pIn[a], pOut[a]) >= faces[a][1] - line.Eps ? 1 : 0;
  }
  first = Infinity;
  int offset[3];
  for (offset[2] = lowest[2]; offset[2] <= highest[2]; ++offset[2])
  {
    for (offset[1] = lowest[1]; offset[1] <= highest[1]; ++offset[1])
    {
      for (offset[0] = lowest[0]; offset[0] <= highest[0]; ++offset[0])
      {
        if ((offset[0] | offset[1] | offset[2]) == 0 ||
          !grid.IsContributing(s[0] + offset[0], s[1] + offset[1], s[2] + offset[2]))
        {
          continue;
        }
        // Where the ray is within the tolerance of the neighbour along each axis it lies
        // across: p <= lower face + eps, or p >= upper face - eps.
        double a0 = tIn, a1 = tOut;
        for (int a = 0; a < 3; ++a)
        {
          if (offset[a] == 0)
          {
            continue;
          }
          const bool below = offset[a] < 0;
          const double bound = below ? faces[a][0] + line.Eps : faces[a][1] - line.Eps;
          if (line.D[a] == 0.0)
          {
            if (below ? line.O[a] > bound : line.O[a] < bound)
            {
              a1 = -Infinity;
            }
            continue;
          }
          const double t = (bound - line.O[a]) / line.D[a];
          if (below == (line.D[a] > 0.0))
          {
            a1 = std::min(a1, t); // moving away from the neighbour
          }
          else
          {
            a0 = std::max(a0, t);
          }
        }
        if (a0 <= a1)
        {
          first = std::min(first, a0);
        }
      }
    }
  }
  return first < Infinity;
}

} // namespace parc
