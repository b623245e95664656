// PARC for VTK: one volume as the core sees it (DESIGN.md section 9): its field, the
// parameters of its ray function, and where it lies in the world. A caster is prepared on
// one; several make a scene (SceneCaster).
#ifndef parcVolume_h
#define parcVolume_h

#include "parcCastParameters.h"
#include "parcMath.h"
#include "parcScalarField.h"

namespace parc
{

struct Volume
{
  const ScalarField* Field = nullptr;          ///< must outlive the casts
  const CastParameters* Parameters = nullptr;  ///< the ray function; must outlive the casts
  /// World -> voxel-index coordinates (affine). "World" is whatever frame the caller uses
  /// for rays, lights and clipping planes alike; the mapper centres it on the camera.
  Matrix4 WorldToIndex;
  /// Its inverse, voxel index -> world.
  Matrix4 IndexToWorld;

  /// Places the volume by its voxel-index -> world matrix; false (the placement
  /// unchanged) when it is singular.
  bool SetIndexToWorld(const Matrix4& indexToWorld)
  {
    if (!Invert(indexToWorld, this->WorldToIndex))
    {
      return false;
    }
    this->IndexToWorld = indexToWorld;
    return true;
  }
  /// The centre of the field's box, in world coordinates.
  Vec3 Centre() const
  {
    const int* dims = this->Field->GetDimensions();
    return this->IndexToWorld.TransformPoint(
      { 0.5 * (dims[0] - 1), 0.5 * (dims[1] - 1), 0.5 * (dims[2] - 1) });
  }
};

} // namespace parc

#endif
