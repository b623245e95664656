// Helpers shared by the core unit tests.
#ifndef parcTestUtilities_h
#define parcTestUtilities_h

#include "parcRayCaster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <vector>

namespace parctest
{
/// A field of n[0] x n[1] x n[2] voxels with values f(i, j, k).
inline parc::ScalarField MakeField(const int n[3], const std::function<float(int, int, int)>& f)
{
  std::vector<float> v(static_cast<size_t>(n[0]) * n[1] * n[2]);
  size_t idx = 0;
  for (int k = 0; k < n[2]; ++k)
  {
    for (int j = 0; j < n[1]; ++j)
    {
      for (int i = 0; i < n[0]; ++i)
      {
        v[idx++] = f(i, j, k);
      }
    }
  }
  parc::ScalarField field;
  field.Assign(v.data(), n);
  return field;
}

/// Two overlapping Gaussian blobs in a 33 x 30 x 28 field, values 0 to 255.
inline parc::ScalarField Blobs()
{
  const int n[3] = { 33, 30, 28 };
  return MakeField(n, [](int i, int j, int k) {
    const double a = std::exp(-0.02 * ((i - 10) * (i - 10) + (j - 12) * (j - 12) + (k - 9) * (k - 9)));
    const double b = std::exp(-0.03 * ((i - 22) * (i - 22) + (j - 18) * (j - 18) + (k - 18) * (k - 18)));
    return static_cast<float>(255.0 * std::max(a, b));
  });
}

/// A white colour table and an opacity function from (x, y) nodes.
inline void SetOpacity(parc::CastParameters& p, std::vector<double> x, std::vector<double> y,
  bool clamp = true)
{
  p.Opacity.SetNodes(std::move(x), std::move(y), clamp);
  p.Color.SetTable(0.0, 1.0, { 1.f, 1.f, 1.f, 1.f, 1.f, 1.f });
}

/// Parallel rays along (sin a, 0, -cos a) over a window of 2 halfWidth x 2 halfWidth
/// around centre: NDC (x, y, z) -> centre + halfWidth (x right + y up) + halfDepth z
/// forward.
inline parc::Camera ParallelView(int w, int h, double angle, double halfWidth = 20.0,
  const parc::Vec3& centre = parc::Vec3{ 16, 16, 16 }, double halfDepth = 60.0)
{
  parc::Camera v;
  v.Width = w;
  v.Height = h;
  v.Parallel = true;
  const double c = std::cos(angle), s = std::sin(angle);
  const parc::Vec3 right{ c, 0, s }, up{ 0, 1, 0 }, forward{ s, 0, -c };
  parc::Matrix4 ndcToWorld, worldToNDC;
  for (int r = 0; r < 3; ++r)
  {
    ndcToWorld(r, 0) = halfWidth * right[r];
    ndcToWorld(r, 1) = halfWidth * up[r];
    ndcToWorld(r, 2) = halfDepth * forward[r];
    ndcToWorld(r, 3) = centre[r];
  }
  parc::Invert(ndcToWorld, worldToNDC);
  v.SetProjection(worldToNDC);
  v.Eye = centre - (halfDepth + 20.0) * forward;
  v.Direction = forward;
  return v;
}

/// A ray from origin along direction (normalized) with a long parameter range.
inline parc::Ray MakeRay(const parc::Vec3& origin, const parc::Vec3& direction)
{
  parc::Ray r;
  r.Origin = origin;
  r.Direction = parc::Normalized(direction);
  r.TMin = 0.0;
  r.TMax = 1e6;
  return r;
}

/// The distance from centre c, sampled on an n^3 grid.
inline parc::ScalarField DistanceField(int n, const parc::Vec3& c)
{
  const int dims[3] = { n, n, n };
  return MakeField(dims,
    [&](int i, int j, int k) { return static_cast<float>(Length(parc::Vec3(i, j, k) - c)); });
}

/// A ray-cast image of a camera, with the statistics of its cast.
struct SceneImage
{
  std::vector<float> RGBA;
  parc::CastStatistics Stats; ///< summed over the members of a scene
  explicit SceneImage(const parc::Camera& view)
    : RGBA(4 * static_cast<std::size_t>(view.Width) * view.Height)
  {
  }
};

/// The image of several volumes cast together (termination opacity 0.99).
inline SceneImage CastScene(
  const std::vector<parc::SceneCaster::Member>& members, const parc::Camera& view)
{
  parc::SceneCaster scene;
  EXPECT_TRUE(scene.SetMembers(members, 0.99));
  SceneImage image(view);
  std::vector<parc::CastStatistics> stats;
  scene.CastImage(view, nullptr, image.RGBA.data(), stats);
  EXPECT_EQ(stats.size(), members.size());
  for (const parc::CastStatistics& s : stats)
  {
    image.Stats += s;
  }
  return image;
}

/// Whether two images are the same bits.
inline bool Identical(const SceneImage& a, const SceneImage& b)
{
  return a.RGBA.size() == b.RGBA.size() &&
    std::memcmp(a.RGBA.data(), b.RGBA.data(), a.RGBA.size() * sizeof(float)) == 0;
}

/// Casts one ray through the whole volume; returns its RGBA.
struct CastResult
{
  float RGBA[4];
  double FirstHit;
  parc::CastStatistics Stats;
};
inline CastResult CastOne(const parc::Volume& volume, const parc::Ray& ray,
  const parc::SegmentSource* source = nullptr)
{
  parc::RayCaster caster;
  caster.Prepare(volume);
  parc::WholeRaySource whole;
  std::vector<parc::Segment> segments;
  std::vector<parc::LatticeRange> ranges;
  CastResult r;
  caster.CastRay(parc::RayQuery::Anywhere(ray), source ? *source : whole, segments, ranges, r.RGBA, r.Stats,
    &r.FirstHit);
  return r;
}
/// CastOne of field with parameters p, in voxel-index coordinates.
inline CastResult CastOne(const parc::ScalarField& field, const parc::CastParameters& p,
  const parc::Ray& ray, const parc::SegmentSource* source = nullptr)
{
  return CastOne(parc::Volume{ &field, &p }, ray, source);
}
}

#endif
