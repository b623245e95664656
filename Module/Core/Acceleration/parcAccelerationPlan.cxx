#include "parcAccelerationPlan.h"

#include <algorithm>
#include <chrono>
#include <cmath>

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
  this->Chosen = -1;
  for (int i = 0; i < Count; ++i)
  {
    const Estimate& e = this->Estimates[i];
    if (!e.Measured)
    {
      if (allowTrials)
      {
        this->Chosen = i;
        return i;
      }
      continue;
    }
    if (this->Chosen < 0 ||
      this->Predict(e, modelVersion, contributing) <
        this->Predict(this->Estimates[this->Chosen], modelVersion, contributing))
    {
      this->Chosen = i;
    }
  }
  this->Chosen = std::max(this->Chosen, 0);
  return this->Chosen;
}

double AutoTrials::Predict(
  const Estimate& e, std::uint64_t modelVersion, std::size_t contributing) const
{
  const double scale = (e.ModelVersion == modelVersion || e.Contributing == 0)
    ? 1.0
    : static_cast<double>(contributing) / static_cast<double>(e.Contributing);
  const double rays = static_cast<double>(this->Size[0]) * this->Size[1];
  const double raysScale = e.Rays > 0.0 ? rays / e.Rays : 1.0;
  return raysScale * (scale * e.Projection + e.Casting);
}

void AutoTrials::Record(std::uint64_t modelVersion, std::size_t contributing, double projection,
  double casting, bool representative)
{
  if (this->Chosen >= 0 && representative)
  {
    Estimate& e = this->Estimates[this->Chosen];
    const double rays = static_cast<double>(this->Size[0]) * this->Size[1];
    if (!e.Measured || e.ModelVersion != modelVersion || e.ViewVersion != this->ViewVersion ||
      e.Rays != rays || projection + casting < e.Projection + e.Casting)
    {
      e = { true, modelVersion, this->ViewVersion, contributing,
        static_cast<double>(this->Size[0]) * this->Size[1], projection, casting };
    }
  }
  this->Chosen = -1;
}

int AutoTrials::Remaining() const
{
  return static_cast<int>(std::count_if(this->Estimates, this->Estimates + Count,
    [](const Estimate& e) { return !e.Measured; }));
}

void AccelerationPlan::SetMergeFaces(bool merge)
{
  if (merge != this->MergeFaces)
  {
    this->MergeFaces = merge;
    this->NewModelVersion();
  }
}

bool AccelerationPlan::Classify(const ScalarField& field, std::uint64_t fieldVersion,
  const ContributionRule& rule, Interpolation interpolation, const double size[3],
  double fitted[3])
{
  if (!this->HavePyramid || this->PyramidFieldVersion != fieldVersion)
  {
    this->Pyramid.Build(field);
    this->PyramidFieldVersion = fieldVersion;
    this->HavePyramid = true;
    ++this->PyramidBuilds;
  }
  this->NewModelVersion();
  const int* cells = this->Pyramid.GetCellDimensions();
  if (!SupercellGrid::FitSize(cells, size, fitted) || !this->Grid.Configure(cells, fitted))
  {
    this->Grid = SupercellGrid();
    return false;
  }
  const auto start = std::chrono::steady_clock::now();
  this->Grid.Classify(this->Pyramid, rule, interpolation);
  this->ClassificationTime =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++this->Classifications;
  return true;
}

void AccelerationPlan::NewModelVersion()
{
  this->Depth.Current = false;
  for (PassModel& pass : this->Color)
  {
    pass.Current = false;
  }
  ++this->ModelVersion;
}

const PolygonModel& AccelerationPlan::Ensure(PassModel& pass, int axis, bool uploaded)
{
  if (!pass.Current || (!uploaded && pass.Model.Vertices.empty()))
  {
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
