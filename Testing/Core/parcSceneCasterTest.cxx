// Several volumes cast together (SceneCaster): one volume alone is its own image, events
// merge in depth order whatever the members' order, a surface inside a cloud is right
// from both sides, and per-volume segment sources keep the image bit-identical.
#include "parcSegmentOracle.h"
#include "parcTestUtilities.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <string>

using parc::BlendMode;
using parc::CastParameters;
using parc::Vec3;
using parctest::Blobs;
using parctest::MakeRay;

namespace
{
constexpr int Width = 40, Height = 36;

/// Parallel rays over a 44 x 44 window around (16, 16, 16) (see parctest::ParallelView).
parc::Camera ParallelView(double angle)
{
  return parctest::ParallelView(Width, Height, angle, 22.0);
}

/// A translucent, shaded cloud over Blobs with a light.
CastParameters CloudParameters()
{
  CastParameters p;
  p.Opacity.SetNodes({ 0.0, 60.0, 200.0 }, { 0.0, 0.0, 0.4 }, true);
  p.Color.SetTable(0.0, 255.0, { 1.f, 0.5f, 0.f, 0.f, 0.5f, 1.f });
  p.SampleDistance = 0.5;
  p.Shade = true;
  parc::Light light;
  light.Position = { 0.0, 50.0, 50.0 };
  p.Lights = { light };
  return p;
}

/// CloudParameters, with opacity from every value above 0: the cloud fills the blobs'
/// surroundings (the scenes where other volumes sit inside it).
CastParameters DenseCloudParameters()
{
  CastParameters p = CloudParameters();
  p.Opacity.SetNodes({ 0.0, 20.0, 255.0 }, { 0.0, 0.05, 0.2 }, true);
  return p;
}

/// An opaque, shaded red isosurface of a distance field: a sphere of radius r.
CastParameters SurfaceParameters(double r)
{
  CastParameters p = CloudParameters();
  p.Blend = BlendMode::IsoSurface;
  p.IsoValues = { r };
  p.Opacity.SetNodes({ 0.0, 100.0 }, { 1.0, 1.0 }, true);
  p.Color.SetTable(0.0, 100.0, { 1.f, 0.f, 0.f, 1.f, 0.f, 0.f });
  return p;
}

/// World -> index of a volume translated by offset.
parc::Matrix4 Shifted(const Vec3& offset)
{
  return parc::Translated(parc::Matrix4(), -offset);
}

}

// A scene of one volume gives the bits of the volume's own caster, for every ray function.
TEST(SceneCaster, OneVolumeIsItsOwnImage)
{
  const parc::ScalarField field = Blobs();
  for (BlendMode mode : { BlendMode::Composite, BlendMode::IsoSurface,
         BlendMode::MaximumIntensity, BlendMode::MinimumIntensity, BlendMode::AverageIntensity,
         BlendMode::Additive, BlendMode::Slice })
  {
    CastParameters p = CloudParameters();
    p.Blend = mode;
    p.SliceOrigin = Vec3(16.0, 16.0, 16.0);
    p.SliceNormal = Vec3(0.3, 0.2, 1.0);
    p.IsoValues = { 80.0, 150.0 };
    p.AverageRange[0] = 30.0;
    p.AverageRange[1] = 220.0;
    p.Opacity.SetNodes({ 0.0, 60.0, 200.0 }, { 0.1, 0.1, 0.6 }, true);
    parc::RayCaster caster;
    ASSERT_TRUE(caster.Prepare({ &field, &p }));
    const parc::Camera view = ParallelView(0.4);
    parctest::SceneImage own(view);
    caster.CastImage(view, nullptr, parc::WholeRaySource(), own.RGBA.data(), own.Stats);
    const parc::WholeRaySource whole;
    const parctest::SceneImage scene = parctest::CastScene({ { &caster, &whole } }, view);
    EXPECT_TRUE(parctest::Identical(own, scene)) << "mode " << static_cast<int>(mode);
    EXPECT_EQ(own.Stats.Samples, scene.Stats.Samples) << "mode " << static_cast<int>(mode);
    EXPECT_GT(own.Stats.ContributingSamples, 0u);
  }
}

