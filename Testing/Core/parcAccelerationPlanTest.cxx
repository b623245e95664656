// The acceleration plan: work is done once per input change, and a failed classification
// leaves nothing stale behind.
#include "parcAccelerationPlan.h"
#include "parcTestUtilities.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

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

TEST(AccelerationPlan, KnowsWhatItsClassificationsWereMadeFrom)
{
  const parc::ScalarField field = parctest::Blobs();
  const parc::ContributionRule rule = Rule(field, 50);
  parc::AccelerationPlan plan;
  parc::ClassificationKey key;
  key.FieldVersion = 1;
  std::fill_n(key.Size, 3, 2.0);
  EXPECT_FALSE(plan.IsClassifiedFrom(key));
  double fitted[3];
  ASSERT_TRUE(plan.ClassifyFrom(key, { &field }, { rule }, parc::Interpolation::Linear, fitted));
  EXPECT_TRUE(plan.IsClassifiedFrom(key));
  EXPECT_EQ(plan.GetGrid().GetSize()[0], 2.0);
  EXPECT_FALSE(plan.AreCellsClassifiedFrom(key)) << "the cells have a key of their own";

  // Any part of the key changed is another classification.
  parc::ClassificationKey changed = key;
  changed.FunctionsTime = 7;
  EXPECT_FALSE(plan.IsClassifiedFrom(changed));
  changed = key;
  changed.Size[2] = 4.0;
  EXPECT_FALSE(plan.IsClassifiedFrom(changed));
  changed = key;
  changed.Blend = 1;
  EXPECT_FALSE(plan.IsClassifiedFrom(changed));

  // A failed classification is noted too: the caller does not retry it every frame.
  parc::ClassificationKey bad = key;
  bad.Size[0] = 0.0;
  EXPECT_FALSE(plan.ClassifyFrom(bad, { &field }, { rule }, parc::Interpolation::Linear, fitted));
  EXPECT_TRUE(plan.IsClassifiedFrom(bad));
  EXPECT_EQ(plan.GetGrid().GetNumberOfSupercells(), 0u);

  parc::ClassificationKey cells = key;
  std::fill_n(cells.Size, 3, 0.0);
  ASSERT_TRUE(plan.ClassifyCellsFrom(cells, field, rule));
  EXPECT_TRUE(plan.AreCellsClassifiedFrom(cells));
  EXPECT_EQ(plan.GetPyramidBuilds(), 1u);
  EXPECT_TRUE(plan.GetContributingCells().Covers(field.GetDimensions()));
  // The map points into the pyramid: a new pyramid (the field changed) lets it go.
  parc::ClassificationKey newField = key;
  newField.FieldVersion += 1;
  plan.ClassifyFrom(newField, { &field }, { rule }, parc::Interpolation::Linear, fitted);
  EXPECT_EQ(plan.GetPyramidBuilds(), 2u);
  EXPECT_TRUE(plan.GetContributingCells().IsEmpty());
  EXPECT_FALSE(plan.AreCellsClassifiedFrom(cells));
  cells.FieldVersion = newField.FieldVersion;
  ASSERT_TRUE(plan.ClassifyCellsFrom(cells, field, rule));
  EXPECT_TRUE(plan.AreCellsClassifiedFrom(cells)) << "kept after the pyramid it builds";
  EXPECT_EQ(plan.GetPyramidBuilds(), 2u);
  plan.ReleaseCells();
  EXPECT_TRUE(plan.GetContributingCells().IsEmpty());
  EXPECT_FALSE(plan.AreCellsClassifiedFrom(cells)) << "released cells are made again";
}

