#include "parcClassification.h"

#include <vtkSMPTools.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>
#include <numeric>

namespace parc
{

namespace
{
/// Float rounding of a trilinear sample stays within a few units in the last place of the
/// largest corner magnitude; the margin is generous on purpose (it costs nothing).
constexpr double RoundingMargin = 32.0 * FLT_EPSILON;

/// The codes of values in a non-decreasing table of code values (RangePyramid's): the
/// same answers as a binary search, found in one step for the tables the pyramid makes
/// (evenly spread values, or consecutive integers), where a guess from the spacing of the
/// first two values is checked against its neighbours.
class CodeFinder
{
public:
  CodeFinder(const double* values, int count)
    : Values(values)
    , Count(count)
    , Scale(values[1] > values[0] ? 1.0 / (values[1] - values[0]) : 0.0)
  {
  }
  /// The last code whose value is at most v (0 when every value is above v).
  int Below(double v) const
  {
    const int c = this->Guess(std::floor((v - this->Values[0]) * this->Scale));
    if (this->Values[c] <= v && (c + 1 == this->Count || this->Values[c + 1] > v))
    {
      return c;
    }
    const auto it = std::upper_bound(this->Values, this->Values + this->Count, v);
    return it == this->Values ? 0 : static_cast<int>(it - this->Values) - 1;
  }
  /// The first code whose value is at least v (the last when every value is below v).
  int Above(double v) const
  {
    const int c = this->Guess(std::ceil((v - this->Values[0]) * this->Scale));
    if (this->Values[c] >= v && (c == 0 || this->Values[c - 1] < v))
    {
      return c;
    }
    const double* end = this->Values + this->Count;
    const auto it = std::lower_bound(this->Values, end, v);
    return it == end ? this->Count - 1 : static_cast<int>(it - this->Values);
  }

private:
  int Guess(double index) const
  {
    return index > 0.0 ? static_cast<int>(std::min(index, this->Count - 1.0)) : 0;
  }
  const double* Values;
  int Count;
  double Scale;
};

/// lo[x] = min(lo[x], row[x * step]) and hi[x] likewise, for x < n; written for a constant
/// step, where it vectorizes.
template <typename T>
PARC_HOT_INLINE void AccumulateRange(const T* row, std::ptrdiff_t step, int n, T* lo, T* hi)
{
  for (int x = 0; x < n; ++x)
  {
    const T v = row[x * step];
    lo[x] = std::min(lo[x], v);
    hi[x] = std::max(hi[x], v);
  }
}

/// Appends [lo, hi] to sorted closed intervals, merging it with the last one if they meet.
void AppendInterval(std::vector<double>& los, std::vector<double>& his, double lo, double hi)
{
  if (!los.empty() && lo <= his.back())
  {
    his.back() = std::max(his.back(), hi);
    return;
  }
  los.push_back(lo);
  his.push_back(hi);
}

/// Closed intervals covering every scalar where f is non-zero (a superset of
/// PiecewiseLinearFunction::IsNonZeroOn, so never smaller than the exact set).
void NonZeroIntervals(const PiecewiseLinearFunction& f, std::vector<double>& los,
  std::vector<double>& his)
{
  constexpr double inf = std::numeric_limits<double>::infinity();
  const std::vector<double>& x = f.GetX();
  const std::vector<double>& y = f.GetY();
  if (x.empty())
  {
    if (f.IsNonZeroOn(0.0, 0.0))
    {
      AppendInterval(los, his, -inf, inf);
    }
    return;
  }
  if (f.IsNonZeroOn(-inf, std::nextafter(x.front(), -inf)))
  {
    AppendInterval(los, his, -inf, x.front());
  }
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    if (y[i] > 0.0)
    {
      AppendInterval(los, his, x[i], x[i]);
    }
    if (i + 1 < x.size() && x[i] < x[i + 1] && std::max(y[i], y[i + 1]) > 0.0)
    {
      AppendInterval(los, his, x[i], x[i + 1]);
    }
  }
  if (f.IsNonZeroOn(std::nextafter(x.back(), inf), inf))
  {
    AppendInterval(los, his, x.back(), inf);
  }
}
}

