// Independent components: VTK's combination of the components' opacities and colours, no
// work for a component of weight 0, and a classification that keeps every component's
// contributing samples (bit-identical images with the oracle's segments, for 1 and N
// threads).
#include "parcSegmentOracle.h"
#include "parcTestUtilities.h"

#include <vtkSMPTools.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <random>

using parc::BlendMode;
using parc::CastParameters;
using parc::Vec3;
using parctest::MakeRay;
using parctest::ParallelView;

namespace
{
using ComponentValue = std::function<float(int c, int i, int j, int k)>;

/// A field of two independent components, interleaved uint8 values, with the parameters
/// and casters of both (component 0's caster casts for both).
struct TwoComponents
{
  std::vector<std::uint8_t> Values;
  parc::ScalarField Fields[2];
  CastParameters Params[2];
  parc::RayCaster Casters[2];

  TwoComponents(const int dims[3], const ComponentValue& value)
  {
    for (int k = 0; k < dims[2]; ++k)
    {
      for (int j = 0; j < dims[1]; ++j)
      {
        for (int i = 0; i < dims[0]; ++i)
        {
          for (int c = 0; c < 2; ++c)
          {
            this->Values.push_back(static_cast<std::uint8_t>(value(c, i, j, k)));
          }
        }
      }
    }
    for (int c = 0; c < 2; ++c)
    {
      this->Fields[c].Wrap(this->Values.data() + c, dims, 2);
    }
  }
  TwoComponents(const TwoComponents&) = delete;

  /// Prepares both casters; component 1 after component 0's settings (blend, sample
  /// distance, lights) are copied into it.
  bool Prepare()
  {
    return this->Casters[0].Prepare({ &this->Fields[0], &this->Params[0] }) &&
      this->Casters[1].Prepare({ &this->Fields[1], &this->Params[1] }) &&
      this->Casters[0].SetComponents({ { &this->Casters[1], 1 } });
  }
  std::array<float, 4> Cast(const parc::Ray& ray, parc::CastStatistics& stats) const
  {
    std::vector<parc::Segment> segments;
    std::vector<parc::LatticeRange> ranges;
    std::array<float, 4> rgba;
    this->Casters[0].CastRay(parc::RayQuery::Anywhere(ray), parc::WholeRaySource(), segments,
      ranges, rgba.data(), stats);
    return rgba;
  }
};

const int SlabDims[3] = { 4, 4, 101 };

/// Constant opacity a per unit distance and colour rgb everywhere, dt = 1/8, no early
/// termination.
void SetConstant(CastParameters& p, double a, const std::vector<float>& rgb, double weight)
{
  p.Opacity.SetNodes({ 0.0, 255.0 }, { a, a }, true);
  p.Color.SetTable(0.0, 255.0, { rgb[0], rgb[1], rgb[2], rgb[0], rgb[1], rgb[2] });
  p.SampleDistance = 0.125;
  p.TerminationOpacity = 1.0;
  p.ComponentWeight = weight;
}

/// Opacity above 60 for component 0 and above 120 for component 1 (red and blue), shaded,
/// dt = 0.37, with gradient opacity.
void SetBlobs(TwoComponents& volume)
{
  for (int c = 0; c < 2; ++c)
  {
    CastParameters& p = volume.Params[c];
    const double start = c == 0 ? 60.0 : 120.0;
    p.Opacity.SetNodes({ 0.0, start, 255.0 }, { 0.0, 0.0, 0.6 }, true);
    p.Color.SetTable(0.0, 255.0,
      c == 0 ? std::vector<float>{ 1.f, 0.f, 0.f, 1.f, 0.5f, 0.f }
             : std::vector<float>{ 0.f, 0.f, 1.f, 0.f, 1.f, 1.f });
    p.SampleDistance = 0.37;
    p.Shade = true;
    p.UseGradientOpacity = c == 1;
    p.GradientOpacity.SetNodes({ 0.0, 30.0 }, { 0.2, 1.0 }, true);
    parc::Light light;
    light.Position = { 0.0, 50.0, 50.0 };
    p.Lights = { light };
    p.ComponentWeight = c == 0 ? 0.8 : 0.6;
  }
}

/// Two blobs, one per component, apart from each other.
double Blob(int c, int i, int j, int k)
{
  const int x = c == 0 ? 10 : 22, y = c == 0 ? 12 : 18, z = c == 0 ? 9 : 18;
  return 255.0 * std::exp(-0.02 * ((i - x) * (i - x) + (j - y) * (j - y) + (k - z) * (k - z)));
}

/// The supercells of size 2 where one of components (indices) may contribute.
void ClassifyComponents(const TwoComponents& volume, const std::vector<int>& components,
  parc::RangePyramid pyramids[2], parc::ContributionRule rules[2], parc::SupercellGrid& grid)
{
  std::vector<parc::SupercellGrid::Channel> channels;
  for (int c : components)
  {
    pyramids[c].Build(volume.Fields[c]);
    rules[c].Set(volume.Params[c], volume.Fields[c].GetRange());
    channels.push_back({ &pyramids[c], &rules[c] });
  }
  const double size[3] = { 2.0, 2.0, 2.0 };
  ASSERT_TRUE(grid.Configure(pyramids[components[0]].GetCellDimensions(), size));
  grid.Classify(channels, volume.Params[0].Interp);
}
}

