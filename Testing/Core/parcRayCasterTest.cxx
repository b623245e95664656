// The ray caster: analytic ground truths, each ray function, shading, lattice invariance and
// thread invariance.
#include "parcNormalVolume.h"
#include "parcSegmentOracle.h"
#include "parcTestUtilities.h"

#include <vtkSMPTools.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

using parc::BlendMode;
using parc::CastParameters;
using parc::Vec3;
using parctest::CastOne;
using parctest::Blobs;
using parctest::MakeRay;
using parctest::ParallelView;

namespace
{
const int SlabDims[3] = { 4, 4, 101 };

parc::ScalarField ConstantSlab(float value)
{
  return parctest::MakeField(SlabDims, [value](int, int, int) { return value; });
}

/// Constant opacity a per unit distance, white, dt = 1/8, no early termination.
CastParameters SlabParameters(double a)
{
  CastParameters p;
  parctest::SetOpacity(p, { 0.0, 255.0 }, { a, a });
  p.SampleDistance = 0.125;
  p.TerminationOpacity = 1.0;
  return p;
}

/// The ray along +z through the middle of the slab, entering it at t = 10.
parc::Ray SlabRay()
{
  return MakeRay({ 1.5, 1.5, -10.0 }, { 0, 0, 1 });
}

/// Random uint8-like values in an 8^3 volume (fixed seed).
parc::ScalarField RandomCube(unsigned seed)
{
  std::mt19937 rng(seed);
  const int n[3] = { 8, 8, 8 };
  return parctest::MakeField(n, [&](int, int, int) { return static_cast<float>(rng() % 256); });
}
}

// Beer-Lambert: a constant opacity a per unit length over a slab of length L gives
// 1 - exp(-sigma L) with sigma = -ln(1 - a). Sampling every dt adds at most one extra
// sample (dt of extra length): tolerance 2e-3 (sigma dt = 1.3e-3, plus float accumulation).
TEST(RayCaster, ConstantSlabFollowsBeerLambert)
{
  const parc::ScalarField field = ConstantSlab(100.f);
  const auto r = CastOne(field, SlabParameters(0.01), SlabRay());
  const double sigma = -std::log(1.0 - 0.01);
  const double expected = 1.0 - std::exp(-sigma * 100.0);
  EXPECT_NEAR(r.RGBA[3], expected, 2e-3);
  EXPECT_EQ(r.Stats.Samples, 801u) << "samples at z = 0, 0.125, ..., 100";
  EXPECT_NEAR(r.FirstHit, 10.0, 1e-12);
}

// The eye on the volume's boundary and inside it: rays start at the eye (t = 0).
TEST(RayCaster, EyeOnTheBoundaryAndInside)
{
  const parc::ScalarField field = ConstantSlab(100.f);
  const CastParameters p = SlabParameters(0.01);
  const auto onFace = CastOne(field, p, MakeRay({ 1.5, 1.5, 0.0 }, { 0, 0, 1 }));
  EXPECT_EQ(onFace.Stats.Samples, 801u) << "samples at t = 0, 0.125, ..., 100";
  EXPECT_EQ(onFace.FirstHit, 0.0);
  const auto inside = CastOne(field, p, MakeRay({ 1.5, 1.5, 50.0 }, { 0, 0, 1 }));
  EXPECT_EQ(inside.Stats.Samples, 401u) << "samples from the eye at z = 50 to z = 100";
  EXPECT_NEAR(inside.RGBA[3], 1.0 - std::pow(0.99, 50.125), 1e-4);
}

TEST(RayCaster, OpacityUnitDistanceScalesTheOpacity)
{
  const parc::ScalarField field = ConstantSlab(100.f);
  CastParameters p = SlabParameters(0.01);
  p.OpacityUnitDistance = 2.0; // half the density
  const auto r = CastOne(field, p, SlabRay());
  EXPECT_NEAR(r.RGBA[3], 1.0 - std::exp(std::log(0.99) * 50.0), 2e-3);
}

TEST(RayCaster, EarlyTerminationStopsAtTheThreshold)
{
  const parc::ScalarField field = ConstantSlab(100.f);
  CastParameters p = SlabParameters(0.2);
  p.TerminationOpacity = 0.5;
  const auto r = CastOne(field, p, SlabRay());
  EXPECT_GE(r.RGBA[3], 0.5f);
  EXPECT_LT(r.RGBA[3], 0.53f);
  EXPECT_LT(r.Stats.Samples, 40u);
}

// A sphere of radius R in a distance field: the isosurface crossing found between lattice
// samples (linear interpolation, then two regula-falsi steps on the trilinear field) lies
// within 0.03 voxel of the true sphere (trilinear interpolation of |p| errs by about
// h^2 / (8 R) per axis).
TEST(RayCaster, IsosurfaceOfASphereDistanceField)
{
  const int n[3] = { 65, 65, 65 };
  const Vec3 c{ 32.0, 32.0, 32.0 };
  const double radius = 20.0;
  const parc::ScalarField field = parctest::MakeField(n, [&](int i, int j, int k) {
    return static_cast<float>(Length(Vec3(i, j, k) - c));
  });
  CastParameters p;
  parctest::SetOpacity(p, { 0.0, 100.0 }, { 1.0, 1.0 });
  p.Blend = BlendMode::IsoSurface;
  p.IsoValues = { radius };
  p.SampleDistance = 0.5;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial)
  {
    const Vec3 from = c + 60.0 * parc::Normalized({ u(rng), u(rng), u(rng) });
    const Vec3 target = c + 8.0 * Vec3(u(rng), u(rng), u(rng));
    const parc::Ray ray = MakeRay(from, target - from);
    const auto r = CastOne(field, p, ray);
    ASSERT_TRUE(std::isfinite(r.FirstHit)) << "trial " << trial;
    const Vec3 hit = ray.Origin + r.FirstHit * ray.Direction;
    EXPECT_NEAR(Length(hit - c), radius, 0.03) << "trial " << trial;
    EXPECT_FLOAT_EQ(r.RGBA[3], 1.f);
  }
}

// An iso value that no float holds (0.7) between a region of exactly the float below it
// and one above it: the crossing is found wherever it falls in a block of samples, in
// both directions, with one iso value and with more than the caster counts lane by lane.
TEST(RayCaster, IsosurfaceBetweenTwoFloatsIsFound)
{
  const float below = static_cast<float>(0.7); // rounds down
  ASSERT_LT(static_cast<double>(below), 0.7);
  const int n[3] = { 40, 4, 4 };
  const parc::ScalarField field =
    parctest::MakeField(n, [below](int i, int, int) { return i < 20 ? below : 1.f; });
  CastParameters p;
  parctest::SetOpacity(p, { 0.0, 100.0 }, { 1.0, 1.0 });
  p.Blend = BlendMode::IsoSurface;
  p.SampleDistance = 0.5;
  for (const std::size_t count : { 1, 9 })
  {
    p.IsoValues = { 0.7 };
    for (std::size_t i = 1; i < count; ++i)
    {
      p.IsoValues.push_back(2.0 + i); // never crossed
    }
    for (int shift = 0; shift < 32; ++shift) // the crossing in every lane of a block
    {
      for (const double direction : { 1.0, -1.0 })
      {
        const double x0 = direction > 0 ? -5.0 - 0.5 * shift : 44.0 + 0.5 * shift;
        const parc::Ray ray = MakeRay({ x0, 1.5, 1.5 }, { direction, 0, 0 });
        const auto r = CastOne(field, p, ray);
        ASSERT_TRUE(std::isfinite(r.FirstHit))
          << count << " values, shift " << shift << ", direction " << direction;
        EXPECT_NEAR(x0 + direction * r.FirstHit, 19.0, 0.01);
        EXPECT_FLOAT_EQ(r.RGBA[3], 1.f);
      }
    }
  }
}