// A composite volume whose opacity and colour depend on the sample's value alone is cast
// in stages over each block of samples (opacities, the lanes composited before the ray
// stops, colours, shading several lanes at a time); behind a mask (here all ones, hiding
// nothing) each sample goes the whole way alone. Both give the same bits, events and counts,
// alone and in a scene, under lights from every side with odd, even and fractional
// specular powers, with quantized normals, opacity corrections by square roots, by series
// and by powers, constant and varying gradient opacity, and rays that stop early.
TEST(SceneCaster, StagedCompositingIsPerSampleCompositing)
{
  const parc::ScalarField field = Blobs();
  struct Variant
  {
    const char* Name;
    std::function<void(CastParameters&)> Apply;
  };
  auto lights = [](CastParameters& p) {
    parc::Light a, b, c;
    a.Position = { 0.0, 50.0, 50.0 };
    b.Position = { -40.0, 10.0, -30.0 }; // from behind: negative half-vector products
    b.Color = { 0.9, 0.4, 0.2 };
    b.SpecularColor = { 0.3, 0.8, 1.0 };
    c.Position = { 30.0, -60.0, 5.0 };
    p.Lights = { a, b, c };
  };
  parc::NormalVolume normals;
  normals.Build(field);
  auto quantized = [&normals](CastParameters& p) {
    p.Shading = parc::ShadingModel::QuantizedNormals;
    p.Normals = &normals;
  };
  const Variant variants[] = {
    { "unshaded", [](CastParameters& p) { p.Shade = false; } },
    { "quantized normals", quantized },
    { "quantized normals, three lights", [&](CastParameters& p) { quantized(p); lights(p); } },
    { "quantized normals, nearest", [&](CastParameters& p) {
       quantized(p);
       p.Interp = parc::Interpolation::Nearest; } },
    { "one light", [](CastParameters&) {} },
    { "three lights, power 3", [&](CastParameters& p) { lights(p); p.SpecularPower = 3.0; } },
    { "three lights, power 1", [&](CastParameters& p) { lights(p); p.SpecularPower = 1.0; } },
    { "three lights, power 7.5", [&](CastParameters& p) { lights(p); p.SpecularPower = 7.5; } },
    { "no lights", [](CastParameters& p) { p.Lights.clear(); } },
    { "quarter voxel", [](CastParameters& p) { p.SampleDistance = 0.25; } },
    { "0.7 voxel, series and power correction",
      [](CastParameters& p) { p.SampleDistance = 0.7; } },
    { "1.5 voxel, power correction", [](CastParameters& p) { p.SampleDistance = 1.5; } },
    { "unit distance", [](CastParameters& p) { p.SampleDistance = 1.0; } },
    { "opaque, rays stop", [](CastParameters& p) {
       p.Opacity.SetNodes({ 0.0, 60.0, 120.0 }, { 0.0, 0.0, 1.0 }, true); } },
    { "unshaded, rays stop", [](CastParameters& p) {
       p.Shade = false;
       p.Opacity.SetNodes({ 0.0, 60.0, 120.0 }, { 0.0, 0.0, 1.0 }, true); } },
    { "constant gradient opacity", [](CastParameters& p) {
       p.UseGradientOpacity = true;
       p.GradientOpacity.SetConstant(0.5); } },
    { "zero gradient opacity", [](CastParameters& p) {
       p.UseGradientOpacity = true;
       p.GradientOpacity.SetConstant(0.0); } },
    { "varying gradient opacity", [](CastParameters& p) {
       p.UseGradientOpacity = true;
       p.GradientOpacity.SetNodes({ 0.0, 20.0 }, { 0.2, 1.0 }, true); } },
  };
  const parc::ScalarField ones =
    parctest::MakeField(field.GetDimensions(), [](int, int, int) { return 1.f; });
  const parc::WholeRaySource whole;
  auto expectSame = [](const parctest::SceneImage& a, const parctest::SceneImage& b,
                      const std::string& what) {
    EXPECT_TRUE(parctest::Identical(a, b)) << what;
    EXPECT_EQ(a.Stats.Samples, b.Stats.Samples) << what;
    EXPECT_EQ(a.Stats.ContributingSamples, b.Stats.ContributingSamples) << what;
    EXPECT_EQ(a.Stats.GradientEvaluations, b.Stats.GradientEvaluations) << what;
  };
  for (const Variant& variant : variants)
  {
    CastParameters staged = CloudParameters();
    variant.Apply(staged);
    CastParameters masked = staged;
    masked.Mask = &ones;
    parc::RayCaster stagedCaster, maskedCaster;
    ASSERT_TRUE(stagedCaster.Prepare({ &field, &staged }));
    ASSERT_TRUE(maskedCaster.Prepare({ &field, &masked }));
    EXPECT_EQ(staged.Normals != nullptr, stagedCaster.UsesQuantizedNormals()) << variant.Name;
    for (const double angle : { 0.3, 2.0 })
    {
      const parc::Camera view = ParallelView(angle);
      const std::string what = std::string(variant.Name) + ", angle " + std::to_string(angle);
      parctest::SceneImage alone(view), aloneMasked(view);
      stagedCaster.CastImage(view, nullptr, whole, alone.RGBA.data(), alone.Stats);
      maskedCaster.CastImage(view, nullptr, whole, aloneMasked.RGBA.data(), aloneMasked.Stats);
      expectSame(alone, aloneMasked, what + ", alone");
      expectSame(parctest::CastScene({ { &stagedCaster, &whole } }, view),
        parctest::CastScene({ { &maskedCaster, &whole } }, view), what + ", in a scene");
    }
  }
}

