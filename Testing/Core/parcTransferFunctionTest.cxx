// The exact piecewise-linear transfer function and its interval test.
#include "parcTransferFunction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using parc::PiecewiseLinearFunction;

TEST(PiecewiseLinear, InterpolatesBetweenNodesAndHitsNodesExactly)
{
  PiecewiseLinearFunction f;
  f.SetNodes({ 0.0, 10.0, 20.0 }, { 0.0, 1.0, 0.5 }, true);
  EXPECT_FLOAT_EQ(f.Evaluate(0.0), 0.f);
  EXPECT_FLOAT_EQ(f.Evaluate(5.0), 0.5f);
  EXPECT_FLOAT_EQ(f.Evaluate(10.0), 1.f);
  EXPECT_FLOAT_EQ(f.Evaluate(15.0), 0.75f);
  EXPECT_FLOAT_EQ(f.Evaluate(20.0), 0.5f);
}

TEST(PiecewiseLinear, ClampingDecidesTheValueOutsideTheRange)
{
  PiecewiseLinearFunction clamped, unclamped;
  clamped.SetNodes({ 0.0, 1.0 }, { 0.2, 0.7 }, true);
  unclamped.SetNodes({ 0.0, 1.0 }, { 0.2, 0.7 }, false);
  EXPECT_FLOAT_EQ(clamped.Evaluate(-5.0), 0.2f);
  EXPECT_FLOAT_EQ(clamped.Evaluate(5.0), 0.7f);
  EXPECT_FLOAT_EQ(unclamped.Evaluate(-5.0), 0.f);
  EXPECT_FLOAT_EQ(unclamped.Evaluate(5.0), 0.f);
  EXPECT_TRUE(clamped.IsNonZeroOn(-10.0, -9.0));
  EXPECT_FALSE(unclamped.IsNonZeroOn(-10.0, -9.0));
}

TEST(PiecewiseLinear, ZeroAtATouchingNodeIsNotNonZero)
{
  PiecewiseLinearFunction f; // zero up to 10, then rising
  f.SetNodes({ 0.0, 10.0, 20.0 }, { 0.0, 0.0, 1.0 }, true);
  EXPECT_FALSE(f.IsNonZeroOn(2.0, 10.0)) << "only the node at 10 (value 0) is touched";
  EXPECT_TRUE(f.IsNonZeroOn(2.0, 10.000001));
  EXPECT_EQ(f.FirstNonZero(), 10.0);
  EXPECT_EQ(f.LastNonZero(), std::numeric_limits<double>::infinity());
}

