// PARC for VTK: drawing a volume at the end of its renderer's render, for the passes of VTK a
// CPU ray caster cannot draw inside.
#ifndef parcEndOfRenderDraw_h
#define parcEndOfRenderDraw_h

#include "vtkNew.h"
#include "vtkWeakPointer.h"

#include <functional>
#include <vector>

class vtkCallbackCommand;
class vtkObject;
class vtkProp;
class vtkRenderer;
class vtkVolume;

namespace parc
{
namespace vtk
{
/// Whether renderer is rendering inside VTK's dual depth peeling (UseDepthPeeling and
/// UseDepthPeelingForVolumes, ParaView's default, with translucent geometry): the pass
/// renders volumes in each peel into its own framebuffer, through shader code only
/// vtkGPUVolumeRayCastMapper provides. The pass marks the renderer's props while it runs
/// (a prop that renders through another, as ParaView's vtkPVLODVolume, passes the mapper
/// a volume without the mark).
bool InsideDualDepthPeeling(vtkRenderer* renderer);

/// Draws volumes once at the end of their renderer's render (its EndEvent): over what the
/// renderer drew, as VTK draws volumes after its translucent geometry when they are not
/// peeled with it.
class EndOfRenderDraw
{
public:
  using Draw = std::function<void(vtkRenderer*, vtkVolume*)>;
  explicit EndOfRenderDraw(Draw draw);
  ~EndOfRenderDraw();
  EndOfRenderDraw(const EndOfRenderDraw&) = delete;
  EndOfRenderDraw& operator=(const EndOfRenderDraw&) = delete;

  /// Draws volume at the end of renderer's current render (once however often asked).
  void Request(vtkRenderer* renderer, vtkVolume* volume);

private:
  struct Entry
  {
    vtkWeakPointer<vtkRenderer> Renderer;
    vtkWeakPointer<vtkVolume> Volume;
    unsigned long Tag = 0;
    bool Pending = false;
  };
  static void OnEndEvent(vtkObject* caller, unsigned long, void* self, void*);

  Draw DrawVolume;
  vtkNew<vtkCallbackCommand> Callback;
  std::vector<Entry> Entries;
};
}
}

#endif
