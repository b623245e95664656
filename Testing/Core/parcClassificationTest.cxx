// Classification, supercells, polygon models and the segment oracle, against brute force.
#include "parcPolygonModel.h"
#include "parcSegmentOracle.h"
#include "parcSupercellWalk.h"
#include "parcTestUtilities.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <tuple>

using parc::BlendMode;
using parc::CastParameters;
using parc::ContributionRule;
using parc::RangePyramid;
using parc::SupercellGrid;
using parc::Vec3;

namespace
{
const BlendMode AllBlendModes[] = { BlendMode::Composite, BlendMode::MaximumIntensity,
  BlendMode::MinimumIntensity, BlendMode::AverageIntensity, BlendMode::Additive,
  BlendMode::IsoSurface };

/// A random volume of dims voxels, values in [0, 100], smooth enough to leave empty regions.
parc::ScalarField RandomVolume(std::mt19937& rng, const int dims[3])
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double cx = u(rng) * dims[0], cy = u(rng) * dims[1], cz = u(rng) * dims[2];
  const double r = 1.0 + 3.0 * u(rng);
  return parctest::MakeField(dims, [&](int i, int j, int k) {
    const double d = std::sqrt((i - cx) * (i - cx) + (j - cy) * (j - cy) + (k - cz) * (k - cz));
    return static_cast<float>(std::max(0.0, 100.0 - 100.0 * d / (2.0 * r)) + 5.0 * u(rng));
  });
}

/// field's values times scale, rounded, plus offset, as 16-bit integers (sixteen) or
/// 8-bit ones (a copy).
parc::ScalarField IntegerField(const parc::ScalarField& field, double scale, int offset,
  bool sixteen)
{
  const int* dims = field.GetDimensions();
  const std::size_t n = static_cast<std::size_t>(dims[0]) * dims[1] * dims[2];
  std::vector<std::uint8_t> bytes(n);
  std::vector<std::int16_t> shorts(n);
  field.Dispatch([&](const auto& view) {
    std::size_t v = 0;
    for (int k = 0; k < dims[2]; ++k)
      for (int j = 0; j < dims[1]; ++j)
        for (int i = 0; i < dims[0]; ++i, ++v)
        {
          const long rounded = std::lround(scale * view.Value(i, j, k)) + offset;
          bytes[v] = static_cast<std::uint8_t>(rounded);
          shorts[v] = static_cast<std::int16_t>(rounded);
        }
  });
  parc::ScalarField integers;
  if (sixteen)
  {
    integers.Assign(shorts.data(), dims);
  }
  else
  {
    integers.Assign(bytes.data(), dims);
  }
  return integers;
}

/// Random parameters of a ray function: a random piecewise-linear opacity with zero
/// stretches, random iso values and averaged range.
CastParameters RandomParameters(std::mt19937& rng, BlendMode blend)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  CastParameters p;
  p.Blend = blend;
  std::vector<double> x, y;
  double at = -10.0 + 30.0 * u(rng);
  for (int n = 1 + static_cast<int>(rng() % 6); n > 0; --n)
  {
    x.push_back(at);
    y.push_back(u(rng) < 0.5 ? 0.0 : u(rng));
    at += (u(rng) < 0.1) ? 0.0 : 40.0 * u(rng);
  }
  parctest::SetOpacity(p, x, y, u(rng) < 0.5);
  p.IsoValues = { 100.0 * u(rng), 100.0 * u(rng) };
  p.AverageRange[0] = 100.0 * u(rng);
  p.AverageRange[1] = p.AverageRange[0] + 30.0 * u(rng);
  p.SampleDistance = 0.3;
  p.TerminationOpacity = 1.0;
  return p;
}

/// Whether a sample of value s, alone, shows in the result of the ray function (the
/// definition the rule must cover: any such sample must lie in a PC cell).
bool SampleMatters(const CastParameters& p, float s)
{
  switch (p.Blend)
  {
    case BlendMode::Composite:
    case BlendMode::Additive:
      return p.Opacity.Evaluate(s) > 0.f;
    case BlendMode::MaximumIntensity:
      return s >= p.Opacity.FirstNonZero();
    case BlendMode::MinimumIntensity:
      return s <= p.Opacity.LastNonZero();
    case BlendMode::AverageIntensity:
      return s >= p.AverageRange[0] && s <= p.AverageRange[1];
    case BlendMode::IsoSurface:
      return false; // crossings are checked by the image test below
  }
  return false;
}

/// The brute-force rule on an exact range (independent of the rule's interval lists).
bool BruteRule(const CastParameters& p, double lo, double hi)
{
  switch (p.Blend)
  {
    case BlendMode::Composite:
    case BlendMode::Additive:
      return p.Opacity.IsNonZeroOn(lo, hi);
    case BlendMode::MaximumIntensity:
      return hi >= p.Opacity.FirstNonZero();
    case BlendMode::MinimumIntensity:
      return lo <= p.Opacity.LastNonZero();
    case BlendMode::AverageIntensity:
      return hi >= p.AverageRange[0] && lo <= p.AverageRange[1];
    case BlendMode::IsoSurface:
      return std::any_of(p.IsoValues.begin(), p.IsoValues.end(),
        [&](double v) { return lo <= v && v <= hi; });
  }
  return false;
}

/// Brute-force cell PC flags (x fastest).
std::vector<char> CellFlags(const RangePyramid& pyramid, const ContributionRule& rule)
{
  const int* n = pyramid.GetCellDimensions();
  std::vector<char> flags;
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
      {
        float lo, hi;
        pyramid.CellRange(i, j, k, lo, hi);
        flags.push_back(rule.IsPossiblyContributing(lo, hi));
      }
  return flags;
}

struct Scene
{
  parc::ScalarField Field;
  CastParameters Params;
  RangePyramid Pyramid;
  ContributionRule Rule;
  SupercellGrid Grid;

  /// A random scene; with mixed, drawn again until some but not all supercells are PC.
  Scene(std::mt19937& rng, const int dims[3], BlendMode blend, const double size[3],
    parc::Interpolation interp = parc::Interpolation::Linear, bool mixed = false)
  {
    do
    {
      this->Make(rng, dims, blend, size, interp);
    } while (mixed &&
      (this->Grid.GetNumberOfContributing() == 0 ||
        this->Grid.GetNumberOfContributing() == this->Grid.GetNumberOfSupercells()));
  }

  void Make(std::mt19937& rng, const int dims[3], BlendMode blend, const double size[3],
    parc::Interpolation interp)
  {
    this->Field = RandomVolume(rng, dims);
    this->Params = RandomParameters(rng, blend);
    this->Params.Interp = interp;
    this->Pyramid.Build(this->Field);
    this->Rule.Set(this->Params, this->Field.GetRange());
    const int cells[3] = { dims[0] - 1, dims[1] - 1, dims[2] - 1 };
    EXPECT_TRUE(this->Grid.Configure(cells, size));
    this->Grid.Classify(this->Pyramid, this->Rule, interp);
  }
};

