// The acceleration plan: work is done once per input change, and a failed classification
// leaves nothing stale behind.
#include "parcAccelerationPlan.h"
#include "parcTestUtilities.h"

#include <gtest/gtest.h>

namespace
{
/// A rule that keeps the scalars in [lo, 255] (composite, opacity 0 below lo).
parc::ContributionRule Rule(const parc::ScalarField& field, double lo)
{
  parc::CastParameters p;
  parctest::SetOpacity(p, { 0.0, lo - 1.0, lo, 255.0 }, { 0.0, 0.0, 1.0, 1.0 });
  parc::ContributionRule rule;
  rule.Set(p, field.GetRange());
  return rule;
}
}

TEST(AccelerationPlan, BuildsThePyramidOncePerFieldAndAModelOncePerClassification)
{
  const parc::ScalarField field = parctest::Blobs();
  parc::AccelerationPlan plan;
  const double size[3] = { 2, 2, 2 };
  double fitted[3];
  ASSERT_TRUE(plan.Classify(field, 1, Rule(field, 200), parc::Interpolation::Linear, size, fitted));
  const std::size_t narrow = plan.GetGrid().GetNumberOfContributing();
  const std::uint64_t first = plan.GetModelVersion();
  plan.GetDepthModel(false);
  plan.GetDepthModel(false);
  EXPECT_EQ(plan.GetModelBuilds(), 1u) << "one model per classification";

  ASSERT_TRUE(plan.Classify(field, 1, Rule(field, 50), parc::Interpolation::Linear, size, fitted));
  EXPECT_EQ(plan.GetPyramidBuilds(), 1u) << "the same field keeps its pyramid";
  EXPECT_EQ(plan.GetClassifications(), 2u);
  EXPECT_GT(plan.GetGrid().GetNumberOfContributing(), narrow);
  EXPECT_NE(plan.GetModelVersion(), first);
  const std::size_t quads = plan.GetDepthModel(false).GetNumberOfQuads();
  EXPECT_EQ(plan.GetModelBuilds(), 2u) << "a new classification makes a new model";
  EXPECT_EQ(plan.GetDepthQuads(), quads);

  // Uploaded: the vertices go and are not made again while the GPU holds them.
  plan.ReleaseDepthVertices();
  EXPECT_TRUE(plan.GetDepthModel(true).Vertices.empty());
  EXPECT_EQ(plan.GetModelBuilds(), 2u);
  EXPECT_EQ(plan.GetDepthQuads(), quads) << "the quad count outlives the vertices";
  // A context without the upload needs them again.
  EXPECT_EQ(plan.GetDepthModel(false).GetNumberOfQuads(), quads);
  EXPECT_EQ(plan.GetModelBuilds(), 3u);

  ASSERT_TRUE(plan.Classify(field, 2, Rule(field, 50), parc::Interpolation::Linear, size, fitted));
  EXPECT_EQ(plan.GetPyramidBuilds(), 2u) << "a new field version makes a new pyramid";
}

TEST(AccelerationPlan, AnInvalidSizeLeavesAnEmptyGrid)
{
  const parc::ScalarField field = parctest::Blobs();
  parc::AccelerationPlan plan;
  const double good[3] = { 2, 2, 2 }, bad[3] = { 0, 2, 2 };
  double fitted[3];
  ASSERT_TRUE(plan.Classify(field, 1, Rule(field, 50), parc::Interpolation::Linear, good, fitted));
  EXPECT_GT(plan.GetGrid().GetNumberOfSupercells(), 0u);
  EXPECT_FALSE(plan.Classify(field, 1, Rule(field, 50), parc::Interpolation::Linear, bad, fitted));
  EXPECT_EQ(plan.GetGrid().GetNumberOfSupercells(), 0u) << "no stale grid";
}

TEST(AccelerationPlan, ColourModelsHaveVersionsOfTheirOwn)
{
  const parc::ScalarField field = parctest::Blobs();
  parc::AccelerationPlan plan;
  const double size[3] = { 2, 2, 2 };
  double fitted[3];
  std::vector<std::uint64_t> versions;
  for (int round = 0; round < 2; ++round)
  {
    ASSERT_TRUE(
      plan.Classify(field, 1, Rule(field, 50), parc::Interpolation::Linear, size, fitted));
    for (int axis = 0; axis < 3; ++axis)
    {
      versions.push_back(plan.GetColorModelVersion(axis));
    }
  }
  std::sort(versions.begin(), versions.end());
  EXPECT_EQ(std::unique(versions.begin(), versions.end()), versions.end());
  EXPECT_EQ(plan.GetColorModel(1, false).MajorAxis, 1);
}
