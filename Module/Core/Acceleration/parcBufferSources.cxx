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

const Segment WholeLine{ -Infinity, Infinity };

/// The common part of a and b into s; false when they do not overlap.
bool Intersect(const Segment& a, const Segment& b, Segment& s)
{
  s = { std::max(a.TNear, b.TNear), std::min(a.TFar, b.TFar) };
  return s.TNear <= s.TFar;
}

/// What a query without a pixel reads of a pass (see the file comment): the pixels whose
/// centres surround the line's image point (columns X, rows Y), and the line's view depth
/// as depth(t) = Depth0 + t * Cosine.
struct LineFootprint
{
  int X[2], Y[2];
  double Depth0, Cosine;

  /// The ray-parameter interval of the view depths [d0, d1], widened by the depths'
  /// rounding.
  Segment Interval(double d0, double d1) const
  {
    d0 -= DepthTolerance * (std::fabs(d0) + 1.0);
    d1 += DepthTolerance * (std::fabs(d1) + 1.0);
    double t0 = (d0 - this->Depth0) / this->Cosine, t1 = (d1 - this->Depth0) / this->Cosine;
    if (t0 > t1)
    {
      std::swap(t0, t1);
    }
    return { t0, t1 };
  }
  /// Appends the parts of the line the pass does not see, in front of the camera's near and
  /// behind its far distance.
  void Unseen(const Camera& camera, std::vector<Segment>& out) const
  {
    out.push_back(this->Interval(-Infinity, camera.NearDistance));
    out.push_back(this->Interval(camera.FarDistance, Infinity));
  }
};

