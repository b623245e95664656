#include "parcSupercellGrid.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace parc
{

namespace
{
/// The range of the trilinear interpolant of the 8 corners v (x fastest) on the box
/// [u0, u1] (local cell coordinates in [0, 1]^3): the range of its values at the corners.
void TrilinearRange(const double v[8], const double u0[3], const double u1[3], double& lo,
  double& hi)
{
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (int c = 0; c < 8; ++c)
  {
    const double x = (c & 1) ? u1[0] : u0[0];
    const double y = (c & 2) ? u1[1] : u0[1];
    const double z = (c & 4) ? u1[2] : u0[2];
    const double v00 = v[0] + x * (v[1] - v[0]);
    const double v10 = v[2] + x * (v[3] - v[2]);
    const double v01 = v[4] + x * (v[5] - v[4]);
    const double v11 = v[6] + x * (v[7] - v[6]);
    const double w0 = v00 + y * (v10 - v00);
    const double w1 = v01 + y * (v11 - v01);
    const double s = w0 + z * (w1 - w0);
    lo = std::min(lo, s);
    hi = std::max(hi, s);
  }
}
}

double SupercellGrid::CountSupercells(const int cellDims[3], const double size[3])
{
  double count = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    if (cellDims[a] < 1 || !(size[a] > 0.0) || !std::isfinite(size[a]))
    {
      return std::numeric_limits<double>::infinity();
    }
    count *= std::max(1.0, std::ceil(cellDims[a] / size[a]));
  }
  return count;
}

bool SupercellGrid::FitSize(const int cellDims[3], const double size[3], double fitted[3])
{
  const double count = CountSupercells(cellDims, size);
  if (!std::isfinite(count))
  {
    return false;
  }
  constexpr double Step = 1.001; ///< growth of the factor while the grid is too large
  double factor = std::max(1.0, std::cbrt(count / static_cast<double>(MaxSupercells)));
  for (;; factor *= Step)
  {
    for (int a = 0; a < 3; ++a)
    {
      fitted[a] = size[a] * factor;
    }
    if (CountSupercells(cellDims, fitted) <= static_cast<double>(MaxSupercells))
    {
      return true;
    }
  }
}

bool SupercellGrid::Configure(const int cellDims[3], const double size[3])
{
  this->Bits.clear();
  this->Count = 0;
  this->ContributingCount = 0;
  std::size_t total = 1;
  for (int a = 0; a < 3; ++a)
  {
    this->Counts[a] = 0;
    if (cellDims[a] < 1 || !(size[a] > 0.0) || !std::isfinite(size[a]))
    {
      return false;
    }
    const double count = std::ceil(cellDims[a] / size[a]);
    if (!(count <= static_cast<double>(MaxSupercells)))
    {
      return false;
    }
    int n = std::max(1, static_cast<int>(count));
    // Rounding may leave an empty last supercell: drop it.
    while (n > 1 && (n - 1) * size[a] >= cellDims[a])
    {
      --n;
    }
    total *= static_cast<std::size_t>(n);
    if (total > MaxSupercells)
    {
      return false;
    }
    this->CellDims[a] = cellDims[a];
    this->Size[a] = size[a];
    this->Counts[a] = n;
  }
  this->Count = total;
  this->Bits.assign((total + 63) / 64, 0);
  return true;
}

bool SupercellGrid::ClassifySupercell(const RangePyramid& pyramid, const ContributionRule& rule,
  Interpolation interpolation, int i, int j, int k) const
{
  const int index[3] = { i, j, k };
  double lo[3], hi[3];
  int c0[3], c1[3];
  bool subcell = false;
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = this->Boundary(a, index[a]);
    hi[a] = this->Boundary(a, index[a] + 1);
    c0[a] = std::max(0, static_cast<int>(std::floor(lo[a])));
    c1[a] = std::min(this->CellDims[a] - 1, static_cast<int>(std::ceil(hi[a])) - 1);
    c1[a] = std::max(c1[a], c0[a]);
    subcell = subcell || this->Size[a] < 1.0;
  }
  // A supercell is PC when it overlaps a PC cell. Subcells (linear interpolation) are
  // tighter: only the part of each overlapped PC cell they cover counts.
  if (!pyramid.AnyContributing(c0, c1, rule))
  {
    return false;
  }
  if (!subcell || interpolation == Interpolation::Nearest)
  {
    return true;
  }
  const ScalarField& field = *pyramid.GetField();
  int c[3];
  for (c[2] = c0[2]; c[2] <= c1[2]; ++c[2])
  {
    for (c[1] = c0[1]; c[1] <= c1[1]; ++c[1])
    {
      for (c[0] = c0[0]; c[0] <= c1[0]; ++c[0])
      {
        double corners[8], u0[3], u1[3];
        for (int n = 0; n < 8; ++n)
        {
          corners[n] = field.GetValue(c[0] + (n & 1), c[1] + ((n >> 1) & 1), c[2] + ((n >> 2) & 1));
        }
        for (int a = 0; a < 3; ++a)
        {
          u0[a] = std::max(lo[a] - c[a], 0.0);
          u1[a] = std::min(hi[a] - c[a], 1.0);
        }
        double vlo, vhi;
        TrilinearRange(corners, u0, u1, vlo, vhi);
        if (rule.IsPossiblyContributing(vlo, vhi))
        {
          return true;
        }
      }
    }
  }
  return false;
}

