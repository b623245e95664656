// Shadow rays (paper section 5): the transmittance of a constant slab and of an opaque
// isosurface along a shadow ray, shadows only for lights that cast them (counted), and
// bit-identical shadowed images whatever the segment sources of primary and shadow rays.
#include "parcSegmentOracle.h"
#include "parcTestUtilities.h"

#include <gtest/gtest.h>

#include <limits>

using parc::BlendMode;
using parc::CastParameters;
using parc::Vec3;
using parctest::MakeRay;

namespace
{
constexpr int Width = 40, Height = 36;
constexpr double Infinity = std::numeric_limits<double>::infinity();

/// An opaque, shaded red sphere of radius r (an isosurface of a distance field).
CastParameters SphereParameters(double r)
{
  CastParameters p;
  p.Blend = BlendMode::IsoSurface;
  p.IsoValues = { r };
  p.Opacity.SetNodes({ 0.0, 100.0 }, { 1.0, 1.0 }, true);
  p.Color.SetTable(0.0, 100.0, { 1.f, 0.f, 0.f, 1.f, 0.f, 0.f });
  p.SampleDistance = 0.5;
  p.Shade = true;
  return p;
}

/// A translucent, shaded cloud over parctest::Blobs.
CastParameters CloudParameters()
{
  CastParameters p;
  p.Opacity.SetNodes({ 0.0, 60.0, 200.0 }, { 0.0, 0.0, 0.5 }, true);
  p.Color.SetTable(0.0, 255.0, { 1.f, 0.8f, 0.2f, 0.2f, 0.6f, 1.f });
  p.SampleDistance = 0.5;
  p.Shade = true;
  return p;
}

parc::Light Directional(const Vec3& towardsLight, double shadowAttenuation = 1.0)
{
  parc::Light light;
  light.Position = towardsLight;
  light.FocalPoint = { 0, 0, 0 };
  light.ShadowAttenuation = shadowAttenuation;
  return light;
}

parc::Light Positional(const Vec3& position, double shadowAttenuation = 1.0)
{
  parc::Light light = Directional(position, shadowAttenuation);
  light.Positional = true;
  light.FocalPoint = { 16, 16, 16 };
  return light;
}

/// A volume of a scene with its own supercell classification (for the oracle).
struct Volume
{
  parc::ScalarField Field;
  CastParameters Params;
  parc::RangePyramid Pyramid;
  parc::SupercellGrid Grid;
  parc::RayCaster Caster;

  void Prepare()
  {
    this->Pyramid.Build(this->Field);
    parc::ContributionRule rule;
    rule.Set(this->Params, this->Field.GetRange());
    const double size[3] = { 2.0, 2.0, 2.0 };
    ASSERT_TRUE(this->Grid.Configure(this->Pyramid.GetCellDimensions(), size));
    this->Grid.Classify(this->Pyramid, rule, this->Params.Interp);
    ASSERT_TRUE(this->Caster.Prepare({ &this->Field, &this->Params }));
  }
};
}

// A constant slab of opacity a (sample distance = opacity unit distance, so a' = a): the
// transmittance is (1 - a) multiplied once per lattice sample t_k = k dt, k >= 1, inside
// the slab and before the light.
TEST(Shadows, ConstantSlabTransmittance)
{
  const int n[3] = { 6, 6, 11 }; // z in [0, 10]
  const parc::ScalarField slab = parctest::MakeField(n, [](int, int, int) { return 100.f; });
  CastParameters p;
  p.Opacity.SetConstant(0.05);
  p.SampleDistance = 0.5;
  p.OpacityUnitDistance = 0.5;
  parc::RayCaster caster;
  ASSERT_TRUE(caster.Prepare({ &slab, &p }));
  parc::Occluders occluders;
  occluders.SetMembers({ { &caster, {} } });
  parc::ShadowScratch scratch;
  const auto expected = [](int samples) {
    float t = 1.f;
    for (int k = 0; k < samples; ++k)
    {
      t *= 1.f - 0.05f;
    }
    return t;
  };
  // From z = -3 towards +z: t in [3, 13] holds k = 6 .. 26.
  parc::Ray ray{ { 2.5, 2.5, -3.0 }, { 0, 0, 1 }, 0.0, Infinity };
  parc::CastStatistics stats;
  EXPECT_EQ(occluders.Transmittance(ray, 0, scratch, stats), expected(21));
  EXPECT_EQ(stats.ShadowRays, 1u);
  EXPECT_EQ(stats.ShadowSamples, 21u);
  EXPECT_GT(stats.ShadowCells, 0u);
  // A light inside the slab at z = 5: k = 6 .. 16.
  ray.TMax = 8.0;
  EXPECT_EQ(occluders.Transmittance(ray, 0, scratch, stats), expected(11));
  // From inside the slab: the point itself (k = 0) is left out, k = 1 .. 10 to z = 10.
  ray = { { 2.5, 2.5, 5.0 }, { 0, 0, 1 }, 0.0, Infinity };
  EXPECT_EQ(occluders.Transmittance(ray, 0, scratch, stats), expected(10));
  // Away from the slab: nothing blocks.
  ray = { { 2.5, 2.5, -3.0 }, { 0, 0, -1 }, 0.0, Infinity };
  stats = parc::CastStatistics();
  EXPECT_EQ(occluders.Transmittance(ray, 0, scratch, stats), 1.f);
  EXPECT_EQ(stats.ShadowSamples, 0u);
}

