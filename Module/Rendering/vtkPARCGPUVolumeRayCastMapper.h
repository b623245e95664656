/**
 * @class   vtkPARCGPUVolumeRayCastMapper
 * @brief   vtkGPUVolumeRayCastMapper's API, rendered by vtkPARCVolumeMapper on the CPU.
 *
 * What vtkGPUVolumeRayCastMapper::New() returns while vtkPARCOverrides are enabled, and so
 * what vtkSmartVolumeMapper, ParaView's volume representation and programs that construct
 * the GPU mapper use then, unchanged. Each render hands the mapper's input and settings to
 * a vtkPARCVolumeMapper (GetPARCMapper) and lets it render: the images are that mapper's,
 * bit for bit.
 *
 * The settings and what they mean here:
 * - Input (port 0), the scalar array selection (scalar mode, array name or index), blend
 *   mode, AverageIPScalarRange, cropping, clipping planes, masks
 *   (binary and label map, MaskBlendFactor), ColorRangeType, ImageSampleDistance and its
 *   minimum and maximum, AutoAdjustSampleDistances, LockSampleDistanceToInputSpacing,
 *   FinalColorWindow/Level: forwarded. Independent components come from the volume
 *   property, as for every mapper.
 * - SampleDistance: forwarded with AutoAdjustSampleDistances off; with it on (the
 *   default) the PARC mapper's own choice, half the smallest voxel edge, is used, as the
 *   GPU mapper chooses its own from the spacing.
 * - UseJittering: PARC samples one exact lattice; jittering is ignored, silently (ParaView
 *   and vtkSmartVolumeMapper turn it on for their GPU mapper).
 * - UseDepthPass and its contour values: a GPU-specific shortcut with no meaning here
 *   (PARC's own acceleration skips empty space); ignored.
 * - RenderToImage: the image is drawn into the window as usual; GetColorImage gives the
 *   last ray-cast image (RGBA, unsigned char), GetDepthImage an empty image.
 * - Further inputs (vtkMultiVolume's ports): use vtkPARCMultiVolume; only port 0 renders.
 * - IsRenderSupported: 1 wherever a render window has an OpenGL 3.3 context.
 *
 * @sa vtkPARCOverrides vtkPARCVolumeMapper
 */
#ifndef vtkPARCGPUVolumeRayCastMapper_h
#define vtkPARCGPUVolumeRayCastMapper_h

#include "PARCRenderingModule.h" // For export macro
#include "vtkGPUVolumeRayCastMapper.h"
#include "vtkNew.h" // For vtkNew

class vtkPARCVolumeMapper;

class PARCRENDERING_EXPORT vtkPARCGPUVolumeRayCastMapper : public vtkGPUVolumeRayCastMapper
{
public:
  static vtkPARCGPUVolumeRayCastMapper* New();
  vtkTypeMacro(vtkPARCGPUVolumeRayCastMapper, vtkGPUVolumeRayCastMapper);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * The mapper that renders: its statistics (GetLastSampleCount, ...) and settings of
   * its own (acceleration mode, threads, ...) are reachable here.
   */
  vtkPARCVolumeMapper* GetPARCMapper();

  /** Renders through the PARC mapper with this mapper's input and settings. */
  void Render(vtkRenderer* ren, vtkVolume* vol) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;
  int IsRenderSupported(vtkRenderWindow* window, vtkVolumeProperty* property) override;
  void GetColorImage(vtkImageData* image) override;
  void GetDepthImage(vtkImageData* image) override;
  void GetReductionRatio(double ratio[3]) override;

protected:
  vtkPARCGPUVolumeRayCastMapper();
  ~vtkPARCGPUVolumeRayCastMapper() override;

  ///@{
  /** The GPU mapper's stages; never called, as Render does not use them. */
  void PreRender(vtkRenderer*, vtkVolume*, double[6], double[2], int, unsigned int) override {}
  void RenderBlock(vtkRenderer*, vtkVolume*, unsigned int) override {}
  void PostRender(vtkRenderer*, int) override {}
  ///@}

private:
  /** Hands the input and settings to the PARC mapper. */
  void Forward();

  vtkNew<vtkPARCVolumeMapper> PARC;

  vtkPARCGPUVolumeRayCastMapper(const vtkPARCGPUVolumeRayCastMapper&) = delete;
  void operator=(const vtkPARCGPUVolumeRayCastMapper&) = delete;
};

#endif
