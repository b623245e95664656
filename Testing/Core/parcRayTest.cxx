// Ray-box clipping, clipping planes, cropping and the conversion of segments to lattice
// ranges.
#include "parcLightFrusta.h"
#include "parcRay.h"
#include "parcSegmentSource.h"
#include "parcTestUtilities.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
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

namespace
{
/// Whether any pixel ray of view, within its [TMin, TMax], meets the box [lo, hi].
bool AnyRayMeets(const parc::Camera& view, const Vec3& lo, const Vec3& hi)
{
  for (int py = 0; py < view.Height; ++py)
  {
    for (int px = 0; px < view.Width; ++px)
    {
      const parc::Ray ray = view.MakeRay(px, py);
      double t0 = ray.TMin, t1 = ray.TMax;
      if (parc::ClipToBox(ray.Origin, ray.Direction, lo, hi, t0, t1))
      {
        return true;
      }
    }
  }
  return false;
}

/// Random boxes around and across the view; a box MayMeetBox rejects meets no ray, and
/// boxes that rays meet are never rejected (the test fails if it rejects nothing).
void CheckMayMeetBox(const parc::Camera& view, const Vec3& centre, double spread)
{
  std::mt19937 random(7);
  std::uniform_real_distribution<double> position(-spread, spread), size(0.1, 0.3 * spread);
  int rejected = 0, met = 0;
  for (int trial = 0; trial < 400; ++trial)
  {
    const Vec3 lo = centre + Vec3{ position(random), position(random), position(random) };
    const Vec3 hi = lo + Vec3{ size(random), size(random), size(random) };
    // The box as index space of a scaled and shifted transform, to test the mapping too.
    parc::Matrix4 toWorld;
    toWorld(0, 0) = toWorld(1, 1) = toWorld(2, 2) = 2.0;
    toWorld(0, 3) = lo.X;
    toWorld(1, 3) = lo.Y;
    toWorld(2, 3) = lo.Z;
    const bool may = view.MayMeetBox(toWorld, Vec3{ 0, 0, 0 }, 0.5 * (hi - lo));
    const bool meets = AnyRayMeets(view, lo, hi);
    EXPECT_TRUE(may || !meets) << "trial " << trial;
    rejected += !may;
    met += meets;
  }
  EXPECT_GT(rejected, 40);
  EXPECT_GT(met, 40);
}
}

TEST(Camera, MayMeetBoxRejectsOnlyBoxesNoRayMeetsParallel)
{
  const parc::Camera view = parctest::ParallelView(24, 20, 0.4, 10.0);
  CheckMayMeetBox(view, Vec3{ 16, 16, 16 }, 30.0);
  // In front of the camera, inside the window: seen; behind the eye plane and beyond the
  // far plane: not.
  parc::Matrix4 identity;
  EXPECT_TRUE(view.MayMeetBox(identity, Vec3{ 15, 15, 15 }, Vec3{ 17, 17, 17 }));
  const Vec3 behind = view.Eye - 100.0 * view.Direction;
  EXPECT_FALSE(view.MayMeetBox(identity, behind - Vec3{ 1, 1, 1 }, behind + Vec3{ 1, 1, 1 }));
  const Vec3 beyond = view.Eye + (view.FarDistance + 200.0) * view.Direction;
  EXPECT_FALSE(view.MayMeetBox(identity, beyond - Vec3{ 1, 1, 1 }, beyond + Vec3{ 1, 1, 1 }));
}

TEST(Camera, MayMeetBoxRejectsOnlyBoxesNoRayMeetsPerspective)
{
  // A light's frustum: a perspective camera from the light over a box.
  parc::Light light;
  light.Positional = true;
  light.Position = Vec3{ -30, 10, 5 };
  light.FocalPoint = Vec3{ 10, 10, 10 };
  std::vector<Vec3> corners;
  for (int c = 0; c < 8; ++c)
  {
    corners.push_back(Vec3{ c & 1 ? 20.0 : 0.0, c & 2 ? 20.0 : 0.0, c & 4 ? 20.0 : 0.0 } - light.Position);
  }
  parc::Light relative = light;
  relative.Position = Vec3{ 0, 0, 0 };
  relative.FocalPoint = light.FocalPoint - light.Position;
  const std::vector<parc::Camera> cameras = parc::LightCameras(relative, corners, 24);
  ASSERT_EQ(cameras.size(), 1u);
  CheckMayMeetBox(cameras[0], Vec3{ 35, 0, 5 }, 40.0);
  // Behind the eye (the light) the side planes reject a box.
  parc::Matrix4 identity;
  EXPECT_FALSE(cameras[0].MayMeetBox(identity, Vec3{ -30, -2, -2 }, Vec3{ -20, 2, 2 }));
  EXPECT_TRUE(cameras[0].MayMeetBox(identity, corners[0], corners[7]));
}

