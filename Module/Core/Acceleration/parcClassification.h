// PARC for VTK: which cells can change a ray's result ("possibly contributing", PC).
//
// DESIGN.md section 2. Every trilinear (or nearest) sample taken inside a cell lies in the
// cell's [min, max] of its 8 corners, up to the float rounding of the caster; the rule
// widens each range by a margin that covers that rounding. A cell is PC when its widened
// range passes the test of the ray function:
// - composite, additive: the scalar opacity (or a label's, CastParameters::Labels) is
//   non-zero somewhere on [min, max];
// - maximum intensity: max >= the smallest scalar with non-zero opacity;
// - minimum intensity: min <= the largest scalar with non-zero opacity;
// - average intensity: [min, max] meets the averaged scalar range;
// - isosurface: some iso value v with min <= v <= max;
// - a component of weight 0 (CastParameters::ComponentWeight): never.
// A sample outside every PC cell cannot change the ray (zero opacity, below the threshold,
// outside the averaged range, or no iso-value crossing nearby), so skipping it is exact.
//
// RangePyramid keeps cell ranges as a min/max pyramid built once per data change, so that
// a transfer-function or iso-value change reclassifies a volume in a few milliseconds.
#ifndef parcClassification_h
#define parcClassification_h

#include "parcCastParameters.h"
#include "parcCellMap.h"
#include "parcScalarField.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace parc
{

class ContributionRule
{
public:
  /// The rule of the ray function in p for a field whose values lie in range[0..1].
  void Set(const CastParameters& p, const double range[2]);

  /// True when a cell whose samples lie in [lo, hi] may change a ray's result.
  PARC_HOT_INLINE bool IsPossiblyContributing(double lo, double hi) const
  {
    if (!this->TestsEndsApart())
    {
      return this->MeetsInterval(lo - this->Margin, hi + this->Margin);
    }
    return this->MeetsLow(lo) && this->MeetsHigh(hi);
  }

  /// Whether the rule tests the two ends of a range apart (one interval or a threshold):
  /// IsPossiblyContributing(lo, hi) is then MeetsLow(lo) && MeetsHigh(hi), where MeetsLow
  /// holds up to some value and MeetsHigh from some value on. False for several intervals.
  PARC_HOT_INLINE bool TestsEndsApart() const
  {
    return this->Blend == BlendMode::MaximumIntensity ||
      this->Blend == BlendMode::MinimumIntensity || this->Hi.size() <= 1;
  }
  /// The test of a range's low end (see TestsEndsApart).
  PARC_HOT_INLINE bool MeetsLow(double lo) const
  {
    lo -= this->Margin;
    switch (this->Blend)
    {
      case BlendMode::MaximumIntensity:
        return true;
      case BlendMode::MinimumIntensity:
        return lo <= this->Threshold;
      default:
        return this->Hi.size() == 1 && lo <= this->Hi[0];
    }
  }
  /// The test of a range's high end (see TestsEndsApart).
  PARC_HOT_INLINE bool MeetsHigh(double hi) const
  {
    hi += this->Margin;
    switch (this->Blend)
    {
      case BlendMode::MaximumIntensity:
        return hi >= this->Threshold;
      case BlendMode::MinimumIntensity:
        return true;
      default:
        return this->Hi.size() == 1 && this->Lo[0] <= hi;
    }
  }

  /// True when every cell whose samples lie within [lo, hi] is possibly contributing: a
  /// query may then stop without looking at the cells (never true for isosurfaces).
  bool AllContributing(double lo, double hi) const;

  /// The margin added on both sides of every range (scalar units).
  double GetMargin() const { return this->Margin; }

private:
  /// Whether [lo, hi] meets one of several intervals.
  PARC_HOT_INLINE bool MeetsInterval(double lo, double hi) const
  {
    // The first interval ending at or after lo; it is met if it starts at or before hi.
    const auto it = std::lower_bound(this->Hi.begin(), this->Hi.end(), lo);
    return it != this->Hi.end() && this->Lo[it - this->Hi.begin()] <= hi;
  }

  BlendMode Blend = BlendMode::Composite;
  /// Closed scalar intervals, sorted and disjoint: non-zero opacity (composite, additive)
  /// or the averaged range; for the isosurface, degenerate intervals at the iso values.
  std::vector<double> Lo, Hi;
  double Threshold = 0.0; ///< maximum / minimum intensity
  double Margin = 0.0;
};

/// Min/max of the cells of a field, as a pyramid: level L holds the range of 2^L x 2^L x 2^L
/// cells. Levels from LowestLevel up are kept (level 0 is the cells, read from the field;
/// the levels between are not kept: a query that reaches one reads its cells). Levels keep
/// one-byte codes of 256 values evenly spread over the field's range, the minimum rounded
/// down and the maximum rounded up: a node's coded range holds its true range, so a query
/// descends wherever it would with exact ranges and decides on the exact cell ranges (for 8-
/// and 16-bit data of at most 256 values the codes are the values themselves: see
/// ExactCodes). The lowest level also keeps its codes' high halves in a byte a node, the
/// cells' map (Level::Packed, MapCells).
class RangePyramid
{
public:
  /// The lowest level kept: nodes of CellMap::NodeCells cells along each axis.
  static constexpr int LowestLevel = CellMap::NodeShift;

  /// Keeps a pointer to field (it must outlive the pyramid's use).
  void Build(const ScalarField& field);

  const ScalarField* GetField() const { return this->Field; }
  /// The number of cells per axis (voxels - 1).
  const int* GetCellDimensions() const { return this->CellDims; }

  /// The range of the 8 corners of cell (i, j, k).
  void CellRange(int i, int j, int k, float& lo, float& hi) const;

  /// Whether some cell of the inclusive cell-index box [c0, c1] is PC under rule.
  bool AnyContributing(const int c0[3], const int c1[3], const ContributionRule& rule) const;

  /// For every node of level (1 to the top level, see GetNumberOfLevels), whether
  /// one of its cells is PC under rule, into flags (x fastest, ceil(cells / 2^level) per
  /// axis): what AnyContributing says of each node's cells, found top-down so that a node
  /// whose whole range decides (nothing or everything contributes) settles all its
  /// descendants at once.
  /// With exact codes the nodes' ranges of a kept level alone give that answer (see
  /// ExactCodes).
  void ClassifyLevel(
    int level, const ContributionRule& rule, std::vector<std::uint8_t>& flags) const
  {
    this->Settle(level, rule, flags, !this->IsExact(level));
  }
  /// The top level (0 for a field without cells): levels 1 to it can be classified.
  int GetNumberOfLevels() const
  {
    return this->Levels.empty() ? 0 : LowestLevel - 1 + static_cast<int>(this->Levels.size());
  }
  /// Which cells may be PC under rule, as the caster reads them (RayCaster::
  /// SetContributingCells): a cell may when the packed range of its node of the lowest
  /// level meets the rule. Every PC cell may, and so may the other cells of its node (finer
  /// nodes would cost memory more than they save a frame). The map points to the pyramid's
  /// lowest level: it holds until the pyramid is built again. False, map empty, for a field
  /// without cells.
  bool MapCells(const ContributionRule& rule, CellMap& map) const;

  /// Memory held by the pyramid, in bytes.
  std::size_t GetMemorySize() const;

private:
  using Code = std::uint8_t;
  static constexpr int CodeCount = 256;
  /// The cells' map keeps a byte a node, its codes' high halves (PackedShift): a wider
  /// range, still holding the true one (so conservative), read through a table of 256.
  static constexpr int PackedShift = 4;
  struct Level
  {
    int Dims[3];
    std::vector<Code> Min, Max; ///< the codes
    /// The lowest level's map: the minimum's code >> PackedShift in the low bits, the
    /// maximum's in the high bits (empty above it).
    std::vector<Code> Packed;
    std::size_t Size() const { return static_cast<std::size_t>(Dims[0]) * Dims[1] * Dims[2]; }
    /// The codes of a packed byte's range.
    static Code PackedMin(Code packed) { return static_cast<Code>((packed & LowBits) << PackedShift); }
    static Code PackedMax(Code packed)
    {
      return static_cast<Code>(((packed >> PackedShift) << PackedShift) | LowBits);
    }
    /// Makes Packed from the codes.
    void Pack();
    static constexpr unsigned LowBits = (1u << PackedShift) - 1u;
  };
  /// Level level (at least LowestLevel).
  const Level& LevelAt(int level) const { return this->Levels[level - LowestLevel]; }
  /// Whether level is kept and its nodes' ranges are exactly the ranges of their voxels.
  bool IsExact(int level) const { return this->ExactCodes && level >= LowestLevel; }
  /// The coded range of node of level (kept).
  void NodeRange(int level, const int node[3], double& lo, double& hi) const;
  /// The nodes of level along each axis (ceil(cells / 2^level)), kept or not.
  void LevelDims(int level, int dims[3]) const;
  /// The lowest level, from the field's voxels.
  Level LowestNodes() const;
  bool Query(int level, const int node[3], const int c0[3], const int c1[3],
    const ContributionRule& rule) const;
  /// ClassifyLevel (exact: whether one of a node's cells is PC) or, without exact, whether
  /// the range of each node of level meets the rule (the pyramid's ranges alone: a node
  /// with a PC cell always does).
  void Settle(int level, const ContributionRule& rule, std::vector<std::uint8_t>& flags,
    bool exact) const;
  /// For a rule that tests the ends of a range apart: a range meets it when its maximum
  /// code is at least high and its minimum at most low. False when no value meets one of
  /// the tests.
  bool CodeBounds(const ContributionRule& rule, Code& high, Code& low) const;
  /// Settle without exact for a rule that tests the ends of a range apart, in one pass
  /// over the level's codes (no descent from above: a node's ancestors all pass when it
  /// does, their ranges holding its range). Only for a level with exact codes, never the
  /// packed one (ClassifyLevel).
  void SettleFromCodes(
    int level, const ContributionRule& rule, std::vector<std::uint8_t>& flags) const;
  /// Settle below the node of level m (>= level).
  void Descend(int m, const int node[3], int level, const ContributionRule& rule,
    std::vector<std::uint8_t>& flags, bool exact) const;

  const ScalarField* Field = nullptr;
  int CellDims[3] = { 0, 0, 0 };
  std::vector<Level> Levels; ///< Levels[L - LowestLevel] is level L
  /// Non-decreasing, from the field's minimum to its maximum.
  double CodeValues[CodeCount];
  /// Whether every value of the field is a code value (8- or 16-bit integers over a range
  /// of at most CodeCount values), so that a node's range is exactly the range of its voxels. That
  /// range is then the union of its cells' ranges, each meeting the next (neighbours share
  /// voxels): a rule, which tests a range against intervals, meets the node's range exactly
  /// when it meets one of its cells' ranges, and no node needs its cells read.
  bool ExactCodes = false;
};

} // namespace parc

#endif