// An opaque isosurface blocks every shadow ray that crosses it, and none that leaves the
// surface outwards from a point on it.
TEST(Shadows, OpaqueSurfaceBlocks)
{
  const parc::ScalarField sphere = parctest::DistanceField(33, { 16, 16, 16 });
  const CastParameters p = SphereParameters(6.0);
  parc::RayCaster caster;
  ASSERT_TRUE(caster.Prepare({ &sphere, &p }));
  parc::Occluders occluders;
  occluders.SetMembers({ { &caster, {} } });
  parc::ShadowScratch scratch;
  parc::CastStatistics stats;
  const auto through = [&](const Vec3& from, const Vec3& to) {
    return occluders.Transmittance(MakeRay(from, to - from), 0, scratch, stats);
  };
  EXPECT_EQ(through({ 2, 16, 16 }, { 30, 17, 15 }), 0.f);
  EXPECT_EQ(through({ 2, 16, 16 }, { 16, 30, 16 }), 1.f) << "passes beside the sphere";
  EXPECT_EQ(through({ 16, 16, 2 }, { 16, 16, 30 }), 0.f);
  // From surface points (where primary rays hit) outwards: no self-shadowing.
  for (const Vec3& direction : { Vec3{ 1, 0, 0 }, Vec3{ 0.3, -0.8, 0.5 }, Vec3{ -1, 1, 1 } })
  {
    const parc::Ray primary = MakeRay(Vec3{ 16, 16, 16 } + 30.0 * direction, -1.0 * direction);
    const parctest::CastResult hit = parctest::CastOne(sphere, p, primary);
    ASSERT_TRUE(std::isfinite(hit.FirstHit));
    const Vec3 x = primary.Origin + hit.FirstHit * primary.Direction;
    EXPECT_EQ(through(x, x + direction), 1.f);
    EXPECT_EQ(through(x, x - direction), 0.f) << "into the sphere and out again";
  }
}

// A light without shadow attenuation casts no shadow ray, and the image is that of no
// occluders at all; with it, shaded contributions behind the sphere lose the light's terms.
TEST(Shadows, OnlyLightsThatCastShadowsCastShadowRays)
{
  Volume sphere{ parctest::DistanceField(33, { 16, 16, 16 }), SphereParameters(5.0) };
  Volume cloud{ parctest::Blobs(), CloudParameters() };
  const parc::Camera view = parctest::ParallelView(Width, Height, 0.3, 22.0);
  const parc::WholeRaySource whole;
  parctest::SceneImage plain(view), off(view), on(view);
  for (parctest::SceneImage* image : { &plain, &off, &on })
  {
    const double attenuation = image == &on ? 1.0 : 0.0;
    for (Volume* v : { &sphere, &cloud })
    {
      v->Params.Lights = { Directional({ 1.0, 0.5, 0.2 }, attenuation) };
      v->Prepare();
    }
    parc::Occluders occluders;
    occluders.SetMembers({ { &sphere.Caster, {} }, { &cloud.Caster, {} } });
    if (image != &plain)
    {
      sphere.Caster.SetOccluders(&occluders);
      cloud.Caster.SetOccluders(&occluders);
    }
    *image = parctest::CastScene({ { &sphere.Caster, &whole }, { &cloud.Caster, &whole } }, view);
    sphere.Caster.SetOccluders(nullptr);
    cloud.Caster.SetOccluders(nullptr);
  }
  EXPECT_TRUE(parctest::Identical(plain, off));
  EXPECT_EQ(off.Stats.ShadowRays, 0u);
  EXPECT_EQ(off.Stats.ShadowSamples, 0u);
  EXPECT_EQ(plain.Stats.Samples, on.Stats.Samples) << "shadows do not change primary rays";
  EXPECT_GT(on.Stats.ShadowRays, 0u);
  EXPECT_LE(on.Stats.ShadowRays, on.Stats.ContributingSamples) << "one light";
  EXPECT_GT(on.Stats.ShadowSamples, on.Stats.ShadowRays);
  // Shadows only darken.
  int darker = 0;
  for (std::size_t i = 0; i < on.RGBA.size(); ++i)
  {
    EXPECT_LE(on.RGBA[i], plain.RGBA[i] + 1e-6f) << "value " << i;
    darker += on.RGBA[i] < plain.RGBA[i] - 1e-3f ? 1 : 0;
  }
  EXPECT_GT(darker, 50);
}