TEST(AccelerationPlan, GivesTheSegmentSourceOfAFramesPasses)
{
  parc::AccelerationPlan plan;
  EXPECT_EQ(&plan.GetSource(parc::AutoTrials::Depth),
    static_cast<const parc::SegmentSource*>(&plan.GetDepthSource()));
  EXPECT_EQ(&plan.GetSource(parc::AutoTrials::Color),
    static_cast<const parc::SegmentSource*>(&plan.GetPlaneSource()));
  // No pass: the whole ray is one segment (the caster clips it); nothing to show: none.
  parc::RayQuery query;
  query.Path = parc::Ray{ parc::Vec3(0, 0, 0), parc::Vec3(0, 0, 1), 0.0, 2.0 };
  std::vector<parc::Segment> segments;
  plan.GetSource(parc::AutoTrials::None).Segments(query, segments);
  ASSERT_EQ(segments.size(), 1u);
  EXPECT_LE(segments[0].TNear, 0.0);
  EXPECT_GE(segments[0].TFar, 2.0);
  segments.clear();
  plan.GetEmptySource().Segments(query, segments);
  EXPECT_TRUE(segments.empty());
  EXPECT_FALSE(plan.GetEmptySource().MayHaveSegments(0, 0));

  // A pass's buffer is kept for the next frame until a settled mode no longer draws it.
  parc::Camera camera;
  camera.Width = camera.Height = 2;
  plan.GetDepthSource().Set(camera, std::vector<float>(8, 0.f), &plan.GetGrid(), parc::Matrix4());
  EXPECT_EQ(plan.GetDepthBufferMemorySize(), 8 * sizeof(float));
  plan.ReleasePassBuffers(true, false);
  EXPECT_EQ(plan.GetDepthBufferMemorySize(), 8 * sizeof(float));
  plan.ReleasePassBuffers(false, false);
  EXPECT_EQ(plan.GetDepthBufferMemorySize(), 0u);
}