using Key = std::tuple<double, double, double>;
Key KeyOf(const Vec3& p) { return Key(p.X, p.Y, p.Z); }

/// Closed and consistently oriented: every directed edge is matched by its reverse.
::testing::AssertionResult IsClosed(const parc::PolygonModel& model)
{
  std::map<std::pair<Key, Key>, int> edges;
  for (std::size_t q = 0; q < model.GetNumberOfQuads(); ++q)
  {
    for (int e = 0; e < 4; ++e)
    {
      const Key a = KeyOf(model.Vertices[4 * q + e]);
      const Key b = KeyOf(model.Vertices[4 * q + (e + 1) % 4]);
      ++edges[{ a, b }];
      --edges[{ b, a }];
    }
  }
  for (const auto& edge : edges)
  {
    if (edge.second != 0)
    {
      return ::testing::AssertionFailure() << "an unmatched edge";
    }
  }
  return ::testing::AssertionSuccess();
}

const double SupercellSizes[][3] = { { 1, 1, 1 }, { 2, 2, 2 }, { 4, 4, 4 }, { 8, 8, 8 }, { 3, 5, 5 },
  { 1.03, 1.03, 1.03 },
  { 3.125, 3.125, 0.15 }, { 6, 4, 3.125 }, { 0.5, 0.7, 0.4 }, { 2.5, 1, 0.75 } };
}

// The rule's interval lists agree with the exact interval test, for every ray function.
TEST(Classification, RuleMatchesBruteForce)
{
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-20.0, 120.0);
  for (int trial = 0; trial < 300; ++trial)
  {
    for (BlendMode blend : AllBlendModes)
    {
      const CastParameters p = RandomParameters(rng, blend);
      ContributionRule rule;
      const double range[2] = { 0.0, 0.0 };
      rule.Set(p, range); // zero margin: compare exactly
      for (int q = 0; q < 50; ++q)
      {
        double lo = u(rng), hi = u(rng);
        if (lo > hi)
        {
          std::swap(lo, hi);
        }
        ASSERT_EQ(rule.IsPossiblyContributing(lo, hi), BruteRule(p, lo, hi))
          << "blend " << static_cast<int>(blend) << " [" << lo << ", " << hi << "]";
      }
    }
  }
}

// Every sample that can show lies in a PC cell: densely sampled cells against the flags.
TEST(Classification, EverySampleThatMattersIsInAPCCell)
{
  std::mt19937 rng(12);
  const int dims[3] = { 7, 6, 8 };
  const double unit[3] = { 1, 1, 1 };
  for (int trial = 0; trial < 40; ++trial)
  {
    for (BlendMode blend : AllBlendModes)
    {
      Scene s(rng, dims, blend, unit);
      const std::vector<char> flags = CellFlags(s.Pyramid, s.Rule);
      std::size_t c = 0;
      for (int k = 0; k < dims[2] - 1; ++k)
        for (int j = 0; j < dims[1] - 1; ++j)
          for (int i = 0; i < dims[0] - 1; ++i, ++c)
          {
            // The supercell grid of unit size has the same flags as the cells.
            ASSERT_EQ(s.Grid.IsContributing(i, j, k), flags[c] != 0);
            for (int n = 0; n < 64 && !flags[c]; ++n)
            {
              const Vec3 p(i + (n & 3) / 3.0, j + ((n >> 2) & 3) / 3.0, k + ((n >> 4) & 3) / 3.0);
              for (auto interp : { parc::Interpolation::Linear, parc::Interpolation::Nearest })
              {
                ASSERT_FALSE(SampleMatters(s.Params, s.Field.Sample(p, interp)))
                  << "a sample that shows in a cell classified empty";
              }
            }
          }
    }
  }
}

// The pyramid answers "is some cell of this box PC" like the cell flags do.
TEST(Classification, PyramidMatchesCellFlagsOnRandomBoxes)
{
  std::mt19937 rng(13);
  const int dims[3] = { 19, 12, 23 };
  const double unit[3] = { 1, 1, 1 };
  for (int trial = 0; trial < 30; ++trial)
  {
    Scene s(rng, dims, AllBlendModes[trial % 6], unit);
    const std::vector<char> flags = CellFlags(s.Pyramid, s.Rule);
    for (int q = 0; q < 200; ++q)
    {
      int c0[3], c1[3];
      for (int a = 0; a < 3; ++a)
      {
        c0[a] = static_cast<int>(rng() % (dims[a] - 1));
        c1[a] = c0[a] + static_cast<int>(rng() % (dims[a] - 1 - c0[a]));
      }
      bool any = false;
      for (int k = c0[2]; k <= c1[2]; ++k)
        for (int j = c0[1]; j <= c1[1]; ++j)
          for (int i = c0[0]; i <= c1[0]; ++i)
            any = any || flags[i + (dims[0] - 1) * (j + (dims[1] - 1) * k)];
      ASSERT_EQ(s.Pyramid.AnyContributing(c0, c1, s.Rule), any);
    }
  }
}

// Supercells of every size (non-integer, subcells): a supercell is PC exactly when it
// overlaps a PC cell (sizes >= 1); with subcells every point where a sample shows touches
// a PC subcell, and a PC subcell always lies in a PC cell.
TEST(SupercellGrid, SupercellsCoverEveryPCCell)
{
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int dims[3] = { 11, 9, 13 };
  for (const auto& size : SupercellSizes)
  {
    for (BlendMode blend : AllBlendModes)
    {
      Scene s(rng, dims, blend, size);
      const std::vector<char> flags = CellFlags(s.Pyramid, s.Rule);
      const int* n = s.Grid.GetCounts();
      for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
          for (int i = 0; i < n[0]; ++i)
          {
            const int idx[3] = { i, j, k };
            bool overlapsPC = false;
            int c0[3], c1[3];
            for (int a = 0; a < 3; ++a)
            {
              c0[a] = static_cast<int>(std::floor(s.Grid.Boundary(a, idx[a])));
              c1[a] = static_cast<int>(std::ceil(s.Grid.Boundary(a, idx[a] + 1))) - 1;
            }
            for (int ck = c0[2]; ck <= c1[2]; ++ck)
              for (int cj = c0[1]; cj <= c1[1]; ++cj)
                for (int ci = c0[0]; ci <= c1[0]; ++ci)
                  overlapsPC = overlapsPC || flags[ci + (dims[0] - 1) * (cj + (dims[1] - 1) * ck)];
            const bool subcell = size[0] < 1 || size[1] < 1 || size[2] < 1;
            if (!subcell)
            {
              ASSERT_EQ(s.Grid.IsContributing(i, j, k), overlapsPC);
            }
            else if (s.Grid.IsContributing(i, j, k))
            {
              ASSERT_TRUE(overlapsPC);
            }
          }
      for (int q = 0; q < 3000; ++q)
      {
        const Vec3 p(u(rng) * (dims[0] - 1), u(rng) * (dims[1] - 1), u(rng) * (dims[2] - 1));
        if (SampleMatters(s.Params, s.Field.SampleLinear(p)))
        {
          ASSERT_TRUE(s.Grid.TouchesContributing(p, 0.0)) << p.X << " " << p.Y << " " << p.Z;
        }
      }
    }
  }
}

