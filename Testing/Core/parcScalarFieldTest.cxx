// Sampling, gradients and conversion of the scalar field.
#include "parcTestUtilities.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <type_traits>
#include <vector>

TEST(ScalarField, TrilinearReproducesLinearFieldsAndVoxelValues)
{
  const int n[3] = { 5, 6, 7 };
  auto linear = [](double x, double y, double z) { return 2.0 * x - 3.0 * y + 0.5 * z + 4.0; };
  const parc::ScalarField field =
    parctest::MakeField(n, [&](int i, int j, int k) { return static_cast<float>(linear(i, j, k)); });
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int s = 0; s < 500; ++s)
  {
    const parc::Vec3 p{ 4.0 * u(rng), 5.0 * u(rng), 6.0 * u(rng) };
    EXPECT_NEAR(field.SampleLinear(p), linear(p.X, p.Y, p.Z), 1e-4) << p.X << " " << p.Y << " " << p.Z;
    const parc::Vec3 g = field.Gradient(p, parc::Interpolation::Linear);
    EXPECT_NEAR(g.X, 2.0, 1e-4);
    EXPECT_NEAR(g.Y, -3.0, 1e-4);
    EXPECT_NEAR(g.Z, 0.5, 1e-4);
  }
  EXPECT_EQ(field.SampleLinear({ 2, 3, 4 }), field.GetValue(2, 3, 4));
  EXPECT_EQ(field.SampleLinear({ 4, 5, 6 }), field.GetValue(4, 5, 6)) << "the far corner";
}

namespace
{
// A field of random values over T's whole range (every `stride`-th of them read; 9x7x8
// voxels, or 140x70x68 in 3x2x2 bricks when bricked), sampled in lattice blocks along random
// rays: each sample must be the same bits as the sample at its own position, and its
// location the cell and fractions of that position. Returns the number of samples outside
// the box (clamped).
template <typename T>
std::size_t CheckLatticeBlocks(int stride, unsigned seed, bool bricked = false)
{
  const int small[3] = { 9, 7, 8 }, large[3] = { 140, 70, 68 };
  const int* n = bricked ? large : small;
  std::vector<T> values(static_cast<std::size_t>(stride) * n[0] * n[1] * n[2]);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (auto& v : values)
  {
    const double lo = static_cast<double>(std::numeric_limits<T>::lowest());
    const double hi = static_cast<double>(std::numeric_limits<T>::max());
    const double x = std::is_integral<T>::value ? std::floor(lo + (hi - lo + 1.0) * unit(rng))
                                               : 1000.0 * unit(rng) - 500.0;
    v = static_cast<T>(std::min(x, hi));
  }
  parc::ScalarField field;
  field.Wrap(values.data(), n, stride);
  EXPECT_TRUE(field.SetBricked(bricked));
  EXPECT_EQ(field.IsBricked(), bricked);
  EXPECT_EQ(field.GetBrickedMemorySize(), bricked ? 3 * 2 * 2 * 67 * 67 * 67 * sizeof(T) : 0);
  const double extent = *std::max_element(n, n + 3);
  std::uniform_real_distribution<double> u(-2.0, extent + 1.0);
  std::size_t outside = 0;
  for (int ray = 0; ray < 300; ++ray)
  {
    const parc::Vec3 o{ u(rng), u(rng), u(rng) };
    const parc::Vec3 d = parc::Normalized(parc::Vec3{ u(rng), u(rng), u(rng) } - o);
    const double dt = 0.05 + 0.5 * (ray % 7) / 7.0;
    const long k0 = static_cast<long>(rng() % 40) - 5;
    for (auto mode : { parc::Interpolation::Linear, parc::Interpolation::Nearest })
    {
      const int count = 1 + static_cast<int>(rng() % parc::LatticeBlock::Size);
      parc::LatticeBlock block;
      const parc::RayLattice lattice(o, d, n);
      field.Dispatch(
        [&](const auto& view) { view.SampleLattice(lattice, dt, k0, count, mode, block); });
      for (int j = 0; j < count; ++j)
      {
        const parc::Vec3 p = lattice.Point(static_cast<double>(k0 + j) * dt);
        const float expected = field.Sample(p, mode);
        EXPECT_EQ(0, std::memcmp(&expected, &block.Values[j], sizeof(float)))
          << ray << " " << j << ": " << expected << " " << block.Values[j];
        if (mode == parc::Interpolation::Linear)
        {
          const parc::Vec3 g = field.Dispatch([&](const auto& view) {
            const parc::SampleLocation where = block.Location(j);
            parc::CellDifferences differences;
            return view.Gradient(p, mode, differences, &where);
          });
          const parc::Vec3 expectedG = field.Gradient(p, mode);
          EXPECT_EQ(0, std::memcmp(&g, &expectedG, sizeof(g))) << ray << " " << j;
        }
        outside += (p.X < 0.0 || p.X > n[0] - 1 || p.Y < 0.0 || p.Y > n[1] - 1 || p.Z < 0.0 ||
          p.Z > n[2] - 1);
      }
    }
  }
  return outside;
}
}