// Lane by lane, EvaluateLanes gives Evaluate's bits, on random functions of 1 to 20 nodes
// (steps, nodes between floats) at floats around the nodes, outside them, infinite and NaN,
// and leaves the lanes it is not asked for alone; so does EvaluateEightLanes on the
// functions of 2 to 7 nodes, where the processor has wide vectors (lanes asked for in
// whole groups of eight too, which it stores without keeping any).
TEST(PiecewiseLinear, LanesGiveEvaluatesBits)
{
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  constexpr int Lanes = 32;
  constexpr float Untouched = -123.f;
  const float inf = std::numeric_limits<float>::infinity();
  int eightLaneTrials = 0;
  for (int trial = 0; trial < 4000; ++trial)
  {
    std::vector<double> x, y;
    const int n = 1 + static_cast<int>(u(rng) * (trial % 2 == 0 ? 20 : 8));
    double pos = -3.0 + u(rng);
    for (int i = 0; i < n; ++i)
    {
      pos += u(rng) < 0.15 ? 0.0 : 0.7 * u(rng) + (u(rng) < 0.3 ? 0.1 : 0.0);
      x.push_back(pos);
      y.push_back(u(rng) < 0.3 ? 0.0 : u(rng) - 0.1); // a few negative values
    }
    PiecewiseLinearFunction f;
    f.SetNodes(x, y, u(rng) < 0.5);
    float s[Lanes], out[Lanes];
    for (float& v : s)
    {
      const double node = x[static_cast<std::size_t>(u(rng) * n) % n];
      const double pick = u(rng);
      v = pick < 0.4 ? std::nextafter(static_cast<float>(node),
                         u(rng) < 0.5 ? inf : -inf) // a neighbour of a node's float
        : pick < 0.6 ? static_cast<float>(node)
        : pick < 0.9 ? static_cast<float>(x.front() - 1.0 + (x.back() - x.front() + 2.0) * u(rng))
        : pick < 0.95 ? (u(rng) < 0.5 ? inf : -inf)
                      : std::numeric_limits<float>::quiet_NaN();
    }
    const unsigned random = static_cast<unsigned>(rng());
    const unsigned lanes = trial % 3 == 0 ? random : trial % 3 == 1 ? ~0u : random | 0x00FF00FFu;
    const auto expectEvaluates = [&](const char* how) {
      for (int j = 0; j < Lanes; ++j)
      {
        const float expected = (lanes >> j) & 1u ? f.Evaluate(s[j]) : Untouched;
        EXPECT_EQ(std::memcmp(&expected, &out[j], sizeof(float)), 0)
          << how << ", trial " << trial << ", lane " << j << ", s " << s[j] << ": " << out[j]
          << " instead of " << expected;
      }
    };
    std::fill_n(out, Lanes, Untouched);
    f.EvaluateLanes(s, lanes, out);
    expectEvaluates("EvaluateLanes");
#if PARC_WIDE_VECTORS
    EXPECT_EQ(f.PermutesPieces(), n >= 2 && n <= static_cast<int>(parc::MaxPermutedNodes));
    if (f.PermutesPieces() && parc::HasWideVectors())
    {
      std::fill_n(out, Lanes, Untouched);
      f.EvaluateEightLanes(s, lanes, out);
      expectEvaluates("EvaluateEightLanes");
      ++eightLaneTrials;
    }
#endif
  }
  if (parc::HasWideVectors())
  {
    EXPECT_GT(eightLaneTrials, 1000);
  }
}

TEST(PiecewiseLinear, ThresholdsOfABump)
{
  PiecewiseLinearFunction f;
  f.SetNodes({ 0.0, 10.0, 20.0, 30.0 }, { 0.0, 0.0, 1.0, 0.0 }, true);
  EXPECT_EQ(f.FirstNonZero(), 10.0);
  EXPECT_EQ(f.LastNonZero(), 30.0);
  PiecewiseLinearFunction zero;
  zero.SetNodes({ 0.0, 1.0 }, { 0.0, 0.0 }, true);
  EXPECT_TRUE(std::isinf(zero.FirstNonZero()) && zero.FirstNonZero() > 0);
  EXPECT_FALSE(zero.IsNonZeroOn(-1e9, 1e9));
}

