#include "parcAccelerationPlan.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace parc
{

void AutoTrials::SetView(const Vec3& direction, double distance)
{
  if (Dot(direction, this->Direction) < SameDirection ||
    std::fabs(distance - this->Distance) > SameDistance * this->Distance)
  {
    ++this->ViewVersion;
    this->Direction = direction;
    this->Distance = distance;
  }
}

int AutoTrials::Choose(std::uint64_t modelVersion, std::size_t contributing, int width,
  int height, bool allowTrials)
{
  this->Size[0] = width;
  this->Size[1] = height;
  this->LastModelVersion = modelVersion;
  this->LastContributing = contributing;
  for (Estimate& e : this->Estimates)
  {
    if (e.Measured && e.ModelVersion == NextModel)
    {
      e.ModelVersion = modelVersion;
      e.Contributing = contributing;
    }
  }
  const bool trials = allowTrials && !this->Settled;
  this->Chosen = std::max(this->Best(modelVersion, contributing, trials), 0);
  // The first frame that may try a pass but needs none ends the trials.
  const Estimate& chosen = this->Estimates[this->Chosen];
  this->Settled = this->Settled || (trials && chosen.Measured && !chosen.Provisional);
  return this->Chosen;
}

int AutoTrials::Best(std::uint64_t modelVersion, std::size_t contributing, bool predictions,
  double* seconds) const
{
  int best = -1;
  double least = 0.0;
  for (int c = 0; c < Count; ++c)
  {
    const Estimate& e = this->Estimates[c];
    double t = 0.0;
    if (e.Measured)
    {
      t = this->Predict(e, modelVersion, contributing);
    }
    else if (!predictions)
    {
      continue;
    }
    else if (!this->PredictUnmeasured(c, modelVersion, contributing, t))
    {
      t = -std::numeric_limits<double>::infinity(); // nothing to predict from: try it
    }
    if (best < 0 || t < least)
    {
      best = c;
      least = t;
    }
  }
  if (seconds)
  {
    *seconds = least;
  }
  return best;
}

double AutoTrials::ProjectionOf(
  const Estimate& e, std::uint64_t modelVersion, std::size_t contributing) const
{
  const double scale = (e.ModelVersion == modelVersion || e.Contributing == 0)
    ? 1.0
    : static_cast<double>(contributing) / static_cast<double>(e.Contributing);
  return this->RaysScale(e) * scale * e.Projection;
}

double AutoTrials::RaysScale(const Estimate& e) const
{
  const double rays = static_cast<double>(this->Size[0]) * this->Size[1];
  return e.Rays > 0.0 ? rays / e.Rays : 1.0;
}

double AutoTrials::Predict(
  const Estimate& e, std::uint64_t modelVersion, std::size_t contributing) const
{
  return this->ProjectionOf(e, modelVersion, contributing) + this->RaysScale(e) * e.Casting;
}

bool AutoTrials::PredictUnmeasured(
  int c, std::uint64_t modelVersion, std::size_t contributing, double& seconds) const
{
  const Estimate& depth = this->Estimates[Depth];
  if (this->SampleSeconds <= 0.0 || !depth.Measured)
  {
    return false;
  }
  if (c == None)
  {
    Estimate none = depth;
    none.Projection = 0.0;
    none.Casting += (this->UnacceleratedSamples - depth.Samples) * this->SampleSeconds;
    seconds = this->Predict(none, modelVersion, contributing);
    return true;
  }
  // Colour: Depth's casting less half of the samples outside PC supercells. When the
  // caster leaves out empty cells those are its empty-cell samples, which cost little;
  // else they are among the non-contributing samples.
  const Estimate& measuredColor = this->Estimates[Color];
  Estimate color = depth;
  color.Projection *= this->ColorProjectionRatio;
  const double leftOut = depth.EmptyCellSamples > 0.0
    ? EmptyCellCostShare * depth.EmptyCellSamples
    : depth.Samples - depth.ContributingSamples;
  color.Casting = std::max(depth.Casting - 0.5 * leftOut * this->SampleSeconds, 0.0);
  if (c == Color)
  {
    seconds = this->Predict(color, modelVersion, contributing);
    return true;
  }
  // Both passes, and at best the faster casting of the two.
  const Estimate& colorPart = measuredColor.Measured ? measuredColor : color;
  seconds = this->ProjectionOf(depth, modelVersion, contributing) +
    this->ProjectionOf(colorPart, modelVersion, contributing) +
    std::min(
      this->RaysScale(depth) * depth.Casting, this->RaysScale(colorPart) * colorPart.Casting);
  return true;
}

void AutoTrials::RecordSampleCost(const FrameMeasure& frame)
{
  const RayCostFit& fit = frame.Timing;
  if (fit.Rays() == 0.0)
  {
    this->SampleSeconds = 0.0; // not timed: no predictions
    return;
  }
  // The timed rays' thread-seconds, scaled to all rays, against the wall time.
  const double threadSeconds = fit.Seconds() * RayCostFit::ColumnStride;
  double b = 0.0;
  if (fit.SampleCost(b) && b > 0.0 && threadSeconds > 0.0)
  {
    this->SampleSeconds = b * frame.Casting / threadSeconds;
  }
  else if (frame.Samples > 0.0)
  {
    this->SampleSeconds = NonContributingShare * frame.Casting / frame.Samples;
  }
  this->UnacceleratedSamples =
    frame.Samples + (fit.Unaccelerated - fit.Samples()) * RayCostFit::ColumnStride;
}

void AutoTrials::Record(std::uint64_t modelVersion, std::size_t contributing,
  const FrameMeasure& frame, bool representative)
{
  if (this->Chosen >= 0 && representative)
  {
    Estimate& e = this->Estimates[this->Chosen];
    const double rays = static_cast<double>(this->Size[0]) * this->Size[1];
    if (!e.Measured || e.Provisional || !this->IsCurrent(e, modelVersion) ||
      frame.Projection + frame.Casting < e.Projection + e.Casting)
    {
      e = { true, false, modelVersion, this->ViewVersion, contributing, rays, frame.Projection,
        frame.Casting, frame.Samples, frame.Contributing, frame.EmptyCells };
    }
    this->RecordSampleCost(frame);
    const Estimate& depth = this->Estimates[Depth];
    const Estimate& color = this->Estimates[Color];
    if (depth.Measured && color.Measured && !depth.Provisional && !color.Provisional &&
      depth.ModelVersion == color.ModelVersion && depth.Projection > 0.0)
    {
      this->ColorProjectionRatio = color.Projection / depth.Projection;
    }
  }
  this->Chosen = -1;
}

void AutoTrials::RecordSetUp(
  std::uint64_t modelVersion, std::size_t contributing, const FrameMeasure& frame)
{
  if (this->Chosen >= 0)
  {
    Estimate& e = this->Estimates[this->Chosen];
    if (!e.Measured || (e.Provisional && !this->IsCurrent(e, modelVersion)))
    {
      const double rays = static_cast<double>(this->Size[0]) * this->Size[1];
      const double projection = std::max(frame.Projection - frame.SetUp, 0.0);
      e = { true, true, modelVersion, this->ViewVersion, contributing, rays, projection,
        frame.Casting, frame.Samples, frame.Contributing, frame.EmptyCells };
    }
    this->RecordSampleCost(frame);
  }
  this->Chosen = -1;
}

bool AutoTrials::IsCurrent(const Estimate& e, std::uint64_t modelVersion) const
{
  return e.ModelVersion == modelVersion && e.ViewVersion == this->ViewVersion &&
    e.Rays == static_cast<double>(this->Size[0]) * this->Size[1];
}

int AutoTrials::Remaining() const
{
  if (this->Settled)
  {
    return 0;
  }
  double best = std::numeric_limits<double>::infinity();
  const int bestMeasured = this->Best(this->LastModelVersion, this->LastContributing, false, &best);
  // A provisional estimate that is the best is measured next.
  int remaining = bestMeasured >= 0 && this->Estimates[bestMeasured].Provisional;
  for (int c = 0; c < Count; ++c)
  {
    double t = -std::numeric_limits<double>::infinity();
    const bool unmeasured = !this->Estimates[c].Measured;
    if (unmeasured)
    {
      this->PredictUnmeasured(c, this->LastModelVersion, this->LastContributing, t);
    }
    remaining += unmeasured && t < best;
  }
  return remaining;
}

bool AutoTrials::DepthMayBeatNoneAtTwiceTheSize() const
{
  const Estimate& depth = this->Estimates[Depth];
  const Estimate& none = this->Estimates[None];
  // A provisional estimate of the depth pass is high (a first draw's costs): it may count.
  const auto current = [this](const Estimate& e) {
    return e.Measured && this->IsCurrent(e, this->LastModelVersion);
  };
  return current(depth) && current(none) &&
    depth.Casting + ProjectionShareAtTwiceTheSize * depth.Projection <
      none.Casting + none.Projection &&
    this->Remaining() == 0 &&
    this->Best(this->LastModelVersion, this->LastContributing, false) == None;
}

void AutoTrials::SettleAfterSearch(bool depthWon, double projection, double casting)
{
  Estimate& e = this->Estimates[depthWon ? Depth : None];
  if (depthWon)
  {
    e.Provisional = false;
    e.ViewVersion = this->ViewVersion;
    e.Rays = static_cast<double>(this->Size[0]) * this->Size[1];
    e.Projection = projection;
    e.Casting = casting;
  }
  e.ModelVersion = NextModel;
  this->Settled = true;
}

void SupercellSearch::Begin(const int cells[3], const double size[3])
{
  this->Reset();
  const auto count = [&](double scale) {
    double n = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      n *= std::ceil(std::max(cells[a], 1) / std::max(scale * size[a], 1e-9));
    }
    return n;
  };
  while (count(this->StartScale) > StartSupercells && 2.0 * this->StartScale <= MaxScale)
  {
    this->StartScale *= 2.0;
  }
  // Scales below the start that would exceed the grid's limit are never tried.
  while (count(this->LeastScale) > static_cast<double>(SupercellGrid::MaxSupercells) &&
    this->LeastScale < this->StartScale)
  {
    this->LeastScale *= 2.0;
  }
  this->Scale = this->BestScale = this->StartScale;
}

