/**
 * @class   vtkPARCPVVolumeMapper
 * @brief   The mapper of a "PARC Volume" representation: renders its view's scene.
 *
 * A vtkPARCVolumeMapper that, while its view's vtkPARCPVVolumeScene renders two or more
 * volumes together, renders that scene (once in a render of the renderer) instead of its
 * own volume alone.
 *
 * @sa vtkPARCPVVolumeScene vtkPARCVolumeRepresentation
 */
#ifndef vtkPARCPVVolumeMapper_h
#define vtkPARCPVVolumeMapper_h

#include "PARCParaViewModule.h" // For export macro
#include "vtkPARCVolumeMapper.h"
#include "vtkWeakPointer.h" // For vtkWeakPointer

class vtkPARCPVVolumeScene;

class PARCPARAVIEW_EXPORT vtkPARCPVVolumeMapper : public vtkPARCVolumeMapper
{
public:
  static vtkPARCPVVolumeMapper* New();
  vtkTypeMacro(vtkPARCPVVolumeMapper, vtkPARCVolumeMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** The scene of the view the representation is shown in (null: none). */
  void SetScene(vtkPARCPVVolumeScene* scene);
  vtkPARCPVVolumeScene* GetScene();
  ///@}

  /** Renders the scene when it renders volumes together, else the volume alone. */
  void Render(vtkRenderer* renderer, vtkVolume* volume) override;

protected:
  vtkPARCPVVolumeMapper();
  ~vtkPARCPVVolumeMapper() override;

private:
  vtkPARCPVVolumeMapper(const vtkPARCPVVolumeMapper&) = delete;
  void operator=(const vtkPARCPVVolumeMapper&) = delete;

  vtkWeakPointer<vtkPARCPVVolumeScene> Scene;
};

#endif