void ContributionRule::Set(const CastParameters& p, const double range[2])
{
  this->Blend = p.Blend;
  this->Lo.clear();
  this->Hi.clear();
  this->Margin = RoundingMargin * std::max(std::fabs(range[0]), std::fabs(range[1]));
  if (!(p.ComponentWeight > 0.0)) // a component of weight 0 contributes nowhere
  {
    this->Blend = BlendMode::Composite;
    return;
  }
  switch (p.Blend)
  {
    case BlendMode::Composite:
    case BlendMode::Additive:
    case BlendMode::Slice: // the caster takes no segments for slices: where it shows
      NonZeroIntervals(p.Opacity, this->Lo, this->Hi);
      for (const LabelFunctions& label : p.Labels) // where any label's opacity is non-zero
      {
        std::vector<double> lo, hi;
        NonZeroIntervals(label.Opacity, lo, hi);
        lo.insert(lo.end(), this->Lo.begin(), this->Lo.end());
        hi.insert(hi.end(), this->Hi.begin(), this->Hi.end());
        std::vector<std::size_t> order(lo.size());
        std::iota(order.begin(), order.end(), 0);
        std::sort(order.begin(), order.end(),
          [&lo](std::size_t a, std::size_t b) { return lo[a] < lo[b]; });
        this->Lo.clear();
        this->Hi.clear();
        for (std::size_t i : order)
        {
          AppendInterval(this->Lo, this->Hi, lo[i], hi[i]);
        }
      }
      break;
    case BlendMode::MaximumIntensity:
      this->Threshold = p.Opacity.FirstNonZero();
      break;
    case BlendMode::MinimumIntensity:
      this->Threshold = p.Opacity.LastNonZero();
      break;
    case BlendMode::AverageIntensity:
      if (p.AverageRange[0] <= p.AverageRange[1])
      {
        AppendInterval(this->Lo, this->Hi, p.AverageRange[0], p.AverageRange[1]);
      }
      break;
    case BlendMode::IsoSurface:
    {
      for (double v : UsedIsoValues(p))
      {
        AppendInterval(this->Lo, this->Hi, v, v);
      }
      break;
    }
  }
}

bool ContributionRule::AllContributing(double lo, double hi) const
{
  switch (this->Blend)
  {
    case BlendMode::MaximumIntensity:
      return lo + this->Margin >= this->Threshold; // every cell's maximum is at least lo
    case BlendMode::MinimumIntensity:
      return hi - this->Margin <= this->Threshold;
    case BlendMode::IsoSurface:
      return false; // a cell inside the range need not hold an iso value
    default:
      // A range inside one interval meets it.
      for (std::size_t i = 0; i < this->Lo.size(); ++i)
      {
        if (this->Lo[i] <= lo && hi <= this->Hi[i])
        {
          return true;
        }
      }
      return false;
  }
}

