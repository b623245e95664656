/**
 * @class   vtkPARCOverrides
 * @brief   Makes vtkGPUVolumeRayCastMapper::New() return a mapper rendered by PARC.
 *
 * An explicit opt-in for programs that construct VTK's GPU volume mapper, or a
 * vtkSmartVolumeMapper (which builds its GPU mapper through the object factory), and
 * cannot be edited: while enabled, vtkGPUVolumeRayCastMapper::New() returns a
 * vtkPARCGPUVolumeRayCastMapper, which keeps the GPU mapper's API and renders with
 * vtkPARCVolumeMapper on the CPU.
 *
 * - C++: vtkPARCOverrides::Enable() and Disable(). Python: `import parc;
 *   parc.enable_overrides()` and `parc.disable_overrides()`.
 * - The environment variable PARC_OVERRIDE_GPU_MAPPER=1 enables the override when the
 *   PARCRendering library loads (and in ParaView when the PARC plugin loads).
 *
 * Order rules. Enable registers a factory of its own and turns off every other factory's
 * override of vtkGPUVolumeRayCastMapper (VTK's OpenGL one, registered by
 * RenderingVolumeOpenGL2); a factory registered later comes after this one, so this one
 * still wins. Disable turns this override off and VTK's OpenGL override
 * (vtkOpenGLGPUVolumeRayCastMapper) on again. Both act on mappers created after the call:
 * a mapper already made keeps its class, and a vtkSmartVolumeMapper makes its GPU mapper
 * when it is constructed.
 *
 * @sa vtkPARCGPUVolumeRayCastMapper vtkPARCVolumeMapper
 */
#ifndef vtkPARCOverrides_h
#define vtkPARCOverrides_h

#include "PARCRenderingModule.h" // For export macro
#include "vtkObject.h"

class vtkPARCVolumeMapper;
class vtkVolumeMapper;

class PARCRENDERING_EXPORT vtkPARCOverrides : public vtkObject
{
public:
  static vtkPARCOverrides* New();
  vtkTypeMacro(vtkPARCOverrides, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /** Switches the override on and off (see the class description for the order rules). */
  static void Enable();
  static void Disable();
  ///@}

  /** Whether vtkGPUVolumeRayCastMapper::New() returns a PARC mapper now. */
  static bool IsEnabled();

  /**
   * Enables the override when the environment variable PARC_OVERRIDE_GPU_MAPPER is 1;
   * returns whether it did. Called when the library loads.
   */
  static bool EnableFromEnvironment();

  /**
   * The vtkPARCVolumeMapper that renders mapper, for its statistics: mapper itself when it
   * is one, the one inside a vtkPARCGPUVolumeRayCastMapper, and for a vtkSmartVolumeMapper
   * the one inside the GPU mapper it made (when the override made it). Null when PARC does
   * not render mapper.
   */
  static vtkPARCVolumeMapper* GetPARCMapper(vtkVolumeMapper* mapper);

protected:
  vtkPARCOverrides() = default;
  ~vtkPARCOverrides() override = default;

private:
  vtkPARCOverrides(const vtkPARCOverrides&) = delete;
  void operator=(const vtkPARCOverrides&) = delete;
};

#endif