// The caster takes a ray's lattice samples in blocks, loading 8- and 16-bit neighbours
// along x in pairs when they are next to each other (one component), one by one otherwise.
TEST(ScalarField, LatticeBlocksAreTheSamplesAtTheirPositions)
{
  for (int stride : { 1, 2 })
  {
    SCOPED_TRACE(stride);
    EXPECT_GT(CheckLatticeBlocks<std::uint8_t>(stride, 5), 100u) << "clamped positions too";
    CheckLatticeBlocks<std::int8_t>(stride, 6);
    CheckLatticeBlocks<std::uint16_t>(stride, 7);
    CheckLatticeBlocks<std::int16_t>(stride, 8);
    CheckLatticeBlocks<float>(stride, 9);
  }
}

// A copy in bricks (ScalarField::SetBricked) gives the same samples, locations and
// gradients, across the bricks' faces, in bricks copied a whole row at a time (the middle
// bricks along x, one component) and voxel by voxel (the first and last bricks, which the
// field fills only in part; two components); Wrap frees it.
TEST(ScalarField, BrickedLatticeBlocksAreTheSamplesAtTheirPositions)
{
  for (int stride : { 1, 2 })
  {
    SCOPED_TRACE(stride);
    EXPECT_GT(CheckLatticeBlocks<std::uint8_t>(stride, 15, true), 100u);
    CheckLatticeBlocks<std::int8_t>(stride, 16, true);
    CheckLatticeBlocks<std::uint16_t>(stride, 17, true);
    CheckLatticeBlocks<std::int16_t>(stride, 18, true);
    CheckLatticeBlocks<float>(stride, 19, true);
    CheckLatticeBlocks<double>(stride, 20, true);
  }
  const int n[3] = { 80, 3, 2 };
  std::vector<std::uint8_t> values(80 * 3 * 2, 7);
  parc::ScalarField field;
  field.Wrap(values.data(), n);
  ASSERT_TRUE(field.SetBricked(true));
  EXPECT_EQ(field.GetBrickedMemorySize(), 2u * 67 * 67 * 67);
  field.Wrap(values.data(), n);
  EXPECT_FALSE(field.IsBricked()) << "new values, no bricks of the old ones";
  EXPECT_TRUE(field.SetBricked(false));
  parc::ScalarField empty;
  EXPECT_FALSE(empty.SetBricked(true)) << "no values, no bricks";
}

// A ray's lattice points lie on the ray, within float rounding of the field's size,
// however far the ray's origin is: the points are made from where it passes the field.
TEST(ScalarField, LatticePointsStayPreciseForFarOrigins)
{
  const int dims[3] = { 300, 200, 500 };
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const double far : { 0.0, 1e4, 1e7, 1e10 })
  {
    for (int trial = 0; trial < 50; ++trial)
    {
      const parc::Vec3 target(150 + 150 * u(rng), 100 + 100 * u(rng), 250 + 250 * u(rng));
      const parc::Vec3 d = parc::Normalized(parc::Vec3(u(rng), u(rng), u(rng)));
      const double dt = 0.37;
      const parc::Vec3 o = target - far * d; // the eye, far back along the ray
      const parc::RayLattice lattice(o, d, dims);
      for (int step = -800; step <= 800; step += 57)
      {
        const double t = far + step * dt; // near target
        const parc::Vec3 exact = o + t * d, p = lattice.Point(t);
        // Float rounding of coordinates up to ~1000 voxels; at 1e10 t itself is only
        // known to ~1e-6 of a voxel in double.
        EXPECT_LT(parc::Length(p - exact), 2e-4) << far << " " << step;
      }
    }
  }
}