// Two volumes one behind the other along the ray: the front one over the back one, and
// the members' order does not matter.
TEST(SceneCaster, DisjointVolumesMergeInDepthOrder)
{
  const int n[3] = { 6, 6, 11 };
  const parc::ScalarField slab = parctest::MakeField(n, [](int, int, int) { return 100.f; });
  CastParameters front, back;
  front.Opacity.SetConstant(0.05);
  front.Color.SetTable(0.0, 255.0, { 1.f, 0.f, 0.f, 1.f, 0.f, 0.f });
  front.SampleDistance = 0.25;
  back = front;
  back.Opacity.SetConstant(0.3);
  back.Color.SetTable(0.0, 255.0, { 0.f, 0.f, 1.f, 0.f, 0.f, 1.f });
  back.SliceOrigin = Vec3(0.0, 0.0, 25.0);
  back.SliceNormal = Vec3(0.0, 0.1, 1.0);
  parc::RayCaster frontCaster, backCaster;
  ASSERT_TRUE(frontCaster.Prepare({ &slab, &front, Shifted({ 0, 0, 0 }) })); // z in [0, 10]
  const parc::WholeRaySource whole;
  // The back volume composited, and as a slice (its one event at the plane).
  for (const BlendMode backBlend : { BlendMode::Composite, BlendMode::Slice })
  {
    back.Blend = backBlend;
    ASSERT_TRUE(backCaster.Prepare({ &slab, &back, Shifted({ 0, 0, 20 }) })); // z in [20, 30]
    for (const double zEye : { -10.0, 40.0 })
    {
      const parc::Ray ray = MakeRay({ 2.5, 2.5, zEye }, { 0, 0, zEye < 0 ? 1.0 : -1.0 });
      std::vector<parc::Segment> segments;
      std::vector<parc::LatticeRange> ranges;
      parc::SceneScratch scratch;
      parc::CastStatistics stats, sceneStats[2];
      float a[4], b[4], merged[4], swapped[4];
      frontCaster.CastRay(parc::RayQuery::Anywhere(ray), whole, segments, ranges, a, stats);
      backCaster.CastRay(parc::RayQuery::Anywhere(ray), whole, segments, ranges, b, stats);
      if (zEye > 0)
      {
        std::swap(a, b); // the eye is on the back volume's side
      }
      parc::SceneCaster scene;
      ASSERT_TRUE(scene.SetMembers({ { &frontCaster, &whole }, { &backCaster, &whole } }, 0.99));
      scene.CastRay(parc::RayQuery::Anywhere(ray), segments, ranges, scratch, merged, sceneStats);
      ASSERT_TRUE(scene.SetMembers({ { &backCaster, &whole }, { &frontCaster, &whole } }, 0.99));
      scene.CastRay(parc::RayQuery::Anywhere(ray), segments, ranges, scratch, swapped, sceneStats);
      EXPECT_EQ(0, std::memcmp(merged, swapped, sizeof(merged)));
      for (int c = 0; c < 4; ++c)
      {
        EXPECT_NEAR(merged[c], a[c] + (1.f - a[3]) * b[c], 1e-6) << "eye " << zEye << " c " << c;
      }
      EXPECT_GT(a[3], 0.2f);
      EXPECT_GT(b[3], 0.2f);
    }
  }
}