/// The footprint of ray in the pass of camera; false when the pass cannot answer for the
/// ray and it gets the whole line: it is not along the camera's rays, it projects outside
/// the image, or it is inside a PC supercell where it crosses the near or far distance
/// (a supercell the pass may have drawn only in part).
bool Footprint(const Camera& camera, const SupercellGrid& grid, const Matrix4& worldToIndex,
  double eps, const Ray& ray, LineFootprint& f)
{
  f.Cosine = Dot(ray.Direction, camera.Direction);
  if (!(std::fabs(f.Cosine) > 0.0) || !camera.IsAlongRays(ray))
  {
    return false;
  }
  // In perspective the image point of a line through the eye is that of its direction.
  const Vec3 point = camera.Parallel
    ? ray.Origin
    : camera.Eye + (f.Cosine > 0.0 ? 1.0 : -1.0) * ray.Direction;
  double u, v;
  if (!camera.Project(point, u, v) || !(u >= 0.0 && u <= camera.Width) ||
    !(v >= 0.0 && v <= camera.Height))
  {
    return false;
  }
  const double image[2] = { u, v };
  const int size[2] = { camera.Width, camera.Height };
  int* pixels[2] = { f.X, f.Y };
  for (int a = 0; a < 2; ++a)
  {
    const int first = static_cast<int>(std::floor(image[a] - 0.5));
    pixels[a][0] = std::min(std::max(first, 0), size[a] - 1);
    pixels[a][1] = std::min(std::max(first + 1, 0), size[a] - 1);
  }
  f.Depth0 = camera.ViewDepth(ray.Origin);
  for (const double depth : { camera.NearDistance, camera.FarDistance })
  {
    const Vec3 x = ray.Origin + ((depth - f.Depth0) / f.Cosine) * ray.Direction;
    if (grid.TouchesContributing(worldToIndex.TransformPoint(x), eps))
    {
      return false;
    }
  }
  return true;
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

void DepthBufferSource::Segments(const RayQuery& query, std::vector<Segment>& out) const
{
  if (!query.HasPixel)
  {
    this->LineSegments(query.Path, out);
    return;
  }
  Segment s;
  if (this->PixelSegment(query.Pixel[0], query.Pixel[1], query.Path, s))
  {
    out.push_back(s);
  }
}

void DepthBufferSource::LineSegments(const Ray& ray, std::vector<Segment>& out) const
{
  LineFootprint f;
  if (!Footprint(this->View, *this->Grid, this->WorldToIndex, this->StartEps, ray, f))
  {
    out.push_back(WholeLine);
    return;
  }
  double zNear = Infinity, zFar = -Infinity;
  for (const int py : f.Y)
  {
    for (const int px : f.X)
    {
      const std::size_t pixel = PixelIndex(this->View, px, py);
      if (this->NearFar[2 * pixel] < Empty)
      {
        zNear = std::min(zNear, static_cast<double>(this->NearFar[2 * pixel]));
        zFar = std::max(zFar, -static_cast<double>(this->NearFar[2 * pixel + 1]));
      }
    }
  }
  f.Unseen(this->View, out);
  if (zNear <= zFar)
  {
    out.push_back(f.Interval(zNear, zFar));
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

const std::uint32_t* PlaneBufferSource::PixelWords(int px, int py) const
{
  return this->Bits.data() + PixelIndex(this->View, px, py) * this->WordsPerPixel;
}

void PlaneBufferSource::Segments(const RayQuery& query, std::vector<Segment>& out) const
{
  if (query.HasPixel)
  {
    this->EmitSlabs(this->PixelWords(query.Pixel[0], query.Pixel[1]), query.Path, out);
    return;
  }
  LineFootprint f;
  if (!Footprint(this->View, *this->Grid, this->WorldToIndex,
        StartTolerance * VolumeScale(*this->Grid), query.Path, f))
  {
    out.push_back(WholeLine);
    return;
  }
  std::vector<std::uint32_t> merged(this->WordsPerPixel, 0u);
  for (const int py : f.Y)
  {
    for (const int px : f.X)
    {
      const std::uint32_t* words = this->PixelWords(px, py);
      for (int w = 0; w < this->WordsPerPixel; ++w)
      {
        merged[w] |= words[w];
      }
    }
  }
  f.Unseen(this->View, out);
  this->EmitSlabs(merged.data(), query.Path, out);
}

void PlaneBufferSource::EmitSlabs(
  const std::uint32_t* words, const Ray& ray, std::vector<Segment>& out) const
{
  const int a = this->Axis;
  const double o = this->WorldToIndex.TransformPoint(ray.Origin)[a];
  const double d = this->WorldToIndex.TransformVector(ray.Direction)[a];
  // A run of set planes [first, last] covers the slab between their outer boundaries.
  auto emit = [&](int first, int last) {
    if (d == 0.0)
    {
      out.push_back(WholeLine); // the ray runs inside one slab
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
  const std::uint32_t* words = this->PixelWords(px, py);
  return std::any_of(words, words + this->WordsPerPixel, [](std::uint32_t w) { return w != 0; });
}

void PlaneBufferSource::PixelPlanes(int px, int py, std::vector<int>& planes) const
{
  planes.clear();
  const std::uint32_t* words = this->PixelWords(px, py);
  for (int w = 0; w < this->WordsPerPixel; ++w)
  {
    for (std::uint32_t word = words[w]; word != 0; word &= word - 1)
    {
      planes.push_back(32 * w + __builtin_ctz(word));
    }
  }
}

void BothSource::Segments(const RayQuery& query, std::vector<Segment>& out) const
{
  const std::size_t begin = out.size();
  if (query.HasPixel)
  {
    Segment limit;
    if (!this->Depth.PixelSegment(query.Pixel[0], query.Pixel[1], query.Path, limit))
    {
      return;
    }
    this->Planes.Segments(query, out);
    std::size_t kept = begin;
    for (std::size_t i = begin; i < out.size(); ++i)
    {
      Segment s;
      if (Intersect(out[i], limit, s))
      {
        out[kept++] = s;
      }
    }
    out.resize(kept);
    return;
  }
  // Without a pixel both sources give several segments: every pair's intersection.
  std::vector<Segment> limits, slabs;
  this->Depth.Segments(query, limits);
  this->Planes.Segments(query, slabs);
  for (const Segment& limit : limits)
  {
    for (const Segment& slab : slabs)
    {
      Segment s;
      if (Intersect(slab, limit, s))
      {
        out.push_back(s);
      }
    }
  }
}

} // namespace parc