TEST(ScalarField, NearestRoundsAndOutsideIsClamped)
{
  const int n[3] = { 3, 3, 3 };
  const parc::ScalarField field =
    parctest::MakeField(n, [](int i, int j, int k) { return static_cast<float>(i + 10 * j + 100 * k); });
  EXPECT_EQ(field.SampleNearest({ 0.49, 1.51, 2.0 }), 0 + 20 + 200);
  EXPECT_EQ(field.SampleNearest({ 0.5, 0.0, 0.0 }), 1) << "ties round up";
  EXPECT_EQ(field.SampleLinear({ -5.0, 1.0, 1.0 }), field.GetValue(0, 1, 1));
  EXPECT_EQ(field.SampleLinear({ 9.0, 9.0, 9.0 }), field.GetValue(2, 2, 2));
}

TEST(ScalarField, TrilinearStaysWithinTheCellRange)
{
  // The classification relies on samples lying in [cell min, cell max] (up to rounding).
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const int n[3] = { 2, 2, 2 };
  for (int trial = 0; trial < 2000; ++trial)
  {
    float v[8];
    for (float& x : v)
    {
      x = static_cast<float>(1000.0 * u(rng) - 500.0);
    }
    parc::ScalarField field;
    field.Assign(v, n);
    const float lo = *std::min_element(v, v + 8), hi = *std::max_element(v, v + 8);
    const float s = field.SampleLinear({ u(rng), u(rng), u(rng) });
    const float slack = 64.f * std::numeric_limits<float>::epsilon() * std::max(std::fabs(lo), std::fabs(hi));
    EXPECT_GE(s, lo - slack);
    EXPECT_LE(s, hi + slack);
  }
}

TEST(ScalarField, ConvertsTypesAndReplacesNonFiniteValues)
{
  const int n[3] = { 2, 2, 1 };
  double in[4] = { std::nan(""), 3.0, -std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  parc::ScalarField field;
  EXPECT_EQ(field.Wrap(in, n), 3u);
  EXPECT_EQ(field.GetValue(0, 0, 0), 3.f) << "NaN becomes the smallest finite value";
  EXPECT_EQ(field.GetValue(0, 1, 0), 3.f);
  EXPECT_EQ(field.GetValue(1, 1, 0), 3.f);
  EXPECT_TRUE(std::isnan(in[0])) << "the caller's values are not changed";
  EXPECT_EQ(field.GetMemorySize(), 4 * sizeof(double)) << "non-finite input is copied";
  const std::uint16_t u16[4] = { 0, 65535, 7, 8 };
  EXPECT_EQ(field.Wrap(u16, n), 0u);
  EXPECT_EQ(field.GetScalarType(), parc::ScalarType::UInt16);
  EXPECT_EQ(field.GetValue(1, 0, 0), 65535.f);
  EXPECT_EQ(field.GetRange()[1], 65535.0);
  const std::int8_t s8[8] = { -128, 0, 1, 2, 3, 4, 5, 127 };
  EXPECT_EQ(field.Wrap(s8, n, 2), 0u) << "every second value of a 2-component array";
  EXPECT_EQ(field.GetValue(1, 0, 0), 1.f);
  EXPECT_EQ(field.GetValue(1, 1, 0), 5.f);
  EXPECT_EQ(field.GetRange()[0], -128.0);
  EXPECT_EQ(field.GetRange()[1], 5.0) << "the range is of the first component";
}

TEST(ScalarField, WrapReadsTheCallersValuesWithoutACopy)
{
  const int n[3] = { 3, 2, 2 };
  std::vector<std::uint8_t> values = { 0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110 };
  parc::ScalarField field;
  EXPECT_EQ(field.Wrap(values.data(), n), 0u);
  EXPECT_EQ(field.GetMemorySize(), 0u) << "8-bit values are sampled where they are";
  EXPECT_EQ(field.GetValue(2, 1, 1), 110.f);
  values[11] = 7;
  EXPECT_EQ(field.GetValue(2, 1, 1), 7.f) << "the field reads the caller's memory";
  parc::ScalarField copy;
  copy.Assign(values.data(), n);
  values[11] = 9;
  EXPECT_EQ(copy.GetValue(2, 1, 1), 7.f) << "Assign keeps a copy";
  EXPECT_EQ(copy.GetMemorySize(), values.size());
  const parc::ScalarField second = copy;
  EXPECT_EQ(second.GetValue(2, 1, 1), 7.f) << "copies of a field share its values";
  // The same values as float and as uint8 sample to the same bits.
  std::vector<float> asFloat(values.begin(), values.end());
  parc::ScalarField floats;
  floats.Wrap(asFloat.data(), n);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.5, 2.5);
  for (int s = 0; s < 1000; ++s)
  {
    const parc::Vec3 p{ u(rng), u(rng), u(rng) };
    ASSERT_EQ(field.SampleLinear(p), floats.SampleLinear(p));
    ASSERT_EQ(field.SampleNearest(p), floats.SampleNearest(p));
  }
}