// A homogeneous slab: every sample has component opacities w_c a_c (a_c corrected), opacity
// sum (w_c a_c)^2 / sum w_c a_c and premultiplied colour sum w_c a_c rgb_c, as VTK's ray
// cast mappers combine them; n such samples composite to 1 - (1 - a)^n.
TEST(Components, SlabCombinesTheComponentsAsVTKDoes)
{
  TwoComponents volume(SlabDims, [](int c, int, int, int) { return c == 0 ? 100.f : 200.f; });
  SetConstant(volume.Params[0], 0.02, { 1.f, 0.f, 0.f }, 0.7);
  SetConstant(volume.Params[1], 0.05, { 0.f, 0.2f, 1.f }, 0.4);
  ASSERT_TRUE(volume.Prepare());
  parc::CastStatistics stats;
  const auto rgba = volume.Cast(MakeRay({ 1.5, 1.5, -10.0 }, { 0, 0, 1 }), stats);

  const double w[2] = { 0.7, 0.4 }, a[2] = { 0.02, 0.05 };
  const double rgb[2][3] = { { 1.0, 0.0, 0.0 }, { 0.0, 0.2, 1.0 } };
  double sum = 0.0, squares = 0.0, premultiplied[3] = { 0.0, 0.0, 0.0 };
  for (int c = 0; c < 2; ++c)
  {
    const double weighted = w[c] * (1.0 - std::pow(1.0 - a[c], 0.125));
    sum += weighted;
    squares += weighted * weighted;
    for (int k = 0; k < 3; ++k)
    {
      premultiplied[k] += weighted * rgb[c][k];
    }
  }
  const double alpha = squares / sum;
  const double accumulated = 1.0 - std::pow(1.0 - alpha, 801.0);
  EXPECT_NEAR(rgba[3], accumulated, 1e-4);
  for (int k = 0; k < 3; ++k)
  {
    EXPECT_NEAR(rgba[k], premultiplied[k] * accumulated / alpha, 1e-4) << "channel " << k;
  }
  EXPECT_EQ(stats.Samples, 801u);
  EXPECT_EQ(stats.ContributingSamples, 801u) << "a sample counts once, not per component";
}

