// PARC for VTK: the GL side of one volume's passes, thin. It draws the acceleration plan's
// models with vtkPARCRasterizer (one for the view, one for the lights) into the plan's
// segment sources: a model's vertices are built only when the GPU lacks its version, and
// freed once the GPU holds it. Which passes a frame draws is the mapper's decision.
#ifndef parcPassDriver_h
#define parcPassDriver_h

#include "parcAccelerationPlan.h"
#include "parcPassView.h"
#include "parcVolume.h"
#include "vtkPARCRasterizer.h"

#include "vtkNew.h"

#include <cstdint>
#include <string>

class vtkRenderWindow;
class vtkWindow;

namespace parc
{
namespace vtk
{

class PassDriver
{
public:
  /// What the view's passes of a frame drew.
  struct Drawn
  {
    std::size_t Polygons = 0;
    int Planes = 0; ///< colour-model planes
    int Passes = 0; ///< colour passes (of up to the rasterizer's planes each)
  };

  /// The depth pass of the plan's depth model for view, into the plan's depth source;
  /// false when GL fails (GetLastError).
  bool DrawDepth(vtkRenderWindow* window, AccelerationPlan& plan, const Volume& volume,
    const PassView& view, Drawn& drawn);
  /// The colour passes of the plan's colour model along axis for view, into the plan's
  /// plane source; false when GL fails.
  bool DrawPlanes(vtkRenderWindow* window, AccelerationPlan& plan, const Volume& volume,
    const PassView& view, int axis, Drawn& drawn);
  /// The passes of a light for shadow rays (axis -1: of the depth model, else of the colour
  /// model along axis), resolution pixels a side, into source; false when GL fails.
  bool DrawLight(vtkRenderWindow* window, AccelerationPlan& plan, const LightFrame& light,
    int axis, int resolution, LightBufferSource& source);

  /// Frees the models and targets of the view's passes not drawn (depth, planes false).
  void ReleaseUnused(vtkRenderWindow* window, bool depth, bool planes);
  /// Frees every GL object when window is the context they belong to (or null).
  void ReleaseGraphicsResources(vtkWindow* window);

  const std::string& GetLastError() const { return this->View->GetLastError(); }
  /// Models uploaded so far by the view's passes (statistics).
  std::uint64_t GetUploadCount() const { return this->View->GetUploadCount(); }
  /// Passes whose model or target the view freed so far (ReleaseUnused).
  std::uint64_t GetReleaseCount() const { return this->View->GetReleaseCount(); }
  /// Seconds the view's passes spent setting up (see vtkPARCRasterizer::GetSetUpTime).
  double GetSetUpTime() const { return this->View->GetSetUpTime(); }
  /// Bytes of the GL models and targets of the view's and the lights' passes.
  std::size_t GetMemorySize() const
  {
    return this->View->GetMemorySize() + this->Lights->GetMemorySize();
  }
  /// Bytes the GL implementation holds for the passes beyond them, measured.
  std::size_t GetDriverMemorySize() const
  {
    return this->View->GetDriverMemorySize() + this->Lights->GetDriverMemorySize();
  }

private:
  vtkNew<vtkPARCRasterizer> View;
  vtkNew<vtkPARCRasterizer> Lights;
};

}
}

#endif