void RangePyramid::Build(const ScalarField& field)
{
  this->Field = &field;
  const int* dims = field.GetDimensions();
  for (int a = 0; a < 3; ++a)
  {
    this->CellDims[a] = std::max(dims[a] - 1, 0);
  }
  const double* range = field.GetRange();
  const ScalarType type = field.GetScalarType();
  // 8- and 16-bit integers (exact in the float ranges the levels are made from).
  const bool smallIntegers = type == ScalarType::Int8 || type == ScalarType::UInt8 ||
    type == ScalarType::Int16 || type == ScalarType::UInt16;
  this->ExactCodes = smallIntegers && range[1] - range[0] <= CodeCount - 1;
  for (int c = 0; c < CodeCount; ++c)
  {
    this->CodeValues[c] = this->ExactCodes
      ? std::min(range[0] + c, range[1])
      : range[0] + (range[1] - range[0]) * c / (CodeCount - 1);
  }
  this->CodeValues[CodeCount - 1] = range[1];
  this->Levels.clear();
  if (this->CellDims[0] < 1 || this->CellDims[1] < 1 || this->CellDims[2] < 1)
  {
    return;
  }
  this->Levels.push_back(this->LowestNodes());
  int levelDims[3] = { this->Levels[0].Dims[0], this->Levels[0].Dims[1], this->Levels[0].Dims[2] };
  while (levelDims[0] > 1 || levelDims[1] > 1 || levelDims[2] > 1) // each level from the last
  {
    Level next;
    for (int a = 0; a < 3; ++a)
    {
      next.Dims[a] = (levelDims[a] + 1) / 2;
    }
    const std::size_t n = static_cast<std::size_t>(next.Dims[0]) * next.Dims[1] * next.Dims[2];
    next.Min.assign(n, CodeCount - 1);
    next.Max.assign(n, 0);
    std::size_t out = 0;
    for (int k = 0; k < next.Dims[2]; ++k)
    {
      for (int j = 0; j < next.Dims[1]; ++j)
      {
        for (int i = 0; i < next.Dims[0]; ++i, ++out)
        {
          // The children: the nodes of the level below.
          for (int ck = 2 * k; ck < std::min(2 * k + 2, levelDims[2]); ++ck)
          {
            for (int cj = 2 * j; cj < std::min(2 * j + 2, levelDims[1]); ++cj)
            {
              for (int ci = 2 * i; ci < std::min(2 * i + 2, levelDims[0]); ++ci)
              {
                const Level& below = this->Levels.back();
                const std::size_t c = static_cast<std::size_t>(ci) +
                  static_cast<std::size_t>(below.Dims[0]) *
                    (cj + static_cast<std::size_t>(below.Dims[1]) * ck);
                next.Min[out] = std::min(next.Min[out], below.Min[c]);
                next.Max[out] = std::max(next.Max[out], below.Max[c]);
              }
            }
          }
        }
      }
    }
    this->Levels.push_back(std::move(next));
    for (int a = 0; a < 3; ++a)
    {
      levelDims[a] = this->Levels.back().Dims[a];
    }
  }
  this->Levels[0].Pack();
}

void RangePyramid::Level::Pack()
{
  this->Packed.resize(this->Min.size());
  Code* packed = this->Packed.data();
  const Code* min = this->Min.data();
  const Code* max = this->Max.data();
  vtkSMPTools::For(0, static_cast<vtkIdType>(this->Min.size()), [=](vtkIdType b, vtkIdType e) {
    for (vtkIdType n = b; n < e; ++n)
    {
      packed[n] =
        static_cast<Code>((min[n] >> PackedShift) | ((max[n] >> PackedShift) << PackedShift));
    }
  });
}

void RangePyramid::NodeRange(int level, const int node[3], double& lo, double& hi) const
{
  const Level& l = this->LevelAt(level);
  const std::size_t n = static_cast<std::size_t>(node[0]) +
    static_cast<std::size_t>(l.Dims[0]) * (node[1] + static_cast<std::size_t>(l.Dims[1]) * node[2]);
  lo = this->CodeValues[l.Min[n]];
  hi = this->CodeValues[l.Max[n]];
}

void RangePyramid::LevelDims(int level, int dims[3]) const
{
  for (int a = 0; a < 3; ++a)
  {
    dims[a] = (this->CellDims[a] + (1 << level) - 1) >> level;
  }
}