// A component of weight 0 is neither sampled nor shaded: the image is component 0's alone
// (up to the rounding of compositing premultiplied colours), with as many gradients.
TEST(Components, ZeroWeightCostsNothing)
{
  const int n[3] = { 33, 30, 28 };
  TwoComponents volume(n, [](int c, int i, int j, int k) { return Blob(c, i, j, k); });
  SetBlobs(volume);
  volume.Params[0].ComponentWeight = 1.0;
  volume.Params[1].ComponentWeight = 0.0;
  ASSERT_TRUE(volume.Prepare());
  parc::RayCaster alone;
  ASSERT_TRUE(alone.Prepare({ &volume.Fields[0], &volume.Params[0] }));
  const parc::Camera view = ParallelView(32, 32, 0.4);
  std::vector<float> both(4 * 32 * 32), single(4 * 32 * 32);
  parc::CastStatistics s1, s2;
  volume.Casters[0].CastImage(view, nullptr, parc::WholeRaySource(), both.data(), s1);
  alone.CastImage(view, nullptr, parc::WholeRaySource(), single.data(), s2);
  for (std::size_t i = 0; i < both.size(); ++i)
  {
    ASSERT_NEAR(both[i], single[i], 1e-6) << "value " << i;
  }
  EXPECT_GT(s2.ContributingSamples, 0u);
  EXPECT_EQ(s1.ContributingSamples, s2.ContributingSamples);
  EXPECT_EQ(s1.GradientEvaluations, s2.GradientEvaluations);

  // Component 1 of weight 0 contributes nowhere to the classification either.
  parc::ContributionRule rule;
  rule.Set(volume.Params[1], volume.Fields[1].GetRange());
  EXPECT_FALSE(rule.IsPossiblyContributing(0.0, 255.0));
}

// Maximum and minimum intensity: each component's own extreme along the ray, then colour
// sum w_c a_c rgb_c and opacity min(1, sum w_c a_c).
TEST(Components, ExtremesAreTakenPerComponent)
{
  std::mt19937 rng(17);
  const int n[3] = { 8, 8, 8 };
  TwoComponents volume(n, [&](int, int, int, int) { return static_cast<float>(rng() % 256); });
  const double w[2] = { 0.9, 0.5 };
  for (int c = 0; c < 2; ++c)
  {
    CastParameters& p = volume.Params[c];
    p.Opacity.SetNodes({ 0.0, 255.0 }, { 0.0, 1.0 }, true);
    p.Color.SetTable(0.0, 255.0,
      c == 0 ? std::vector<float>{ 1.f, 0.f, 0.f, 1.f, 0.f, 0.f }
             : std::vector<float>{ 0.f, 1.f, 0.f, 0.f, 1.f, 0.f });
    p.Interp = parc::Interpolation::Nearest;
    p.SampleDistance = 0.25;
    p.ComponentWeight = w[c];
  }
  for (const int sign : { 1, -1 })
  {
    for (CastParameters& p : volume.Params)
    {
      p.Blend = sign > 0 ? BlendMode::MaximumIntensity : BlendMode::MinimumIntensity;
    }
    ASSERT_TRUE(volume.Prepare());
    double extreme[2];
    for (int c = 0; c < 2; ++c)
    {
      extreme[c] = volume.Fields[c].GetValue(0, 3, 5);
      for (int i = 1; i < 8; ++i)
      {
        const double v = volume.Fields[c].GetValue(i, 3, 5);
        extreme[c] = sign > 0 ? std::max(extreme[c], v) : std::min(extreme[c], v);
      }
    }
    parc::CastStatistics stats;
    const auto rgba = volume.Cast(MakeRay({ -3.0, 3.0, 5.0 }, { 1, 0, 0 }), stats);
    const double a0 = w[0] * extreme[0] / 255.0, a1 = w[1] * extreme[1] / 255.0;
    EXPECT_NEAR(rgba[0], a0, 1e-6) << "sign " << sign;
    EXPECT_NEAR(rgba[1], a1, 1e-6) << "sign " << sign;
    EXPECT_EQ(rgba[2], 0.f);
    EXPECT_NEAR(rgba[3], std::min(1.0, a0 + a1), 1e-6) << "sign " << sign;
  }
}

