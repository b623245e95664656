#include "parcCamera.h"

#include <cmath>

namespace parc
{

namespace
{
/// Relative tolerance of IsAlongRays: about a thousand double roundings.
constexpr double AlongRaysTolerance = 1e-12;

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

} // namespace parc