// Property: on random functions and intervals, IsNonZeroOn is never false where a dense
// evaluation finds a non-zero value, and never true where the exact function is zero on the
// whole interval (checked at the nodes and interval ends, where a piecewise-linear maximum
// is).
TEST(PiecewiseLinear, IntervalTestAgreesWithBruteForce)
{
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial)
  {
    std::vector<double> x, y;
    const int n = 1 + static_cast<int>(u(rng) * 6);
    double pos = -1.0 + u(rng);
    for (int i = 0; i < n; ++i)
    {
      pos += (u(rng) < 0.1) ? 0.0 : u(rng); // some steps (equal x)
      x.push_back(pos);
      y.push_back(u(rng) < 0.5 ? 0.0 : u(rng));
    }
    const bool clamp = u(rng) < 0.5;
    PiecewiseLinearFunction f;
    f.SetNodes(x, y, clamp);
    double lo = -2.0 + 6.0 * u(rng), hi = lo + 2.0 * u(rng) * u(rng);
    if (u(rng) < 0.1 && !x.empty())
    {
      lo = hi = x[static_cast<size_t>(u(rng) * n) % n]; // a single point on a node
    }
    bool dense = false;
    for (int s = 0; s <= 2000; ++s)
    {
      dense = dense || f.Evaluate(lo + (hi - lo) * s / 2000.0) > 0.f;
    }
    bool exact = f.Evaluate(lo) > 0.f || f.Evaluate(hi) > 0.f;
    for (size_t i = 0; i < x.size(); ++i)
    {
      // A positive node value in [lo, hi] (a limit value at a step counts), or a positive
      // piece next to a node strictly inside.
      const bool positiveNear =
        (i + 1 < x.size() && y[i + 1] > 0.0) || (i > 0 && y[i - 1] > 0.0);
      exact = exact || (x[i] >= lo && x[i] <= hi && y[i] > 0.0) ||
        (x[i] > lo && x[i] < hi && positiveNear);
    }
    const bool claimed = f.IsNonZeroOn(lo, hi);
    EXPECT_TRUE(!dense || claimed) << "trial " << trial << " [" << lo << ", " << hi << "]";
    EXPECT_TRUE(!claimed || exact) << "trial " << trial << " [" << lo << ", " << hi << "]";
  }
}

TEST(ColorTable, InterpolatesAndClamps)
{
  parc::ColorTable t;
  t.SetTable(0.0, 2.0, { 0.f, 0.f, 0.f, 1.f, 0.5f, 0.f, 1.f, 1.f, 1.f });
  float rgb[3];
  t.Lookup(0.5, rgb);
  EXPECT_FLOAT_EQ(rgb[0], 0.5f);
  EXPECT_FLOAT_EQ(rgb[1], 0.25f);
  t.Lookup(-3.0, rgb);
  EXPECT_FLOAT_EQ(rgb[0], 0.f);
  t.Lookup(9.0, rgb);
  EXPECT_FLOAT_EQ(rgb[2], 1.f);
}

#if defined(__SSE2__)
// Four lanes at once give Lookup's bits, lane by lane: inside the table, on its entries,
// outside it, at infinities and NaN.
TEST(ColorTable, FourLanesGiveLookupsBits)
{
  std::mt19937 rng(78);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const float inf = std::numeric_limits<float>::infinity();
  for (int trial = 0; trial < 2000; ++trial)
  {
    const int n = 2 + static_cast<int>(u(rng) * 300);
    std::vector<float> rgb(3 * static_cast<std::size_t>(n));
    for (float& c : rgb)
    {
      c = static_cast<float>(u(rng));
    }
    const double lo = -1000.0 + 2000.0 * u(rng), hi = lo + (u(rng) < 0.05 ? 0.0 : 500.0 * u(rng));
    parc::ColorTable t;
    t.SetTable(lo, hi, rgb);
    alignas(16) float s[4];
    for (float& v : s)
    {
      const double pick = u(rng);
      v = pick < 0.7 ? static_cast<float>(lo - 10.0 + (hi - lo + 20.0) * u(rng))
        : pick < 0.85 ? static_cast<float>(lo + (hi - lo) * std::floor(u(rng) * n) / (n - 1))
        : pick < 0.95 ? (u(rng) < 0.5 ? inf : -inf)
                      : std::numeric_limits<float>::quiet_NaN();
    }
    __m128 four[4];
    t.LookupFour(_mm_load_ps(s), four);
    for (int l = 0; l < 4; ++l)
    {
      float expected[3];
      t.Lookup(s[l], expected);
      alignas(16) float got[4];
      _mm_store_ps(got, four[l]);
      EXPECT_EQ(std::memcmp(expected, got, sizeof(expected)), 0)
        << "trial " << trial << ", s " << s[l] << ": " << got[0] << " instead of " << expected[0];
      EXPECT_EQ(got[3], 0.f);
    }
  }
}
#endif