TEST(RayCaster, IsosurfaceMissedRayIsTransparent)
{
  const int n[3] = { 33, 33, 33 };
  const parc::ScalarField field = parctest::MakeField(n, [](int i, int j, int k) {
    return static_cast<float>(Length(Vec3(i - 16.0, j - 16.0, k - 16.0)));
  });
  CastParameters p;
  parctest::SetOpacity(p, { 0.0, 100.0 }, { 1.0, 1.0 });
  p.Blend = BlendMode::IsoSurface;
  p.IsoValues = { 5.0 };
  const auto r = CastOne(field, p, MakeRay({ -10.0, 28.0, 16.0 }, { 1, 0, 0 }));
  EXPECT_EQ(r.RGBA[3], 0.f);
  EXPECT_TRUE(std::isinf(r.FirstHit));
}

TEST(RayCaster, MaximumAndMinimumIntensityAlongAGridLine)
{
  const parc::ScalarField field = RandomCube(11);
  CastParameters p;
  parctest::SetOpacity(p, { 0.0, 255.0 }, { 0.0, 1.0 });
  p.Interp = parc::Interpolation::Nearest;
  p.SampleDistance = 0.25;
  float hi = 0.f, lo = 255.f;
  for (int i = 0; i < 8; ++i)
  {
    hi = std::max(hi, field.GetValue(i, 3, 5));
    lo = std::min(lo, field.GetValue(i, 3, 5));
  }
  p.Blend = BlendMode::MaximumIntensity;
  auto r = CastOne(field, p, MakeRay({ -3.0, 3.0, 5.0 }, { 1, 0, 0 }));
  EXPECT_FLOAT_EQ(r.RGBA[3], hi / 255.f);
  EXPECT_FLOAT_EQ(r.RGBA[0], hi / 255.f) << "white, premultiplied";
  p.Blend = BlendMode::MinimumIntensity;
  r = CastOne(field, p, MakeRay({ -3.0, 3.0, 5.0 }, { 1, 0, 0 }));
  EXPECT_FLOAT_EQ(r.RGBA[3], lo / 255.f);
}

TEST(RayCaster, AverageIntensityCountsOnlyItsRange)
{
  // VTK's meaning: the mean over the samples in the range of value (normalised to the
  // intensity range) times opacity, as an opaque grey. The opacity is not corrected for
  // the sample distance (VTK's GPU mapper takes it as it is).
  const parc::ScalarField field = RandomCube(12);
  CastParameters p;
  parctest::SetOpacity(p, { 0.0, 255.0 }, { 0.0, 1.0 });
  p.Interp = parc::Interpolation::Nearest;
  p.SampleDistance = 1.0; // samples exactly on the voxels x = 0..7
  p.OpacityUnitDistance = 2.0; // would change every opacity if it were corrected
  p.Blend = BlendMode::AverageIntensity;
  p.AverageRange[0] = 100.0;
  p.AverageRange[1] = 255.0;
  p.IntensityRange[0] = 0.0;
  p.IntensityRange[1] = 255.0;
  double sum = 0.0;
  int count = 0;
  for (int i = 0; i < 8; ++i)
  {
    const float v = field.GetValue(i, 2, 6);
    if (v >= 100.f)
    {
      sum += (v / 255.0) * (v / 255.0); // opacity v / 255
      ++count;
    }
  }
  ASSERT_GT(count, 0);
  const auto r = CastOne(field, p, MakeRay({ -3.0, 2.0, 6.0 }, { 1, 0, 0 }));
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(r.RGBA[c], sum / count, 1e-6) << "grey";
  }
  EXPECT_EQ(r.RGBA[3], 1.f);
  EXPECT_EQ(r.Stats.ContributingSamples, static_cast<unsigned>(count));
  p.AverageRange[0] = 300.0; // no sample in the range: nothing
  const auto none = CastOne(field, p, MakeRay({ -3.0, 2.0, 6.0 }, { 1, 0, 0 }));
  EXPECT_EQ(none.RGBA[3], 0.f);
  EXPECT_EQ(none.RGBA[0], 0.f);
}

TEST(RayCaster, AdditiveSumsIntensityTimesScaledOpacity)
{
  // 801 samples of value 100 in [0, 200]: each adds 0.5 times its opacity times dt / unit
  // distance (VTK's GPU mapper scales the opacity of additive blending linearly).
  const parc::ScalarField field = ConstantSlab(100.f);
  CastParameters p = SlabParameters(0.01);
  p.Blend = BlendMode::Additive;
  p.IntensityRange[0] = 0.0;
  p.IntensityRange[1] = 200.0;
  auto r = CastOne(field, p, SlabRay());
  const double perSample = 0.01 * 0.125; // 1 - 0.99^0.125 would be 0.4% more
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(r.RGBA[c], 801 * 0.5 * perSample, 1e-4) << "grey";
  }
  EXPECT_EQ(r.RGBA[3], 1.f);
  p = SlabParameters(0.5); // the sum goes past 1: clamped
  p.Blend = BlendMode::Additive;
  p.IntensityRange[1] = 200.0;
  r = CastOne(field, p, SlabRay());
  EXPECT_EQ(r.RGBA[0], 1.f);
  p = SlabParameters(0.0); // no opacity anywhere: opaque black, as VTK draws it
  p.Blend = BlendMode::Additive;
  r = CastOne(field, p, SlabRay());
  EXPECT_EQ(r.RGBA[0], 0.f);
  EXPECT_EQ(r.RGBA[3], 1.f);
}

TEST(RayCaster, BinaryMaskConfinesTheSamples)
{
  // The slab along z behind a mask: all ones changes nothing, all zeros hides everything,
  // ones up to k = 50 leave about the first half.
  const parc::ScalarField field = ConstantSlab(100.f);
  CastParameters p = SlabParameters(0.01);
  const auto open = CastOne(field, p, SlabRay());
  auto maskOf = [](int lastInside) {
    return parctest::MakeField(
      SlabDims, [lastInside](int, int, int k) { return k <= lastInside ? 255.f : 0.f; });
  };
  const parc::ScalarField ones = maskOf(100), zeros = maskOf(-1), half = maskOf(50);
  p.Mask = &ones;
  const auto all = CastOne(field, p, SlabRay());
  EXPECT_EQ(std::memcmp(all.RGBA, open.RGBA, sizeof(all.RGBA)), 0);
  p.Mask = &zeros;
  const auto none = CastOne(field, p, SlabRay());
  EXPECT_EQ(none.RGBA[3], 0.f);
  EXPECT_EQ(none.Stats.ContributingSamples, 0u);
  p.Mask = &half;
  const auto front = CastOne(field, p, SlabRay());
  const double sigma = -std::log(1.0 - 0.01);
  EXPECT_NEAR(front.RGBA[3], 1.0 - std::exp(-sigma * 50.5), 2e-3) << "up to z = 50.5";
  p.Blend = BlendMode::MaximumIntensity;
  parc::RayCaster caster;
  EXPECT_FALSE(caster.Prepare({ &field, &p })) << "masks apply to compositing ray functions";
  p.Blend = BlendMode::Composite;
  EXPECT_TRUE(caster.Prepare({ &field, &p }));
  const int shorter[3] = { 4, 4, 100 };
  const parc::ScalarField other = parctest::MakeField(shorter, [](int, int, int) { return 1.f; });
  p.Mask = &other;
  EXPECT_FALSE(caster.Prepare({ &field, &p })) << "a mask of other dimensions";
}