// An opaque sphere inside a translucent cloud, seen from both sides: the part of the cloud
// in front of the surface, over the surface's colour.
TEST(SceneCaster, SurfaceInsideACloudFromBothSides)
{
  const parc::ScalarField sphere = parctest::DistanceField(33, { 16, 16, 16 });
  const parc::ScalarField cloud = Blobs();
  CastParameters surfaceParams = SurfaceParameters(6.0);
  surfaceParams.Shade = false;
  CastParameters cloudParams = DenseCloudParameters();
  cloudParams.Shade = false;
  parc::RayCaster surface, cloudCaster;
  ASSERT_TRUE(surface.Prepare({ &sphere, &surfaceParams }));
  ASSERT_TRUE(cloudCaster.Prepare({ &cloud, &cloudParams }));
  const parc::WholeRaySource whole;
  parc::SceneCaster scene;
  ASSERT_TRUE(scene.SetMembers({ { &surface, &whole }, { &cloudCaster, &whole } }, 1.0));
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int hits = 0;
  for (int trial = 0; trial < 100; ++trial)
  {
    // From either side of the sphere, through a point near its centre.
    const Vec3 target = Vec3{ 16, 16, 16 } + 3.0 * Vec3(u(rng), u(rng), u(rng));
    const Vec3 from = target + 50.0 * parc::Normalized({ u(rng), u(rng), u(rng) });
    parc::Ray ray = MakeRay(from, target - from);
    std::vector<parc::Segment> segments;
    std::vector<parc::LatticeRange> ranges;
    parc::SceneScratch scratch;
    parc::CastStatistics stats, sceneStats[2];
    float merged[4], hitColor[4], front[4];
    double hit;
    scene.CastRay(parc::RayQuery::Anywhere(ray), segments, ranges, scratch, merged, sceneStats);
    surface.CastRay(parc::RayQuery::Anywhere(ray), whole, segments, ranges, hitColor, stats, &hit);
    ASSERT_TRUE(std::isfinite(hit)) << "trial " << trial;
    ray.TMax = hit; // the cloud in front of the surface
    cloudCaster.CastRay(parc::RayQuery::Anywhere(ray), whole, segments, ranges, front, stats);
    for (int c = 0; c < 4; ++c)
    {
      EXPECT_NEAR(merged[c], front[c] + (1.f - front[3]) * hitColor[c], 2e-6)
        << "trial " << trial << " c " << c;
    }
    hits += front[3] > 0.01f ? 1 : 0;
  }
  EXPECT_GT(hits, 50); // the cloud is in front of the surface on most rays
}