TEST(AccelerationPlan, KeepsALightsPassesWhileTheirKeyHoldsWithinRounding)
{
  parc::AccelerationPlan plan;
  parc::AccelerationPlan::LightPasses& passes = plan.GetLightPasses(1, 2);
  EXPECT_FALSE(passes.IsDrawnFrom({ 1.0, 2.0 })) << "never drawn";
  passes.Key = { 1.0, 2000.0 };
  EXPECT_TRUE(passes.IsDrawnFrom({ 1.0, 2000.0 * (1.0 + 1e-12) })) << "rounding";
  EXPECT_FALSE(passes.IsDrawnFrom({ 1.0, 2000.0 * (1.0 + 1e-6) }));
  EXPECT_FALSE(passes.IsDrawnFrom({ 1.0 })) << "another light";
  EXPECT_EQ(&plan.GetLightPasses(1, 2), &passes);
  EXPECT_EQ(plan.GetLightPassesMemorySize(), passes.Key.capacity() * sizeof(double));
  plan.ReleaseLightPasses();
  EXPECT_EQ(plan.GetLightPassesMemorySize(), 0u);
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

using parc::AutoTrials;
using parc::FrameMeasure;
using parc::RayCostFit;

namespace
{
/// A fit of rays whose times follow t = 100 ns + sample s + 40 ns k exactly; each ray's
/// unaccelerated samples are twice its samples.
RayCostFit ExactFit(double sample, int rays = 1000)
{
  RayCostFit fit;
  for (int i = 0; i < rays; ++i)
  {
    const double s = 100 + i % 301, k = (7 * i) % 151;
    fit.Add(s, k, 100e-9 + sample * s + 40e-9 * k, 2.0 * s);
  }
  return fit;
}

/// A frame measure of the given times over samples and contributing samples, with fit.
FrameMeasure Frame(double projection, double casting, double samples, const RayCostFit& fit)
{
  FrameMeasure frame;
  frame.Projection = projection;
  frame.Casting = casting;
  frame.Samples = samples;
  frame.Contributing = 0.5 * samples;
  frame.Timing = fit;
  return frame;
}
}

TEST(RayCostFit, RecoversTheCostOfASampleAndRefusesDegenerateRays)
{
  double b = 0.0;
  ASSERT_TRUE(ExactFit(7e-9).SampleCost(b));
  EXPECT_NEAR(b, 7e-9, 1e-13);
  EXPECT_FALSE(ExactFit(7e-9, 10).SampleCost(b)) << "too few rays";
  RayCostFit proportional; // k = s / 2 on every ray: b and c cannot be told apart
  for (int i = 0; i < 100; ++i)
  {
    proportional.Add(2.0 * i, i, 1e-6 * i, 0.0);
  }
  b = -1.0;
  EXPECT_FALSE(proportional.SampleCost(b));
  EXPECT_EQ(b, -1.0);
}

TEST(AutoTrials, TriesOnlyThePassesPredictedToWin)
{
  AutoTrials autoTrials;
  EXPECT_EQ(autoTrials.Choose(1, 100, 200, 200), AutoTrials::Depth) << "depth first";
  EXPECT_EQ(autoTrials.Remaining(), AutoTrials::Count);
  // Depth: a dear pass (0.1 s) and cheap empty samples: None, which adds as many samples
  // as Depth takes (see ExactFit), is predicted at about 0.02 + 0.01 s; Color's projection
  // alone (1.75 x 0.1 s) is predicted slower than Depth, and Both slower still.
  const RayCostFit fit = ExactFit(10e-9);
  const double samples = fit.Samples() * RayCostFit::ColumnStride;
  autoTrials.Record(1, 100, Frame(0.1, 0.02, samples, fit), true);
  EXPECT_EQ(autoTrials.Remaining(), 1);
  ASSERT_EQ(autoTrials.Choose(1, 100, 200, 200), AutoTrials::None);
  RayCostFit noneFit = ExactFit(10e-9);
  autoTrials.Record(1, 100, Frame(0.0, 0.03, 2.0 * samples, noneFit), true);
  EXPECT_EQ(autoTrials.Remaining(), 0) << "settled: Color and Both are predicted slower";
  for (int frame = 0; frame < 3; ++frame)
  {
    EXPECT_EQ(autoTrials.Choose(1, 100, 200, 200), AutoTrials::None);
    autoTrials.Record(1, 100, Frame(0.0, 0.03, 2.0 * samples, noneFit), true);
  }
  EXPECT_FALSE(autoTrials.Estimates[AutoTrials::Color].Measured);
  EXPECT_FALSE(autoTrials.Estimates[AutoTrials::Both].Measured);
  // A new image size is predicted from the same measurements: no trial.
  EXPECT_EQ(autoTrials.Choose(2, 100, 400, 400), AutoTrials::None);
  EXPECT_EQ(autoTrials.Remaining(), 0);
}

TEST(AutoTrials, KnowsWhenOnlyTheDepthPassProjectionLost)
{
  // None took 0.19 s, the depth pass 0.15 s casting and 0.01, 0.05 or 0.2 s projection:
  // with 0.01 the pass is the fastest; with 0.05 None is, but at twice the supercell size
  // (a quarter of the projection) the pass may beat it; with 0.2 it may not.
  const RayCostFit fit = ExactFit(10e-9);
  const double samples = fit.Samples() * RayCostFit::ColumnStride;
  for (const double projection : { 0.01, 0.05, 0.2 })
  {
    AutoTrials autoTrials;
    ASSERT_EQ(autoTrials.Choose(1, 100, 200, 200), AutoTrials::Depth);
    autoTrials.Record(1, 100, Frame(projection, 0.15, samples, fit), true);
    autoTrials.Choose(1, 100, 200, 200);
    EXPECT_FALSE(autoTrials.DepthMayBeatNoneAtTwiceTheSize()) << "None not measured";
    autoTrials.Estimates[AutoTrials::None] = autoTrials.Estimates[AutoTrials::Depth];
    autoTrials.Estimates[AutoTrials::None].Projection = 0.0;
    autoTrials.Estimates[AutoTrials::None].Casting = 0.19;
    autoTrials.Settled = true; // no trial to come
    EXPECT_EQ(autoTrials.DepthMayBeatNoneAtTwiceTheSize(), projection == 0.05) << projection;
    autoTrials.Choose(1, 100, 300, 300);
    EXPECT_FALSE(autoTrials.DepthMayBeatNoneAtTwiceTheSize()) << "stale at another image size";
  }
  // A search against None ends: with the depth pass at 0.17 s at the kept size, or none
  // that beat None's 0.19 s. The next frame classifies anew (model 2; at the kept size 10
  // PC supercells, at the start size 100 again): the estimate holds for it, so a slower
  // frame after it does not turn the choice.
  for (const bool depthWon : { true, false })
  {
    AutoTrials searched;
    searched.Choose(1, 100, 200, 200);
    searched.Record(1, 100, Frame(0.05, 0.15, samples, fit), true);
    searched.Estimates[AutoTrials::None] = searched.Estimates[AutoTrials::Depth];
    searched.Estimates[AutoTrials::None].Projection = 0.0;
    searched.Estimates[AutoTrials::None].Casting = 0.19;
    searched.SettleAfterSearch(depthWon, 0.01, 0.16);
    EXPECT_TRUE(searched.Settled);
    EXPECT_EQ(searched.Remaining(), 0);
    const int expected = depthWon ? AutoTrials::Depth : AutoTrials::None;
    const std::size_t contributing = depthWon ? 10 : 100;
    for (int frame = 0; frame < 3; ++frame)
    {
      ASSERT_EQ(searched.Choose(2, contributing, 200, 200), expected) << depthWon << frame;
      searched.Record(2, contributing, Frame(depthWon ? 0.02 : 0.0, 0.3, samples, fit), true);
    }
    const AutoTrials::Estimate& kept = searched.Estimates[expected];
    EXPECT_EQ(kept.ModelVersion, 2u);
    EXPECT_DOUBLE_EQ(kept.Projection + kept.Casting, depthWon ? 0.17 : 0.19);
  }
}

TEST(AutoTrials, TriesAPassPredictedFasterAndLearnsTheColourProjection)
{
  AutoTrials autoTrials;
  autoTrials.Choose(1, 100, 200, 200);
  // Depth: a cheap pass and dear empty samples inside its segments: Color, which is
  // predicted to skip half of them, is tried; None is predicted slower.
  const RayCostFit fit = ExactFit(40e-9);
  const double samples = fit.Samples() * RayCostFit::ColumnStride;
  autoTrials.Record(1, 100, Frame(0.005, 0.2, samples, fit), true);
  ASSERT_EQ(autoTrials.Choose(1, 100, 200, 200), AutoTrials::Color);
  autoTrials.Record(1, 100, Frame(0.02, 0.05, 0.4 * samples, fit), true);
  EXPECT_DOUBLE_EQ(autoTrials.ColorProjectionRatio, 0.02 / 0.005);
  // Both: both projections and at best Color's casting, 0.075 s against Color's 0.07 s.
  EXPECT_EQ(autoTrials.Remaining(), 0);
  EXPECT_EQ(autoTrials.Choose(1, 100, 200, 200), AutoTrials::Color);
}

// A Depth frame whose pass costs 0.02 s (Color's predicted 0.035 s) and whose rays hold
// 0.5M non-contributing samples of about 0.15 us: Color, predicted to leave out half of
// them (0.038 s), is tried. When the caster left out 0.4M of them as samples of empty
// cells, those are what Color would leave out, at EmptyCellCostShare of the cost (0.009
// s): Color is not predicted faster, and not tried (a colour trial frame was 1.4x the
// settled one on the iron protein, whose empty cells are left out).
TEST(AutoTrials, EmptyCellSamplesLeftOutMakeColourNoFaster)
{
  for (const bool emptyCells : { true, false })
  {
    AutoTrials autoTrials;
    autoTrials.Choose(1, 100, 200, 200);
    const RayCostFit fit = ExactFit(40e-9);
    const double samples = fit.Samples() * RayCostFit::ColumnStride;
    FrameMeasure depth = Frame(0.02, 0.2, samples, fit);
    depth.EmptyCells = emptyCells ? 0.4 * samples : 0.0;
    autoTrials.Record(1, 100, depth, true);
    const int next = autoTrials.Choose(1, 100, 200, 200);
    EXPECT_EQ(next == AutoTrials::Color, !emptyCells) << emptyCells;
    if (emptyCells)
    {
      EXPECT_EQ(next, AutoTrials::Depth);
      EXPECT_EQ(autoTrials.Remaining(), 0) << "settled on Depth";
    }
  }
}

TEST(AutoTrials, WithoutTimedRaysEveryPassIsTriedInTurn)
{
  AutoTrials autoTrials;
  const int order[] = { AutoTrials::Depth, AutoTrials::Color, AutoTrials::Both, AutoTrials::None };
  for (int c : order)
  {
    ASSERT_EQ(autoTrials.Choose(1, 100, 200, 200), c);
    autoTrials.Record(1, 100, Frame(0.01, 0.01 * (c + 1), 1000.0, RayCostFit()), true);
  }
  EXPECT_EQ(autoTrials.Remaining(), 0);
  EXPECT_EQ(autoTrials.Choose(1, 100, 200, 200), AutoTrials::Depth) << "the fastest";
}

// The first frame also sets up (classification, models, shaders): without its set-up time
// it predicts the others, so that None, predicted faster than Depth's pass, is taken next
// instead of a second, slow Depth frame. A provisional estimate does not settle Auto, the
// candidate's next frame replaces it, and it never replaces a measured one.
TEST(AutoTrials, AFrameThatSetsUpPredictsTheNextWithoutItsSetUpTime)
{
  const RayCostFit fit = ExactFit(10e-9);
  const double samples = fit.Samples() * RayCostFit::ColumnStride;
  FrameMeasure first = Frame(0.3, 0.02, samples, fit);
  first.SetUp = 0.2; // a 0.1 s pass: None (about 0.03 s) is predicted faster
  AutoTrials dearPass;
  ASSERT_EQ(dearPass.Choose(1, 100, 200, 200), AutoTrials::Depth);
  dearPass.RecordSetUp(1, 100, first);
  EXPECT_TRUE(dearPass.Estimates[AutoTrials::Depth].Provisional);
  EXPECT_DOUBLE_EQ(dearPass.Estimates[AutoTrials::Depth].Projection, 0.1);
  EXPECT_EQ(dearPass.Choose(1, 100, 200, 200), AutoTrials::None);

  first.SetUp = 0.294; // a 6 ms pass: Depth is the least, and is measured warm next
  AutoTrials cheapPass;
  cheapPass.Choose(1, 100, 200, 200);
  cheapPass.RecordSetUp(1, 100, first);
  EXPECT_EQ(cheapPass.Remaining(), 1) << "Depth's warm frame";
  ASSERT_EQ(cheapPass.Choose(1, 100, 200, 200), AutoTrials::Depth);
  EXPECT_FALSE(cheapPass.Settled) << "a provisional estimate ends no trial";
  cheapPass.Record(1, 100, Frame(0.008, 0.02, samples, fit), true);
  const AutoTrials::Estimate& depth = cheapPass.Estimates[AutoTrials::Depth];
  EXPECT_FALSE(depth.Provisional);
  EXPECT_DOUBLE_EQ(depth.Projection, 0.008) << "replaced, though slower";
  // An edit's frame sets up again: the measured estimate stays.
  ASSERT_EQ(cheapPass.Choose(2, 100, 200, 200), AutoTrials::Depth);
  EXPECT_TRUE(cheapPass.Settled);
  cheapPass.RecordSetUp(2, 100, Frame(0.5, 0.02, samples, fit));
  EXPECT_FALSE(depth.Provisional);
  EXPECT_DOUBLE_EQ(depth.Projection, 0.008);
}

using parc::SupercellSearch;

namespace
{
/// Runs a search until it ends, each frame at scale s taking seconds(s); the scales of the
/// frames, in order.
template <class Seconds>
std::vector<double> RunSearch(SupercellSearch& search, int candidate, const Seconds& seconds)
{
  std::vector<double> scales;
  for (int frame = 0; frame < 100 && !search.IsDone(); ++frame)
  {
    scales.push_back(search.GetScale());
    search.Record(candidate, true, 0.0, seconds(search.GetScale()));
  }
  return scales;
}
}

TEST(SupercellSearch, WaitsForAutoToSettleOnAPass)
{
  SupercellSearch search;
  search.Record(AutoTrials::Depth, false, 0.0, 1.0); // trials still under way
  search.Record(AutoTrials::None, true, 0.0, 1.0);   // settled on no pass
  EXPECT_FALSE(search.IsSearching());
  EXPECT_EQ(search.GetScale(), 1.0);
  search.Record(AutoTrials::Color, true, 0.0, 1.0);
  EXPECT_TRUE(search.IsSearching());
  EXPECT_FALSE(search.IsSearchingAgainstNone());
  EXPECT_EQ(search.GetCandidate(), AutoTrials::Color);
}

TEST(SupercellSearch, AgainstNoneTriesTheDepthPassAtLargerSizesOnly)
{
  // None took 1 s at scale 1; the depth pass takes 1.2 s at 2 and 0.8 s at 4, 0.9 at 8.
  SupercellSearch search;
  EXPECT_FALSE(search.SearchesAgainstNone(false));
  EXPECT_TRUE(search.SearchesAgainstNone(true)) << "starts on None's next frame";
  search.Record(AutoTrials::None, true, 0.0, 1.0, true);
  ASSERT_TRUE(search.IsSearchingAgainstNone());
  EXPECT_EQ(search.GetCandidate(), AutoTrials::Depth);
  const auto faster = [](double s) { return s == 4.0 ? 0.8 : s == 8.0 ? 0.9 : 1.2; };
  EXPECT_EQ(RunSearch(search, AutoTrials::Depth, faster), (std::vector<double>{ 2, 2 }))
    << "twice the size slower than None: smaller sizes are not tried";
  EXPECT_TRUE(search.IsDone());
  EXPECT_FALSE(search.SearchesAgainstNone(true)) << "once";
  EXPECT_EQ(search.GetScale(), 1.0) << "back to the start";
  double projection = -1.0, casting = -1.0;
  EXPECT_FALSE(search.BeatNone(projection, casting));

  SupercellSearch growing;
  growing.Record(AutoTrials::None, true, 0.0, 1.0, true);
  const auto growingFaster = [](double s) { return s == 2.0 ? 0.95 : s == 4.0 ? 0.8 : 0.9; };
  EXPECT_EQ(RunSearch(growing, AutoTrials::Depth, growingFaster),
    (std::vector<double>{ 2, 2, 4, 4, 8, 8 }));
  EXPECT_EQ(growing.GetScale(), 4.0);
  ASSERT_TRUE(growing.BeatNone(projection, casting));
  EXPECT_EQ(projection + casting, 0.8) << "the fastest frame of the kept scale";
}

TEST(SupercellSearch, GrowsWhileFasterAndKeepsTheFastest)
{
  // Fastest at 4x the size: 1 -> 2 -> 4 -> 8 (slower) -> back to 4.
  SupercellSearch search;
  const auto seconds = [](double s) { return std::fabs(std::log2(s) - 2.0) + 1.0; };
  const std::vector<double> scales = RunSearch(search, AutoTrials::Depth, seconds);
  EXPECT_EQ(scales, (std::vector<double>{ 1, 1, 2, 2, 4, 4, 8, 8 }));
  EXPECT_TRUE(search.IsDone());
  EXPECT_EQ(search.GetScale(), 4.0);
}

TEST(SupercellSearch, ShrinksWhenTwiceTheSizeIsSlower)
{
  // Fastest at half the size: 1 -> 2 (slower) -> 0.5 -> 0.25 (slower) -> 0.5.
  SupercellSearch search;
  const auto seconds = [](double s) { return std::fabs(std::log2(s) + 1.0) + 1.0; };
  const std::vector<double> scales = RunSearch(search, AutoTrials::Both, seconds);
  EXPECT_EQ(scales, (std::vector<double>{ 1, 1, 2, 2, 0.5, 0.5, 0.25, 0.25 }));
  EXPECT_EQ(search.GetScale(), 0.5);
}

TEST(SupercellSearch, TakesTheLeastFrameOfAScaleAndStopsAtTheLimits)
{
  // Ever faster: up to MaxScale; a slow frame among two of a scale does not count.
  SupercellSearch search;
  int frame = 0;
  const auto seconds = [&frame](double s) { return ++frame % 2 ? 10.0 : 1.0 / s; };
  RunSearch(search, AutoTrials::Depth, seconds);
  EXPECT_EQ(search.GetScale(), SupercellSearch::MaxScale);
}

TEST(SupercellSearch, KeepsTheBestWhenAutoLeavesThePassAndStartsAgainAfterAReset)
{
  SupercellSearch search;
  for (int i = 0; i < 4; ++i) // scale 1, then 2 faster
  {
    search.Record(AutoTrials::Depth, true, 0.0, i < 2 ? 2.0 : 1.0);
  }
  EXPECT_EQ(search.GetScale(), 4.0);
  search.Record(AutoTrials::None, true, 0.0, 0.5);
  EXPECT_TRUE(search.IsDone());
  EXPECT_EQ(search.GetScale(), 2.0);
  search.Reset();
  EXPECT_EQ(search.GetScale(), 1.0);
  EXPECT_FALSE(search.IsDone());
}

TEST(SupercellSearch, ALargeVolumeStartsAtALargerScale)
{
  const double size[3] = { 4, 4, 4 };
  SupercellSearch search;
  const int small[3] = { 60, 60, 60 }; // 3,375 supercells of 4
  search.Begin(small, size);
  EXPECT_EQ(search.GetScale(), 1.0);
  const int head[3] = { 180, 216, 180 }; // 109,350 of 4, 13,669 of 8
  search.Begin(head, size);
  EXPECT_EQ(search.GetScale(), 2.0);
  // Twice that scale slower: the search tries half of it next, not half of 1.
  const auto seconds = [](double s) { return s == 2.0 ? 1.0 : 2.0; };
  const std::vector<double> scales = RunSearch(search, AutoTrials::Depth, seconds);
  EXPECT_EQ(scales, (std::vector<double>{ 2, 2, 4, 4, 1, 1 }));
  EXPECT_EQ(search.GetScale(), 2.0);
  const int large[3] = { 720, 864, 720 }; // 109,350 of 16, 13,669 of 32
  search.Begin(large, size);
  EXPECT_EQ(search.GetScale(), SupercellSearch::MaxScale);
}

// Started at the largest scale, the search has nothing above it and goes down at once.
TEST(SupercellSearch, FromTheLargestScaleTheSearchGoesDown)
{
  const double size[3] = { 4, 4, 4 };
  const int large[3] = { 720, 864, 720 };
  SupercellSearch search;
  search.Begin(large, size);
  const auto seconds = [](double s) { return 1.0 + std::abs(std::log2(s / 2.0)); };
  const std::vector<double> scales = RunSearch(search, AutoTrials::Depth, seconds);
  EXPECT_EQ(scales, (std::vector<double>{ 8, 8, 4, 4, 2, 2, 1, 1 }));
  EXPECT_EQ(search.GetScale(), 2.0);
  EXPECT_TRUE(search.IsDone());
}

TEST(SupercellSearch, NeverTriesMoreSupercellsThanTheGridAllows)
{
  // Ever faster as supercells shrink, on a volume where a quarter of the size (1 cell,
  // 448 million supercells) exceeds SupercellGrid::MaxSupercells: the search ends at half.
  const double size[3] = { 4, 4, 4 };
  const int large[3] = { 720, 864, 720 };
  SupercellSearch search;
  search.Begin(large, size);
  const std::vector<double> scales = RunSearch(search, AutoTrials::Depth, [](double s) { return s; });
  EXPECT_EQ(scales, (std::vector<double>{ 8, 8, 4, 4, 2, 2, 1, 1, 0.5, 0.5 }));
  EXPECT_EQ(search.GetScale(), 0.5);
  EXPECT_TRUE(search.IsDone());
}
