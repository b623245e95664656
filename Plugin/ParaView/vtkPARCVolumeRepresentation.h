/**
 * @class   vtkPARCVolumeRepresentation
 * @brief   ParaView's image volume representation with vtkPARCVolumeMapper as its mapper.
 *
 * The "PARC Volume" representation type of image data in ParaView: everything of
 * vtkImageVolumeRepresentation (transfer functions, blend modes, iso values, shading,
 * cropping), rendered by vtkPARCVolumeMapper on the CPU, bit-identical in every
 * acceleration mode. The mapper's own settings are forwarded: acceleration mode,
 * supercell size, sample distance and threads. The statistics of the last render are
 * read from the mapper (GetPARCMapper). Several "PARC Volume" representations in one
 * view render together, intermixed (see vtkPARCPVVolumeScene).
 *
 * @sa vtkPARCVolumeMapper vtkPARCPVPolygonModelFilter
 */
#ifndef vtkPARCVolumeRepresentation_h
#define vtkPARCVolumeRepresentation_h

#include "PARCParaViewModule.h" // For export macro
#include "vtkImageVolumeRepresentation.h"

class vtkPARCPVVolumeMapper;
class vtkPARCPVVolumeScene;
class vtkPARCVolumeMapper;

class PARCPARAVIEW_EXPORT vtkPARCVolumeRepresentation : public vtkImageVolumeRepresentation
{
public:
  static vtkPARCVolumeRepresentation* New();
  vtkTypeMacro(vtkPARCVolumeRepresentation, vtkImageVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Forwarded to vtkPARCVolumeMapper (see there; SetSampleDistance <= 0: half the smallest
   * voxel edge).
   */
  void SetAccelerationMode(int mode);
  void SetSupercellSize(double x, double y, double z);
  void SetAutoSupercellSize(bool automatic);
  void SetSampleDistance(double distance);
  void SetNumberOfThreads(int threads);
  void SetBrickedCopy(bool bricked);
  ///@}

  /**
   * Whether the view's lights cast shadows through the volume (ShadowMode On; off:
   * FromRenderer, as ParaView's own shadow switch does not reach the renderer).
   */
  void SetShadows(bool shadows);

  /**
   * Forwarded to the volume property; a split volume's pieces are read again when shading
   * changes their border layers (BorderLayers).
   */
  void SetShade(bool shade);

  /**
   * The mapper.
   */
  vtkPARCVolumeMapper* GetPARCMapper();

  /**
   * The view's scene of "PARC Volume" representations (see vtkPARCPVVolumeScene), or null
   * when the representation is in no render view.
   */
  vtkPARCPVVolumeScene* GetScene();

  /**
   * The mapper that rendered the volume last: the scene's when it rendered the volume
   * together with others, else GetPARCMapper().
   */
  vtkPARCVolumeMapper* GetRenderingMapper();

  ///@{
  /**
   * The statistics of the last render on this process (see vtkPARCVolumeMapper), of
   * GetRenderingMapper(): with several volumes together, of all of them; the acceleration
   * mode is this volume's.
   */
  double GetLastRenderTime();
  double GetLastCastingTime();
  double GetLastProjectionTime();
  vtkIdType GetLastSampleCount();
  vtkIdType GetLastRayCount();
  vtkIdType GetLastShadowRayCount();
  const char* GetLastAccelerationModeAsString();
  ///@}

protected:
  ///@{
  /** Joins the view's scene of "PARC Volume" representations, and leaves it. */
  bool AddToView(vtkView* view) override;
  bool RemoveFromView(vtkView* view) override;
  ///@}

  /**
   * When the volume is split across ranks, asks for the rank's piece (OwnedExtent: the
   * pipeline's block split) with the layers of cells the mapper needs at its border, as
   * ordinary cells: one for point scalars with gradients (shading or gradient opacity),
   * two for cell scalars (made point scalars with their neighbours, and the gradients at
   * the border reach one cell further); with shadows, the whole volume, as shadow rays
   * cross the other pieces. Point scalars without gradients need no layer:
   * the piece is then asked for as the pipeline split it, which ParaView has read already
   * to show it (a piece asked for otherwise is read again, and its ranges computed again:
   * seconds on 2 ranks at 181 MB). Asking for ghost levels instead would make the source
   * build a ghost array the size of the piece, and ParaView crop and scan it, tens of
   * seconds for a volume of a few hundred MB.
   */
  int RequestUpdateExtent(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  /**
   * The PARC mapper is given the piece with its border layers, and the extent it owns
   * (vtkPARCVolumeMapper::SetOwnedExtent), and casts in the piece's own cells; the ranks'
   * images are ordered by the bounds of those cells. A piece with ghost cells from
   * upstream keeps them (the superclass crops them away for its bounds).
   */
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkPARCVolumeRepresentation();
  ~vtkPARCVolumeRepresentation() override;

private:
  /** The point extent of the rank's piece, when ReadsOwnedPiece. */
  int OwnedExtent[6] = { 0, -1, 0, -1, 0, -1 };
  /** Whether RequestUpdateExtent asked for the piece with its border layers. */
  bool ReadsOwnedPiece = false;
  /** The border layers RequestUpdateExtent asked for (-1: the whole volume). */
  int Layers = -1;

  /**
   * The layers of cells the mapper needs beyond a piece (RequestUpdateExtent): 2 for cell
   * scalars, 1 for point scalars whose gradients it takes (shading, gradient opacity), 0
   * for the others.
   */
  int BorderLayers();

  /** The mapper, as the member of the view's scene it is. */
  vtkPARCPVVolumeMapper* GetSceneMemberMapper();

  vtkPARCVolumeRepresentation(const vtkPARCVolumeRepresentation&) = delete;
  void operator=(const vtkPARCVolumeRepresentation&) = delete;
};

#endif
