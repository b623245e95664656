#include "parcBufferSources.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace parc
{

namespace
{
constexpr double Infinity = std::numeric_limits<double>::infinity();
/// Relative float rounding of the depths the pass writes (generous: 64 float ulps).
constexpr double DepthTolerance = 64.0 * 1.1920929e-7;
/// Tolerance (voxel-index units, relative to the volume size) of "the ray starts inside".
constexpr double StartTolerance = 1e-6;

std::size_t PixelIndex(const Camera& v, int px, int py)
{
  return static_cast<std::size_t>(py) * static_cast<std::size_t>(v.Width) + px;
}

double VolumeScale(const SupercellGrid& grid)
{
  const int* c = grid.GetCellDimensions();
  return std::max({ 1, c[0], c[1], c[2] });
}
}

void DepthBufferSource::Set(const Camera& view, std::vector<float> nearFar,
  const SupercellGrid* grid, const Matrix4& worldToIndex)
{
  this->View = view;
  this->NearFar = std::move(nearFar);
  this->Grid = grid;
  this->WorldToIndex = worldToIndex;
  this->StartEps = grid ? StartTolerance * VolumeScale(*grid) : 0.0;
}

bool DepthBufferSource::PixelSegment(int px, int py, const Ray& ray, Segment& segment) const
{
  const std::size_t pixel = PixelIndex(this->View, px, py);
  const double zNear = this->NearFar[2 * pixel];
  const double zFar = -static_cast<double>(this->NearFar[2 * pixel + 1]);
  if (!(zNear < Empty))
  {
    // No face covers the pixel, so the ray meets no PC supercell: a ray starting inside
    // one would leave it through a face in front of its start, and that face is drawn.
    return false;
  }
  // Depth along the view direction -> ray parameter: t = z / cos(ray, view direction).
  const double cosine = this->View.Parallel ? 1.0 : Dot(ray.Direction, this->View.Direction);
  if (!(cosine > 0.0))
  {
    segment = { -Infinity, Infinity };
    return true;
  }
  const Vec3 start = this->WorldToIndex.TransformPoint(ray.Origin + ray.TMin * ray.Direction);
  const bool startsInside = this->Grid->TouchesContributing(start, this->StartEps);
  segment.TNear = zNear / cosine - DepthTolerance * (std::fabs(zNear / cosine) + 1.0);
  segment.TFar = zFar / cosine + DepthTolerance * (std::fabs(zFar / cosine) + 1.0);
  if (startsInside)
  {
    segment.TNear = -Infinity;
  }
  return true;
}

bool DepthBufferSource::MayHaveSegments(int px, int py) const
{
  return this->NearFar[2 * PixelIndex(this->View, px, py)] < Empty;
}

void DepthBufferSource::GetSegments(int px, int py, const Ray& ray, std::vector<Segment>& out) const
{
  Segment s;
  if (this->PixelSegment(px, py, ray, s))
  {
    out.push_back(s);
  }
}

void PlaneBufferSource::Set(const Camera& view, std::vector<std::uint32_t> bits,
  int wordsPerPixel, const SupercellGrid* grid, int axis, int firstPlane,
  const Matrix4& worldToIndex)
{
  this->View = view;
  this->Bits = std::move(bits);
  this->WordsPerPixel = wordsPerPixel;
  this->Grid = grid;
  this->Axis = axis;
  this->FirstPlane = firstPlane;
  this->WorldToIndex = worldToIndex;
}

void PlaneBufferSource::GetSegments(int px, int py, const Ray& ray, std::vector<Segment>& out) const
{
  const std::uint32_t* words = this->Bits.data() + PixelIndex(this->View, px, py) * this->WordsPerPixel;
  const int a = this->Axis;
  const double o = this->WorldToIndex.TransformPoint(ray.Origin)[a];
  const double d = this->WorldToIndex.TransformVector(ray.Direction)[a];
  // A run of set planes [first, last] covers the slab between their outer boundaries.
  auto emit = [&](int first, int last) {
    if (d == 0.0)
    {
      out.push_back({ -Infinity, Infinity }); // the ray runs inside one slab
      return;
    }
    const double x0 = this->Grid->Boundary(a, this->FirstPlane + first);
    const double x1 = this->Grid->Boundary(a, this->FirstPlane + last + 1);
    double t0 = (x0 - o) / d, t1 = (x1 - o) / d;
    if (t0 > t1)
    {
      std::swap(t0, t1);
    }
    const double slack = 1e-9 * (std::fabs(t0) + std::fabs(t1) + 1.0);
    out.push_back({ t0 - slack, t1 + slack });
  };
  int runFirst = -1, runLast = -2;
  for (int w = 0; w < this->WordsPerPixel; ++w)
  {
    std::uint32_t word = words[w];
    while (word != 0) // zero words are skipped whole
    {
      const int plane = 32 * w + __builtin_ctz(word);
      word &= word - 1;
      if (plane == runLast + 1)
      {
        runLast = plane;
        continue;
      }
      if (runFirst >= 0)
      {
        emit(runFirst, runLast);
      }
      runFirst = runLast = plane;
    }
  }
  if (runFirst >= 0)
  {
    emit(runFirst, runLast);
  }
}

bool PlaneBufferSource::MayHaveSegments(int px, int py) const
{
  const std::uint32_t* words =
    this->Bits.data() + PixelIndex(this->View, px, py) * this->WordsPerPixel;
  return std::any_of(words, words + this->WordsPerPixel, [](std::uint32_t w) { return w != 0; });
}

void PlaneBufferSource::PixelPlanes(int px, int py, std::vector<int>& planes) const
{
  planes.clear();
  const std::uint32_t* words = this->Bits.data() + PixelIndex(this->View, px, py) * this->WordsPerPixel;
  for (int w = 0; w < this->WordsPerPixel; ++w)
  {
    for (std::uint32_t word = words[w]; word != 0; word &= word - 1)
    {
      planes.push_back(32 * w + __builtin_ctz(word));
    }
  }
}

void BothSource::GetSegments(int px, int py, const Ray& ray, std::vector<Segment>& out) const
{
  Segment limit;
  if (!this->Depth.PixelSegment(px, py, ray, limit))
  {
    return;
  }
  const std::size_t begin = out.size();
  this->Planes.GetSegments(px, py, ray, out);
  std::size_t kept = begin;
  for (std::size_t i = begin; i < out.size(); ++i)
  {
    const Segment s{ std::max(out[i].TNear, limit.TNear), std::min(out[i].TFar, limit.TFar) };
    if (s.TNear <= s.TFar)
    {
      out[kept++] = s;
    }
  }
  out.resize(kept);
}

} // namespace parc