/// Casts a scene of casters (each unaccelerated, termination opacity 0.99) over view and
/// expects, pixel by pixel, the bits of the merge of every volume's whole events by (ray
/// parameter, member index), stopped where the merged opacity reaches 0.99. Returns the
/// samples the scene took of member, and in whole those its caster takes alone.
std::uint64_t ExpectMergeOfWholeEvents(const std::vector<const parc::RayCaster*>& casters,
  const parc::Camera& view, std::size_t member, std::uint64_t& whole)
{
  constexpr double Termination = 0.99;
  const parc::WholeRaySource wholeRay;
  std::vector<parc::SceneCaster::Member> members;
  for (const parc::RayCaster* caster : casters)
  {
    members.push_back({ caster, &wholeRay });
  }
  parc::SceneCaster scene;
  EXPECT_TRUE(scene.SetMembers(members, Termination));
  const std::size_t n = casters.size();
  std::uint64_t taken = 0;
  whole = 0;
  std::vector<parc::Segment> segments;
  std::vector<parc::LatticeRange> ranges;
  parc::SceneScratch sceneScratch;
  std::vector<std::vector<parc::RayEvent>> events(n);
  std::vector<parc::CastStatistics> sceneStats(n);
  for (int py = 0; py < view.Height; ++py)
  {
    for (int px = 0; px < view.Width; ++px)
    {
      const parc::RayQuery query = parc::RayQuery::AtPixel(view.MakeRay(px, py), px, py);
      float merged[4], own[4];
      sceneStats.assign(n, parc::CastStatistics());
      scene.CastRay(query, segments, ranges, sceneScratch, merged, sceneStats.data());
      taken += sceneStats[member].Samples;
      for (std::size_t v = 0; v < n; ++v)
      {
        parc::CastStatistics stats;
        events[v].clear();
        casters[v]->CastRay(query, wholeRay, segments, ranges, own, stats, nullptr, &events[v]);
        whole += v == member ? stats.Samples : 0;
      }
      parc::EventCompositor reference;
      std::vector<std::size_t> next(n, 0);
      while (reference.Below(Termination))
      {
        std::size_t best = n;
        for (std::size_t v = 0; v < n; ++v)
        {
          if (next[v] < events[v].size() &&
            (best == n || events[v][next[v]].T < events[best][next[best]].T))
          {
            best = v;
          }
        }
        if (best == n)
        {
          break;
        }
        reference.Add(events[best][next[best]++]);
      }
      float expected[4];
      reference.Finish(expected);
      EXPECT_EQ(0, std::memcmp(merged, expected, sizeof(merged)))
        << "pixel " << px << ", " << py;
    }
  }
  return taken;
}

// A volume whose own opacity stops the ray stops it for every volume: the volumes cast
// after it are cast only a little beyond, and the image is the merge of every volume's
// whole events, stopped where the merged opacity reaches the termination opacity, bit for
// bit, whatever the members' order. An opaque surface in a translucent cloud: the cloud
// behind the surface is not sampled. An opaque surface just inside a translucent one of
// another volume: the translucent crossing just before the stop is found.
TEST(SceneCaster, OpaqueVolumesStopTheOthers)
{
  const parc::ScalarField sphere = parctest::DistanceField(33, { 16, 16, 16 });
  const parc::ScalarField cloud = Blobs();
  const CastParameters opaqueParams = SurfaceParameters(10.0);
  CastParameters translucentParams = SurfaceParameters(10.2);
  translucentParams.Opacity.SetConstant(0.3);
  const CastParameters cloudParams = DenseCloudParameters();
  parc::RayCaster opaque, translucent, cloudCaster;
  ASSERT_TRUE(opaque.Prepare({ &sphere, &opaqueParams }));
  ASSERT_TRUE(translucent.Prepare({ &sphere, &translucentParams }));
  ASSERT_TRUE(cloudCaster.Prepare({ &cloud, &cloudParams }));
  const parc::Camera view = ParallelView(0.6);
  std::uint64_t whole = 0;
  for (const std::size_t cloudIndex : { 0, 1 })
  {
    std::vector<const parc::RayCaster*> casters = { &opaque };
    casters.insert(casters.begin() + cloudIndex, &cloudCaster);
    const std::uint64_t taken = ExpectMergeOfWholeEvents(casters, view, cloudIndex, whole);
    EXPECT_LT(taken, whole * 9 / 10) << "cloud " << cloudIndex;
  }
  // Both isosurfaces: cast in member order, the translucent one after the opaque one.
  const std::uint64_t taken =
    ExpectMergeOfWholeEvents({ &opaque, &translucent }, view, 1, whole);
  EXPECT_LT(taken, whole * 9 / 10);
  ExpectMergeOfWholeEvents({ &translucent, &opaque }, view, 1, whole);
}

