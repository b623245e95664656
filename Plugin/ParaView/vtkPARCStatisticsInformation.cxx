#include "vtkPARCStatisticsInformation.h"

#include "vtkClientServerStream.h"
#include "vtkObjectFactory.h"
#include "vtkPARCVolumeRepresentation.h"

#include <algorithm>

vtkStandardNewMacro(vtkPARCStatisticsInformation);

vtkPARCStatisticsInformation::vtkPARCStatisticsInformation()
{
  this->RootOnly = 0; // every rank renders its piece
}

vtkPARCStatisticsInformation::~vtkPARCStatisticsInformation() = default;

void vtkPARCStatisticsInformation::CopyFromObject(vtkObject* object)
{
  auto* representation = vtkPARCVolumeRepresentation::SafeDownCast(object);
  if (!representation)
  {
    return; // not a PARC representation here: nothing rendered
  }
  this->RenderTime = representation->GetLastRenderTime();
  this->CastingTime = representation->GetLastCastingTime();
  this->ProjectionTime = representation->GetLastProjectionTime();
  this->SampleCount = representation->GetLastSampleCount();
  this->RayCount = representation->GetLastRayCount();
  this->ShadowRayCount = representation->GetLastShadowRayCount();
  this->AccelerationMode = this->RayCount > 0 || this->SampleCount > 0
    ? representation->GetLastAccelerationModeAsString()
    : "";
}

void vtkPARCStatisticsInformation::AddInformation(vtkPVInformation* other)
{
  auto* rank = vtkPARCStatisticsInformation::SafeDownCast(other);
  if (!rank)
  {
    return;
  }
  this->RenderTime = std::max(this->RenderTime, rank->RenderTime);
  this->CastingTime = std::max(this->CastingTime, rank->CastingTime);
  this->ProjectionTime = std::max(this->ProjectionTime, rank->ProjectionTime);
  this->SampleCount += rank->SampleCount;
  this->RayCount += rank->RayCount;
  this->ShadowRayCount += rank->ShadowRayCount;
  if (this->AccelerationMode.empty())
  {
    this->AccelerationMode = rank->AccelerationMode;
  }
}

void vtkPARCStatisticsInformation::CopyToStream(vtkClientServerStream* stream)
{
  stream->Reset();
  *stream << vtkClientServerStream::Reply << this->RenderTime << this->CastingTime
          << this->ProjectionTime << this->SampleCount << this->RayCount
          << this->ShadowRayCount << this->AccelerationMode.c_str()
          << vtkClientServerStream::End;
}

void vtkPARCStatisticsInformation::CopyFromStream(const vtkClientServerStream* stream)
{
  const char* mode = nullptr;
  if (!stream->GetArgument(0, 0, &this->RenderTime) ||
    !stream->GetArgument(0, 1, &this->CastingTime) ||
    !stream->GetArgument(0, 2, &this->ProjectionTime) ||
    !stream->GetArgument(0, 3, &this->SampleCount) || !stream->GetArgument(0, 4, &this->RayCount) ||
    !stream->GetArgument(0, 5, &this->ShadowRayCount) || !stream->GetArgument(0, 6, &mode))
  {
    vtkErrorMacro("The PARC statistics could not be read from the stream.");
    return;
  }
  this->AccelerationMode = mode ? mode : "";
}

void vtkPARCStatisticsInformation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RenderTime: " << this->RenderTime << "\n";
  os << indent << "CastingTime: " << this->CastingTime << "\n";
  os << indent << "ProjectionTime: " << this->ProjectionTime << "\n";
  os << indent << "SampleCount: " << this->SampleCount << "\n";
  os << indent << "RayCount: " << this->RayCount << "\n";
  os << indent << "ShadowRayCount: " << this->ShadowRayCount << "\n";
  os << indent << "AccelerationMode: " << this->AccelerationMode << "\n";
}