// The linear gradient equals central differences of SampleLinear: exactly within one
// voxel of a face (where the offsets are clamped), up to float rounding inside (where it
// interpolates the voxel differences in the sample's own cell).
TEST(ScalarField, LinearGradientIsCentralDifferencesOfSamples)
{
  const int n[3] = { 7, 6, 5 };
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> value(-50.f, 200.f);
  const parc::ScalarField field = parctest::MakeField(n, [&](int, int, int) { return value(rng); });
  std::uniform_real_distribution<double> u(-1.5, 7.0);
  for (int s = 0; s < 4000; ++s)
  {
    parc::Vec3 p{ u(rng), u(rng), u(rng) };
    if (s % 4 == 0)
    {
      p[s % 3] = std::floor(p[s % 3]); // on a voxel plane
    }
    const parc::Vec3 g = field.Gradient(p, parc::Interpolation::Linear);
    for (int a = 0; a < 3; ++a)
    {
      parc::Vec3 lo = p, hi = p;
      lo[a] = std::max(p[a] - 1.0, 0.0);
      hi[a] = std::min(p[a] + 1.0, static_cast<double>(n[a] - 1));
      const double h = hi[a] - lo[a];
      const double expected =
        h > 0.0 ? (field.SampleLinear(hi) - field.SampleLinear(lo)) / h : 0.0;
      bool interior = true;
      for (int b = 0; b < 3; ++b)
      {
        interior = interior && p[b] >= 1.0 && p[b] < n[b] - 2.0;
      }
      if (interior)
      {
        ASSERT_NEAR(g[a], expected, 64 * FLT_EPSILON * 250.0) << "axis " << a << " at " << p.X << " " << p.Y << " " << p.Z;
      }
      else
      {
        ASSERT_EQ(g[a], expected) << "axis " << a << " at " << p.X << " " << p.Y << " " << p.Z;
      }
    }
  }
}

namespace
{
/// Gradients of a field of T's whole range against the same values as floats, at points
/// inside and near the faces: the same bits (8- and 16-bit differences are loaded row by
/// row, float ones value by value, and both are exact). stride 2: every second value.
template <typename T>
void ExpectIntegerGradientsOfFloats(int stride)
{
  const int n[3] = { 9, 8, 7 };
  std::mt19937 rng(13);
  std::uniform_int_distribution<int> value(
    std::numeric_limits<T>::min(), std::numeric_limits<T>::max());
  std::vector<T> values(static_cast<std::size_t>(stride) * n[0] * n[1] * n[2]);
  for (T& v : values)
  {
    v = static_cast<T>(value(rng));
  }
  values[0] = std::numeric_limits<T>::min(); // both extremes, next to each other
  values[stride] = std::numeric_limits<T>::max();
  std::vector<float> asFloat(values.size() / stride);
  for (std::size_t i = 0; i < asFloat.size(); ++i)
  {
    asFloat[i] = static_cast<float>(values[i * stride]);
  }
  parc::ScalarField integers, floats;
  integers.Wrap(values.data(), n, stride);
  floats.Wrap(asFloat.data(), n);
  std::uniform_real_distribution<double> u(-0.5, 8.5);
  for (int s = 0; s < 4000; ++s)
  {
    const parc::Vec3 p{ u(rng), u(rng), u(rng) };
    const parc::Vec3 a = integers.Gradient(p, parc::Interpolation::Linear);
    const parc::Vec3 b = floats.Gradient(p, parc::Interpolation::Linear);
    for (int axis = 0; axis < 3; ++axis)
    {
      ASSERT_EQ(a[axis], b[axis]) << "axis " << axis << " at " << p.X << " " << p.Y << " "
                                  << p.Z << ", stride " << stride;
    }
  }
}
}

TEST(ScalarField, IntegerGradientsAreThoseOfTheSameFloats)
{
  ExpectIntegerGradientsOfFloats<std::uint8_t>(1);
  ExpectIntegerGradientsOfFloats<std::int8_t>(1);
  ExpectIntegerGradientsOfFloats<std::uint16_t>(1);
  ExpectIntegerGradientsOfFloats<std::int16_t>(1);
  ExpectIntegerGradientsOfFloats<std::int16_t>(2);
}
