/**
 * @class   vtkPARCMultiVolume
 * @brief   vtkMultiVolume for vtkPARCVolumeMapper: several overlapping volumes in one image.
 *
 * VTK 9.1's vtkMultiVolume computes its bounds only for vtkGPUVolumeRayCastMapper. This
 * subclass keeps its API (SetVolume(volume, port), GetVolume(port), RemoveVolume(port)) and
 * computes the bounds for any vtkAbstractVolumeMapper whose input ports hold image data:
 * the union, in world coordinates, of each port's data bounds transformed by the matrix of
 * the vtkVolume registered for that port. Its own matrix is the identity.
 *
 * Use it as VTK's examples use vtkMultiVolume:
 * @code
 * mapper->SetInputConnection(0, surfaceReader->GetOutputPort());
 * mapper->SetInputConnection(1, cloudReader->GetOutputPort());
 * mapper->SetInputBlendMode(0, vtkVolumeMapper::ISOSURFACE_BLEND);
 * multiVolume->SetMapper(mapper);
 * multiVolume->SetVolume(surfaceVolume, 0); // property and transform of port 0
 * multiVolume->SetVolume(cloudVolume, 1);
 * renderer->AddVolume(multiVolume);
 * @endcode
 *
 * @sa vtkPARCVolumeMapper vtkMultiVolume
 */
#ifndef vtkPARCMultiVolume_h
#define vtkPARCMultiVolume_h

#include "PARCRenderingModule.h" // For export macro
#include "vtkMultiVolume.h"

class PARCRENDERING_EXPORT vtkPARCMultiVolume : public vtkMultiVolume
{
public:
  static vtkPARCMultiVolume* New();
  vtkTypeMacro(vtkPARCMultiVolume, vtkMultiVolume);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /** The volume registered for port, or null (without the error GetVolume gives). */
  vtkVolume* FindVolumeOfPort(int port) { return this->FindVolume(port); }

  /**
   * World bounds of all registered volumes (see the class comment); uninitialized bounds
   * when no registered port has data.
   */
  double* GetBounds() override;

  /** Renders all registered volumes with the mapper in one image. */
  int RenderVolumetricGeometry(vtkViewport* viewport) override;

protected:
  vtkPARCMultiVolume();
  ~vtkPARCMultiVolume() override;

private:
  vtkPARCMultiVolume(const vtkPARCMultiVolume&) = delete;
  void operator=(const vtkPARCMultiVolume&) = delete;
};

#endif