bool SupercellSearch::BeatNone(double& projection, double& casting) const
{
  if (!this->AgainstNone || this->BestScale == this->StartScale)
  {
    return false;
  }
  projection = this->BestProjection;
  casting = this->BestSeconds - this->BestProjection;
  return true;
}

void SupercellSearch::Record(
  int candidate, bool settled, double projection, double casting, bool depthMayBeatNone)
{
  const double seconds = projection + casting;
  if (this->State == Done)
  {
    return;
  }
  const bool pass = candidate == AutoTrials::Depth || candidate == AutoTrials::Color ||
    candidate == AutoTrials::Both;
  if (this->State == Waiting)
  {
    if (candidate == AutoTrials::None && depthMayBeatNone)
    {
      // None's frame is the time to beat, at the start scale; larger sizes from there.
      this->State = Searching;
      this->Candidate = AutoTrials::Depth;
      this->BestSeconds = seconds;
      this->BestProjection = projection;
      this->AgainstNone = true;
      this->Try(2.0 * this->Scale);
      return;
    }
    if (!settled || !pass)
    {
      return;
    }
    this->State = Searching;
    this->Candidate = candidate;
    this->ScaleFrames = 0;
    this->BestSeconds = std::numeric_limits<double>::infinity();
  }
  if (candidate != this->Candidate)
  {
    this->Try(0.0); // Auto left the pass (a view or data change): keep the best so far
    return;
  }
  if (this->ScaleFrames == 0 || seconds < this->ScaleSeconds)
  {
    this->ScaleSeconds = seconds;
    this->ScaleProjection = projection;
  }
  if (++this->ScaleFrames < FramesPerScale)
  {
    return;
  }
  if (this->ScaleSeconds < this->BestSeconds)
  {
    this->BestSeconds = this->ScaleSeconds;
    this->BestProjection = this->ScaleProjection;
    this->BestScale = this->Scale;
    this->Try(this->Growing ? 2.0 * this->Scale : 0.5 * this->Scale);
    return;
  }
  this->TurnOrEnd(); // slower than the best
}