// A label map: samples whose nearest mask voxel has a label with functions take
// (1 - f) times the default opacity and colour plus f times the label's; the others keep
// the default ones. The slab along z: label 0 before k = 50, label 1 (red, denser) after.
TEST(RayCaster, LabelMapBlendsTheLabelsFunctions)
{
  const parc::ScalarField field = ConstantSlab(100.f);
  const parc::ScalarField labels =
    parctest::MakeField(SlabDims, [](int, int, int k) { return k >= 50 ? 1.f : 0.f; });
  CastParameters p = SlabParameters(0.01);
  parc::LabelFunctions red;
  red.Label = 1;
  red.Opacity.SetNodes({ 0.0, 255.0 }, { 0.05, 0.05 }, true);
  red.Color.SetTable(0.0, 255.0, { 1.f, 0.f, 0.f, 1.f, 0.f, 0.f });
  p.Mask = &labels;
  p.Labels = { red };
  for (const float f : { 1.f, 0.25f })
  {
    p.MaskBlendFactor = f;
    const auto r = CastOne(field, p, SlabRay());
    // 396 samples at z = 0 .. 49.375 (nearest voxel k <= 49), 405 at z = 49.5 .. 100.
    const double a0 = 1.0 - std::pow(1.0 - 0.01, 0.125);
    const double a1 = 1.0 - std::pow(1.0 - ((1.0 - f) * 0.01 + f * 0.05), 0.125);
    const double front = 1.0 - std::pow(1.0 - a0, 396.0);
    const double back = (1.0 - front) * (1.0 - std::pow(1.0 - a1, 405.0));
    EXPECT_NEAR(r.RGBA[3], front + back, 1e-4) << "f " << f;
    EXPECT_NEAR(r.RGBA[0], front + back, 1e-4) << "red in both parts";
    EXPECT_NEAR(r.RGBA[1], front + (1.0 - f) * back, 1e-4) << "green of the default only";
    EXPECT_EQ(r.Stats.ContributingSamples, 801u);
  }
  // Label 0, and a label without functions, keep the default functions.
  p.Labels[0].Label = 2;
  const auto unlabelled = CastOne(field, p, SlabRay());
  p.Labels.clear();
  p.Mask = nullptr;
  const auto plain = CastOne(field, p, SlabRay());
  EXPECT_EQ(std::memcmp(unlabelled.RGBA, plain.RGBA, sizeof(plain.RGBA)), 0);
  // Label maps apply to composite blending, with sorted positive labels and a mask.
  parc::RayCaster caster;
  p.Labels = { red };
  EXPECT_FALSE(caster.Prepare({ &field, &p })) << "no mask";
  p.Mask = &labels;
  EXPECT_TRUE(caster.Prepare({ &field, &p }));
  p.Blend = BlendMode::MaximumIntensity;
  EXPECT_FALSE(caster.Prepare({ &field, &p }));
}

TEST(RayCaster, CompositingIsFrontToBack)
{
  // Value 1 (red) for z < 50, value 2 (blue) beyond: each side sees its own colour first.
  const parc::ScalarField field =
    parctest::MakeField(SlabDims, [](int, int, int k) { return k < 50 ? 1.f : 2.f; });
  CastParameters p;
  p.Opacity.SetNodes({ 0.0, 3.0 }, { 0.5, 0.5 }, true);
  p.Color.SetTable(1.0, 2.0, { 1.f, 0.f, 0.f, 0.f, 0.f, 1.f });
  p.SampleDistance = 0.25;
  p.TerminationOpacity = 1.0;
  const auto front = CastOne(field, p, MakeRay({ 1.5, 1.5, -10.0 }, { 0, 0, 1 }));
  const auto back = CastOne(field, p, MakeRay({ 1.5, 1.5, 110.0 }, { 0, 0, -1 }));
  EXPECT_GT(front.RGBA[0], 0.99f * front.RGBA[3]);
  EXPECT_LT(front.RGBA[2], 0.01f);
  EXPECT_GT(back.RGBA[2], 0.99f * back.RGBA[3]);
  EXPECT_LT(back.RGBA[0], 0.01f);
}

/// s = x on an 11 x 5 x 5 box: the opaque, white isosurface x = 5 with its normal along x,
/// shaded with ambient 0.2, diffuse 0.3 and specular 0.1, lit by a directional light from
/// +x, and the ray that meets it from +x.
struct ShadedPlane
{
  const int Dims[3] = { 11, 5, 5 };
  parc::ScalarField Field =
    parctest::MakeField(Dims, [](int i, int, int) { return static_cast<float>(i); });
  CastParameters P;
  parc::Ray Ray = MakeRay({ 20.0, 2.0, 2.0 }, { -1, 0, 0 });

  ShadedPlane()
  {
    parctest::SetOpacity(this->P, { 0.0, 10.0 }, { 1.0, 1.0 });
    this->P.Blend = BlendMode::IsoSurface;
    this->P.IsoValues = { 5.0 };
    this->P.Shade = true;
    this->P.Ambient = 0.2;
    this->P.Diffuse = 0.3;
    this->P.Specular = 0.1;
    parc::Light light;
    light.Position = { 100.0, 2.0, 2.0 };
    light.FocalPoint = { 0.0, 2.0, 2.0 };
    this->P.Lights = { light };
  }
};

TEST(RayCaster, ShadingFollowsTheLight)
{
  ShadedPlane scene;
  CastParameters& p = scene.P;
  auto r = CastOne(scene.Field, p, scene.Ray);
  EXPECT_NEAR(r.RGBA[0], 0.6f, 1e-5) << "facing the light: ambient + diffuse + specular";
  EXPECT_NEAR(r.FirstHit, 15.0, 1e-6);
  p.Lights[0].Position = { 5.0, 100.0, 2.0 };
  p.Lights[0].FocalPoint = { 5.0, 0.0, 2.0 };
  r = CastOne(scene.Field, p, scene.Ray);
  EXPECT_NEAR(r.RGBA[0], 0.2f, 1e-5) << "light along the surface: ambient only";
  p.Lights.clear();
  p.Shade = false;
  r = CastOne(scene.Field, p, scene.Ray);
  EXPECT_EQ(r.Stats.GradientEvaluations, 0u) << "no gradient without shading";
}

