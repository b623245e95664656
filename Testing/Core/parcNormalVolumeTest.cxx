// Quantized normals (the fast shading model): the encoding, the normals of a field, and
// the caster's table shading against the exact model.
#include "parcNormalVolume.h"
#include "parcRayCaster.h"
#include "parcClassification.h"
#include "parcSegmentOracle.h"
#include "parcSupercellGrid.h"
#include "parcTestUtilities.h"

#include <vtkSMPTools.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

namespace
{
using parc::NormalVolume;
using parc::Vec3;

double AngleBetween(const Vec3& a, const Vec3& b)
{
  const double c = parc::Dot(parc::Normalized(a), parc::Normalized(b));
  return std::acos(std::min(std::max(c, -1.0), 1.0));
}

/// Shaded blobs lit by one directional light (composite, sample distance 0.5).
parc::CastParameters ShadedBlobParameters(parc::ShadingModel model, const NormalVolume* normals)
{
  parc::CastParameters p;
  p.Opacity.SetNodes({ 0.0, 60.0, 200.0 }, { 0.0, 0.0, 0.5 }, true);
  p.Color.SetTable(0.0, 255.0, { 1.f, 0.5f, 0.f, 0.f, 0.5f, 1.f });
  p.SampleDistance = 0.5;
  p.Shade = true;
  p.Ambient = 0.2;
  p.Diffuse = 0.6;
  p.Specular = 0.3;
  parc::Light light;
  light.Position = { 16.0 - 80.0 * std::sin(0.3), 40.0, 16.0 + 80.0 * std::cos(0.3) };
  light.FocalPoint = { 16.0, 16.0, 16.0 };
  p.Lights = { light };
  p.Shading = model;
  p.Normals = normals;
  // The test camera (ParallelView at angle 0.3) looks along (sin a, 0, -cos a).
  p.ShadingViewDirection = { -std::sin(0.3), 0.0, std::cos(0.3) };
  return p;
}

std::vector<float> CastBlobs(const parc::ScalarField& field, const parc::CastParameters& p,
  const parc::SegmentSource& source, parc::CastStatistics& stats, bool* quantized = nullptr)
{
  parc::RayCaster caster;
  EXPECT_TRUE(caster.Prepare({ &field, &p }));
  if (quantized)
  {
    *quantized = caster.UsesQuantizedNormals();
  }
  std::vector<float> image(4 * 64 * 64);
  caster.CastImage(parctest::ParallelView(64, 64, 0.3), nullptr, source, image.data(), stats);
  return image;
}

bool SameBits(const std::vector<float>& a, const std::vector<float>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}
}

TEST(NormalVolume, EncodingStaysWithinItsAngularError)
{
  std::mt19937 rng(11);
  std::normal_distribution<double> gauss;
  double worst = 0.0;
  for (int n = 0; n < 200000; ++n)
  {
    const Vec3 d{ gauss(rng), gauss(rng), gauss(rng) };
    worst = std::max(worst, AngleBetween(d, NormalVolume::Decode(NormalVolume::Encode(d))));
  }
  // The axes and the folds of the octahedron, where rounding is hardest.
  for (const Vec3& d : { Vec3{ 0, 0, -1 }, Vec3{ 1, 0, 0 }, Vec3{ 0, -1, 0 }, Vec3{ 1, 1, -1e-9 },
         Vec3{ -1, 1, 1e-9 }, Vec3{ 1e-12, 0, -1 } })
  {
    const std::uint16_t code = NormalVolume::Encode(d);
    EXPECT_NE(code, NormalVolume::ZeroNormal);
    EXPECT_LT(code, NormalVolume::Count);
    worst = std::max(worst, AngleBetween(d, NormalVolume::Decode(code)));
  }
  EXPECT_LE(worst, NormalVolume::MaxEncodingError);
  EXPECT_GT(worst, NormalVolume::MaxEncodingError / 4) << "the bound is not far too loose";
}

TEST(NormalVolume, ZeroAndNonFiniteGradientsHaveNoNormal)
{
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (const Vec3& d : { Vec3{ 0, 0, 0 }, Vec3{ nan, 1, 0 }, Vec3{ inf, 0, 0 } })
  {
    EXPECT_EQ(NormalVolume::Encode(d), NormalVolume::ZeroNormal);
  }
  const Vec3 zero = NormalVolume::Decode(NormalVolume::ZeroNormal);
  EXPECT_EQ(parc::Length(zero), 0.0);
}

// A linear field has the same gradient at every voxel, faces included (one-sided
// differences there); a constant one has none.
TEST(NormalVolume, VoxelNormalsFollowTheGradient)
{
  const int n[3] = { 7, 6, 5 };
  const parc::ScalarField linear = parctest::MakeField(
    n, [](int i, int j, int k) { return static_cast<float>(3 * i + 2 * j - k); });
  NormalVolume normals;
  normals.Build(linear);
  EXPECT_EQ(normals.GetMemorySize(), 7u * 6u * 5u * sizeof(std::uint16_t));
  for (int k = 0; k < n[2]; ++k)
  {
    for (int j = 0; j < n[1]; ++j)
    {
      for (int i = 0; i < n[0]; ++i)
      {
        const Vec3 d = NormalVolume::Decode(normals.At(i, j, k));
        ASSERT_LE(AngleBetween(d, { 3, 2, -1 }), NormalVolume::MaxEncodingError)
          << i << " " << j << " " << k;
      }
    }
  }
  const parc::ScalarField flat = parctest::MakeField(n, [](int, int, int) { return 4.f; });
  normals.Build(flat);
  EXPECT_EQ(normals.At(3, 3, 3), NormalVolume::ZeroNormal);
  normals.Clear();
  EXPECT_TRUE(normals.IsEmpty());
  EXPECT_EQ(normals.GetMemorySize(), 0u);
}