void SupercellGrid::Classify(const std::vector<Channel>& channels, Interpolation interpolation)
{
  // One byte a supercell while classifying in parallel (threads write different bytes),
  // packed into bits after.
  std::vector<std::uint8_t> flags(this->Count, 0);
  // Supercells of 2^L cells along every axis are the pyramids' nodes of level L: classified
  // top-down there (the same answer as each supercell's query, far fewer visits).
  const int level = static_cast<int>(std::lround(std::log2(this->Size[0])));
  const bool levels = level >= 1 && this->Size[0] == std::ldexp(1.0, level) &&
    this->Size[1] == this->Size[0] && this->Size[2] == this->Size[0] &&
    std::all_of(channels.begin(), channels.end(),
      [level](const Channel& c) { return level <= c.Pyramid->GetNumberOfLevels(); });
  if (levels)
  {
    // The first channel's flags in place, the others ORed into them.
    std::vector<std::uint8_t> channelFlags;
    for (std::size_t c = 0; c < channels.size(); ++c)
    {
      channels[c].Pyramid->ClassifyLevel(level, *channels[c].Rule, c == 0 ? flags : channelFlags);
      for (std::size_t n = 0; c > 0 && n < flags.size() && n < channelFlags.size(); ++n)
      {
        flags[n] |= channelFlags[n];
      }
    }
    flags.resize(this->Count, 0); // as many nodes as supercells: no change
  }
  else
  {
    const int nx = this->Counts[0], ny = this->Counts[1];
    vtkSMPTools::For(0, this->Counts[2], [&](vtkIdType k0, vtkIdType k1) {
      for (int k = static_cast<int>(k0); k < k1; ++k)
      {
        for (int j = 0; j < ny; ++j)
        {
          for (int i = 0; i < nx; ++i)
          {
            flags[this->Index(i, j, k)] = std::any_of(channels.begin(), channels.end(),
              [&](const Channel& c) {
                return this->ClassifySupercell(*c.Pyramid, *c.Rule, interpolation, i, j, k);
              });
          }
        }
      }
    });
  }
  this->PackFlags(flags);
}

void SupercellGrid::PackFlags(const std::vector<std::uint8_t>& flags)
{
  std::fill(this->Bits.begin(), this->Bits.end(), 0);
  this->ContributingCount = 0;
  const std::size_t n = std::min(flags.size(), this->Count);
  std::size_t i = 0;
  // Eight flags at a time: the low bit of each byte gathered into one byte by a multiply
  // (the flags are 0 or 1, so no carries cross the bytes that are summed).
  for (; i + 8 <= n; i += 8)
  {
    std::uint64_t eight;
    std::memcpy(&eight, flags.data() + i, 8); // byte m of the flags is bits 8m on (x86)
    const std::uint64_t packed = ((eight & 0x0101010101010101ull) * 0x0102040810204080ull) >> 56;
    this->Bits[i >> 6] |= packed << (i & 63);
    this->ContributingCount += static_cast<std::size_t>(PopCount(static_cast<std::uint32_t>(
      packed)));
  }
  for (; i < n; ++i)
  {
    this->Bits[i >> 6] |= static_cast<std::uint64_t>(flags[i] != 0) << (i & 63);
    this->ContributingCount += flags[i] != 0;
  }
}

bool SupercellGrid::Locate(int axis, double x, double eps, int& first, int& last) const
{
  const int n = this->Counts[axis];
  if (n == 0 || !(x >= -eps) || !(x <= this->CellDims[axis] + eps))
  {
    return false;
  }
  const double s = this->Size[axis];
  first = std::max(0, std::min(n - 1, static_cast<int>(std::floor((x - eps) / s)) - 1));
  while (first < n - 1 && this->Boundary(axis, first + 1) < x - eps)
  {
    ++first;
  }
  last = std::max(0, std::min(n - 1, static_cast<int>(std::floor((x + eps) / s)) + 1));
  while (last > 0 && this->Boundary(axis, last) > x + eps)
  {
    --last;
  }
  return first <= last;
}

bool SupercellGrid::TouchesContributing(const Vec3& p, double eps) const
{
  int first[3], last[3];
  for (int a = 0; a < 3; ++a)
  {
    if (!this->Locate(a, p[a], eps, first[a], last[a]))
    {
      return false;
    }
  }
  for (int k = first[2]; k <= last[2]; ++k)
  {
    for (int j = first[1]; j <= last[1]; ++j)
    {
      for (int i = first[0]; i <= last[0]; ++i)
      {
        if (this->IsContributing(i, j, k))
        {
          return true;
        }
      }
    }
  }
  return false;
}

void SupercellGrid::ContributingPlanes(int axis, int& first, int& last) const
{
  first = this->Counts[axis];
  last = -1;
  for (int k = 0; k < this->Counts[2]; ++k)
  {
    for (int j = 0; j < this->Counts[1]; ++j)
    {
      for (int i = 0; i < this->Counts[0]; ++i)
      {
        if (this->IsContributing(i, j, k))
        {
          const int p = axis == 0 ? i : (axis == 1 ? j : k);
          first = std::min(first, p);
          last = std::max(last, p);
        }
      }
    }
  }
}

} // namespace parc
