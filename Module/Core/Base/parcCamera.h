// PARC for VTK: the one camera type of the core, for the primary view and, through the same
// type, for the frusta of lights.
//
// A Camera maps a Width x Height pixel image to rays in world coordinates. Pixel (px, py)
// has its centre at NDC ((2 px + 1) / Width - 1, (2 py + 1) / Height - 1); NDC z runs from
// -1 (near plane) to 1 (far plane). Perspective rays start at the eye; parallel rays start
// on the plane through the eye normal to the view direction, so that the global sample
// lattice (parcRay.h) has t = 0 there.
#ifndef parcCamera_h
#define parcCamera_h

#include "parcMath.h"
#include "parcRay.h"

#include <vector>

namespace parc
{

class Camera
{
public:
  int Width = 0, Height = 0;
  Matrix4 WorldToNDC; ///< the composite projection (z in [-1, 1])
  Matrix4 NDCToWorld; ///< its inverse
  bool Parallel = false;
  Vec3 Eye;       ///< camera position (world)
  Vec3 Direction; ///< unit view direction (world)
  double NearDistance = 0.0; ///< near clipping distance along Direction
  double FarDistance = 0.0;  ///< far clipping distance along Direction

  /// Sets WorldToNDC and NDCToWorld; false (the camera unchanged) when worldToNDC is
  /// singular.
  bool SetProjection(const Matrix4& worldToNDC);

  /// The ray through the centre of pixel (px, py), from the near to the far plane.
  Ray MakeRay(int px, int py) const;
  /// The ray parameter of the point at window depth z (in [0, 1]) on that ray.
  double DepthToParameter(const Ray& ray, int px, int py, double z) const;
  /// The depth of world point x along the view direction, measured from the eye.
  double ViewDepth(const Vec3& x) const { return Dot(x - this->Eye, this->Direction); }
  /// The continuous pixel coordinates of world point x (pixel (px, py) has its centre at
  /// (px + 0.5, py + 0.5)); false when x projects nowhere (on the eye plane in perspective).
  bool Project(const Vec3& x, double& u, double& v) const;
  /// The world vector from the ray of a pixel to the ray of its right-hand neighbour, at
  /// the view depth of world point x (the rays' spacing there); not finite when x projects
  /// nowhere.
  Vec3 PixelStepAt(const Vec3& x) const;
  /// Whether ray lies on one of the camera's rays (through the eye in perspective, along
  /// the view direction in parallel), within a relative tolerance: all its points then
  /// project to one image point.
  bool IsAlongRays(const Ray& ray) const;
  /// Bounds of all rays in the coordinates of transform (affine): the corners of the convex
  /// set of their start points (the near plane's corners, and the eye in perspective) and
  /// the directions whose positive combinations hold every ray's (at the image corners).
  void RayBounds(const Matrix4& transform, std::vector<Vec3>& starts,
    std::vector<Vec3>& directions) const;
  /// False when the box [lo, hi], in coordinates that toWorld (affine) maps to world, lies
  /// wholly outside one of the six planes of the view frustum (by more than a relative
  /// rounding margin): then no ray of the camera meets it. True otherwise.
  bool MayMeetBox(const Matrix4& toWorld, const Vec3& lo, const Vec3& hi) const;
};

} // namespace parc

#endif
