// PARC for VTK: depth-buffer PARC for shadow rays (paper section 5, DESIGN.md section 5):
// the cameras of a light's passes, and the segment source that reads their buffers.
//
// A light's cameras look from the light's eye over a volume's bounding box:
// - a positional light: one perspective frustum towards the box centre whose field of view
//   is twice the largest angle to the box corners (with a margin), when that is at most
//   MaxLightFrustumDegrees; otherwise (a light near or inside the box) the six faces of a
//   cube around the light, each a little wider than 90 degrees so that they overlap;
// - a directional light: one parallel camera along the light's direction, fitted to the
//   projected box, its eye outside the box on the light's side.
// A shadow ray runs from a shaded point towards the light, so it lies on a line of the
// light's cameras (through the eye, or along the direction): the buffer sources answer it
// without a pixel, reading the 2 x 2 pixels around its image point (parcBufferSources.h).
// The passes are drawn for any line through a pixel's neighbourhood (every face keeps its
// whole depth range), so that answer is conservative.
#ifndef parcLightFrusta_h
#define parcLightFrusta_h

#include "parcBufferSources.h"
#include "parcCamera.h"
#include "parcCastParameters.h"

#include <vector>

namespace parc
{

/// The widest single frustum of a positional light; wider views take six cube faces.
constexpr double MaxLightFrustumDegrees = 90.0;

/// The eye of a light's cameras over a box with corners (any frame): the light's position,
/// or for a directional light a point outside the box on the light's side.
Vec3 LightEye(const Light& light, const std::vector<Vec3>& corners);

/// The cameras (resolution x resolution pixels) of a light over a box, in a frame whose
/// origin is the eye: corners and the light are given relative to LightEye.
std::vector<Camera> LightCameras(const Light& light, const std::vector<Vec3>& corners, int resolution);

/// A volume's box as a light's passes see it: in the light's frame, whose origin is the eye.
struct LightFrame
{
  Vec3 Eye;                  ///< LightEye, in the caller's frame
  Light Relative;            ///< the light, relative to Eye
  std::vector<Vec3> Corners; ///< the corners of the volume's box, relative to Eye
  Matrix4 IndexToLight;      ///< voxel index -> the light's frame
  Matrix4 LightToIndex;
};
/// The light frame of a volume of dims voxels placed by indexToWorld (the caller's frame);
/// false when indexToWorld is singular.
bool MakeLightFrame(
  const Light& light, const Matrix4& indexToWorld, const int dims[3], LightFrame& frame);

/// The segment source of one volume's shadow rays towards one light: a ray (in the render's
/// frame) is moved by Offset into the cameras' frame, and the first camera whose image holds
/// the ray's start point, one pixel inside the border, answers it from its buffer (depth
/// or colour planes: a light uses one kind); any other ray gets the whole line.
class LightBufferSource final : public SegmentSource
{
public:
  Vec3 Offset; ///< added to a query's ray origin: render frame -> the cameras' frame
  std::vector<DepthBufferSource> Depth;  ///< one per camera, set from its depth pass
  std::vector<PlaneBufferSource> Planes; ///< or one per camera, set from its plane passes

  /// The light's cameras (frusta) with a buffer.
  std::size_t GetFrustumCount() const { return this->Depth.size() + this->Planes.size(); }
  /// Drops every buffer.
  void Clear()
  {
    this->Depth.clear();
    this->Planes.clear();
  }

  void Segments(const RayQuery& query, std::vector<Segment>& out) const override;
  /// Memory held by the buffers, in bytes.
  std::size_t GetMemorySize() const;
};

} // namespace parc

#endif