TEST(RayCaster, HighlightsTakeTheLightsSpecularColour)
{
  // Facing the light: ambient 0.2 + diffuse 0.3 in the diffuse colour (white), specular
  // 0.1 in the specular colour (green), for a directional and a positional light.
  ShadedPlane scene;
  parc::Light& light = scene.P.Lights[0];
  light.SpecularColor = { 0.0, 1.0, 0.0 };
  for (const bool positional : { false, true })
  {
    light.Positional = positional;
    const auto r = CastOne(scene.Field, scene.P, scene.Ray);
    EXPECT_NEAR(r.RGBA[0], 0.5f, 1e-5) << "positional " << positional;
    EXPECT_NEAR(r.RGBA[1], 0.6f, 1e-5) << "positional " << positional;
    EXPECT_NEAR(r.RGBA[2], 0.5f, 1e-5) << "positional " << positional;
  }
}

// Whole and fractional specular powers on an opaque composited plane lit at 45 degrees
// (n.l = cos 45, n.h = cos 22.5): the lanes shaded together (a directional light) and one
// by one (a positional light far along the same direction) take std::pow's power to float
// precision.
TEST(RayCaster, SpecularPowersShadeLikeThePower)
{
  ShadedPlane scene;
  CastParameters& p = scene.P;
  p.Blend = BlendMode::Composite;
  p.SampleDistance = 0.25; // the first sample on the face x = 10
  const double diagonal = std::sqrt(0.5);
  const double ndh = std::cos(std::acos(-1.0) / 8.0);
  parc::Light& light = p.Lights[0];
  for (const double power : { 10.0, 7.5, 12.25, 0.5 })
  {
    p.SpecularPower = power;
    const double expected = 0.2 + 0.3 * diagonal + 0.1 * std::pow(ndh, power);
    for (const bool positional : { false, true })
    {
      light.Positional = positional;
      const double far = positional ? 1e4 : 100.0;
      light.Position = { 10.0 + far * diagonal, 2.0 + far * diagonal, 2.0 };
      light.FocalPoint = { 10.0, 2.0, 2.0 };
      const auto r = CastOne(scene.Field, p, scene.Ray);
      EXPECT_EQ(r.Stats.ContributingSamples, 1u);
      EXPECT_NEAR(r.RGBA[0], expected, 2e-6) << "power " << power << ", positional " << positional;
    }
  }
}

TEST(RayCaster, GradientOpacityUsesTheWorldGradient)
{
  const int n[3] = { 11, 5, 5 };
  const parc::ScalarField field =
    parctest::MakeField(n, [](int i, int, int) { return static_cast<float>(3 * i); });
  CastParameters p;
  parctest::SetOpacity(p, { 0.0, 30.0 }, { 0.5, 0.5 });
  p.UseGradientOpacity = true;
  p.GradientOpacity.SetNodes({ 0.0, 1.0, 2.0 }, { 0.0, 0.0, 1.0 }, true);
  const auto plain = CastOne(field, p, MakeRay({ -5.0, 2.0, 2.0 }, { 1, 0, 0 }));
  EXPECT_GT(plain.RGBA[3], 0.f) << "|grad| = 3 per unit: opacity kept";
  parc::Volume volume{ &field, &p };
  volume.WorldToIndex(0, 0) = 0.25; // voxels 4 world units apart: |grad| = 0.75, opacity 0
  const auto stretched = CastOne(volume, MakeRay({ -5.0, 2.0, 2.0 }, { 1, 0, 0 }));
  EXPECT_EQ(stretched.RGBA[3], 0.f);
  EXPECT_GT(stretched.Stats.GradientEvaluations, 0u);
}

namespace
{
/// Cuts [tEnter, tExit] of each ray into random pieces, leaving out stretches whose lattice
/// samples all have zero opacity: a segment source that leaves out only samples that
/// cannot change the image.
class SparseSource : public parc::SegmentSource
{
public:
  SparseSource(const parc::RayCaster& caster, unsigned seed)
    : Caster(caster)
    , Seed(seed)
  {
  }
  void Segments(const parc::RayQuery& query, std::vector<parc::Segment>& out) const override
  {
    const parc::Ray& ray = query.Path;
    const int px = query.Pixel[0], py = query.Pixel[1];
    double t0, t1;
    if (!this->Caster.ClipRay(ray, t0, t1))
    {
      return;
    }
    std::mt19937 rng(this->Seed + 7919u * px + 104729u * py);
    const CastParameters& p = *this->Caster.GetParameters();
    const Matrix4Ref m = this->Caster.GetWorldToIndex();
    const double dt = p.SampleDistance;
    for (long k = static_cast<long>(std::ceil(t0 / dt)); k * dt <= t1; ++k)
    {
      const double t = k * dt;
      const Vec3 x = m.TransformPoint(ray.Origin + t * ray.Direction);
      if (p.Opacity.Evaluate(this->Caster.GetField()->Sample(x, p.Interp)) > 0.f)
      {
        // A random piece around the sample, never reaching its neighbours' centres.
        const double before = 0.9 * dt * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        const double after = 0.9 * dt * std::uniform_real_distribution<double>(0.0, 1.0)(rng);
        out.push_back({ t - before, t + after });
      }
    }
    std::shuffle(out.begin(), out.end(), rng);
  }

private:
  using Matrix4Ref = const parc::Matrix4&;
  const parc::RayCaster& Caster;
  unsigned Seed;
};

/// Composite parameters for Blobs: the blobs' cores opaque-ish, their rims empty.
CastParameters BlobParameters()
{
  CastParameters p;
  p.Opacity.SetNodes({ 0.0, 60.0, 200.0 }, { 0.0, 0.0, 0.5 }, true);
  p.Color.SetTable(0.0, 255.0, { 1.f, 0.5f, 0.f, 0.f, 0.5f, 1.f });
  p.SampleDistance = 0.5;
  return p;
}
}

// The lattice does not depend on the segments: a source that leaves out only zero-opacity
// samples, in shuffled random pieces, gives bit-identical pixels for the blend modes where
// zero-opacity samples change nothing.
TEST(RayCaster, SparseSegmentsGiveBitIdenticalImages)
{
  const parc::ScalarField field = Blobs();
  for (BlendMode mode : { BlendMode::Composite, BlendMode::Additive })
  {
    for (bool shade : { false, true })
    {
      CastParameters p;
      p.Opacity.SetNodes({ 0.0, 60.0, 90.0, 140.0, 200.0 }, { 0.0, 0.0, 0.3, 0.0, 0.8 }, true);
      p.Color.SetTable(0.0, 255.0, { 1.f, 0.f, 0.f, 0.f, 1.f, 0.5f });
      p.Blend = mode;
      p.Shade = shade;
      p.SampleDistance = 0.37;
      parc::Light light;
      light.Position = { 0.0, 50.0, 50.0 };
      p.Lights = { light };
      parc::RayCaster caster;
      ASSERT_TRUE(caster.Prepare({ &field, &p }));
      const parc::Camera view = ParallelView(48, 40, 0.4);
      std::vector<float> whole(4 * 48 * 40), sparse(4 * 48 * 40);
      parc::CastStatistics s1, s2;
      caster.CastImage(view, nullptr, parc::WholeRaySource(), whole.data(), s1);
      caster.CastImage(view, nullptr, SparseSource(caster, 5), sparse.data(), s2);
      EXPECT_EQ(0, std::memcmp(whole.data(), sparse.data(), whole.size() * sizeof(float)))
        << "mode " << static_cast<int>(mode) << " shade " << shade;
      EXPECT_LT(s2.Samples, s1.Samples);
      EXPECT_EQ(s1.ContributingSamples, s2.ContributingSamples);
      EXPECT_GT(s1.ContributingSamples, 0u);
      // Both casts know the samples of the unaccelerated one (early termination included).
      EXPECT_EQ(s1.UnacceleratedSamples, s1.Samples);
      EXPECT_EQ(s2.UnacceleratedSamples, s1.Samples);
      // Every fourth column is timed.
      EXPECT_EQ(s2.Timing.Rays(), 12.0 * 40.0);
    }
  }
}

