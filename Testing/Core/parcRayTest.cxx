// Ray-box clipping and the conversion of segments to lattice ranges.
#include "parcRay.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using parc::LatticeRange;
using parc::Segment;
using parc::Vec3;

TEST(ClipToBox, RayThroughTheMiddle)
{
  double t0 = -1e9, t1 = 1e9;
  ASSERT_TRUE(parc::ClipToBox({ -5, 1, 1 }, { 1, 0, 0 }, { 0, 0, 0 }, { 3, 2, 2 }, t0, t1));
  EXPECT_DOUBLE_EQ(t0, 5.0);
  EXPECT_DOUBLE_EQ(t1, 8.0);
}

TEST(ClipToBox, RayMissesAndParallelOutside)
{
  double t0 = -1e9, t1 = 1e9;
  EXPECT_FALSE(parc::ClipToBox({ -5, 3, 1 }, { 1, 0, 0 }, { 0, 0, 0 }, { 3, 2, 2 }, t0, t1));
  t0 = -1e9;
  t1 = 1e9;
  EXPECT_FALSE(parc::ClipToBox({ -5, -2, 1 }, { 1, 1, 0 }, { 0, 0, 0 }, { 3, 2, 2 }, t0, t1))
    << "a diagonal ray passing beside the box";
}

TEST(ClipToBox, RayOnAFaceAndThroughAnEdge)
{
  double t0 = -1e9, t1 = 1e9;
  ASSERT_TRUE(parc::ClipToBox({ -1, 0, 0 }, { 1, 0, 0 }, { 0, 0, 0 }, { 3, 2, 2 }, t0, t1))
    << "a ray along an edge of the box belongs to the closed box";
  EXPECT_DOUBLE_EQ(t0, 1.0);
  EXPECT_DOUBLE_EQ(t1, 4.0);
  t0 = -1e9;
  t1 = 1e9;
  const Vec3 d = parc::Normalized({ 1, 1, 0 });
  ASSERT_TRUE(parc::ClipToBox({ 2, -1, 1 }, d, { 0, 0, 0 }, { 3, 2, 2 }, t0, t1))
    << "a diagonal ray through the corner edge (3, 0)";
  EXPECT_NEAR(t0, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(t1, std::sqrt(2.0), 1e-12);
}

TEST(ClipToBox, RespectsTheGivenRange)
{
  double t0 = 6.0, t1 = 7.0;
  ASSERT_TRUE(parc::ClipToBox({ -5, 1, 1 }, { 1, 0, 0 }, { 0, 0, 0 }, { 3, 2, 2 }, t0, t1));
  EXPECT_DOUBLE_EQ(t0, 6.0);
  EXPECT_DOUBLE_EQ(t1, 7.0);
}

TEST(LatticeRanges, OneSegmentIsClampedToTheBox)
{
  std::vector<LatticeRange> r;
  constexpr double inf = std::numeric_limits<double>::infinity();
  parc::SegmentsToLatticeRanges({ { -inf, inf } }, 1.05, 3.95, 0.5, r);
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0].First, 3); // ceil(1.05 / 0.5)
  EXPECT_EQ(r[0].Last, 7);  // floor(3.95 / 0.5)
}

TEST(LatticeRanges, SegmentsGetOneStepOfSlackAndMerge)
{
  std::vector<LatticeRange> r;
  parc::SegmentsToLatticeRanges({ { 7.2, 7.3 }, { 2.1, 2.2 }, { 2.6, 2.9 } }, 0.0, 100.0, 1.0, r);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].First, 1); // floor(2.1) - 1
  EXPECT_EQ(r[0].Last, 4);  // ceil(2.9) + 1, overlapping [1, 4] merged
  EXPECT_EQ(r[1].First, 6); // floor(7.2) - 1
  EXPECT_EQ(r[1].Last, 9);  // ceil(7.3) + 1
}

TEST(LatticeRanges, AdjacentRangesMergeAndEmptySegmentsVanish)
{
  std::vector<LatticeRange> r;
  parc::SegmentsToLatticeRanges({ { 2.5, 2.5 }, { 6.5, 6.5 }, { 50.0, 40.0 }, { -9, -8 } }, 0.0,
    100.0, 1.0, r);
  ASSERT_EQ(r.size(), 1u) << "[1, 4] and [5, 8] are adjacent and merge; the others are empty";
  EXPECT_EQ(r[0].First, 1);
  EXPECT_EQ(r[0].Last, 8);
}

TEST(WholeRaySource, GivesOneUnboundedSegment)
{
  std::vector<Segment> s;
  parc::WholeRaySource().GetSegments(3, 4, parc::Ray(), s);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_TRUE(std::isinf(s[0].TNear) && s[0].TNear < 0);
  EXPECT_TRUE(std::isinf(s[0].TFar) && s[0].TFar > 0);
}
