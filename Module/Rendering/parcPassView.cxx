#include "parcPassView.h"

#include "parcVTKConversion.h"

#include "vtkCamera.h"
#include "vtkRenderer.h"

#include <algorithm>
#include <cmath>

namespace parc
{
namespace vtk
{
namespace
{
/// Relative size of the x, y terms of the inverse projection's w row below which the rays
/// count as affine in NDC x, y (otherwise the depth pass keeps whole face ranges).
constexpr double AffineTolerance = 1e-12;
}

//------------------------------------------------------------------------------
CameraFrame ReadCameraFrame(vtkRenderer* ren)
{
  vtkCamera* camera = ren->GetActiveCamera();
  const double* eye = camera->GetPosition();
  const double* direction = camera->GetDirectionOfProjection();
  CameraFrame frame;
  frame.Origin = { eye[0], eye[1], eye[2] };
  frame.Direction = Normalized({ direction[0], direction[1], direction[2] });
  frame.Parallel = camera->GetParallelProjection() != 0;
  return frame;
}

//------------------------------------------------------------------------------
bool MakePassView(
  vtkRenderer* ren, const CameraFrame& frame, int width, int height, PassView& view)
{
  vtkCamera* camera = ren->GetActiveCamera();
  // The view transform of the camera's frame: the translation by the camera position, large
  // far from the origin, cancels in double here (leaving at most a constant offset that the
  // rays and the passes share) and never enters float.
  view.FrameOrigin = frame.Origin;
  const Matrix4 worldToView = ToMatrix4(camera->GetViewTransformMatrix());
  const Matrix4 frameToView =
    Translated(worldToView, worldToView.TransformVector(view.FrameOrigin));
  Camera& c = view.Camera;
  c.Width = width;
  c.Height = height;
  c.Parallel = frame.Parallel;
  c.Eye = Vec3();
  c.Direction = frame.Direction;
  c.NearDistance = camera->GetClippingRange()[0];
  c.FarDistance = camera->GetClippingRange()[1];
  if (!c.SetProjection(Multiply(
        ToMatrix4(camera->GetProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1)),
        frameToView)))
  {
    return false;
  }
  SetRayCoefficients(view);
  return true;
}

//------------------------------------------------------------------------------
void SetRayCoefficients(PassView& pass)
{
  const Camera& rays = pass.Camera;
  // With the camera's projections the homogeneous w of a point of NDC depth z does not
  // depend on NDC x, y, so ray start and (unnormalized) direction are affine in x, y.
  const Matrix4& m = rays.NDCToWorld;
  auto start = [&](double x, double y) {
    return rays.Parallel ? m.TransformHomogeneous({ x, y, -1.0 }) - rays.Eye : Vec3();
  };
  auto direction = [&](double x, double y) {
    return m.TransformHomogeneous({ x, y, 1.0 }) - m.TransformHomogeneous({ x, y, -1.0 });
  };
  pass.RayBase[0] = start(0.0, 0.0);
  pass.RayBase[1] = start(1.0, 0.0) - pass.RayBase[0];
  pass.RayBase[2] = start(0.0, 1.0) - pass.RayBase[0];
  pass.RayDirection[0] = direction(0.0, 0.0);
  pass.RayDirection[1] = direction(1.0, 0.0) - pass.RayDirection[0];
  pass.RayDirection[2] = direction(0.0, 1.0) - pass.RayDirection[0];
  if (rays.Parallel)
  {
    pass.RayDirection[1] = pass.RayDirection[2] = Vec3();
  }
  // |u| is convex in (x, y): its largest value on the image is at a corner.
  pass.MaxRayDirectionLength = 0.0;
  for (double x : { -1.0, 1.0 })
  {
    for (double y : { -1.0, 1.0 })
    {
      pass.MaxRayDirectionLength = std::max(pass.MaxRayDirectionLength,
        Length(pass.RayDirection[0] + x * pass.RayDirection[1] + y * pass.RayDirection[2]));
    }
  }
  const double wScale = std::fabs(m(3, 2)) + std::fabs(m(3, 3));
  pass.AffineRays = std::fabs(m(3, 0)) + std::fabs(m(3, 1)) <= AffineTolerance * wScale;
}

}
}