// 8- and 16-bit fields of at most 256 values have exact codes: supercells of 2^L cells are
// then classified from the pyramid's ranges alone, and still exactly (a supercell is PC
// when it overlaps a PC cell). A 16-bit field of a wider range reads cells as before.
TEST(SupercellGrid, ExactCodesClassifyLevelsExactly)
{
  std::mt19937 rng(21);
  const int dims[3] = { 19, 17, 21 };
  for (const double scale : { 1.0, 2.4, 7.0 })
  {
    for (const bool sixteen : { false, true })
    {
      if (scale > 1.0 && !sixteen)
      {
        continue; // 8 bits hold at most 256 values
      }
      for (BlendMode blend : AllBlendModes)
      {
        Scene s(rng, dims, blend, SupercellSizes[2]);
        // The scene's values rounded, in an integer type (scaled: ranges of about 100,
        // 250 and 735; negative 16-bit values).
        const parc::ScalarField field = IntegerField(s.Field, scale, sixteen ? -300 : 0, sixteen);
        s.Params.Opacity.SetNodes({ -300.0 + 20.0 * scale, -300.0 + 40.0 * scale,
                                    -300.0 + 41.0 * scale, 99.0 },
          { 0.0, 0.5, 0.0, 0.0 }, false); // a band: some cells leap over it
        if (!sixteen)
        {
          s.Params.Opacity.SetNodes({ 20.0, 40.0, 41.0 }, { 0.0, 0.5, 0.0 }, false);
        }
        RangePyramid pyramid;
        pyramid.Build(field);
        ContributionRule rule;
        rule.Set(s.Params, field.GetRange());
        for (const double* size : { SupercellSizes[1], SupercellSizes[2] })
        {
          SupercellGrid grid;
          const int cells[3] = { dims[0] - 1, dims[1] - 1, dims[2] - 1 };
          ASSERT_TRUE(grid.Configure(cells, size));
          grid.Classify(pyramid, rule, parc::Interpolation::Linear);
          const std::vector<char> flags = CellFlags(pyramid, rule);
          const int* count = grid.GetCounts();
          for (int k = 0; k < count[2]; ++k)
            for (int j = 0; j < count[1]; ++j)
              for (int i = 0; i < count[0]; ++i)
              {
                const int width = static_cast<int>(size[0]);
                bool overlapsPC = false;
                for (int ck = width * k; ck < std::min(width * (k + 1), cells[2]); ++ck)
                  for (int cj = width * j; cj < std::min(width * (j + 1), cells[1]); ++cj)
                    for (int ci = width * i; ci < std::min(width * (i + 1), cells[0]); ++ci)
                      overlapsPC = overlapsPC || flags[ci + cells[0] * (cj + cells[1] * ck)];
                ASSERT_EQ(grid.IsContributing(i, j, k), overlapsPC)
                  << scale << " " << sixteen << " " << static_cast<int>(blend);
              }
        }
      }
    }
  }
}

TEST(SupercellGrid, RejectsInvalidSizes)
{
  SupercellGrid grid;
  const int cells[3] = { 10, 10, 10 };
  for (double bad : { 0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity(), 1e-9 })
  {
    const double size[3] = { 1.0, bad, 1.0 };
    EXPECT_FALSE(grid.Configure(cells, size)) << bad;
    EXPECT_EQ(grid.GetNumberOfSupercells(), 0u);
  }
  const double partial[3] = { 3.0, 4.0, 10.0 };
  ASSERT_TRUE(grid.Configure(cells, partial));
  EXPECT_EQ(grid.GetCounts()[0], 4);
  EXPECT_EQ(grid.Boundary(0, 4), 10.0) << "the last supercell is partial";
  EXPECT_EQ(grid.GetCounts()[1], 3);
  EXPECT_EQ(grid.GetCounts()[2], 1);
}

// A volume too large for the requested supercells (1300^3 voxels at 2x2x2) gets the
// smallest uniform enlargement found that fits; sizes that fit are kept; invalid ones fail.
TEST(SupercellGrid, FitSizeScalesUpOnlyWhatDoesNotFit)
{
  const int huge[3] = { 1299, 1299, 1299 };
  const double two[3] = { 2.0, 2.0, 2.0 };
  EXPECT_GT(SupercellGrid::CountSupercells(huge, two), double(SupercellGrid::MaxSupercells));
  double fitted[3];
  ASSERT_TRUE(SupercellGrid::FitSize(huge, two, fitted));
  EXPECT_LE(SupercellGrid::CountSupercells(huge, fitted), double(SupercellGrid::MaxSupercells));
  EXPECT_GT(fitted[0], 2.0);
  EXPECT_LT(fitted[0], 2.02) << "enlarged by little more than needed";
  EXPECT_EQ(fitted[0], fitted[1]);
  EXPECT_EQ(fitted[1], fitted[2]);
  const double sized[3] = { 4.0, 6.0, 8.0 };
  const double shifted[3] = { 2.0, 3.0, 4.0 };
  const int small[3] = { 10, 10, 10 };
  ASSERT_TRUE(SupercellGrid::FitSize(small, shifted, fitted));
  EXPECT_TRUE(std::equal(fitted, fitted + 3, shifted));
  ASSERT_TRUE(SupercellGrid::FitSize(huge, sized, fitted));
  EXPECT_TRUE(std::equal(fitted, fitted + 3, sized));
  const double bad[3] = { 1.0, std::nan(""), 1.0 };
  EXPECT_FALSE(SupercellGrid::FitSize(small, bad, fitted));
}