RangePyramid::Level RangePyramid::LowestNodes() const
{
  // Node (i, j, k) holds cells n i to n i + n - 1 (n = 2^LowestLevel, where they exist)
  // along x, and so on: the voxels n i to n i + n. In parallel over slices of nodes, each
  // row of nodes takes the range of every voxel column x over its (n + 1) x (n + 1) voxels
  // in y and z (whole rows in the values' own type), then of each node's n + 1 columns,
  // and codes it once. Float rounding is monotonic, so the range in the values' type
  // converted to float is the range of the values converted to float.
  constexpr int span = 1 << LowestLevel;
  Level first;
  this->LevelDims(LowestLevel, first.Dims);
  const std::size_t n = static_cast<std::size_t>(first.Dims[0]) * first.Dims[1] * first.Dims[2];
  first.Min.resize(n);
  first.Max.resize(n);
  const int* dims = this->Field->GetDimensions();
  const CodeFinder coder(this->CodeValues, CodeCount);
  this->Field->Dispatch([&](const auto& field) {
    using T = std::remove_cv_t<std::remove_pointer_t<decltype(field.Row(0, 0))>>;
    const std::ptrdiff_t step = field.GetXStep();
    const bool exact = std::is_integral<T>::value && this->ExactCodes;
    const auto bottom = static_cast<T>(this->CodeValues[0]);
    const auto top = static_cast<T>(this->CodeValues[CodeCount - 1]);
    vtkSMPTools::For(0, first.Dims[2], [&](vtkIdType k0, vtkIdType k1) {
      std::vector<T> columnMin(dims[0]), columnMax(dims[0]);
      for (int k = static_cast<int>(k0); k < k1; ++k)
      {
        for (int j = 0; j < first.Dims[1]; ++j)
        {
          const T* start = field.Row(span * j, span * k);
          for (int x = 0; x < dims[0]; ++x)
          {
            columnMin[x] = columnMax[x] = start[x * step];
          }
          for (int z = span * k; z <= std::min(span * (k + 1), dims[2] - 1); ++z)
          {
            for (int y = span * j; y <= std::min(span * (j + 1), dims[1] - 1); ++y)
            {
              if (step == 1)
              {
                AccumulateRange(field.Row(y, z), 1, dims[0], columnMin.data(), columnMax.data());
              }
              else
              {
                AccumulateRange(field.Row(y, z), step, dims[0], columnMin.data(), columnMax.data());
              }
            }
          }
          const std::size_t rowStart = static_cast<std::size_t>(first.Dims[0]) *
            (j + static_cast<std::size_t>(first.Dims[1]) * k);
          for (int i = 0; i < first.Dims[0]; ++i)
          {
            T lo = columnMin[span * i], hi = columnMax[span * i];
            for (int x = span * i + 1; x <= std::min(span * (i + 1), dims[0] - 1); ++x)
            {
              lo = std::min(lo, columnMin[x]);
              hi = std::max(hi, columnMax[x]);
            }
            if (exact)
            {
              // Code c holds bottom + c (the last codes repeat the top, and the code below
              // the top is the last of them).
              first.Min[rowStart + i] = static_cast<Code>(lo == top ? CodeCount - 1 : lo - bottom);
              first.Max[rowStart + i] = static_cast<Code>(hi - bottom);
            }
            else
            {
              first.Min[rowStart + i] = static_cast<Code>(coder.Below(static_cast<float>(lo)));
              first.Max[rowStart + i] = static_cast<Code>(coder.Above(static_cast<float>(hi)));
            }
          }
        }
      }
    });
  });
  return first;
}

void RangePyramid::CellRange(int i, int j, int k, float& lo, float& hi) const
{
  this->Field->CellRange(i, j, k, lo, hi);
}

bool RangePyramid::Query(int level, const int node[3], const int c0[3], const int c1[3],
  const ContributionRule& rule) const
{
  for (int a = 0; a < 3; ++a)
  {
    const int first = node[a] << level;
    const int last = ((node[a] + 1) << level) - 1;
    if (last < c0[a] || first > c1[a] || first >= this->CellDims[a])
    {
      return false;
    }
  }
  if (level == 0)
  {
    float lo, hi;
    this->CellRange(node[0], node[1], node[2], lo, hi);
    return rule.IsPossiblyContributing(lo, hi);
  }
  if (level >= LowestLevel) // a level below it is not kept: its children decide
  {
    double lo, hi;
    this->NodeRange(level, node, lo, hi);
    if (!rule.IsPossiblyContributing(lo, hi))
    {
      return false;
    }
    if (rule.AllContributing(lo, hi))
    {
      return true; // the node meets the box in at least one cell, and every cell is PC
    }
  }
  for (int c = 0; c < 8; ++c)
  {
    const int child[3] = { 2 * node[0] + (c & 1), 2 * node[1] + ((c >> 1) & 1),
      2 * node[2] + ((c >> 2) & 1) };
    if (this->Query(level - 1, child, c0, c1, rule))
    {
      return true;
    }
  }
  return false;
}

