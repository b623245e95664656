/**
 * @class   vtkPARCPVVolumeScene
 * @brief   The "PARC Volume" representations of one ParaView view, rendered as one scene.
 *
 * ParaView gives each representation a prop of its own, and props are drawn one after
 * another: two overlapping volumes would each be composited whole over the other. The
 * representations of a view share this scene instead (one per renderer, kept in the
 * renderer's information). While two or more of them are visible, the first of their
 * mappers asked to render in a render of the renderer renders all of them together, as
 * vtkPARCMultiVolume does (one vtkPARCVolumeMapper, one input port per volume in the
 * order the representations were added to the view): every ray meets every volume, so
 * composite samples, isosurfaces and maximum intensities intermix front to back; the other
 * mappers draw nothing in that render. Each volume keeps its representation's data,
 * property, transform and blend mode; the mapper's settings (acceleration, supercell size,
 * sample distance, threads, shadows, cropping) are those of the first visible
 * representation. One visible representation renders alone, as before.
 *
 * On several ranks each rank renders its pieces of all the volumes together, and ParaView
 * composites the ranks' images in the order of their pieces: exact when the volumes share
 * a partition (volumes on one grid, which ParaView splits alike).
 *
 * While the scene has members, the view's volumes are not depth-peeled with its
 * translucent geometry: they are drawn after it, as with the view's "Depth Peeling for
 * Volumes" off (see PeelingForVolumesSuspended).
 *
 * @sa vtkPARCVolumeRepresentation vtkPARCMultiVolume
 */
#ifndef vtkPARCPVVolumeScene_h
#define vtkPARCPVVolumeScene_h

#include "PARCParaViewModule.h" // For export macro
#include "vtkNew.h"             // For vtkNew
#include "vtkObject.h"
#include "vtkWeakPointer.h" // For vtkWeakPointer

#include <vector> // For the members

class vtkInformationObjectBaseKey;
class vtkPARCMultiVolume;
class vtkPARCVolumeMapper;
class vtkPARCVolumeRepresentation;
class vtkRenderer;

class PARCPARAVIEW_EXPORT vtkPARCPVVolumeScene : public vtkObject
{
public:
  static vtkPARCPVVolumeScene* New();
  vtkTypeMacro(vtkPARCPVVolumeScene, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The scene of renderer's representations, made on the first call. */
  static vtkPARCPVVolumeScene* Of(vtkRenderer* renderer);

  ///@{
  /** A representation shown in the scene's view, or no longer. */
  void AddMember(vtkPARCVolumeRepresentation* member);
  void RemoveMember(vtkPARCVolumeRepresentation* member);
  ///@}

  /**
   * When two or more members are visible with data, renders them together into renderer
   * once in each of its renders (later calls in the same render do nothing) and returns
   * true; otherwise returns false, and the caller renders its own volume alone.
   */
  bool RenderTogether(vtkRenderer* renderer);

  /**
   * The input port of member in the last render that rendered the members together, or -1
   * when that render left it out or the members rendered alone since.
   */
  int GetPortOf(vtkPARCVolumeRepresentation* member) const;

  /** The mapper that renders the members together (its statistics are theirs). */
  vtkPARCVolumeMapper* GetMapper();

protected:
  vtkPARCPVVolumeScene();
  ~vtkPARCPVVolumeScene() override;

private:
  vtkPARCPVVolumeScene(const vtkPARCPVVolumeScene&) = delete;
  void operator=(const vtkPARCPVVolumeScene&) = delete;

  /** Where a renderer keeps its scene. */
  static vtkInformationObjectBaseKey* SCENE();
  /** The visible members with data, in the order they were added. */
  std::vector<vtkPARCVolumeRepresentation*> VisibleMembers() const;
  /**
   * Lets go of the members' data and props from port firstPort on (all: 0), so that the
   * scene holds nothing of a representation it does not render.
   */
  void Release(int firstPort);
  /**
   * Starts a render of the renderer: the members are not rendered in it yet, and the
   * renderer's volumes are not peeled while it has members (see PeelingForVolumesSuspended).
   */
  void StartRender();

  std::vector<vtkPARCVolumeRepresentation*> Members;
  /** The members of the last render together, by port (empty after a render alone). */
  std::vector<vtkPARCVolumeRepresentation*> LastPorts;
  vtkWeakPointer<vtkRenderer> Renderer;
  unsigned long StartObserver = 0;
  bool RenderedInThisRender = false;
  /**
   * Whether the scene turned the renderer's UseDepthPeelingForVolumes off (it turns it on
   * again when its last member leaves). VTK's dual depth peeling renders volumes inside
   * its peels with shader code only the GPU mapper has; vtkPARCVolumeMapper then draws
   * when the renderer ends, which on several ranks is after ParaView composited their
   * images. Without peeling for volumes, they render after the translucent geometry
   * before compositing, as ParaView's own volumes do with the view's "Depth Peeling for
   * Volumes" off.
   */
  bool PeelingForVolumesSuspended = false;
  vtkNew<vtkPARCVolumeMapper> Mapper;
  vtkNew<vtkPARCMultiVolume> Volumes;
};

#endif