// Depth model: face count and area against an independent count of PC/empty transitions
// along each grid line; merging keeps the area and never adds quads; closed and oriented.
// Rows of more than 64 supercells along x (the model reads the flags 64 at a time).
TEST(PolygonModel, DepthModelMatchesAnIndependentCount)
{
  std::mt19937 rng(15);
  const std::array<int, 3> grids[] = { { 12, 10, 14 }, { 140, 7, 9 } };
  for (int g = 0; g < 2 * static_cast<int>(std::size(SupercellSizes)); ++g)
  {
    const std::array<int, 3>& dims = grids[g % 2];
    const double* size = SupercellSizes[g / 2];
    Scene s(rng, dims.data(), BlendMode::Composite, size, parc::Interpolation::Linear, true);
    const int* n = s.Grid.GetCounts();
    std::size_t faces = 0;
    double area = 0.0;
    for (int axis = 0; axis < 3; ++axis)
    {
      const int b = (axis + 1) % 3, c = (axis + 2) % 3;
      int idx[3];
      for (idx[b] = 0; idx[b] < n[b]; ++idx[b])
        for (idx[c] = 0; idx[c] < n[c]; ++idx[c])
        {
          const double faceArea = (s.Grid.Boundary(b, idx[b] + 1) - s.Grid.Boundary(b, idx[b])) *
            (s.Grid.Boundary(c, idx[c] + 1) - s.Grid.Boundary(c, idx[c]));
          bool previous = false;
          for (idx[axis] = 0; idx[axis] <= n[axis]; ++idx[axis])
          {
            const bool current =
              idx[axis] < n[axis] && s.Grid.IsContributing(idx[0], idx[1], idx[2]);
            if (current != previous)
            {
              ++faces;
              area += faceArea;
            }
            previous = current;
          }
        }
    }
    parc::PolygonModel model, merged;
    parc::BuildDepthModel(s.Grid, false, model);
    parc::BuildDepthModel(s.Grid, true, merged);
    EXPECT_EQ(model.GetNumberOfQuads(), faces);
    EXPECT_NEAR(model.GetArea(), area, 1e-9 * std::max(1.0, area));
    EXPECT_NEAR(merged.GetArea(), area, 1e-9 * std::max(1.0, area));
    EXPECT_LE(merged.GetNumberOfQuads(), faces);
    if (faces > 20)
    {
      EXPECT_LT(merged.GetNumberOfQuads(), faces);
    }
    EXPECT_TRUE(IsClosed(model));
    const parc::ModelStatistics stats = parc::ComputeStatistics(s.Grid, model);
    EXPECT_EQ(stats.Cells, static_cast<std::uint64_t>(dims[0] - 1) * (dims[1] - 1) * (dims[2] - 1));
    EXPECT_EQ(stats.Polygons, faces);
    EXPECT_NEAR(stats.ContributingPercent,
      100.0 * s.Grid.GetNumberOfContributing() / s.Grid.GetNumberOfSupercells(), 1e-12);
  }
}

// Colour model: closed per plane, plane indices from 0, two faces per PC supercell across
// the axis plus the in-plane transitions.
TEST(PolygonModel, ColorModelIsClosedPerPlane)
{
  std::mt19937 rng(16);
  const int dims[3] = { 12, 10, 14 };
  for (const auto& size : SupercellSizes)
  {
    Scene s(rng, dims, BlendMode::Composite, size, parc::Interpolation::Linear, true);
    for (int axis = 0; axis < 3; ++axis)
    {
      parc::PolygonModel model;
      parc::BuildColorModel(s.Grid, axis, false, model);
      ASSERT_EQ(model.Planes.size(), model.GetNumberOfQuads());
      int first, last;
      s.Grid.ContributingPlanes(axis, first, last);
      EXPECT_EQ(model.FirstPlane, first);
      EXPECT_EQ(model.PlaneCount, last - first + 1);
      std::map<int, parc::PolygonModel> perPlane;
      for (std::size_t q = 0; q < model.GetNumberOfQuads(); ++q)
      {
        ASSERT_GE(model.Planes[q], 0);
        ASSERT_LT(model.Planes[q], model.PlaneCount);
        auto& m = perPlane[model.Planes[q]];
        m.Vertices.insert(m.Vertices.end(), model.Vertices.begin() + 4 * q,
          model.Vertices.begin() + 4 * q + 4);
      }
      EXPECT_EQ(perPlane.begin()->first, 0);
      for (const auto& plane : perPlane)
      {
        EXPECT_TRUE(IsClosed(plane.second)) << "plane " << plane.first;
      }
      // Count: per PC supercell 2 faces across the axis and one per empty in-plane side.
      const int* n = s.Grid.GetCounts();
      std::size_t faces = 0;
      for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
          for (int i = 0; i < n[0]; ++i)
          {
            if (!s.Grid.IsContributing(i, j, k))
              continue;
            faces += 2;
            for (int a = 0; a < 3; ++a)
              for (int d : { -1, 1 })
              {
                int o[3] = { i, j, k };
                o[a] += d;
                if (a != axis && !s.Grid.IsContributingOrOutside(o[0], o[1], o[2]))
                  ++faces;
              }
          }
      EXPECT_EQ(model.GetNumberOfQuads(), faces);

      // Merged: the same area in every plane with at most as many quads.
      parc::PolygonModel merged;
      parc::BuildColorModel(s.Grid, axis, true, merged);
      ASSERT_EQ(merged.Planes.size(), merged.GetNumberOfQuads());
      EXPECT_EQ(merged.FirstPlane, model.FirstPlane);
      EXPECT_EQ(merged.PlaneCount, model.PlaneCount);
      EXPECT_LE(merged.GetNumberOfQuads(), model.GetNumberOfQuads());
      std::map<int, parc::PolygonModel> mergedPerPlane;
      for (std::size_t q = 0; q < merged.GetNumberOfQuads(); ++q)
      {
        auto& m = mergedPerPlane[merged.Planes[q]];
        m.Vertices.insert(m.Vertices.end(), merged.Vertices.begin() + 4 * q,
          merged.Vertices.begin() + 4 * q + 4);
      }
      ASSERT_EQ(mergedPerPlane.size(), perPlane.size());
      for (const auto& plane : perPlane)
      {
        EXPECT_NEAR(mergedPerPlane[plane.first].GetArea(), plane.second.GetArea(),
          1e-9 * plane.second.GetArea())
          << "plane " << plane.first;
      }
    }
  }
}

namespace
{
/// Checks the oracle's intervals of one ray against dense sampling: every sampled point
/// that touches a PC supercell is inside an interval, and the planes it touches are among
/// the oracle's. With exact, the plane sets must be equal.
void CheckRay(const Scene& s, const parc::SegmentOracle& oracle, const parc::Ray& ray,
  bool exact)
{
  std::vector<parc::Segment> segments;
  std::vector<int> planes;
  oracle.Intervals(ray, ray.TMin, ray.TMax, segments, 2, &planes);
  for (std::size_t i = 1; i < segments.size(); ++i)
  {
    ASSERT_LT(segments[i - 1].TFar, segments[i].TNear) << "sorted and disjoint";
  }
  std::vector<int> seen;
  constexpr int Steps = 4000;
  const double eps = oracle.GetTolerance();
  for (int n = 0; n <= Steps; ++n)
  {
    const double t = ray.TMin + (ray.TMax - ray.TMin) * n / Steps;
    const Vec3 p = ray.Origin + t * ray.Direction;
    const bool touches = s.Grid.TouchesContributing(p, eps);
    bool inside = false;
    for (const auto& seg : segments)
    {
      inside = inside || (t >= seg.TNear - 1e-9 && t <= seg.TFar + 1e-9);
    }
    ASSERT_TRUE(!touches || inside) << "a PC point outside the intervals at t = " << t;
    if (touches)
    {
      std::vector<parc::Segment> pointInterval;
      std::vector<int> pointPlanes;
      oracle.Intervals(ray, t, t, pointInterval, 2, &pointPlanes);
      seen.insert(seen.end(), pointPlanes.begin(), pointPlanes.end());
    }
  }
  // Each interval is PC inside (at its midpoint, unless it is a single point).
  for (const auto& seg : segments)
  {
    const Vec3 p = ray.Origin + 0.5 * (seg.TNear + seg.TFar) * ray.Direction;
    ASSERT_TRUE(s.Grid.TouchesContributing(p, 2 * eps));
  }
  std::sort(seen.begin(), seen.end());
  seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
  ASSERT_TRUE(std::includes(planes.begin(), planes.end(), seen.begin(), seen.end()));
  if (exact)
  {
    ASSERT_EQ(planes, seen);
  }
}
}

