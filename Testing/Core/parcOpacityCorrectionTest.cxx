// The opacity correction for the sample distance against std::pow in double, and a lane's
// bits alone and in a block.
#include "parcOpacityCorrection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

using parc::OpacityCorrection;

namespace
{
constexpr int BlockLanes = 32;

/// Whether c is within 1.2e-7 of 1 - (1 - a)^e or of 1 - t^e for the float t = 1 - a
/// (what a power of the transparency gets), both in double.
bool NearTheExactValue(float c, float a, float e)
{
  const double exact = 1.0 - std::pow(1.0 - static_cast<double>(a), static_cast<double>(e));
  const double ofFloat = 1.0 - std::pow(static_cast<double>(1.f - a), static_cast<double>(e));
  constexpr double tolerance = 1.2e-7;
  return std::abs(c - exact) <= tolerance || std::abs(c - ofFloat) <= tolerance;
}

/// Opacities of every kind: from 0 up, small ones (1 - a rounds), ones near 1, and ones at
/// and around the series' bound.
std::array<float, BlockLanes> Opacities(std::mt19937& rng, float bound)
{
  std::uniform_real_distribution<float> uniform(0.f, 1.f);
  std::array<float, BlockLanes> a;
  for (int j = 0; j < BlockLanes; ++j)
  {
    float v = uniform(rng);
    switch (j % 5)
    {
      case 0: v = v * v * v * v; break;
      case 1: v = 1.f - v * v * v * v; break;
      case 2: v = bound > 0.f ? bound * (1.f + (v - 0.5f) * 1e-5f) : v; break;
      case 3: v = bound > 0.f ? bound * v : v; break;
      default: break;
    }
    a[j] = std::min(std::max(v, 0.f), std::nextafter(1.f, 0.f));
  }
  a[BlockLanes - 1] = bound; // exactly at the bound
  std::shuffle(a.begin(), a.end(), rng);
  return a;
}
} // namespace

TEST(OpacityCorrection, MatchesThePowerAloneAndInABlock)
{
  std::mt19937 rng(11);
  for (const double exponent : { 0.0, 1e-3, 1.0 / 12.0, 1.0 / 6.0, 0.25, 0.3, 1.0 / 3.0, 0.5,
         0.7, 0.99, 1.5, 2.0, 3.0, 3.7, 10.0, 100.0 })
  {
    const auto e = static_cast<float>(exponent);
    OpacityCorrection correction;
    correction.SetExponent(e);
    for (int trial = 0; trial < 20000; ++trial)
    {
      const std::array<float, BlockLanes> a = Opacities(rng, correction.GetSeriesBound());
      std::array<float, BlockLanes> block = a;
      correction.CorrectLanes<BlockLanes>(block.data());
      for (int j = 0; j < BlockLanes; ++j)
      {
        ASSERT_TRUE(NearTheExactValue(block[j], a[j], e))
          << block[j] << " for " << a[j] << " and the exponent " << e;
        ASSERT_EQ(correction.Correct(a[j]), block[j]) << "lane " << j << " alone and in a block";
      }
    }
    EXPECT_EQ(correction.Correct(0.f), 0.f);
    EXPECT_EQ(correction.Correct(1.f), 1.f);
    EXPECT_EQ(correction.Correct(1.5f), 1.5f) << "an opacity of 1 or more stays as it is";
  }
}

TEST(OpacityCorrection, TakesRootsForPowersOfAHalfAndTheSeriesBelowItsBound)
{
  OpacityCorrection correction;
  correction.SetExponent(0.125f);
  EXPECT_EQ(correction.GetRoots(), 3);
  EXPECT_EQ(correction.Correct(0.75f), 1.f - std::sqrt(std::sqrt(std::sqrt(0.25f))));

  correction.SetExponent(1.f / 6.f);
  EXPECT_EQ(correction.GetRoots(), 0);
  EXPECT_GT(correction.GetSeriesBound(), 0.2f) << "most opacities of a translucent volume";
  EXPECT_LT(correction.GetSeriesBound(), 0.5f);

  correction.SetExponent(1.f);
  EXPECT_TRUE(correction.IsIdentity());
  EXPECT_EQ(correction.Correct(0.3f), 0.3f);

  correction.SetExponent(1.5f);
  EXPECT_EQ(correction.GetSeriesBound(), 0.f) << "no series where its terms alternate";
  EXPECT_TRUE(NearTheExactValue(correction.Correct(0.1f), 0.1f, 1.5f));
}