bool RangePyramid::AnyContributing(const int c0[3], const int c1[3],
  const ContributionRule& rule) const
{
  // Start at the coarsest level whose nodes are at least as large as the box: the box then
  // meets at most 2 nodes per axis.
  int extent = 1;
  for (int a = 0; a < 3; ++a)
  {
    extent = std::max(extent, c1[a] - c0[a] + 1);
  }
  int level = 0;
  while ((1 << level) < extent && level < this->GetNumberOfLevels())
  {
    ++level;
  }
  int first[3], last[3];
  for (int a = 0; a < 3; ++a)
  {
    first[a] = c0[a] >> level;
    last[a] = c1[a] >> level;
  }
  int node[3];
  for (node[2] = first[2]; node[2] <= last[2]; ++node[2])
  {
    for (node[1] = first[1]; node[1] <= last[1]; ++node[1])
    {
      for (node[0] = first[0]; node[0] <= last[0]; ++node[0])
      {
        if (this->Query(level, node, c0, c1, rule))
        {
          return true;
        }
      }
    }
  }
  return false;
}

bool RangePyramid::CodeBounds(const ContributionRule& rule, Code& high, Code& low) const
{
  // Both tests are monotone, and code values do not decrease.
  int first = 0, last = CodeCount - 1;
  while (first < CodeCount && !rule.MeetsHigh(this->CodeValues[first]))
  {
    ++first;
  }
  while (last >= 0 && !rule.MeetsLow(this->CodeValues[last]))
  {
    --last;
  }
  high = static_cast<Code>(std::min(first, CodeCount - 1));
  low = static_cast<Code>(std::max(last, 0));
  return first < CodeCount && last >= 0;
}

void RangePyramid::SettleFromCodes(
  int level, const ContributionRule& rule, std::vector<std::uint8_t>& flags) const
{
  const Level& target = this->LevelAt(level);
  flags.assign(target.Size(), 0);
  Code high, low;
  if (!this->CodeBounds(rule, high, low))
  {
    return; // no value meets one of the tests
  }
  constexpr vtkIdType Chunk = 1 << 16;
  const vtkIdType n = static_cast<vtkIdType>(flags.size());
  vtkSMPTools::For(0, (n + Chunk - 1) / Chunk, [&](vtkIdType c0, vtkIdType c1) {
    // Locals only (a byte store could alias anything reached through a reference): the
    // compiler then compares many bytes at once.
    std::uint8_t* out = flags.data();
    const vtkIdType begin = c0 * Chunk, end = std::min(c1 * Chunk, n);
    const Code* lo = target.Min.data();
    const Code* hi = target.Max.data();
    const Code h = high, l = low;
    for (vtkIdType i = begin; i < end; ++i)
    {
      out[i] = static_cast<std::uint8_t>((hi[i] >= h) & (lo[i] <= l));
    }
  });
}

void RangePyramid::Settle(int level, const ContributionRule& rule,
  std::vector<std::uint8_t>& flags, bool exact) const
{
  if (!exact && rule.TestsEndsApart())
  {
    this->SettleFromCodes(level, rule, flags);
    return;
  }
  int dims[3];
  this->LevelDims(level, dims);
  flags.assign(static_cast<std::size_t>(dims[0]) * dims[1] * dims[2], 0);
  // Start a few levels up (enough nodes to share among threads, each settling many), at a
  // kept one.
  constexpr int LevelsAbove = 3;
  const int top = std::max(std::min(level + LevelsAbove, this->GetNumberOfLevels()), LowestLevel);
  const Level& start = this->LevelAt(top);
  vtkSMPTools::For(0, start.Dims[2], [&](vtkIdType k0, vtkIdType k1) {
    int node[3];
    for (node[2] = static_cast<int>(k0); node[2] < k1; ++node[2])
    {
      for (node[1] = 0; node[1] < start.Dims[1]; ++node[1])
      {
        for (node[0] = 0; node[0] < start.Dims[0]; ++node[0])
        {
          this->Descend(top, node, level, rule, flags, exact);
        }
      }
    }
  });
}