void SupercellSearch::TurnOrEnd()
{
  if (this->Growing && !this->AgainstNone && this->BestScale == this->StartScale)
  {
    this->Growing = false;
    this->Try(0.5 * this->BestScale);
    return;
  }
  this->Try(0.0);
}

void SupercellSearch::Try(double scale)
{
  this->ScaleFrames = 0;
  if (scale > MaxScale && this->Growing)
  {
    this->TurnOrEnd(); // nothing above
    return;
  }
  if (scale < this->LeastScale || scale > MaxScale)
  {
    this->State = Done;
    this->Scale = this->BestScale;
    return;
  }
  this->Scale = scale;
}

void AccelerationPlan::SetMergeFaces(bool merge)
{
  if (merge != this->MergeFaces)
  {
    this->MergeFaces = merge;
    this->NewModelVersion();
  }
}

bool AccelerationPlan::Classify(const std::vector<const ScalarField*>& fields,
  std::uint64_t fieldVersion, const std::vector<ContributionRule>& rules,
  Interpolation interpolation, const double size[3], double fitted[3])
{
  if (fields.empty() || rules.size() != fields.size())
  {
    this->Grid = SupercellGrid();
    return false;
  }
  const auto start = std::chrono::steady_clock::now();
  this->EnsurePyramids(fields, fieldVersion);
  this->NewModelVersion();
  const int* cells = this->Pyramids[0].GetCellDimensions();
  if (!SupercellGrid::FitSize(cells, size, fitted) || !this->Grid.Configure(cells, fitted))
  {
    this->Grid = SupercellGrid();
    return false;
  }
  std::vector<SupercellGrid::Channel> channels;
  for (std::size_t c = 0; c < fields.size(); ++c)
  {
    channels.push_back({ &this->Pyramids[c], &rules[c] });
  }
  const auto classification = std::chrono::steady_clock::now();
  this->Grid.Classify(channels, interpolation);
  this->ClassificationTime = SecondsSince(classification);
  ++this->Classifications;
  this->SetUpTime += SecondsSince(start);
  return true;
}