// Random rays through random grids of every supercell size.
TEST(SegmentOracle, MatchesDenseSamplingOnRandomRays)
{
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int dims[3] = { 10, 9, 11 };
  for (const auto& size : SupercellSizes)
  {
    Scene s(rng, dims, BlendMode::Composite, size);
    const parc::SegmentOracle oracle(s.Grid, parc::Matrix4());
    for (int r = 0; r < 60; ++r)
    {
      const Vec3 target(4.5 + 4 * u(rng), 4 + 4 * u(rng), 5 + 5 * u(rng));
      const Vec3 dir(u(rng), u(rng), u(rng));
      parc::Ray ray = parctest::MakeRay(target - 20.0 * parc::Normalized(dir), dir);
      ray.TMax = 40.0;
      ASSERT_NO_FATAL_FAILURE(CheckRay(s, oracle, ray, false));
    }
  }
}

// Rays exactly along supercell faces and edges and through corners, along the axes and
// diagonals: closed boxes, so every touched PC supercell counts.
TEST(SegmentOracle, RaysOnFacesEdgesAndCorners)
{
  // One PC supercell, (1, 1, 1) of 2^3 supercells, in a 4^3-cell grid.
  const int cells[3] = { 8, 8, 8 };
  const double size[3] = { 2, 2, 2 };
  const int dims[3] = { 9, 9, 9 };
  const parc::ScalarField field = parctest::MakeField(dims, [](int i, int j, int k) {
    return (i == 3 && j == 3 && k == 3) ? 50.f : 0.f;
  });
  CastParameters p;
  parctest::SetOpacity(p, { 40.0, 60.0 }, { 1.0, 1.0 }, false);
  RangePyramid pyramid;
  pyramid.Build(field);
  ContributionRule rule;
  rule.Set(p, field.GetRange());
  SupercellGrid grid;
  ASSERT_TRUE(grid.Configure(cells, size));
  grid.Classify(pyramid, rule, parc::Interpolation::Linear);
  ASSERT_EQ(grid.GetNumberOfContributing(), 1u);
  ASSERT_TRUE(grid.IsContributing(1, 1, 1));
  const parc::SegmentOracle oracle(grid, parc::Matrix4());
  struct Case
  {
    Vec3 Origin, Direction;
    double Near, Far; // expected touching interval (ray parameter), Near > Far: none
  };
  const double s3 = std::sqrt(3.0), s2 = std::sqrt(2.0);
  const Case cases[] = {
    { { -1, 2, 3 }, { 1, 0, 0 }, 3, 5 },            // on the face y = 2
    { { -1, 4, 4 }, { 1, 0, 0 }, 3, 5 },            // on the edge y = z = 4
    { { -1, 4.000001, 4 }, { 1, 0, 0 }, 1, 0 },     // just outside that edge
    { { 0, 0, 0 }, { 1, 1, 1 }, 2 * s3, 4 * s3 },   // the main diagonal, corner to corner
    { { 0, 8, 0 }, { 1, -1, 1 }, 4 * s3, 4 * s3 }, // only the corner (4, 4, 4)
    { { 0, 6, 2 }, { 1, -1, 0 }, 2 * s2, 4 * s2 },  // across the face z = 2
    { { 2, 2, -3 }, { 0, 0, 1 }, 5, 7 },            // along the edge x = y = 2
    { { 6, 6, 6 }, { -1, -1, -1 }, s3 * 2, s3 * 4 } // from outside a corner, backwards diagonal
  };
  for (const Case& c : cases)
  {
    parc::Ray ray = parctest::MakeRay(c.Origin, c.Direction);
    ray.TMax = 30.0;
    std::vector<parc::Segment> segments;
    oracle.Intervals(ray, ray.TMin, ray.TMax, segments);
    if (c.Near > c.Far)
    {
      EXPECT_TRUE(segments.empty()) << c.Origin.X << " " << c.Origin.Y << " " << c.Origin.Z;
      continue;
    }
    ASSERT_EQ(segments.size(), 1u) << c.Origin.X << " " << c.Origin.Y << " " << c.Origin.Z;
    EXPECT_NEAR(segments[0].TNear, c.Near, 1e-9);
    EXPECT_NEAR(segments[0].TFar, c.Far, 1e-9);
  }
}

namespace
{
/// The end-to-end proof that skipping is exact: casting with the segments of the source
/// made by source(scene) gives the bits of casting whole rays, for every ray function,
/// interpolation and supercell size, with fewer samples.
template <class MakeSource>
void CheckCastingIsBitIdentical(unsigned seed, MakeSource&& source)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int dims[3] = { 14, 12, 16 };
  std::uint64_t wholeSamples = 0, fastSamples = 0;
  for (const auto& size : SupercellSizes)
  {
    for (BlendMode blend : AllBlendModes)
    {
      for (auto interp : { parc::Interpolation::Linear, parc::Interpolation::Nearest })
      {
        Scene s(rng, dims, blend, size, interp);
        s.Params.Shade = (rng() % 2) == 0;
        s.Params.Lights.push_back(parc::Light());
        s.Params.Lights.back().Position = { 0, 0, 1 };
        const auto segments = source(s); // for voxel-index rays
        for (int r = 0; r < 40; ++r)
        {
          const Vec3 target(6.5 + 6 * u(rng), 5.5 + 5 * u(rng), 7.5 + 7 * u(rng));
          const Vec3 dir(u(rng), u(rng), u(rng));
          const parc::Ray ray = parctest::MakeRay(target - 30.0 * parc::Normalized(dir), dir);
          const auto whole = parctest::CastOne(s.Field, s.Params, ray);
          const auto fast = parctest::CastOne(s.Field, s.Params, ray, segments.get());
          ASSERT_EQ(std::memcmp(whole.RGBA, fast.RGBA, sizeof(whole.RGBA)), 0)
            << "blend " << static_cast<int>(blend) << " size " << size[0] << " rgba "
            << whole.RGBA[3] << " vs " << fast.RGBA[3];
          ASSERT_LE(fast.Stats.Samples, whole.Stats.Samples);
          wholeSamples += whole.Stats.Samples;
          fastSamples += fast.Stats.Samples;
        }
      }
    }
  }
  EXPECT_LT(fastSamples, wholeSamples) << "empty samples are skipped";
}
}

TEST(SegmentOracle, CastingWithTheOracleIsBitIdentical)
{
  CheckCastingIsBitIdentical(18, [](const Scene& s) {
    return std::make_unique<parc::SegmentOracle>(s.Grid, parc::Matrix4());
  });
}

