#include "vtkPARCVolumeRepresentation.h"

#include "vtkDataObject.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPARCVolumeMapper.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>

vtkStandardNewMacro(vtkPARCVolumeRepresentation);

vtkPARCVolumeRepresentation::vtkPARCVolumeRepresentation()
{
  // The superclass connects whatever mapper VolumeMapper holds when it renders.
  auto mapper = vtkSmartPointer<vtkPARCVolumeMapper>::New();
  // ParaView's lookup table spans the whole data set's range: the colour table follows it,
  // and the ranks, whose pieces' ranges differ, agree.
  mapper->SetColorRangeType(vtkPARCVolumeMapper::NATIVE);
  this->VolumeMapper = mapper;
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

void vtkPARCVolumeRepresentation::SetShadows(bool shadows)
{
  this->GetPARCMapper()->SetShadowMode(
    shadows ? vtkPARCVolumeMapper::SHADOWS_ON : vtkPARCVolumeMapper::SHADOWS_FROM_RENDERER);
}

double vtkPARCVolumeRepresentation::GetLastRenderTime()
{
  return this->GetPARCMapper()->GetLastRenderTime();
}

double vtkPARCVolumeRepresentation::GetLastCastingTime()
{
  return this->GetPARCMapper()->GetLastCastingTime();
}

double vtkPARCVolumeRepresentation::GetLastProjectionTime()
{
  return this->GetPARCMapper()->GetLastProjectionTime();
}

vtkIdType vtkPARCVolumeRepresentation::GetLastSampleCount()
{
  return this->GetPARCMapper()->GetLastSampleCount();
}

vtkIdType vtkPARCVolumeRepresentation::GetLastRayCount()
{
  return this->GetPARCMapper()->GetLastRayCount();
}

vtkIdType vtkPARCVolumeRepresentation::GetLastShadowRayCount()
{
  return this->GetPARCMapper()->GetLastShadowRayCount();
}

const char* vtkPARCVolumeRepresentation::GetLastAccelerationModeAsString()
{
  return vtkPARCVolumeMapper::GetAccelerationModeAsString(
    this->GetPARCMapper()->GetLastAccelerationMode());
}

int vtkPARCVolumeRepresentation::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestUpdateExtent(request, inputVector, outputVector))
  {
    return 0;
  }
  vtkInformation* array = this->GetInputArrayInformation(0);
  const bool cells = array && array->Has(vtkDataObject::FIELD_ASSOCIATION()) &&
    array->Get(vtkDataObject::FIELD_ASSOCIATION()) == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  const int levels = cells ? 2 : 1;
  const auto key = vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS();
  for (int i = 0; i < inputVector[0]->GetNumberOfInformationObjects(); ++i)
  {
    vtkInformation* in = inputVector[0]->GetInformationObject(i);
    in->Set(key, std::max(levels, in->Has(key) ? in->Get(key) : 0));
  }
  return 1;
}

int vtkPARCVolumeRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkSmartPointer<vtkImageData> piece;
  vtkImageData* input = inputVector[0]->GetNumberOfInformationObjects() == 1
    ? vtkImageData::GetData(inputVector[0], 0)
    : nullptr;
  if (input && input->HasAnyGhostCells())
  {
    piece.TakeReference(input->NewInstance()); // a vtkUniformGrid stays one
    piece->ShallowCopy(input);
  }
  if (!this->Superclass::RequestData(request, inputVector, outputVector))
  {
    return 0;
  }
  if (piece)
  {
    if (this->UseSeparateOpacityArray)
    {
      this->AppendOpacityComponent(piece);
    }
    this->Cache = piece;
    this->VolumeMapper->SetInputData(piece);
  }
  return 1;
}

void vtkPARCVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PARC mapper:\n";
  this->GetPARCMapper()->PrintSelf(os, indent.GetNextIndent());
}