const SegmentSource& AccelerationPlan::GetSource(AutoTrials::Candidate passes) const
{
  switch (passes)
  {
    case AutoTrials::Depth:
      return this->DepthSource;
    case AutoTrials::Color:
      return this->PlaneSource;
    case AutoTrials::Both:
      return this->Both;
    default:
      return this->WholeRays;
  }
}

void AccelerationPlan::ReleasePassBuffers(bool depth, bool planes)
{
  if (!depth)
  {
    this->DepthSource.ReleaseBuffer();
  }
  if (!planes)
  {
    this->PlaneSource.ReleaseBuffer();
  }
}

bool AccelerationPlan::LightPasses::IsDrawnFrom(const std::vector<double>& key) const
{
  const auto same = [](double a, double b) {
    return std::fabs(a - b) <= LightKeyTolerance * std::max({ 1.0, std::fabs(a), std::fabs(b) });
  };
  return this->Key.size() == key.size() &&
    std::equal(key.begin(), key.end(), this->Key.begin(), same);
}

AccelerationPlan::LightPasses& AccelerationPlan::GetLightPasses(
  std::size_t index, std::size_t lights)
{
  if (this->Lights.size() < lights)
  {
    this->Lights.resize(lights);
  }
  return this->Lights[index];
}

std::size_t AccelerationPlan::GetLightPassesMemorySize() const
{
  std::size_t bytes = 0;
  for (const LightPasses& passes : this->Lights)
  {
    bytes += passes.Source.GetMemorySize() + passes.Key.capacity() * sizeof(double);
  }
  return bytes;
}

bool ClassificationKey::operator==(const ClassificationKey& o) const
{
  return FieldVersion == o.FieldVersion && Functions == o.Functions &&
    FunctionsTime == o.FunctionsTime && Blend == o.Blend && Labels == o.Labels &&
    LabelsTime == o.LabelsTime && std::equal(Average, Average + 2, o.Average) &&
    std::equal(Size, Size + 3, o.Size);
}