namespace
{
/// The walk's segment of ray holds every oracle interval (closed boxes, the tolerance
/// included) and ends where they end: the first and last parameters where the ray
/// touches a PC supercell.
void CheckWalk(const SupercellGrid& grid, const parc::SupercellWalk& walk, const parc::Ray& ray)
{
  const parc::SegmentOracle oracle(grid, parc::Matrix4());
  std::vector<parc::Segment> expected, walked;
  oracle.Intervals(ray, ray.TMin, ray.TMax, expected);
  walk.Segments(parc::RayQuery::Anywhere(ray), walked);
  const auto where = [&ray]() {
    return ::testing::Message() << "ray from (" << ray.Origin.X << ", " << ray.Origin.Y << ", "
                                << ray.Origin.Z << ") along (" << ray.Direction.X << ", "
                                << ray.Direction.Y << ", " << ray.Direction.Z << ")";
  };
  if (expected.empty())
  {
    ASSERT_TRUE(walked.empty()) << where();
    return;
  }
  ASSERT_EQ(walked.size(), 1u) << where();
  // The walk's tolerance (voxel index, relative to the largest coordinate, as large as the
  // oracle's or larger) along the axis the ray crosses most slowly, in ray parameter.
  double slowest = 1.0, largest = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    slowest = ray.Direction[a] != 0.0 ? std::min(slowest, std::abs(ray.Direction[a])) : slowest;
    largest = std::max({ largest, 1.0 * grid.GetCellDimensions()[a], std::abs(ray.Origin[a]) });
  }
  const double Tolerance = 2e-9 * largest / slowest;
  EXPECT_LE(walked[0].TNear, expected.front().TNear + 1e-12) << where();
  EXPECT_GE(walked[0].TFar, expected.back().TFar - 1e-12) << where();
  EXPECT_NEAR(walked[0].TNear, expected.front().TNear, Tolerance) << where();
  EXPECT_NEAR(walked[0].TFar, expected.back().TFar, Tolerance) << where();
}
}

// The walk against the oracle on random grids of every supercell size: random rays, rays
// that start inside, and rays along the axes and diagonals through supercell corners,
// edges and faces (closed boxes: every PC supercell a ray touches counts).
TEST(SupercellWalk, MatchesTheOracle)
{
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int dims[3] = { 23, 19, 27 };
  for (const auto& size : SupercellSizes)
  {
    for (int trial = 0; trial < 3; ++trial)
    {
      Scene s(rng, dims, AllBlendModes[trial], size, parc::Interpolation::Linear, true);
      parc::SupercellWalk walk;
      walk.Set(&s.Grid, parc::Matrix4());
      for (int r = 0; r < 60; ++r)
      {
        const Vec3 target(11 + 11 * u(rng), 9 + 9 * u(rng), 13 + 13 * u(rng));
        const Vec3 dir(u(rng), u(rng), u(rng));
        const double back = r % 3 == 0 ? 3.0 : 50.0; // a third start inside the volume
        parc::Ray ray = parctest::MakeRay(target - back * parc::Normalized(dir), dir);
        ray.TMax = 100.0;
        ASSERT_NO_FATAL_FAILURE(CheckWalk(s.Grid, walk, ray));
      }
      // Through supercell corners: along the axes, the face and the space diagonals.
      for (int r = 0; r < 60; ++r)
      {
        const int* counts = s.Grid.GetCounts();
        Vec3 corner;
        for (int a = 0; a < 3; ++a)
        {
          corner[a] = s.Grid.Boundary(a, static_cast<int>(rng() % (counts[a] + 1)));
        }
        Vec3 dir;
        for (int a = 0; a < 3; ++a)
        {
          dir[a] = static_cast<double>(static_cast<int>(rng() % 3) - 1);
        }
        if (dir.X == 0 && dir.Y == 0 && dir.Z == 0)
        {
          dir.Z = 1;
        }
        parc::Ray ray = parctest::MakeRay(corner - 60.0 * parc::Normalized(dir), dir);
        ray.TMax = 200.0;
        ASSERT_NO_FATAL_FAILURE(CheckWalk(s.Grid, walk, ray));
      }
    }
  }
}

TEST(SupercellWalk, CastingWithTheWalkIsBitIdentical)
{
  CheckCastingIsBitIdentical(22, [](const Scene& s) {
    auto walk = std::make_unique<parc::SupercellWalk>();
    walk->Set(&s.Grid, parc::Matrix4());
    return walk;
  });
}

// The sign of the rays along a colour model's axis: only when every ray runs the same way
// and starts before every plane.
TEST(PolygonModel, RayAxisSign)
{
  parc::PolygonModel model;
  model.MajorAxis = 0;
  model.PlanesLow = 2.0;
  model.PlanesHigh = 10.0;
  const std::vector<parc::Vec3> forward = { { 1, 0.2, 0 }, { 0.5, -1, 0 }, { 2, 0, 1 } };
  const std::vector<parc::Vec3> backward = { { -1, 0.2, 0 }, { -0.5, -1, 0 } };
  EXPECT_EQ(parc::RayAxisSign(model, { { 0, 5, 5 }, { 1.9, -3, 8 } }, forward), 1);
  EXPECT_EQ(parc::RayAxisSign(model, { { 12, 5, 5 }, { 10.1, 0, 0 } }, backward), -1);
  EXPECT_EQ(parc::RayAxisSign(model, { { 0, 5, 5 }, { 2.5, 0, 0 } }, forward), 0); // inside
  EXPECT_EQ(parc::RayAxisSign(model, { { 12, 5, 5 } }, forward), 0);               // behind
  std::vector<parc::Vec3> mixed = forward;
  mixed.push_back({ -0.1, 1, 0 });
  EXPECT_EQ(parc::RayAxisSign(model, { { 0, 5, 5 } }, mixed), 0);
  mixed.back() = { 0, 1, 0 }; // parallel to the planes
  EXPECT_EQ(parc::RayAxisSign(model, { { 0, 5, 5 } }, mixed), 0);
  model.MajorAxis = -1; // a depth model
  EXPECT_EQ(parc::RayAxisSign(model, { { 0, 5, 5 } }, forward), 0);
}

namespace
{
/// The pyramid, rule and map of the cells of a field under parameters p.
struct ClassifiedCells
{
  RangePyramid Pyramid;
  ContributionRule Rule;
  parc::CellMap Map;

  ClassifiedCells(const parc::ScalarField& field, const CastParameters& p)
  {
    this->Pyramid.Build(field);
    this->Rule.Set(p, field.GetRange());
    EXPECT_TRUE(this->Pyramid.MapCells(this->Rule, this->Map));
    EXPECT_TRUE(this->Map.Covers(field.GetDimensions()));
  }
};

/// Calls visit(ci, cj, ck) for every cell of the map's node of cell (i, j, k), those past
/// the field's end included.
template <typename Visit>
void ForNodeCells(int i, int j, int k, Visit&& visit)
{
  constexpr int n = parc::CellMap::NodeCells;
  const int first[3] = { i - i % n, j - j % n, k - k % n };
  for (int ck = first[2]; ck < first[2] + n; ++ck)
    for (int cj = first[1]; cj < first[1] + n; ++cj)
      for (int ci = first[0]; ci < first[0] + n; ++ci)
        visit(ci, cj, ck);
}
}