// Shadowed images are bit-identical whether primary and shadow rays are cast whole or
// through the exact segment oracle of each volume, for directional and positional lights
// outside, on a face of and inside the volumes, one and two at a time.
TEST(Shadows, SegmentSourcesGiveBitIdenticalShadowedImages)
{
  Volume sphere{ parctest::DistanceField(25, { 12, 12, 12 }), SphereParameters(6.0) };
  Volume cloud{ parctest::Blobs(), CloudParameters() };
  const std::vector<std::vector<parc::Light>> lightSets = {
    { Directional({ 1.0, 0.5, 0.2 }) },
    { Positional({ 16.0, 40.0, 30.0 }) },
    { Positional({ 0.0, 15.0, 14.0 }) },  // on the cloud's face x = 0
    { Positional({ 16.0, 14.0, 13.0 }) }, // inside both volumes
    { Directional({ -0.2, 1.0, 0.3 }, 0.6), Positional({ 30.0, 5.0, 20.0 }) },
  };
  const parc::WholeRaySource whole;
  for (std::size_t set = 0; set < lightSets.size(); ++set)
  {
    for (Volume* v : { &sphere, &cloud })
    {
      v->Params.Lights = lightSets[set];
      v->Prepare();
    }
    const parc::SegmentOracle sphereOracle(sphere.Grid, sphere.Caster.GetWorldToIndex());
    const parc::SegmentOracle cloudOracle(cloud.Grid, cloud.Caster.GetWorldToIndex());
    const std::size_t lights = lightSets[set].size();
    parc::Occluders wholeShadows, oracleShadows;
    wholeShadows.SetMembers({ { &sphere.Caster, {} }, { &cloud.Caster, {} } });
    oracleShadows.SetMembers({ { &sphere.Caster, std::vector<const parc::SegmentSource*>(lights, &sphereOracle) },
      { &cloud.Caster, std::vector<const parc::SegmentSource*>(lights, &cloudOracle) } });
    for (const double angle : { 0.2, 2.0 })
    {
      const parc::Camera view = parctest::ParallelView(Width, Height, angle, 22.0);
      const parctest::SceneImage reference = [&] {
        sphere.Caster.SetOccluders(&wholeShadows);
        cloud.Caster.SetOccluders(&wholeShadows);
        return parctest::CastScene({ { &sphere.Caster, &whole }, { &cloud.Caster, &whole } }, view);
      }();
      sphere.Caster.SetOccluders(&oracleShadows);
      cloud.Caster.SetOccluders(&oracleShadows);
      const parctest::SceneImage shadowsOnly =
        parctest::CastScene({ { &sphere.Caster, &whole }, { &cloud.Caster, &whole } }, view);
      const parctest::SceneImage both =
        parctest::CastScene({ { &sphere.Caster, &sphereOracle }, { &cloud.Caster, &cloudOracle } }, view);
      EXPECT_TRUE(parctest::Identical(reference, shadowsOnly)) << "lights " << set << " angle " << angle;
      EXPECT_TRUE(parctest::Identical(reference, both)) << "lights " << set << " angle " << angle;
      EXPECT_EQ(reference.Stats.ShadowRays, both.Stats.ShadowRays);
      EXPECT_GT(reference.Stats.ShadowRays, 0u);
      EXPECT_LT(shadowsOnly.Stats.ShadowSamples, reference.Stats.ShadowSamples);
      EXPECT_LT(both.Stats.Samples, reference.Stats.Samples);
    }
    sphere.Caster.SetOccluders(nullptr);
    cloud.Caster.SetOccluders(nullptr);
  }
}