// A gradient opacity that is the same everywhere (VTK creates a constant 1 on any
// GetGradientOpacity call) costs no gradient, and a constant factor scales the opacity.
TEST(RayCaster, ConstantGradientOpacityNeedsNoGradient)
{
  const parc::ScalarField field = Blobs();
  CastParameters p = BlobParameters();
  const parc::Camera view = ParallelView(32, 32, 0.3);
  auto cast = [&](std::vector<float>& image, parc::CastStatistics& stats) {
    parc::RayCaster caster;
    ASSERT_TRUE(caster.Prepare({ &field, &p }));
    image.assign(4 * 32 * 32, 0.f);
    caster.CastImage(view, nullptr, parc::WholeRaySource(), image.data(), stats);
  };
  std::vector<float> without, constantOne, half, halfOpacity;
  parc::CastStatistics s0, s1, s2, s3;
  cast(without, s0);
  p.UseGradientOpacity = true;
  p.GradientOpacity.SetNodes({ 0.0, 100.0 }, { 1.0, 1.0 }, true);
  cast(constantOne, s1);
  EXPECT_EQ(s1.GradientEvaluations, 0u);
  EXPECT_EQ(0, std::memcmp(without.data(), constantOne.data(), without.size() * sizeof(float)));
  p.GradientOpacity.SetNodes({ 0.0, 100.0 }, { 0.5, 0.5 }, true);
  cast(half, s2);
  EXPECT_EQ(s2.GradientEvaluations, 0u);
  p.UseGradientOpacity = false;
  p.Opacity.SetNodes({ 0.0, 60.0, 200.0 }, { 0.0, 0.0, 0.25 }, true);
  cast(halfOpacity, s3);
  EXPECT_EQ(0, std::memcmp(half.data(), halfOpacity.data(), half.size() * sizeof(float)))
    << "a constant factor 0.5 equals half the scalar opacity";
  p.Opacity.SetNodes({ 0.0, 60.0, 200.0 }, { 0.0, 0.0, 0.5 }, true);
  p.UseGradientOpacity = true;
  p.GradientOpacity.SetNodes({ 0.0, 100.0 }, { 0.5, 1.0 }, true);
  cast(half, s2);
  EXPECT_GT(s2.GradientEvaluations, 0u) << "a varying gradient opacity needs gradients";
}

TEST(RayCaster, ImageIsTheSameForOneAndManyThreads)
{
  const parc::ScalarField field = Blobs();
  CastParameters p = BlobParameters();
  parc::RayCaster caster;
  ASSERT_TRUE(caster.Prepare({ &field, &p }));
  const parc::Camera view = ParallelView(64, 64, 0.3);
  std::vector<float> one(4 * 64 * 64), many(4 * 64 * 64);
  parc::CastStatistics s1, s2;
  vtkSMPTools::Initialize(1);
  caster.CastImage(view, nullptr, parc::WholeRaySource(), one.data(), s1);
  vtkSMPTools::Initialize(4);
  caster.CastImage(view, nullptr, parc::WholeRaySource(), many.data(), s2);
  EXPECT_EQ(0, std::memcmp(one.data(), many.data(), one.size() * sizeof(float)));
  EXPECT_EQ(s1.Samples, s2.Samples);
}

// The rays of an image share a thread's cache of cell differences: neighbouring rays cross
// the same cells, so most gradients load none, and the image is the one of rays cast alone.
TEST(RayCaster, NeighbouringRaysShareCellDifferences)
{
  const parc::ScalarField field = Blobs();
  CastParameters p = BlobParameters();
  p.Shade = true;
  parc::RayCaster caster;
  ASSERT_TRUE(caster.Prepare({ &field, &p }));
  const int size = 96; // rays about 0.4 voxel apart
  const parc::Camera view = ParallelView(size, size, 0.3);
  std::vector<float> image(4 * size * size), alone(4 * size * size);
  parc::CastStatistics stats, aloneStats;
  vtkSMPTools::Initialize(1);
  caster.CastImage(view, nullptr, parc::WholeRaySource(), image.data(), stats);
  std::vector<parc::Segment> segments;
  std::vector<parc::LatticeRange> ranges;
  for (int py = 0; py < size; ++py)
  {
    for (int px = 0; px < size; ++px)
    {
      caster.CastRay(parc::RayQuery::AtPixel(view.MakeRay(px, py), px, py),
        parc::WholeRaySource(), segments, ranges, &alone[4 * (py * size + px)], aloneStats);
    }
  }
  EXPECT_EQ(0, std::memcmp(image.data(), alone.data(), image.size() * sizeof(float)));
  EXPECT_EQ(stats.GradientEvaluations, aloneStats.GradientEvaluations);
  EXPECT_GT(stats.GradientEvaluations, 10000u);
  EXPECT_LT(stats.DifferenceLoads, aloneStats.DifferenceLoads / 2);
}

// Rays closer than a voxel cross the cells of the rows of rays before them in their tile:
// the thread's cache holds a whole row's cells, deep as the field is, so that a cell's
// differences are loaded about once per tile.
TEST(RayCaster, CloseRaysShareTheCellsOfTheRowBefore)
{
  const int n[3] = { 12, 12, 200 };
  const parc::ScalarField field = parctest::MakeField(n, [](int i, int j, int k) {
    return static_cast<float>(
      128.0 + 100.0 * std::sin(0.7 * i) * std::cos(0.5 * j) * std::sin(0.3 * k));
  });
  CastParameters p;
  parctest::SetOpacity(p, { 0.0, 255.0 }, { 0.005, 0.005 });
  p.Shade = true;
  p.SampleDistance = 0.5;
  parc::RayCaster caster;
  ASSERT_TRUE(caster.Prepare({ &field, &p }));
  // Rays 0.3 voxel apart along -z, through the whole depth.
  const parc::Camera view =
    ParallelView(40, 40, 0.0, 6.0, parc::Vec3{ 5.5, 5.5, 99.5 }, 120.0);
  std::vector<float> image(4 * 40 * 40);
  parc::CastStatistics stats;
  vtkSMPTools::Initialize(1);
  caster.CastImage(view, nullptr, parc::WholeRaySource(), image.data(), stats);
  // Each cell loaded less than once on average (a cache of one row's cells reloads each
  // about twice); the image is the one of the rays cast alone.
  const std::uint64_t cells = 11 * 11 * 199;
  EXPECT_GT(stats.GradientEvaluations, 10 * cells);
  EXPECT_LT(stats.DifferenceLoads, cells);
  std::vector<parc::Segment> segments;
  std::vector<parc::LatticeRange> ranges;
  parc::CastStatistics alone;
  for (const int pixel : { 0, 17, 40 * 20 + 21, 40 * 40 - 1 })
  {
    float rgba[4];
    const int px = pixel % 40, py = pixel / 40;
    caster.CastRay(parc::RayQuery::AtPixel(view.MakeRay(px, py), px, py),
      parc::WholeRaySource(), segments, ranges, rgba, alone);
    EXPECT_EQ(0, std::memcmp(rgba, &image[4 * pixel], sizeof(rgba))) << pixel;
  }
}

