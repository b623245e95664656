#include "vtkPARCVolumeRepresentation.h"

#include "vtkObjectFactory.h"
#include "vtkPARCVolumeMapper.h"

vtkStandardNewMacro(vtkPARCVolumeRepresentation);

vtkPARCVolumeRepresentation::vtkPARCVolumeRepresentation()
{
  // The superclass connects whatever mapper VolumeMapper holds when it renders.
  this->VolumeMapper = vtkSmartPointer<vtkPARCVolumeMapper>::New();
}

vtkPARCVolumeRepresentation::~vtkPARCVolumeRepresentation() = default;

vtkPARCVolumeMapper* vtkPARCVolumeRepresentation::GetPARCMapper()
{
  return vtkPARCVolumeMapper::SafeDownCast(this->VolumeMapper);
}

void vtkPARCVolumeRepresentation::SetAccelerationMode(int mode)
{
  this->GetPARCMapper()->SetAccelerationMode(mode);
}

void vtkPARCVolumeRepresentation::SetSupercellSize(double x, double y, double z)
{
  this->GetPARCMapper()->SetSupercellSize(x, y, z);
}

void vtkPARCVolumeRepresentation::SetSampleDistance(double distance)
{
  this->GetPARCMapper()->SetSampleDistance(distance);
}

void vtkPARCVolumeRepresentation::SetNumberOfThreads(int threads)
{
  this->GetPARCMapper()->SetNumberOfThreads(threads);
}

void vtkPARCVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PARC mapper:\n";
  this->GetPARCMapper()->PrintSelf(os, indent.GetNextIndent());
}