bool RangePyramid::MapCells(const ContributionRule& rule, CellMap& map) const
{
  map = CellMap();
  if (this->Levels.empty())
  {
    return false;
  }
  const Level& lowest = this->Levels[0];
  for (int p = 0; p < CellMap::CodeCount; ++p)
  {
    const Code packed = static_cast<Code>(p);
    map.Contributes[p] = rule.IsPossiblyContributing(
      this->CodeValues[Level::PackedMin(packed)], this->CodeValues[Level::PackedMax(packed)]);
  }
  map.SetNodes(lowest.Packed.data(), lowest.Dims);
  return true;
}

void RangePyramid::Descend(int m, const int node[3], int level, const ContributionRule& rule,
  std::vector<std::uint8_t>& flags, bool exact) const
{
  int dims[3];
  this->LevelDims(m, dims);
  if (node[0] >= dims[0] || node[1] >= dims[1] || node[2] >= dims[2])
  {
    return; // a child past the volume's end
  }
  // A level below the lowest kept has no ranges: its nodes are descended through, and
  // queried at level (exact is true there).
  const bool kept = m >= LowestLevel;
  double lo = 0.0, hi = 0.0;
  if (kept)
  {
    this->NodeRange(m, node, lo, hi);
    if (!rule.IsPossiblyContributing(lo, hi))
    {
      return; // no cell below contributes: the flags stay 0
    }
  }
  int target[3];
  this->LevelDims(level, target);
  const int shift = m - level;
  int first[3], last[3];
  for (int a = 0; a < 3; ++a)
  {
    first[a] = node[a] << shift;
    last[a] = std::min(((node[a] + 1) << shift) - 1, target[a] - 1);
  }
  auto flag = [&](int i, int j, int k) -> std::uint8_t& {
    return flags[static_cast<std::size_t>(i) +
      static_cast<std::size_t>(target[0]) * (j + static_cast<std::size_t>(target[1]) * k)];
  };
  if (m == level && !exact)
  {
    flag(node[0], node[1], node[2]) = 1;
    return;
  }
  if (m == level)
  {
    int c0[3], c1[3];
    for (int a = 0; a < 3; ++a)
    {
      c0[a] = node[a] << level;
      c1[a] = std::min(((node[a] + 1) << level) - 1, this->CellDims[a] - 1);
    }
    flag(node[0], node[1], node[2]) = this->Query(level, node, c0, c1, rule) ? 1 : 0;
    return;
  }
  if (kept && rule.AllContributing(lo, hi))
  {
    for (int k = first[2]; k <= last[2]; ++k)
    {
      for (int j = first[1]; j <= last[1]; ++j)
      {
        std::fill_n(&flag(first[0], j, k), last[0] - first[0] + 1, 1);
      }
    }
    return;
  }
  for (int c = 0; c < 8; ++c)
  {
    const int child[3] = { 2 * node[0] + (c & 1), 2 * node[1] + ((c >> 1) & 1),
      2 * node[2] + ((c >> 2) & 1) };
    this->Descend(m - 1, child, level, rule, flags, exact);
  }
}

std::size_t RangePyramid::GetMemorySize() const
{
  std::size_t bytes = sizeof(this->CodeValues);
  for (const Level& l : this->Levels)
  {
    bytes += (l.Min.size() + l.Max.size() + l.Packed.size()) * sizeof(Code);
  }
  return bytes;
}

} // namespace parc
