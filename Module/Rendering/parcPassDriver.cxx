#include "parcPassDriver.h"

#include "vtkRenderWindow.h"

#include <utility>
#include <vector>

namespace parc
{
namespace vtk
{

//------------------------------------------------------------------------------
bool PassDriver::DrawDepth(vtkRenderWindow* window, AccelerationPlan& plan,
  const Volume& volume, const PassView& view, Drawn& drawn)
{
  constexpr vtkPARCRasterizer::Pass pass = vtkPARCRasterizer::Pass::Depth;
  const std::uint64_t version = plan.GetModelVersion();
  const PolygonModel& model = plan.GetDepthModel(this->View->HasModel(window, pass, version));
  std::vector<float> nearFar = plan.GetDepthSource().ReleaseBuffer();
  const bool ok =
    this->View->RenderDepth(window, model, version, volume.IndexToWorld, view, nearFar);
  if (this->View->HasModel(window, pass, version))
  {
    plan.ReleaseDepthVertices();
  }
  plan.GetDepthSource().Set(view.Camera, std::move(nearFar), &plan.GetGrid(), volume.WorldToIndex);
  drawn.Polygons += plan.GetDepthQuads();
  return ok;
}

//------------------------------------------------------------------------------
bool PassDriver::DrawPlanes(vtkRenderWindow* window, AccelerationPlan& plan,
  const Volume& volume, const PassView& view, int axis, Drawn& drawn)
{
  constexpr vtkPARCRasterizer::Pass pass = vtkPARCRasterizer::Pass::Planes;
  const std::uint64_t version = plan.GetColorModelVersion(axis);
  const PolygonModel& model =
    plan.GetColorModel(axis, this->View->HasModel(window, pass, version));
  std::vector<std::uint32_t> bits = plan.GetPlaneSource().ReleaseBuffer();
  int words = 0;
  std::vector<Vec3> starts, directions;
  view.Camera.RayBounds(volume.WorldToIndex, starts, directions);
  const bool ok = this->View->RenderPlanes(window, model, version, volume.IndexToWorld, view,
    RayAxisSign(model, starts, directions), bits, words, drawn.Passes);
  if (this->View->HasModel(window, pass, version))
  {
    plan.ReleaseColorVertices(axis);
  }
  plan.GetPlaneSource().Set(view.Camera, std::move(bits), words, &plan.GetGrid(), axis,
    model.FirstPlane, volume.WorldToIndex);
  drawn.Planes = model.PlaneCount;
  drawn.Polygons += plan.GetColorQuads(axis);
  return ok;
}

//------------------------------------------------------------------------------
bool PassDriver::DrawLight(vtkRenderWindow* window, AccelerationPlan& plan,
  const LightFrame& light, int axis, int resolution, LightBufferSource& source)
{
  const bool planes = axis >= 0;
  const std::uint64_t version = planes ? plan.GetColorModelVersion(axis) : plan.GetModelVersion();
  const bool uploaded = this->Lights->HasModel(
    window, planes ? vtkPARCRasterizer::Pass::Planes : vtkPARCRasterizer::Pass::Depth, version);
  const PolygonModel& model =
    planes ? plan.GetColorModel(axis, uploaded) : plan.GetDepthModel(uploaded);
  return this->Lights->RenderLight(
    window, model, version, light, resolution, &plan.GetGrid(), source);
}

//------------------------------------------------------------------------------
void PassDriver::ReleaseUnused(vtkRenderWindow* window, bool depth, bool planes)
{
  if (!depth)
  {
    this->View->ReleasePass(window, vtkPARCRasterizer::Pass::Depth);
  }
  if (!planes)
  {
    this->View->ReleasePass(window, vtkPARCRasterizer::Pass::Planes);
  }
}

//------------------------------------------------------------------------------
void PassDriver::ReleaseGraphicsResources(vtkWindow* window)
{
  this->View->ReleaseGraphicsResources(window);
  this->Lights->ReleaseGraphicsResources(window);
}

}
}