bool AccelerationPlan::ClassifyFrom(const ClassificationKey& key,
  const std::vector<const ScalarField*>& fields, const std::vector<ContributionRule>& rules,
  Interpolation interpolation, double fitted[3])
{
  this->SupercellsKey = key;
  return this->Classify(fields, key.FieldVersion, rules, interpolation, key.Size, fitted);
}

bool AccelerationPlan::ClassifyCellsFrom(
  const ClassificationKey& key, const ScalarField& field, const ContributionRule& rule)
{
  const bool classified = this->ClassifyCells(field, key.FieldVersion, rule);
  this->CellsKey = key; // after the pyramid, whose building releases the cells
  return classified;
}

bool AccelerationPlan::ClassifyCells(
  const ScalarField& field, std::uint64_t fieldVersion, const ContributionRule& rule)
{
  const auto start = std::chrono::steady_clock::now();
  this->EnsurePyramids({ &field }, fieldVersion);
  const bool classified = this->Pyramids[0].MapCells(rule, this->Cells);
  ++this->CellClassifications;
  this->SetUpTime += SecondsSince(start);
  return classified;
}

void AccelerationPlan::EnsurePyramids(
  const std::vector<const ScalarField*>& fields, std::uint64_t fieldVersion)
{
  if (this->Pyramids.size() != fields.size() || this->PyramidFieldVersion != fieldVersion)
  {
    this->ReleaseCells(); // the map points into the pyramid
    this->Pyramids.resize(fields.size());
    for (std::size_t c = 0; c < fields.size(); ++c)
    {
      this->Pyramids[c].Build(*fields[c]);
    }
    this->PyramidFieldVersion = fieldVersion;
    ++this->PyramidBuilds;
  }
}

std::size_t AccelerationPlan::GetPyramidMemorySize() const
{
  std::size_t bytes = 0;
  for (const RangePyramid& pyramid : this->Pyramids)
  {
    bytes += pyramid.GetMemorySize();
  }
  return bytes;
}

void AccelerationPlan::NewModelVersion()
{
  this->Depth.Current = false;
  for (PassModel& pass : this->Color)
  {
    pass.Current = false;
  }
  this->WalkCurrent = false;
  ++this->ModelVersion;
}

const SupercellWalk& AccelerationPlan::GetWalk(const Matrix4& worldToIndex)
{
  if (!this->WalkCurrent || !this->Walk.IsSet())
  {
    const auto start = std::chrono::steady_clock::now();
    this->Walk.Set(&this->Grid, worldToIndex);
    this->WalkCurrent = true;
    ++this->ModelBuilds;
    this->SetUpTime += SecondsSince(start);
  }
  this->Walk.SetWorldToIndex(worldToIndex);
  return this->Walk;
}

const PolygonModel& AccelerationPlan::Ensure(PassModel& pass, int axis, bool uploaded)
{
  if (!pass.Current || (!uploaded && pass.Model.Vertices.empty()))
  {
    const auto start = std::chrono::steady_clock::now();
    if (axis < 0)
    {
      BuildDepthModel(this->Grid, this->MergeFaces, pass.Model);
    }
    else
    {
      BuildColorModel(this->Grid, axis, this->MergeFaces, pass.Model);
    }
    pass.Quads = pass.Model.GetNumberOfQuads();
    pass.Current = true;
    ++this->ModelBuilds;
    this->SetUpTime += SecondsSince(start);
  }
  return pass.Model;
}

void AccelerationPlan::Release(PassModel& pass)
{
  std::vector<Vec3>().swap(pass.Model.Vertices);
  std::vector<int>().swap(pass.Model.Planes);
}

std::size_t AccelerationPlan::GetColorModelsMemorySize() const
{
  std::size_t bytes = 0;
  for (const PassModel& pass : this->Color)
  {
    bytes += pass.Model.GetMemorySize();
  }
  return bytes;
}

} // namespace parc
