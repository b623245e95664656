/**
 * @class   vtkPARCVolumeRepresentation
 * @brief   ParaView's image volume representation with vtkPARCVolumeMapper as its mapper.
 *
 * The "PARC Volume" representation type of image data in ParaView: everything of
 * vtkImageVolumeRepresentation (transfer functions, blend modes, iso values, shading,
 * cropping), rendered by vtkPARCVolumeMapper on the CPU, bit-identical in every
 * acceleration mode. The mapper's own settings are forwarded: acceleration mode,
 * supercell size, sample distance and threads. The statistics of the last render are
 * read from the mapper (GetPARCMapper).
 *
 * @sa vtkPARCVolumeMapper vtkPARCPVPolygonModelFilter
 */
#ifndef vtkPARCVolumeRepresentation_h
#define vtkPARCVolumeRepresentation_h

#include "PARCParaViewModule.h" // For export macro
#include "vtkImageVolumeRepresentation.h"

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
  void SetSampleDistance(double distance);
  void SetNumberOfThreads(int threads);
  ///@}

  /**
   * The mapper, for its statistics of the last render.
   */
  vtkPARCVolumeMapper* GetPARCMapper();

protected:
  vtkPARCVolumeRepresentation();
  ~vtkPARCVolumeRepresentation() override;

private:
  vtkPARCVolumeRepresentation(const vtkPARCVolumeRepresentation&) = delete;
  void operator=(const vtkPARCVolumeRepresentation&) = delete;
};

#endif