// PixelStepAt leads from a point on a pixel's ray to the point at the same depth on the
// ray of the pixel to its right.
TEST(Camera, PixelStepAtReachesTheNeighbouringRay)
{
  parc::Light light;
  light.Positional = true;
  light.Position = Vec3{ 0, 0, 0 };
  light.FocalPoint = Vec3{ 40, 0, 5 };
  std::vector<Vec3> corners;
  for (int c = 0; c < 8; ++c)
  {
    corners.push_back(Vec3{ c & 1 ? 50.0 : 30.0, c & 2 ? 10.0 : -10.0, c & 4 ? 20.0 : -10.0 });
  }
  const std::vector<parc::Camera> perspective = parc::LightCameras(light, corners, 24);
  ASSERT_EQ(perspective.size(), 1u);
  for (const parc::Camera& view : { parctest::ParallelView(24, 20, 0.4, 10.0), perspective[0] })
  {
    const parc::Ray ray = view.MakeRay(7, 5), right = view.MakeRay(8, 5);
    std::vector<double> lengths;
    for (const double f : { 0.25, 0.5 })
    {
      const Vec3 x = ray.Origin + (ray.TMin + f * (ray.TMax - ray.TMin)) * ray.Direction;
      const Vec3 step = view.PixelStepAt(x);
      const Vec3 y = x + step;
      const Vec3 fromRight = y - right.Origin;
      const Vec3 offRay = fromRight - Dot(fromRight, right.Direction) * right.Direction;
      EXPECT_LT(Length(offRay), 1e-9 * Length(x)) << (view.Parallel ? "parallel" : "perspective");
      EXPECT_NEAR(Dot(step, view.Direction), 0.0, 1e-9 * Length(step));
      lengths.push_back(Length(step));
    }
    if (view.Parallel)
    {
      EXPECT_NEAR(lengths[0], 20.0 / 24, 1e-12); // 2 halfWidth / width
      EXPECT_NEAR(lengths[1], 20.0 / 24, 1e-12);
    }
    else
    {
      EXPECT_GT(lengths[1], lengths[0]); // farther from the eye, farther apart
    }
  }
}

TEST(Ray, LatticeSampleCountCountsTheSamplesOfAnInterval)
{
  EXPECT_EQ(parc::LatticeSampleCount(0.3, 2.0, 0.5), 4); // 0.5, 1, 1.5, 2
  EXPECT_EQ(parc::LatticeSampleCount(-1.0, 1.0, 0.5), 5);
  EXPECT_EQ(parc::LatticeSampleCount(0.6, 0.9, 0.5), 0);
  EXPECT_EQ(parc::LatticeSampleCount(2.0, 1.0, 0.5), 0);
}

// The bit counts and positions the caster's lane masks rely on, against bit-by-bit loops.
TEST(BitOperations, PopCountAndTrailingZerosMatchBitLoops)
{
  std::mt19937 rng(31);
  for (int trial = 0; trial < 20000; ++trial)
  {
    // Sparse and dense masks, and the extremes.
    std::uint32_t x = trial == 0 ? 0u : (trial == 1 ? ~0u : static_cast<std::uint32_t>(rng()));
    if (trial % 3 == 2)
    {
      x &= static_cast<std::uint32_t>(rng());
    }
    int count = 0, lowest = -1;
    for (int b = 31; b >= 0; --b)
    {
      if ((x >> b) & 1u)
      {
        ++count;
        lowest = b;
      }
    }
    ASSERT_EQ(parc::PopCount(x), count) << x;
    if (x != 0)
    {
      ASSERT_EQ(parc::CountTrailingZeros(x), lowest) << x;
    }
  }
}

#if defined(__SSE2__)
// The opacity correction's power against std::pow in double: the corrected opacity
// 1 - x^e to float precision, every lane alike, and exact where no correction is due.
TEST(LaneMath, PowOfUnitIntervalMatchesThePower)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.f, 1.f);
  for (const double exponent : { 1e-3, 1.0 / 12.0, 1.0 / 6.0, 0.3, 0.7, 0.99, 1.5, 3.0, 10.0 })
  {
    const auto e = static_cast<float>(exponent);
    for (int trial = 0; trial < 200000; ++trial)
    {
      // Opacities from 0 up, small ones (1 - a rounds) and ones near 1 (tiny powers).
      std::array<float, 4> a;
      for (float& v : a)
      {
        v = uniform(rng);
        v = trial % 3 == 0 ? v * v * v * v : (trial % 3 == 1 ? 1.f - v * v * v * v : v);
        v = std::min(v, std::nextafter(1.f, 0.f));
      }
      alignas(16) float x[4], power[4];
      for (int j = 0; j < 4; ++j)
      {
        x[j] = 1.f - a[j];
      }
      _mm_store_ps(power, parc::PowOfUnitInterval(_mm_load_ps(x), _mm_set1_ps(e)));
      for (int j = 0; j < 4; ++j)
      {
        const double reference = std::pow(static_cast<double>(x[j]), static_cast<double>(e));
        ASSERT_NEAR(1.f - power[j], 1.0 - reference, 1.2e-7) << x[j] << "^" << e;
        if (reference > std::ldexp(1.0, -24))
        {
          ASSERT_NEAR(power[j] / reference, 1.0, 2e-6) << x[j] << "^" << e;
        }
        const float alone =
          _mm_cvtss_f32(parc::PowOfUnitInterval(_mm_set1_ps(x[j]), _mm_set1_ps(e)));
        ASSERT_EQ(alone, power[j]) << "lane " << j << " alone and in a block";
      }
    }
    EXPECT_EQ(_mm_cvtss_f32(parc::PowOfUnitInterval(_mm_set1_ps(1.f), _mm_set1_ps(e))), 1.f);
  }
  EXPECT_EQ(_mm_cvtss_f32(parc::PowOfUnitInterval(_mm_set1_ps(0.3f), _mm_set1_ps(0.f))), 1.f);
  EXPECT_GT(_mm_cvtss_f32(parc::PowOfUnitInterval(_mm_set1_ps(1e-30f), _mm_set1_ps(10.f))), 0.f)
    << "below 2^-126 taken as 2^-126, never a denormal or an infinite exponent";
}
#endif