// Every PC cell (brute force, from the cell ranges) is in the map, read cell by cell and
// lane by lane (a block's located samples); the cells of nodes (CellMap::NodeCells cells
// along each axis) without a PC one rarely are (only where the pyramid's coded range of the
// node is wider than its cells' ranges). Dimensions that are not whole nodes leave partial
// nodes.
TEST(ContributingCells, EveryPossiblyContributingCellIsInTheMap)
{
  std::mt19937 rng(31);
  const int dims[3] = { 23, 14, 31 };
  int mixed = 0;
  std::size_t spurious = 0, outside = 0;
  for (int trial = 0; trial < 24; ++trial)
  {
    for (BlendMode blend : AllBlendModes)
    {
      const parc::ScalarField field = RandomVolume(rng, dims);
      const ClassifiedCells cells(field, RandomParameters(rng, blend));
      const std::vector<char> expected = CellFlags(cells.Pyramid, cells.Rule);
      const int c[3] = { dims[0] - 1, dims[1] - 1, dims[2] - 1 };
      auto pc = [&](int i, int j, int k) {
        return i < c[0] && j < c[1] && k < c[2] && expected[i + c[0] * (j + c[1] * k)] != 0;
      };
      std::size_t set = 0;
      parc::LatticeBlock block;
      int lane = 0;
      for (int k = 0; k < c[2]; ++k)
        for (int j = 0; j < c[1]; ++j)
          for (int i = 0; i < c[0]; ++i)
          {
            const bool may = cells.Map.MayContribute(i, j, k);
            bool nodePC = false;
            ForNodeCells(i, j, k, [&](int ci, int cj, int ck) { nodePC |= pc(ci, cj, ck); });
            ASSERT_TRUE(!pc(i, j, k) || may) << i << " " << j << " " << k;
            outside += !nodePC;
            spurious += may && !nodePC;
            set += may;
            // The same cell as lane `lane` of a block, in the cells' order turned around.
            const int l = parc::LatticeBlock::Size - 1 - lane;
            block.Cell[0][l] = i;
            block.Cell[1][l] = j;
            block.Cell[2][l] = k;
            if (++lane == parc::LatticeBlock::Size)
            {
              const unsigned lanes = cells.Map.Lanes(block, parc::LatticeBlock::Size);
              for (int m = 0; m < parc::LatticeBlock::Size; ++m)
              {
                ASSERT_EQ((lanes >> m) & 1u,
                  cells.Map.MayContribute(block.Cell[0][m], block.Cell[1][m], block.Cell[2][m]))
                  << "lane " << m;
              }
              lane = 0;
            }
          }
      mixed += set > 0 && set < expected.size();
    }
  }
  EXPECT_GT(mixed, 20) << "scenes with some cells PC and some not";
  EXPECT_LT(spurious, outside / 5) << "cells of nodes without a PC cell";
  const int slice[3] = { 4, 4, 1 }; // one slice: no cells
  const parc::ScalarField flatField = parctest::MakeField(slice, [](int, int, int) { return 1.f; });
  RangePyramid flat;
  flat.Build(flatField);
  parc::CellMap map;
  ContributionRule rule;
  rule.Set(RandomParameters(rng, BlendMode::Composite), flatField.GetRange());
  EXPECT_FALSE(flat.MapCells(rule, map));
  EXPECT_TRUE(map.IsEmpty());
  EXPECT_FALSE(map.Covers(slice));
}

// Nodes past 32-bit indices (a field of more than 2^34 voxels) leave the map empty, so the
// caster samples every cell instead of indexing past the codes; the largest field that
// fits is mapped.
TEST(ContributingCells, NodesBeyond32BitIndicesLeaveTheMapEmpty)
{
  const std::uint8_t code = 0; // SetNodes keeps the pointer; it reads no code
  parc::CellMap map;
  const int beyond[3] = { 2048, 2048, 512 }; // 2^31 nodes
  map.SetNodes(&code, beyond);
  EXPECT_TRUE(map.IsEmpty());
  constexpr int n = parc::CellMap::NodeCells;
  const int field[3] = { n * beyond[0] + 1, n * beyond[1] + 1, n * beyond[2] + 1 };
  EXPECT_FALSE(map.Covers(field));
  const int largest[3] = { 2048, 2048, 511 }; // 2^31 - 2^22 nodes
  map.SetNodes(&code, largest);
  EXPECT_FALSE(map.IsEmpty());
  const int fits[3] = { n * largest[0] + 1, n * (largest[1] - 1) + 2, n * largest[2] };
  EXPECT_TRUE(map.Covers(fits));
}

// With exact codes (8-bit values) a cell is in the map exactly when the range of its node
// (the pyramid's lowest level) widened to whole sixteenths of the codes (the map is packed)
// meets the rule: so is every cell of a node with a PC cell. Rules of one interval or
// threshold and of several intervals.
TEST(ContributingCells, ExactCodesGiveTheNodesWhosePackedRangeMeetsTheRule)
{
  std::mt19937 rng(32);
  const int dims[3] = { 26, 19, 30 };
  constexpr int Sixteenth = 16;
  int several = 0, widened = 0;
  for (int trial = 0; trial < 12; ++trial)
  {
    for (BlendMode blend : AllBlendModes)
    {
      const parc::ScalarField field = IntegerField(RandomVolume(rng, dims), 2.0, 0, false);
      const CastParameters p = RandomParameters(rng, blend);
      const ClassifiedCells cells(field, p);
      several += !cells.Rule.TestsEndsApart();
      const std::vector<char> pcCells = CellFlags(cells.Pyramid, cells.Rule);
      const double bottom = field.GetRange()[0], top = field.GetRange()[1];
      const int c[3] = { dims[0] - 1, dims[1] - 1, dims[2] - 1 };
      for (int k = 0; k < c[2]; ++k)
        for (int j = 0; j < c[1]; ++j)
          for (int i = 0; i < c[0]; ++i)
          {
            bool nodePC = false;
            float lo = std::numeric_limits<float>::max(), hi = -lo;
            ForNodeCells(i, j, k, [&](int ci, int cj, int ck) {
              if (ci < c[0] && cj < c[1] && ck < c[2])
              {
                nodePC |= pcCells[ci + c[0] * (cj + c[1] * ck)] != 0;
                float cellLo, cellHi;
                field.CellRange(ci, cj, ck, cellLo, cellHi);
                lo = std::min(lo, cellLo);
                hi = std::max(hi, cellHi);
              }
            });
            const int loCode = static_cast<int>(lo - bottom), hiCode = static_cast<int>(hi - bottom);
            const double wideLo = bottom + (loCode & ~(Sixteenth - 1));
            const double wideHi = std::min(bottom + (hiCode | (Sixteenth - 1)), top);
            const bool meets = cells.Rule.IsPossiblyContributing(wideLo, wideHi);
            const bool bit = cells.Map.MayContribute(i, j, k);
            ASSERT_TRUE(!nodePC || bit) << "a node with a PC cell is in: " << i << " " << j
                                        << " " << k << " blend " << static_cast<int>(blend);
            ASSERT_EQ(bit, meets) << "in where the packed range meets the rule: " << i << " "
                                  << j << " " << k;
            widened += bit && !nodePC;
          }
    }
  }
  EXPECT_GT(several, 5) << "rules of several intervals";
  EXPECT_GT(widened, 0) << "the packed ranges are wider than the nodes'";
}