// The classification keeps the supercells where either component may contribute: the
// oracle's segments then give the unaccelerated image bit for bit (shaded, with gradient
// opacity, for 1 and 4 threads); component 0's supercells alone would lose component 1.
TEST(Components, UnionClassificationGivesBitIdenticalImages)
{
  const int n[3] = { 33, 30, 28 };
  TwoComponents volume(n, [](int c, int i, int j, int k) { return Blob(c, i, j, k); });
  SetBlobs(volume);
  ASSERT_TRUE(volume.Prepare());
  parc::RangePyramid pyramids[2];
  parc::ContributionRule rules[2];
  parc::SupercellGrid both, first;
  ClassifyComponents(volume, { 0, 1 }, pyramids, rules, both);
  ClassifyComponents(volume, { 0 }, pyramids, rules, first);
  EXPECT_GT(both.GetNumberOfContributing(), first.GetNumberOfContributing());
  EXPECT_LT(both.GetNumberOfContributing(), both.GetNumberOfSupercells());

  const parc::SegmentOracle oracle(both, volume.Casters[0].GetWorldToIndex());
  const parc::SegmentOracle firstOracle(first, volume.Casters[0].GetWorldToIndex());
  const std::size_t values = 4 * 48 * 40;
  for (const double angle : { 0.4, 2.2 })
  {
    const parc::Camera view = ParallelView(48, 40, angle);
    std::vector<float> whole(values), accelerated(values), lossy(values);
    parc::CastStatistics s1, s2, s3;
    vtkSMPTools::Initialize(1);
    volume.Casters[0].CastImage(view, nullptr, parc::WholeRaySource(), whole.data(), s1);
    vtkSMPTools::Initialize(4);
    volume.Casters[0].CastImage(view, nullptr, oracle, accelerated.data(), s2);
    volume.Casters[0].CastImage(view, nullptr, firstOracle, lossy.data(), s3);
    EXPECT_EQ(0, std::memcmp(whole.data(), accelerated.data(), values * sizeof(float)))
      << "angle " << angle;
    EXPECT_NE(0, std::memcmp(whole.data(), lossy.data(), values * sizeof(float)))
      << "angle " << angle;
    EXPECT_LT(s2.Samples, s1.Samples);
    EXPECT_EQ(s1.ContributingSamples, s2.ContributingSamples);
    EXPECT_GT(s1.ContributingSamples, 0u);
    EXPECT_GT(s1.GradientEvaluations, 0u);
  }
}

// Components the caster cannot combine are refused, and none is kept.
TEST(Components, RejectsComponentsItCannotCombine)
{
  const int n[3] = { 6, 5, 4 };
  TwoComponents volume(n, [](int c, int i, int, int) { return static_cast<float>(c * 10 + i); });
  ASSERT_TRUE(volume.Prepare());
  EXPECT_EQ(volume.Casters[0].GetComponents().size(), 1u);

  volume.Params[1].SampleDistance = 0.5; // another lattice
  ASSERT_TRUE(volume.Casters[1].Prepare({ &volume.Fields[1], &volume.Params[1] }));
  EXPECT_FALSE(volume.Casters[0].SetComponents({ { &volume.Casters[1], 1 } }));
  EXPECT_TRUE(volume.Casters[0].GetComponents().empty());

  for (CastParameters& p : volume.Params)
  {
    p.SampleDistance = 1.0;
    p.Blend = BlendMode::IsoSurface; // no combination defined
    p.IsoValues = { 3.0 };
  }
  EXPECT_FALSE(volume.Prepare());

  for (CastParameters& p : volume.Params)
  {
    p.Blend = BlendMode::Composite;
  }
  ASSERT_TRUE(volume.Prepare());
  EXPECT_FALSE(volume.Casters[0].SetComponents(std::vector<parc::RayCaster::Component>(
    parc::MaxComponents, { &volume.Casters[1], 1 })))
    << "at most MaxComponents in all";
}
