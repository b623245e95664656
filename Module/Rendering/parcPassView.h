// PARC for VTK: the view of a ray image and of the PARC passes, read from a renderer's
// camera once per frame. No OpenGL.
#ifndef parcPassView_h
#define parcPassView_h

#include "parcCamera.h" // For Camera

class vtkRenderer;

namespace parc
{
namespace vtk
{
/// The camera of a pass and of the rays, plus what the shaders need, in the camera's
/// frame: world coordinates minus the camera position (FrameOrigin), so that a volume far
/// from the world's origin loses no precision. The eye is the frame's origin; the models'
/// index-to-world matrices given to the passes must be in the same frame.
struct PassView
{
  parc::Camera Camera; ///< the eye is at 0
  Vec3 FrameOrigin; ///< world position of the coordinates' origin
  /// The ray through NDC (x, y) in eye-relative world coordinates: it starts at
  /// RayBase[0] + x RayBase[1] + y RayBase[2] (0 in perspective) and runs along
  /// RayDirection[0] + x RayDirection[1] + y RayDirection[2] (not normalized).
  Vec3 RayBase[3];
  Vec3 RayDirection[3];
  double MaxRayDirectionLength = 0.0; ///< the largest |direction| over the image
  bool AffineRays = false; ///< false: the coefficients do not describe the rays
};

/// The renderer's active camera as a render reads it once, when it begins: what its
/// phases need of it before the ray image's view.
struct CameraFrame
{
  Vec3 Origin; ///< the camera position: the world position of the render frame's origin
  Vec3 Direction; ///< the direction of projection, unit length
  bool Parallel = false;
};

/// The frame of the renderer's active camera.
CameraFrame ReadCameraFrame(vtkRenderer* ren);

/// The view of a width x height ray image of the renderer's active camera (whose frame is
/// frame), in the camera's frame (see PassView; the eye is at 0). False when the
/// projection is singular.
bool MakePassView(vtkRenderer* ren, const CameraFrame& frame, int width, int height,
  PassView& view);

/// Fills the ray coefficients of view from its camera.
void SetRayCoefficients(PassView& view);
}
}

#endif