TEST(NormalVolume, BuildIsTheSameForOneAndManyThreads)
{
  const parc::ScalarField field = parctest::Blobs();
  NormalVolume one, many;
  vtkSMPTools::Initialize(1);
  one.Build(field);
  vtkSMPTools::Initialize(4);
  many.Build(field);
  const int* n = field.GetDimensions();
  for (int k = 0; k < n[2]; ++k)
  {
    for (int j = 0; j < n[1]; ++j)
    {
      for (int i = 0; i < n[0]; ++i)
      {
        ASSERT_EQ(one.At(i, j, k), many.At(i, j, k));
      }
    }
  }
}

// The table shading replaces the gradient: no gradient is evaluated, the image is close to
// the exact model's but not the same, and it does not depend on the segment source or the
// number of threads; with linear and nearest interpolation.
TEST(NormalVolume, QuantizedShadingIsCloseToExactAndTheSameForEverySource)
{
  const parc::ScalarField field = parctest::Blobs();
  NormalVolume normals;
  normals.Build(field);
  for (const parc::Interpolation interpolation :
    { parc::Interpolation::Linear, parc::Interpolation::Nearest })
  {
    SCOPED_TRACE(interpolation == parc::Interpolation::Linear ? "linear" : "nearest");
    auto exactParameters = ShadedBlobParameters(parc::ShadingModel::Exact, nullptr);
    auto quantizedParameters = ShadedBlobParameters(parc::ShadingModel::QuantizedNormals, &normals);
    exactParameters.Interp = quantizedParameters.Interp = interpolation;
    parc::CastStatistics exactStats, wholeStats, oracleStats, oneThreadStats;
    bool quantized = false;
    const auto exact = CastBlobs(field, exactParameters, parc::WholeRaySource(), exactStats);
    vtkSMPTools::Initialize(4);
    const auto whole =
      CastBlobs(field, quantizedParameters, parc::WholeRaySource(), wholeStats, &quantized);
    EXPECT_TRUE(quantized);
    EXPECT_EQ(wholeStats.GradientEvaluations, 0u);
    EXPECT_GT(exactStats.GradientEvaluations, 1000u);

    parc::RangePyramid pyramid;
    pyramid.Build(field);
    parc::ContributionRule rule;
    rule.Set(quantizedParameters, field.GetRange());
    parc::SupercellGrid grid;
    const double size[3] = { 2.0, 2.0, 2.0 };
    ASSERT_TRUE(grid.Configure(pyramid.GetCellDimensions(), size));
    grid.Classify(pyramid, rule, interpolation);
    const parc::SegmentOracle oracle(grid, parc::Matrix4()); // voxel-index rays
    const auto oracleImage = CastBlobs(field, quantizedParameters, oracle, oracleStats);
    EXPECT_TRUE(SameBits(whole, oracleImage));
    EXPECT_LT(oracleStats.Samples, wholeStats.Samples);
    vtkSMPTools::Initialize(1);
    EXPECT_TRUE(SameBits(whole,
      CastBlobs(field, quantizedParameters, parc::WholeRaySource(), oneThreadStats)));

    double sum = 0.0, largest = 0.0;
    for (std::size_t i = 0; i < exact.size(); ++i)
    {
      const double d = std::abs(exact[i] - whole[i]);
      sum += d;
      largest = std::max(largest, d);
    }
    EXPECT_GT(largest, 0.0) << "the quantized model is in use";
    EXPECT_LT(sum / exact.size(), 0.01);
    EXPECT_LT(largest, 0.15);
  }
}

// Lights that the table cannot hold (positional, shadow-casting) and normals of another
// field shade exactly.
TEST(NormalVolume, OtherLightsFallBackToExactShading)
{
  const parc::ScalarField field = parctest::Blobs();
  NormalVolume normals;
  normals.Build(field);
  auto exactParameters = ShadedBlobParameters(parc::ShadingModel::Exact, nullptr);
  auto quantizedParameters = ShadedBlobParameters(parc::ShadingModel::QuantizedNormals, &normals);
  exactParameters.Lights[0].Positional = quantizedParameters.Lights[0].Positional = true;
  parc::CastStatistics s1, s2;
  bool quantized = true;
  const auto exact = CastBlobs(field, exactParameters, parc::WholeRaySource(), s1);
  EXPECT_TRUE(SameBits(exact,
    CastBlobs(field, quantizedParameters, parc::WholeRaySource(), s2, &quantized)));
  EXPECT_FALSE(quantized);
  EXPECT_GT(s2.GradientEvaluations, 0u);

  quantizedParameters.Lights[0].Positional = false;
  quantizedParameters.Lights[0].ShadowAttenuation = 1.0;
  CastBlobs(field, quantizedParameters, parc::WholeRaySource(), s2, &quantized);
  EXPECT_FALSE(quantized);

  quantizedParameters.Lights[0].ShadowAttenuation = 0.0;
  const int n[3] = { 4, 4, 4 };
  NormalVolume other;
  other.Build(parctest::MakeField(n, [](int i, int, int) { return static_cast<float>(i); }));
  quantizedParameters.Normals = &other;
  CastBlobs(field, quantizedParameters, parc::WholeRaySource(), s2, &quantized);
  EXPECT_FALSE(quantized);
}
