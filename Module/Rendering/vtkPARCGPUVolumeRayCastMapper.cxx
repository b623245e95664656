#include "vtkPARCGPUVolumeRayCastMapper.h"

#include "parcVTKConversion.h"

#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPARCVolumeMapper.h"
#include "vtkPointData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>

vtkStandardNewMacro(vtkPARCGPUVolumeRayCastMapper);

namespace
{
/// The PARC mapper's range of image sample distances (the GPU mapper allows 0.1 to 100).
double ImageStep(float distance)
{
  constexpr double Finest = 1.0, Coarsest = 64.0;
  return std::min(Coarsest, std::max(Finest, static_cast<double>(distance)));
}
}

//------------------------------------------------------------------------------
vtkPARCGPUVolumeRayCastMapper::vtkPARCGPUVolumeRayCastMapper() = default;

//------------------------------------------------------------------------------
vtkPARCGPUVolumeRayCastMapper::~vtkPARCGPUVolumeRayCastMapper() = default;

//------------------------------------------------------------------------------
vtkPARCVolumeMapper* vtkPARCGPUVolumeRayCastMapper::GetPARCMapper()
{
  return this->PARC;
}

//------------------------------------------------------------------------------
void vtkPARCGPUVolumeRayCastMapper::Forward()
{
  vtkPARCVolumeMapper* to = this->PARC;
  to->SetInputConnection(0, this->GetNumberOfInputConnections(0) > 0
      ? this->GetInputConnection(0, 0)
      : nullptr);
  to->SetScalarMode(this->GetScalarMode()); // the array ParaView and programs select
  if (this->GetArrayAccessMode() == VTK_GET_ARRAY_BY_NAME)
  {
    to->SelectScalarArray(this->GetArrayName());
  }
  else
  {
    to->SelectScalarArray(this->GetArrayId());
  }
  to->SetBlendMode(this->GetBlendMode());
  to->SetAverageIPScalarRange(this->GetAverageIPScalarRange());
  to->SetCropping(this->GetCropping());
  to->SetCroppingRegionFlags(this->GetCroppingRegionFlags());
  to->SetCroppingRegionPlanes(this->GetCroppingRegionPlanes());
  to->SetClippingPlanes(this->GetClippingPlanes());
  to->SetMaskInput(this->MaskInput);
  to->SetMaskType(this->GetMaskType());
  to->SetMaskBlendFactor(this->GetMaskBlendFactor());
  to->SetColorRangeType(this->GetColorRangeType());
  to->SetAutoAdjustSampleDistances(this->GetAutoAdjustSampleDistances());
  to->SetSampleDistance(this->GetAutoAdjustSampleDistances() ? 0.0 : this->GetSampleDistance());
  to->SetLockSampleDistanceToInputSpacing(this->GetLockSampleDistanceToInputSpacing());
  to->SetImageSampleDistance(ImageStep(this->GetImageSampleDistance()));
  to->SetMinimumImageSampleDistance(ImageStep(this->GetMinimumImageSampleDistance()));
  to->SetMaximumImageSampleDistance(ImageStep(this->GetMaximumImageSampleDistance()));
  to->SetFinalColorWindow(this->GetFinalColorWindow());
  to->SetFinalColorLevel(this->GetFinalColorLevel());
  to->SetReportProgress(this->GetReportProgress());
}

//------------------------------------------------------------------------------
void vtkPARCGPUVolumeRayCastMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  this->Forward();
  this->PARC->Render(ren, vol);
  this->TimeToDraw = this->PARC->GetTimeToDraw();
}

//------------------------------------------------------------------------------
void vtkPARCGPUVolumeRayCastMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->PARC->ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
int vtkPARCGPUVolumeRayCastMapper::IsRenderSupported(vtkRenderWindow* window, vtkVolumeProperty*)
{
  return vtkOpenGLRenderWindow::SafeDownCast(window) ? 1 : 0;
}

//------------------------------------------------------------------------------
void vtkPARCGPUVolumeRayCastMapper::GetColorImage(vtkImageData* image)
{
  if (!image)
  {
    return;
  }
  vtkNew<vtkImageData> rays;
  this->PARC->GetLastRayCastImage(rays);
  image->Initialize();
  image->SetDimensions(rays->GetDimensions());
  vtkFloatArray* rgba = vtkFloatArray::SafeDownCast(rays->GetPointData()->GetScalars());
  vtkNew<vtkUnsignedCharArray> bytes;
  bytes->SetNumberOfComponents(4);
  bytes->SetNumberOfTuples(rgba ? rgba->GetNumberOfTuples() : 0);
  // What the mapper shows: the same bytes as its display image.
  const parc::vtk::FinalColor finalColor(
    this->PARC->GetFinalColorWindow(), this->PARC->GetFinalColorLevel());
  for (vtkIdType p = 0; p < bytes->GetNumberOfTuples(); ++p)
  {
    finalColor.ToBytes(rgba->GetPointer(4 * p), bytes->GetPointer(4 * p));
  }
  image->GetPointData()->SetScalars(bytes);
}

//------------------------------------------------------------------------------
void vtkPARCGPUVolumeRayCastMapper::GetDepthImage(vtkImageData* image)
{
  if (image)
  {
    image->Initialize();
  }
}

//------------------------------------------------------------------------------
void vtkPARCGPUVolumeRayCastMapper::GetReductionRatio(double ratio[3])
{
  ratio[0] = ratio[1] = ratio[2] = 1.0;
}

//------------------------------------------------------------------------------
void vtkPARCGPUVolumeRayCastMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PARC mapper:\n";
  this->PARC->PrintSelf(os, indent.GetNextIndent());
}