TEST(RayCaster, ProgressCanAbortTheImage)
{
  const parc::ScalarField field = Blobs();
  CastParameters p;
  p.Opacity.SetNodes({ 0.0, 255.0 }, { 0.1, 0.1 }, true);
  parc::RayCaster caster;
  ASSERT_TRUE(caster.Prepare({ &field, &p }));
  const parc::Camera view = ParallelView(64, 256, 0.0);
  std::vector<float> image(4 * 64 * 256);
  parc::CastStatistics s;
  std::vector<double> reported;
  const bool done = caster.CastImage(view, nullptr, parc::WholeRaySource(), image.data(), s,
    [&](double f) {
      reported.push_back(f);
      return reported.size() < 2;
    });
  EXPECT_FALSE(done);
  EXPECT_EQ(reported.size(), 2u);
  EXPECT_GT(reported[1], reported[0]);
  EXPECT_EQ(image[4 * (64 * 255) + 3], 0.f) << "the last row was never cast";
}

// Slice: the one sample where the ray crosses the plane, off the lattice, with its
// uncorrected opacity. On a linear field trilinear interpolation is exact, so the value
// there is the field's at the crossing.
TEST(RayCaster, SliceTakesTheValueWhereTheRayCrossesThePlane)
{
  const int n[3] = { 8, 8, 8 };
  const auto linear = [](double x, double y, double z) { return 10.0 * x + 3.0 * y + 2.0 * z; };
  const parc::ScalarField field = parctest::MakeField(
    n, [&](int i, int j, int k) { return static_cast<float>(linear(i, j, k)); });
  CastParameters p;
  parctest::SetOpacity(p, { 0.0, 255.0 }, { 0.0, 1.0 });
  p.OpacityUnitDistance = 0.25; // would change the opacity if it were corrected
  p.Blend = BlendMode::Slice;
  p.SliceOrigin = Vec3(3.3, 0.0, 0.0);
  p.SliceNormal = Vec3(2.0, 1.0, 0.5); // not of unit length
  const parc::Ray ray = MakeRay({ -5.0, 2.5, 4.2 }, { 1.0, 0.1, 0.05 });
  const double t = parc::Dot(p.SliceOrigin - ray.Origin, p.SliceNormal) /
    parc::Dot(ray.Direction, p.SliceNormal);
  const Vec3 x = ray.Origin + t * ray.Direction;
  const double a = linear(x.X, x.Y, x.Z) / 255.0;
  const auto r = CastOne(field, p, ray);
  for (int c = 0; c < 4; ++c)
  {
    EXPECT_NEAR(r.RGBA[c], a, 1e-6) << "white, premultiplied: " << c;
  }
  EXPECT_DOUBLE_EQ(r.FirstHit, t);
  EXPECT_EQ(r.Stats.Samples, 1u);
  // No segment is asked for: a source with none gives the same bits.
  const parc::EmptySource none;
  const auto unasked = CastOne(field, p, ray, &none);
  EXPECT_EQ(std::memcmp(unasked.RGBA, r.RGBA, sizeof(r.RGBA)), 0);
  // A ray along the plane, and one crossing it outside the field, take no sample.
  const Vec3 along(-1.0, 2.0, 0.0); // at right angles to the normal
  EXPECT_EQ(CastOne(field, p, MakeRay({ 3.3, 3.0, 3.0 }, along)).Stats.Samples, 0u);
  EXPECT_EQ(CastOne(field, p, MakeRay({ -5.0, 2.5, 20.0 }, { 1.0, 0.1, 0.05 })).RGBA[3], 0.f);
  parc::RayCaster caster;
  p.SliceNormal = Vec3(0.0, 0.0, 0.0);
  EXPECT_FALSE(caster.Prepare({ &field, &p })) << "a plane needs a normal";
}

TEST(RayCaster, RejectsUnusableParameters)
{
  const parc::ScalarField field = Blobs();
  CastParameters p;
  parc::RayCaster caster;
  p.SampleDistance = 0.0;
  EXPECT_FALSE(caster.Prepare({ &field, &p }));
  p.SampleDistance = 1.0;
  p.OpacityUnitDistance = -1.0;
  EXPECT_FALSE(caster.Prepare({ &field, &p }));
  const int flat[3] = { 5, 5, 1 };
  const parc::ScalarField slice = parctest::MakeField(flat, [](int, int, int) { return 1.f; });
  p.OpacityUnitDistance = 1.0;
  EXPECT_FALSE(caster.Prepare({ &slice, &p })) << "one slice has no cells";
  EXPECT_TRUE(caster.Prepare({ &field, &p }));
  p.ColorShiftCount = 2;
  EXPECT_FALSE(caster.Prepare({ &field, &p })) << "colour from 0, 1 or 3 other components";
}

TEST(Camera, PerspectiveRaysStartAtTheEyeAndParallelRaysOnTheCameraPlane)
{
  const parc::Camera v = ParallelView(10, 10, 0.0);
  const parc::Ray a = v.MakeRay(0, 0), b = v.MakeRay(9, 9);
  EXPECT_NEAR(a.Direction.Z, -1.0, 1e-12);
  EXPECT_NEAR(a.Origin.Z, b.Origin.Z, 1e-12) << "one camera plane";
  EXPECT_NEAR(a.Origin.Z, 96.0, 1e-12);
  EXPECT_NEAR(v.DepthToParameter(a, 0, 0, 0.5), 80.0, 1e-9) << "window depth 0.5 is NDC 0";
}

