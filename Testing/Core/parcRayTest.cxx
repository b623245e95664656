// Ray-box clipping, clipping planes, cropping and the conversion of segments to lattice
// ranges.
#include "parcRay.h"
#include "parcSegmentSource.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <vector>

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
  parc::WholeRaySource().Segments(parc::RayQuery::AtPixel(parc::Ray(), 3, 4), s);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_TRUE(std::isinf(s[0].TNear) && s[0].TNear < 0);
  EXPECT_TRUE(std::isinf(s[0].TFar) && s[0].TFar > 0);
}

// Clipping planes keep the side the normal points to; a ray parallel to a plane is kept or
// dropped whole.
TEST(ClipToPlanes, KeepsTheSideTheNormalPointsTo)
{
  parc::Ray ray;
  ray.Origin = { 0, 0, 0 };
  ray.Direction = { 1, 0, 0 };
  double t0 = 0, t1 = 10;
  const std::vector<parc::ClipPlane> planes = { { { 3, 0, 0 }, { 1, 0, 0 } },
    { { 7, 0, 0 }, { -2, 0, 0 } } };
  ASSERT_TRUE(parc::ClipToPlanes(ray, planes, t0, t1));
  EXPECT_DOUBLE_EQ(t0, 3.0);
  EXPECT_DOUBLE_EQ(t1, 7.0);
  const std::vector<parc::ClipPlane> parallelOut = { { { 0, 1, 0 }, { 0, 1, 0 } } };
  t0 = 0, t1 = 10;
  EXPECT_FALSE(parc::ClipToPlanes(ray, parallelOut, t0, t1));
  const std::vector<parc::ClipPlane> parallelIn = { { { 0, -1, 0 }, { 0, 1, 0 } } };
  t0 = 0, t1 = 10;
  EXPECT_TRUE(parc::ClipToPlanes(ray, parallelIn, t0, t1));
  EXPECT_EQ(t1, 10.0);
}

// Cropped intervals and their lattice samples against a brute-force test of every lattice
// sample's region, on random rays and region sets.
TEST(Cropping, IntervalsHoldExactlyTheSamplesOfRenderedRegions)
{
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  parc::Cropping crop;
  crop.Enabled = true;
  const double planes[6] = { 2.5, 6.0, 1.0, 7.5, 3.0, 4.0 };
  std::copy_n(planes, 6, crop.Planes);
  const double dt = 0.37;
  for (int trial = 0; trial < 300; ++trial)
  {
    crop.RegionFlags = static_cast<int>(rng() & ((1u << 27) - 1));
    const parc::Vec3 o(5 + 6 * u(rng), 5 + 6 * u(rng), 5 + 6 * u(rng));
    const parc::Vec3 d = parc::Normalized({ u(rng), u(rng), trial % 7 == 0 ? 0.0 : u(rng) });
    std::vector<parc::Segment> intervals;
    parc::CroppedIntervals(o, d, crop, -2.0, 25.0, intervals);
    std::vector<parc::LatticeRange> ranges = { { -10, 20 }, { 30, 80 } };
    parc::IntersectLatticeRanges(ranges, intervals, dt);
    std::set<long> kept;
    for (const parc::LatticeRange& r : ranges)
    {
      for (long k = r.First; k <= r.Last; ++k)
      {
        kept.insert(k);
      }
    }
    for (long k = -10; k <= 80; ++k)
    {
      const double t = k * dt;
      bool inRanges = (k <= 20 || k >= 30) && t >= -2.0 && t <= 25.0;
      int region = 0;
      for (int a = 2; a >= 0; --a)
      {
        const double x = o[a] + t * d[a];
        region = 3 * region + (x < planes[2 * a] ? 0 : (x <= planes[2 * a + 1] ? 1 : 2));
      }
      // Samples on a cropping plane may fall on either side: only check the others.
      bool onPlane = false;
      for (int a = 0; a < 3; ++a)
      {
        for (int side = 0; side < 2; ++side)
        {
          onPlane = onPlane || std::fabs(o[a] + t * d[a] - planes[2 * a + side]) < 1e-9;
        }
      }
      if (!onPlane)
      {
        EXPECT_EQ(kept.count(k) == 1, inRanges && ((crop.RegionFlags >> region) & 1))
          << "trial " << trial << ", k " << k;
      }
    }
  }
}
