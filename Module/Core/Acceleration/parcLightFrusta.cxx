#include "parcLightFrusta.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace parc
{

namespace
{
/// Growth of a light's field of view (and of a parallel camera's window) beyond the box.
constexpr double ViewMargin = 1.02;
/// Half-angle tangent of the cube faces: a little over 45 degrees, so that faces overlap.
constexpr double CubeFaceTangent = 1.05;
/// Near distance of the cube faces as a fraction of the box's diagonal (nearer parts of a
/// line count as covered).
constexpr double CubeNearFraction = 1e-3;
/// How far outside the box a directional light's eye lies, in box radii.
constexpr double DirectionalEyeRadii = 2.0;
/// A shadow ray's start must project this many pixels inside a camera's image.
constexpr double BorderPixels = 1.0;

Vec3 Centre(const std::vector<Vec3>& corners)
{
  Vec3 c;
  for (const Vec3& x : corners)
  {
    c = c + x;
  }
  return (1.0 / static_cast<double>(corners.size())) * c;
}

/// Unit vectors right and up completing forward to a right-handed frame.
void Basis(const Vec3& forward, Vec3& right, Vec3& up)
{
  const Vec3 a = std::fabs(forward.X) < 0.6 ? Vec3{ 1, 0, 0 }
    : (std::fabs(forward.Y) < 0.6 ? Vec3{ 0, 1, 0 } : Vec3{ 0, 0, 1 });
  right = Normalized(Cross(forward, a));
  up = Cross(right, forward);
}

/// A camera at the origin looking along forward; perspective with half-angle tangent
/// tangent, or parallel over [-half, half]^2 (tangent then holds half).
bool MakeCamera(const Vec3& forward, bool parallel, double tangent, double nearDistance,
  double farDistance, int resolution, Camera& camera)
{
  Vec3 right, up;
  Basis(forward, right, up);
  const double n = nearDistance, f = farDistance;
  Matrix4 m;
  for (int c = 0; c < 3; ++c)
  {
    m(0, c) = right[c] / tangent;
    m(1, c) = up[c] / tangent;
    if (parallel)
    {
      m(2, c) = 2.0 * forward[c] / (f - n);
      m(3, c) = 0.0;
    }
    else
    {
      m(2, c) = (f + n) / (f - n) * forward[c];
      m(3, c) = forward[c];
    }
  }
  m(0, 3) = m(1, 3) = 0.0;
  m(2, 3) = parallel ? -(f + n) / (f - n) : -2.0 * f * n / (f - n);
  m(3, 3) = parallel ? 1.0 : 0.0;
  camera.Width = camera.Height = resolution;
  camera.Parallel = parallel;
  camera.Eye = Vec3();
  camera.Direction = forward;
  camera.NearDistance = n;
  camera.FarDistance = f;
  return camera.SetProjection(m);
}
}

Vec3 LightEye(const Light& light, const std::vector<Vec3>& corners)
{
  if (light.Positional)
  {
    return light.Position;
  }
  const Vec3 centre = Centre(corners);
  double radius = 0.0;
  for (const Vec3& x : corners)
  {
    radius = std::max(radius, Length(x - centre));
  }
  return centre + (DirectionalEyeRadii * radius) * Normalized(light.Position - light.FocalPoint);
}

std::vector<Camera> LightCameras(const Light& light, const std::vector<Vec3>& corners, int resolution)
{
  std::vector<Camera> cameras;
  const Vec3 centre = Centre(corners);
  double farthest = 0.0;
  for (const Vec3& x : corners)
  {
    farthest = std::max(farthest, Length(x));
  }
  if (!light.Positional)
  {
    const Vec3 forward = Normalized(light.FocalPoint - light.Position);
    Vec3 right, up;
    Basis(forward, right, up);
    double half = 0.0, nearest = std::numeric_limits<double>::infinity(), deepest = 0.0;
    for (const Vec3& x : corners)
    {
      half = std::max({ half, std::fabs(Dot(x, right)), std::fabs(Dot(x, up)) });
      nearest = std::min(nearest, Dot(x, forward));
      deepest = std::max(deepest, Dot(x, forward));
    }
    Camera camera;
    if (half > 0.0 && MakeCamera(forward, true, ViewMargin * half, 0.5 * nearest,
                        ViewMargin * deepest, resolution, camera))
    {
      cameras.push_back(camera);
    }
    return cameras;
  }
  // Positional: one frustum when the box is seen under at most MaxLightFrustumDegrees.
  const double distance = Length(centre);
  double halfAngle = distance > 0.0 ? 0.0 : M_PI;
  double nearest = std::numeric_limits<double>::infinity();
  const Vec3 forward = distance > 0.0 ? (1.0 / distance) * centre : Vec3{ 0, 0, 1 };
  for (const Vec3& x : corners)
  {
    const double length = Length(x);
    const double depth = Dot(x, forward);
    nearest = std::min(nearest, depth);
    halfAngle = std::max(halfAngle, length > 0.0 ? std::acos(std::min(1.0, depth / length)) : M_PI);
  }
  const double fov = 2.0 * ViewMargin * halfAngle * (180.0 / M_PI);
  Camera camera;
  if (fov <= MaxLightFrustumDegrees && nearest > 0.0 &&
    MakeCamera(forward, false, std::tan(ViewMargin * halfAngle), 0.5 * nearest,
      ViewMargin * farthest, resolution, camera))
  {
    cameras.push_back(camera);
    return cameras;
  }
  double diagonal = 0.0;
  for (const Vec3& x : corners)
  {
    diagonal = std::max(diagonal, 2.0 * Length(x - centre));
  }
  for (int axis = 0; axis < 3; ++axis)
  {
    for (const double sign : { 1.0, -1.0 })
    {
      Vec3 face;
      face[axis] = sign;
      if (MakeCamera(face, false, CubeFaceTangent, CubeNearFraction * diagonal,
            ViewMargin * farthest, resolution, camera))
      {
        cameras.push_back(camera);
      }
    }
  }
  return cameras;
}

bool MakeLightFrame(
  const Light& light, const Matrix4& indexToWorld, const int dims[3], LightFrame& frame)
{
  std::vector<Vec3> corners;
  for (int c = 0; c < 8; ++c)
  {
    corners.push_back(indexToWorld.TransformPoint({ (c & 1) ? dims[0] - 1.0 : 0.0,
      (c & 2) ? dims[1] - 1.0 : 0.0, (c & 4) ? dims[2] - 1.0 : 0.0 }));
  }
  frame.Eye = LightEye(light, corners);
  frame.Relative = light;
  frame.Relative.Position = light.Position - frame.Eye;
  frame.Relative.FocalPoint = light.FocalPoint - frame.Eye;
  frame.Corners.clear();
  for (const Vec3& x : corners)
  {
    frame.Corners.push_back(x - frame.Eye);
  }
  frame.IndexToLight = Translated(indexToWorld, -1.0 * frame.Eye);
  return Invert(frame.IndexToLight, frame.LightToIndex);
}

namespace
{
/// Answers moved from the first buffer whose camera's image holds the ray's start, one
/// pixel inside the border; false when none does.
template <class Buffer>
bool AnswerFromCamera(
  const std::vector<Buffer>& buffers, const RayQuery& moved, std::vector<Segment>& out)
{
  for (const Buffer& buffer : buffers)
  {
    const Camera& camera = buffer.GetView();
    double u, v;
    if ((camera.Parallel || camera.ViewDepth(moved.Path.Origin) > 0.0) &&
      camera.Project(moved.Path.Origin, u, v) && u >= BorderPixels &&
      u <= camera.Width - BorderPixels && v >= BorderPixels && v <= camera.Height - BorderPixels)
    {
      buffer.Segments(moved, out);
      return true;
    }
  }
  return false;
}

template <class Buffer>
std::size_t MemoryOf(const std::vector<Buffer>& buffers)
{
  std::size_t bytes = 0;
  for (const Buffer& buffer : buffers)
  {
    bytes += buffer.GetMemorySize();
  }
  return bytes;
}
}

void LightBufferSource::Segments(const RayQuery& query, std::vector<Segment>& out) const
{
  RayQuery moved = RayQuery::Anywhere(query.Path);
  moved.Path.Origin = query.Path.Origin + this->Offset;
  if (!AnswerFromCamera(this->Depth, moved, out) && !AnswerFromCamera(this->Planes, moved, out))
  {
    constexpr double inf = std::numeric_limits<double>::infinity();
    out.push_back({ -inf, inf });
  }
}

std::size_t LightBufferSource::GetMemorySize() const
{
  return MemoryOf(this->Depth) + MemoryOf(this->Planes);
}

} // namespace parc
