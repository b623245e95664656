#include "parcCamera.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace parc
{

namespace
{
/// Relative tolerance of IsAlongRays: about a thousand double roundings.
constexpr double AlongRaysTolerance = 1e-12;

/// Relative margin of MayMeetBox: a box must be this far outside a plane, relative to the
/// size of the clip coordinates, to be outside.
constexpr double OutsideMargin = 1e-9;

/// The NDC x, y of the centre of pixel (px, py).
void PixelToNDC(const Camera& camera, int px, int py, double& x, double& y)
{
  x = (2.0 * px + 1.0) / camera.Width - 1.0;
  y = (2.0 * py + 1.0) / camera.Height - 1.0;
}
}

bool Camera::SetProjection(const Matrix4& worldToNDC)
{
  Matrix4 inverse;
  if (!Invert(worldToNDC, inverse))
  {
    return false;
  }
  this->WorldToNDC = worldToNDC;
  this->NDCToWorld = inverse;
  return true;
}

Ray Camera::MakeRay(int px, int py) const
{
  double x, y;
  PixelToNDC(*this, px, py, x, y);
  const Vec3 nearPoint = this->NDCToWorld.TransformHomogeneous({ x, y, -1.0 });
  const Vec3 farPoint = this->NDCToWorld.TransformHomogeneous({ x, y, 1.0 });
  Ray ray;
  ray.Direction = Normalized(farPoint - nearPoint);
  if (this->Parallel)
  {
    // The lattice starts on the plane through the camera position normal to the rays.
    ray.Origin = nearPoint - Dot(nearPoint - this->Eye, ray.Direction) * ray.Direction;
  }
  else
  {
    ray.Origin = this->Eye;
  }
  ray.TMin = Dot(nearPoint - ray.Origin, ray.Direction);
  ray.TMax = Dot(farPoint - ray.Origin, ray.Direction);
  return ray;
}

double Camera::DepthToParameter(const Ray& ray, int px, int py, double z) const
{
  double x, y;
  PixelToNDC(*this, px, py, x, y);
  const Vec3 p = this->NDCToWorld.TransformHomogeneous({ x, y, 2.0 * z - 1.0 });
  return Dot(p - ray.Origin, ray.Direction);
}

bool Camera::Project(const Vec3& x, double& u, double& v) const
{
  const Matrix4& m = this->WorldToNDC;
  const double w = m(3, 0) * x.X + m(3, 1) * x.Y + m(3, 2) * x.Z + m(3, 3);
  if (!(std::fabs(w) > 0.0))
  {
    return false;
  }
  const Vec3 ndc = (1.0 / w) * m.TransformPoint(x);
  u = 0.5 * (ndc.X + 1.0) * this->Width;
  v = 0.5 * (ndc.Y + 1.0) * this->Height;
  return std::isfinite(u) && std::isfinite(v);
}

Vec3 Camera::PixelStepAt(const Vec3& x) const
{
  const Vec3 ndc = this->WorldToNDC.TransformHomogeneous(x);
  const Vec3 right = { ndc.X + 2.0 / this->Width, ndc.Y, ndc.Z };
  return this->NDCToWorld.TransformHomogeneous(right) - x;
}

bool Camera::IsAlongRays(const Ray& ray) const
{
  if (this->Parallel)
  {
    return Length(Cross(ray.Direction, this->Direction)) <= AlongRaysTolerance;
  }
  const Vec3 toEye = this->Eye - ray.Origin;
  const double distance = Length(toEye);
  return Length(Cross(ray.Direction, toEye)) <= AlongRaysTolerance * distance;
}

void Camera::RayBounds(
  const Matrix4& transform, std::vector<Vec3>& starts, std::vector<Vec3>& directions) const
{
  starts.clear();
  directions.clear();
  if (!this->Parallel)
  {
    starts.push_back(transform.TransformPoint(this->Eye));
  }
  for (const double x : { -1.0, 1.0 })
  {
    for (const double y : { -1.0, 1.0 })
    {
      const Vec3 nearPoint = this->NDCToWorld.TransformHomogeneous({ x, y, -1.0 });
      const Vec3 farPoint = this->NDCToWorld.TransformHomogeneous({ x, y, 1.0 });
      starts.push_back(transform.TransformPoint(nearPoint));
      directions.push_back(transform.TransformVector(farPoint - nearPoint));
    }
  }
}

bool Camera::MayMeetBox(const Matrix4& toWorld, const Vec3& lo, const Vec3& hi) const
{
  const Matrix4 toClip = Multiply(this->WorldToNDC, toWorld);
  // Each frustum plane is linear in homogeneous clip coordinates (x <= w, -w <= x, ...), so
  // the box is outside a plane when all its corners are.
  std::array<int, 6> outside{};
  for (int corner = 0; corner < 8; ++corner)
  {
    const Vec3 p{ corner & 1 ? hi.X : lo.X, corner & 2 ? hi.Y : lo.Y, corner & 4 ? hi.Z : lo.Z };
    const Vec3 c = toClip.TransformPoint(p);
    const double w = toClip(3, 0) * p.X + toClip(3, 1) * p.Y + toClip(3, 2) * p.Z + toClip(3, 3);
    const double clip[3] = { c.X, c.Y, c.Z };
    for (int axis = 0; axis < 3; ++axis)
    {
      const double margin = OutsideMargin * (std::fabs(clip[axis]) + std::fabs(w));
      outside[2 * axis] += clip[axis] - w > margin;
      outside[2 * axis + 1] += -clip[axis] - w > margin;
    }
  }
  return std::none_of(outside.begin(), outside.end(), [](int n) { return n == 8; });
}

} // namespace parc