namespace
{
/// The same rays cast by a caster that interpolates every sample and by one that reads
/// the map of contributing cells.
struct PlainAndSkipping
{
  parc::RayCaster Plain, Skipping;
  const parc::WholeRaySource Whole;
  std::vector<parc::Segment> Segments;
  std::vector<parc::LatticeRange> Ranges;
  bool Prepared = false; ///< both casters prepared (a test asserts it before casting)

  PlainAndSkipping(
    const parc::ScalarField& field, const CastParameters& p, const ClassifiedCells& cells)
  {
    this->Prepared =
      this->Plain.Prepare({ &field, &p }) && this->Skipping.Prepare({ &field, &p });
    this->Skipping.SetContributingCells(&cells.Map);
  }
  /// The ray's colours (plain a, skipping b) and counts (sa, sb).
  void Cast(const parc::Ray& ray, float a[4], float b[4], parc::CastStatistics& sa,
    parc::CastStatistics& sb)
  {
    const auto query = parc::RayQuery::Anywhere(ray);
    this->Plain.CastRay(query, this->Whole, this->Segments, this->Ranges, a, sa);
    this->Skipping.CastRay(query, this->Whole, this->Segments, this->Ranges, b, sb);
  }
};
}

// A ray reads the map of contributing cells only where it crosses cells that cannot
// contribute: along +x through a slab of as many empty cells as a block has samples (two
// blocks of samples), then 36 contributing cells, a pocket of 2 empty cells (4 samples), and
// contributing cells again, it leaves out the slab's samples after the block that found it,
// and not the pocket's, which the map turned off by the cells before it does not see: fewer
// than the slab's and the pocket's samples in empty cells, and the same bits and counts as a
// ray that interpolates every sample.
TEST(ContributingCells, RaysReadTheMapOnlyWhereTheyCrossEmptyCells)
{
  // The slab starts where the ray's first block (half a block of cells) ends.
  constexpr int block = parc::LatticeBlock::Size, slab = block / 2, slabEnd = slab + block;
  constexpr int pocket = slabEnd + 36;
  const int dims[3] = { pocket + 36, 6, 6 };
  const parc::ScalarField field = parctest::MakeField(dims, [](int i, int, int) {
    const bool empty = (i >= slab && i <= slabEnd) || (i >= pocket && i <= pocket + 2);
    return empty ? 0.f : 200.f;
  });
  CastParameters p;
  p.Blend = BlendMode::Composite;
  parctest::SetOpacity(p, { 0.0, 100.0, 200.0 }, { 0.0, 0.0, 0.01 });
  p.SampleDistance = 0.5;
  p.TerminationOpacity = 1.0;
  const ClassifiedCells cells(field, p);
  PlainAndSkipping casters(field, p, cells);
  ASSERT_TRUE(casters.Prepared);
  float a[4], b[4];
  parc::CastStatistics sa, sb;
  casters.Cast(parctest::MakeRay(Vec3(-3.0, 2.5, 2.5), Vec3(1.0, 0.0, 0.0)), a, b, sa, sb);
  ASSERT_EQ(std::memcmp(a, b, sizeof(a)), 0);
  ASSERT_EQ(sa.Samples, sb.Samples);
  ASSERT_EQ(sa.ContributingSamples, sb.ContributingSamples);
  EXPECT_GT(a[3], 0.f) << "the ray composites the contributing cells";
  const auto slabSamples = static_cast<std::uint64_t>(2 * block);
  EXPECT_GE(sb.EmptyCellSamples, slabSamples - block - parc::LatticeBlock::Lanes)
    << "the slab's samples after its first block";
  EXPECT_LE(sb.EmptyCellSamples, slabSamples - block / 2)
    << "neither the slab's first block nor the pocket";
}

// Composite rays leave out the samples of cells that cannot contribute and give the same
// bits and counts as rays that interpolate every sample; other ray functions, and nearest
// interpolation, do not use the bits.
TEST(ContributingCells, CastingLeavesOutEmptyCellsExactly)
{
  std::mt19937 rng(37);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int dims[3] = { 15, 12, 17 };
  std::uint64_t left = 0;
  for (int trial = 0; trial < 30; ++trial)
  {
    for (BlendMode blend : AllBlendModes)
    {
      for (auto interp : { parc::Interpolation::Linear, parc::Interpolation::Nearest })
      {
        const parc::ScalarField field = RandomVolume(rng, dims);
        CastParameters p = RandomParameters(rng, blend);
        p.Interp = interp;
        p.Shade = trial % 2 == 0;
        p.TerminationOpacity = trial % 3 == 0 ? 0.95 : 1.0;
        p.Lights.push_back(parc::Light());
        p.Lights.back().Position = { 0, 0, 1 };
        const ClassifiedCells cells(field, p);
        PlainAndSkipping casters(field, p, cells);
        ASSERT_TRUE(casters.Prepared);
        for (int r = 0; r < 30; ++r)
        {
          const Vec3 target(7 + 7 * u(rng), 5.5 + 5 * u(rng), 8 + 8 * u(rng));
          const Vec3 dir(u(rng), u(rng), u(rng));
          float a[4], b[4];
          parc::CastStatistics sa, sb;
          casters.Cast(parctest::MakeRay(target - 30.0 * parc::Normalized(dir), dir), a, b, sa, sb);
          ASSERT_EQ(std::memcmp(a, b, sizeof(a)), 0) << "blend " << static_cast<int>(blend);
          ASSERT_EQ(sa.Samples, sb.Samples);
          ASSERT_EQ(sa.ContributingSamples, sb.ContributingSamples);
          ASSERT_EQ(sa.GradientEvaluations, sb.GradientEvaluations);
          const bool uses = blend == BlendMode::Composite && interp == parc::Interpolation::Linear;
          if (!uses)
          {
            ASSERT_EQ(sb.EmptyCellSamples, 0u);
          }
          ASSERT_LE(sb.EmptyCellSamples + sb.ContributingSamples, sb.Samples);
          left += sb.EmptyCellSamples;
        }
      }
    }
  }
  EXPECT_GT(left, 1000u) << "composite rays leave samples out";
}