// Where a label's opacity is non-zero and the default one is not, the classification
// keeps the cells (the union of the functions' intervals): the oracle's segments give the
// unaccelerated image bit for bit, which the default function's cells alone would not.
TEST(RayCaster, LabelMapClassificationGivesBitIdenticalImages)
{
  const parc::ScalarField field = Blobs();
  const int* dims = field.GetDimensions();
  const parc::ScalarField labels =
    parctest::MakeField(dims, [](int i, int, int) { return i < 16 ? 3.f : 0.f; });
  CastParameters p = BlobParameters(); // opacity from 60 up
  parc::LabelFunctions rim;
  rim.Label = 3;
  rim.Opacity.SetNodes({ 10.0, 30.0, 50.0 }, { 0.0, 0.4, 0.0 }, true); // below 60 only
  rim.Color.SetTable(0.0, 255.0, { 0.f, 1.f, 0.f, 0.f, 1.f, 0.f });
  rim.UseGradientOpacity = true;
  rim.GradientOpacity.SetNodes({ 0.0, 20.0 }, { 0.3, 1.0 }, true);
  p.Mask = &labels;
  p.Labels = { rim };
  p.MaskBlendFactor = 0.7f;
  p.Shade = true;
  parc::Light light;
  light.Position = { 0.0, 50.0, 50.0 };
  p.Lights = { light };
  parc::RayCaster caster;
  ASSERT_TRUE(caster.Prepare({ &field, &p }));
  EXPECT_TRUE(caster.NeedsGradient());
  parc::RangePyramid pyramid;
  pyramid.Build(field);
  const double size[3] = { 2.0, 2.0, 2.0 };
  parc::SupercellGrid grids[2];
  CastParameters withoutLabels = p;
  withoutLabels.Labels.clear();
  const CastParameters* rules[2] = { &p, &withoutLabels };
  for (int g = 0; g < 2; ++g)
  {
    parc::ContributionRule rule;
    rule.Set(*rules[g], field.GetRange());
    ASSERT_TRUE(grids[g].Configure(pyramid.GetCellDimensions(), size));
    grids[g].Classify(pyramid, rule, p.Interp);
  }
  EXPECT_GT(grids[0].GetNumberOfContributing(), grids[1].GetNumberOfContributing());
  const parc::SegmentOracle oracle(grids[0], caster.GetWorldToIndex());
  const parc::SegmentOracle lossy(grids[1], caster.GetWorldToIndex());
  const parc::Camera view = ParallelView(48, 40, 0.6);
  std::vector<float> whole(4 * 48 * 40), accelerated(whole.size()), lost(whole.size());
  parc::CastStatistics s1, s2, s3;
  caster.CastImage(view, nullptr, parc::WholeRaySource(), whole.data(), s1);
  caster.CastImage(view, nullptr, oracle, accelerated.data(), s2);
  caster.CastImage(view, nullptr, lossy, lost.data(), s3);
  EXPECT_EQ(0, std::memcmp(whole.data(), accelerated.data(), whole.size() * sizeof(float)));
  EXPECT_NE(0, std::memcmp(whole.data(), lost.data(), whole.size() * sizeof(float)));
  EXPECT_LT(s2.Samples, s1.Samples);
  EXPECT_EQ(s1.ContributingSamples, s2.ContributingSamples);
}

namespace
{
/// A smooth blob with a ripple, of dimensions n (x fastest), as bytes.
std::vector<std::uint8_t> RippledBlob(const int n[3])
{
  std::vector<std::uint8_t> values;
  for (int k = 0; k < n[2]; ++k)
  {
    for (int j = 0; j < n[1]; ++j)
    {
      for (int i = 0; i < n[0]; ++i)
      {
        const double r2 = 0.001 * ((i - 60) * (i - 60) + (j - 35) * (j - 35) + (k - 33) * (k - 33));
        values.push_back(static_cast<std::uint8_t>(255.0 * std::exp(-r2) + (i * 7 + j * 3) % 11));
      }
    }
  }
  return values;
}

/// A ray function, shaded or not, with gradient opacity or not, for RippledBlob.
struct BlobCase
{
  BlendMode Blend;
  bool Shade, GradientOpacity;
  double SampleDistance = 0.41;

  CastParameters Parameters() const
  {
    CastParameters p;
    p.Opacity.SetNodes({ 0.0, 40.0, 120.0, 255.0 }, { 0.0, 0.0, 0.2, 0.9 }, true);
    p.Color.SetTable(0.0, 255.0, { 1.f, 0.f, 0.f, 0.f, 1.f, 0.5f });
    p.Blend = this->Blend;
    p.Shade = this->Shade;
    p.IsoValues = { 100.0 };
    p.UseGradientOpacity = this->GradientOpacity;
    p.GradientOpacity.SetNodes({ 0.0, 30.0 }, { 0.2, 1.0 }, true);
    p.SampleDistance = this->SampleDistance;
    parc::Light light;
    light.Position = { 0.0, 80.0, 80.0 };
    p.Lights = { light };
    return p;
  }
};

/// A cast of field under p with a view from the side, from source.
std::vector<float> CastBlobImage(const parc::ScalarField& field, const CastParameters& p,
  const parc::SegmentSource& source, parc::CastStatistics& stats)
{
  const parc::Camera view = ParallelView(64, 48, 0.7, 90.0);
  std::vector<float> image(4 * 64 * 48, 0.f);
  parc::RayCaster caster;
  EXPECT_TRUE(caster.Prepare({ &field, &p }));
  caster.CastImage(view, nullptr, source, image.data(), stats);
  return image;
}

/// RippledBlob(n) as 8-bit, 16-bit and float values, each wrapped in a field.
struct TypedBlobs
{
  explicit TypedBlobs(const int n[3])
    : Bytes(RippledBlob(n))
    , Shorts(Bytes.begin(), Bytes.end())
    , Floats(Bytes.begin(), Bytes.end())
  {
    this->Fields[0].Wrap(this->Bytes.data(), n);
    this->Fields[1].Wrap(this->Shorts.data(), n);
    this->Fields[2].Wrap(this->Floats.data(), n);
  }
  TypedBlobs(const TypedBlobs&) = delete;
  TypedBlobs& operator=(const TypedBlobs&) = delete;

  const std::vector<std::uint8_t> Bytes;
  const std::vector<std::int16_t> Shorts;
  const std::vector<float> Floats;
  parc::ScalarField Fields[3];
};
}

// A field's copy in bricks (ScalarField::SetBricked) changes where the samples' voxels are
// read from, never the image: every ray function, shaded or not, with gradient opacity,
// across the bricks' faces, bit for bit.
TEST(RayCaster, BrickedFieldGivesBitIdenticalImages)
{
  const int n[3] = { 140, 70, 68 }; // 3 x 2 x 2 bricks, the last ones filled in part
  const std::vector<std::uint8_t> values = RippledBlob(n);
  parc::ScalarField linear, bricked;
  linear.Wrap(values.data(), n);
  bricked.Wrap(values.data(), n);
  ASSERT_TRUE(bricked.SetBricked(true));
  for (const BlobCase c : { BlobCase{ BlendMode::Composite, false, false },
         BlobCase{ BlendMode::Composite, true, false },
         BlobCase{ BlendMode::Composite, false, true },
         BlobCase{ BlendMode::MaximumIntensity, false, false },
         BlobCase{ BlendMode::IsoSurface, true, false } })
  {
    const CastParameters p = c.Parameters();
    parc::CastStatistics stats[2];
    const std::vector<float> images[2] = {
      CastBlobImage(linear, p, parc::WholeRaySource(), stats[0]),
      CastBlobImage(bricked, p, parc::WholeRaySource(), stats[1])
    };
    SCOPED_TRACE(static_cast<int>(c.Blend));
    EXPECT_EQ(0, std::memcmp(images[0].data(), images[1].data(), images[0].size() * sizeof(float)))
      << "shade " << c.Shade << " gradient opacity " << c.GradientOpacity;
    EXPECT_EQ(stats[0].Samples, stats[1].Samples);
    EXPECT_GT(*std::max_element(images[0].begin(), images[0].end()), 0.1f);
    EXPECT_EQ(stats[0].GradientEvaluations, stats[1].GradientEvaluations);
    EXPECT_EQ(stats[1].GradientEvaluations > 0, c.Shade || c.GradientOpacity);
  }
}