// The last composite volume cast composites its samples with the other volumes' events in
// between (SceneCaster::Streamed): a translucent surface crossed inside a cloud, and a
// minimum-intensity volume whose one event lies at a lattice position of the cloud's own
// (the same sample distance), before or after the cloud's sample there as their member
// indices say; in every member order, the bits of the merge of every volume's events.
TEST(SceneCaster, EventsOfOtherVolumesComeBetweenACloudsSamples)
{
  const parc::ScalarField sphere = parctest::DistanceField(33, { 16, 16, 16 });
  const parc::ScalarField cloud = Blobs();
  CastParameters surfaceParams = SurfaceParameters(6.0);
  surfaceParams.Opacity.SetConstant(0.3);
  CastParameters nearestParams = CloudParameters();
  nearestParams.Blend = BlendMode::MinimumIntensity;
  nearestParams.Opacity.SetConstant(0.3);
  nearestParams.Color.SetTable(0.0, 30.0, { 0.f, 1.f, 0.f, 0.f, 1.f, 1.f });
  const CastParameters cloudParams = DenseCloudParameters();
  parc::RayCaster surface, nearest, cloudCaster;
  ASSERT_TRUE(surface.Prepare({ &sphere, &surfaceParams }));
  ASSERT_TRUE(nearest.Prepare({ &sphere, &nearestParams }));
  ASSERT_TRUE(cloudCaster.Prepare({ &cloud, &cloudParams }));
  std::vector<const parc::RayCaster*> casters = { &cloudCaster, &nearest, &surface };
  std::sort(casters.begin(), casters.end());
  do
  {
    const std::size_t cloudIndex =
      std::find(casters.begin(), casters.end(), &cloudCaster) - casters.begin();
    for (const double angle : { 0.0, 0.9 })
    {
      std::uint64_t whole = 0;
      const std::uint64_t taken =
        ExpectMergeOfWholeEvents(casters, ParallelView(angle), cloudIndex, whole);
      EXPECT_GT(taken, 0u);
    }
  } while (std::next_permutation(casters.begin(), casters.end()));
}

// Each volume through its own exact segment source (the oracle of its own supercells, at
// its own transform), in overlapping scenes: bit-identical to unaccelerated casting.
TEST(SceneCaster, PerVolumeSourcesGiveBitIdenticalImages)
{
  const parc::ScalarField sphere = parctest::DistanceField(25, { 12, 12, 12 });
  const parc::ScalarField cloud = Blobs();
  struct Volume
  {
    const parc::ScalarField* Field;
    CastParameters Params;
    parc::Matrix4 WorldToIndex;
    parc::RangePyramid Pyramid;
    parc::SupercellGrid Grid;
    parc::RayCaster Caster;
  };
  for (const Vec3& offset : { Vec3{ 4, 3, 2 }, Vec3{ 30, 0, 0 }, Vec3{ -2, -1, 0 } })
  {
    Volume volumes[2];
    volumes[0].Field = &cloud;
    volumes[0].Params = CloudParameters();
    volumes[1].Field = &sphere;
    volumes[1].Params = SurfaceParameters(7.0);
    volumes[1].WorldToIndex = Shifted(offset); // partial, no or full overlap
    for (Volume& v : volumes)
    {
      v.Pyramid.Build(*v.Field);
      parc::ContributionRule rule;
      rule.Set(v.Params, v.Field->GetRange());
      const double size[3] = { 2.0, 2.0, 2.0 };
      ASSERT_TRUE(v.Grid.Configure(v.Pyramid.GetCellDimensions(), size));
      v.Grid.Classify(v.Pyramid, rule, v.Params.Interp);
      ASSERT_TRUE(v.Caster.Prepare({ v.Field, &v.Params, v.WorldToIndex }));
    }
    const parc::WholeRaySource whole;
    const parc::SegmentOracle oracle0(volumes[0].Grid, volumes[0].WorldToIndex);
    const parc::SegmentOracle oracle1(volumes[1].Grid, volumes[1].WorldToIndex);
    for (const double angle : { 0.0, 0.7, 2.5 })
    {
      const parc::Camera view = ParallelView(angle);
      const parctest::SceneImage reference =
        parctest::CastScene({ { &volumes[0].Caster, &whole }, { &volumes[1].Caster, &whole } }, view);
      const parctest::SceneImage accelerated =
        parctest::CastScene({ { &volumes[0].Caster, &oracle0 }, { &volumes[1].Caster, &oracle1 } }, view);
      const parctest::SceneImage mixed =
        parctest::CastScene({ { &volumes[0].Caster, &whole }, { &volumes[1].Caster, &oracle1 } }, view);
      EXPECT_TRUE(parctest::Identical(reference, accelerated)) << "angle " << angle;
      EXPECT_TRUE(parctest::Identical(reference, mixed)) << "angle " << angle;
      EXPECT_LT(accelerated.Stats.Samples, reference.Stats.Samples);
      EXPECT_GT(reference.Stats.ContributingSamples, 0u);
    }
  }
}