// Prefetching the voxels ahead of the rays (CastParameters::PrefetchMinBytes) is chosen
// only where it was measured to pay (unshaded, no gradient, values read in place, large
// fields), and never changes an image: every ray function, 8-bit, 16-bit and float values,
// prefetching forced on a small field against none, bit for bit.
TEST(RayCaster, PrefetchChosenWhereItPaysAndGivesBitIdenticalImages)
{
  const int n[3] = { 140, 70, 68 };
  const TypedBlobs blobs(n);
  const parc::ScalarField* fields = blobs.Fields;
  const auto prefetches = [](const parc::ScalarField& field, const CastParameters& p) {
    parc::RayCaster caster;
    EXPECT_TRUE(caster.Prepare({ &field, &p }));
    return caster.PrefetchesVoxels();
  };
  CastParameters forced = BlobCase{ BlendMode::Composite, false, false }.Parameters();
  EXPECT_FALSE(prefetches(fields[0], forced)); // 666 KB: below the default size
  forced.PrefetchMinBytes = blobs.Bytes.size();
  EXPECT_TRUE(prefetches(fields[0], forced));
  forced.PrefetchMinBytes = blobs.Bytes.size() + 1;
  EXPECT_FALSE(prefetches(fields[0], forced));
  EXPECT_TRUE(prefetches(fields[1], forced)); // two bytes a value
  forced.PrefetchMinBytes = 0;
  forced.Shade = true;
  EXPECT_FALSE(prefetches(fields[0], forced)); // shaded: none
  parc::NormalVolume normals;
  normals.Build(fields[0]);
  forced.Shading = parc::ShadingModel::QuantizedNormals; // shaded without gradients
  forced.Normals = &normals;
  EXPECT_FALSE(prefetches(fields[0], forced));
  forced.Shade = false;
  forced.UseGradientOpacity = true;
  EXPECT_FALSE(prefetches(fields[0], forced)); // gradients: none
  forced.UseGradientOpacity = false;
  forced.Interp = parc::Interpolation::Nearest;
  EXPECT_FALSE(prefetches(fields[0], forced));
  parc::ScalarField bricked;
  bricked.Wrap(blobs.Bytes.data(), n);
  ASSERT_TRUE(bricked.SetBricked(true));
  EXPECT_FALSE(prefetches(bricked, BlobCase{ BlendMode::Composite, false, false }.Parameters()));

  for (const parc::ScalarField& field : blobs.Fields)
  {
    for (const BlendMode blend : { BlendMode::Composite, BlendMode::MaximumIntensity,
           BlendMode::MinimumIntensity, BlendMode::AverageIntensity, BlendMode::Additive,
           BlendMode::IsoSurface })
    {
      CastParameters p = BlobCase{ blend, false, false }.Parameters();
      p.PrefetchMinBytes = 0;
      ASSERT_TRUE(prefetches(field, p));
      parc::CastStatistics stats[2];
      const std::vector<float> ahead = CastBlobImage(field, p, parc::WholeRaySource(), stats[0]);
      p.PrefetchMinBytes = std::numeric_limits<std::size_t>::max();
      ASSERT_FALSE(prefetches(field, p));
      const std::vector<float> none = CastBlobImage(field, p, parc::WholeRaySource(), stats[1]);
      EXPECT_EQ(0, std::memcmp(ahead.data(), none.data(), ahead.size() * sizeof(float)))
        << "type " << static_cast<int>(field.GetScalarType()) << " blend "
        << static_cast<int>(blend);
      EXPECT_GT(*std::max_element(ahead.begin(), ahead.end()), 0.f);
      EXPECT_EQ(stats[0].Samples, stats[1].Samples);
    }
  }
}

// The rays' loops compiled for wide vectors (CastParameters::WideVectors) give the images
// of the baseline code, bit for bit: every ray function, shaded or not (exact shading under
// a directional light, two of them, one coloured, a positional light, a fractional specular
// power, quantized normals), with gradient opacity, each kind of opacity correction, 8-bit,
// 16-bit and float values, bricked, and a sparse source. The opacity function has four
// nodes: in wide vectors it is evaluated eight lanes at once (EvaluateEightLanes).
TEST(RayCaster, WideVectorsGiveBitIdenticalImages)
{
  if (!parc::HasWideVectors())
  {
    GTEST_SKIP() << "this processor has no wide vectors (AVX2)";
  }
  const int n[3] = { 140, 70, 68 };
  const TypedBlobs blobs(n);
  parc::ScalarField bricked;
  bricked.Wrap(blobs.Bytes.data(), n);
  ASSERT_TRUE(bricked.SetBricked(true));
  parc::NormalVolume normals;
  normals.Build(blobs.Fields[0]);
  std::vector<BlobCase> cases;
  for (const BlendMode blend : { BlendMode::Composite, BlendMode::MaximumIntensity,
         BlendMode::MinimumIntensity, BlendMode::AverageIntensity, BlendMode::Additive,
         BlendMode::IsoSurface })
  {
    cases.push_back({ blend, false, false });
    cases.push_back({ blend, true, false });
  }
  // A root (half the unit distance), the series and the power, and the power alone.
  for (const double dt : { 0.5, 0.41, 1.5 })
  {
    cases.push_back({ BlendMode::Composite, false, true, dt });
    cases.push_back({ BlendMode::Composite, true, false, dt });
  }
  const parc::ScalarField* const fields[] = { &blobs.Fields[0], &blobs.Fields[1],
    &blobs.Fields[2], &bricked };
  for (const parc::ScalarField* each : fields)
  {
    const parc::ScalarField& field = *each;
    for (const BlobCase& c : cases)
    {
      // Directional, positional, quantized normals, a second light of colour (eight lanes
      // at a time, each channel), a fractional specular power (four lanes at a time).
      for (const int lighting : { 0, 1, 2, 3, 4 })
      {
        CastParameters p = c.Parameters();
        p.Lights[0].Positional = (lighting == 1);
        if (lighting == 2)
        {
          p.Shading = parc::ShadingModel::QuantizedNormals;
          p.Normals = &normals;
        }
        if (lighting == 3)
        {
          parc::Light coloured;
          coloured.Position = { 60.0, -40.0, 30.0 };
          coloured.Color = { 0.9, 0.5, 0.2 };
          coloured.SpecularColor = { 0.3, 0.6, 1.0 };
          p.Lights.push_back(coloured);
        }
        p.SpecularPower = lighting == 4 ? 12.5 : p.SpecularPower;
        parc::CastStatistics stats[2];
        const std::vector<float> wide = CastBlobImage(field, p, parc::WholeRaySource(), stats[0]);
        p.WideVectors = false;
        // Zero-opacity samples change nothing in these two: they may be left out.
        const bool sparse = c.Blend == BlendMode::Composite || c.Blend == BlendMode::Additive;
        parc::RayCaster caster;
        ASSERT_TRUE(caster.Prepare({ &field, &p }));
        const SparseSource some(caster, 3);
        const parc::WholeRaySource whole;
        const parc::SegmentSource& source = sparse ? static_cast<const parc::SegmentSource&>(some)
                                                   : whole;
        const std::vector<float> baseline = CastBlobImage(field, p, source, stats[1]);
        SCOPED_TRACE(static_cast<int>(c.Blend));
        EXPECT_EQ(0, std::memcmp(wide.data(), baseline.data(), wide.size() * sizeof(float)))
          << "type " << static_cast<int>(field.GetScalarType()) << " shade " << c.Shade
          << " lighting " << lighting << " gradient opacity " << c.GradientOpacity
          << " dt " << c.SampleDistance;
        EXPECT_GT(*std::max_element(wide.begin(), wide.end()), 0.f);
        EXPECT_EQ(stats[0].ContributingSamples, stats[1].ContributingSamples);
      }
    }
  }
}
