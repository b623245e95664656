#include "vtkSMPARCVolumeRepresentationProxy.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPARCStatisticsInformation.h"
#include "vtkPVSession.h"
#include "vtkSMPropertyHelper.h"

#include <cstring>

vtkStandardNewMacro(vtkSMPARCVolumeRepresentationProxy);

vtkSMPARCVolumeRepresentationProxy::vtkSMPARCVolumeRepresentationProxy() = default;

vtkSMPARCVolumeRepresentationProxy::~vtkSMPARCVolumeRepresentationProxy() = default;

namespace
{
/// The prefix of the statistics' property names.
constexpr const char* StatisticsPrefix = "PARCLast";
}

void vtkSMPARCVolumeRepresentationProxy::UpdatePropertyInformationInternal(
  vtkSMProperty* property)
{
  this->Superclass::UpdatePropertyInformationInternal(property);
  const char* name = property ? this->GetPropertyName(property) : nullptr;
  if (!this->ObjectsCreated ||
    (property && (!name || std::strncmp(name, StatisticsPrefix, std::strlen(StatisticsPrefix)))))
  {
    return;
  }
  vtkNew<vtkPARCStatisticsInformation> statistics;
  this->GatherInformation(statistics, vtkPVSession::RENDER_SERVER);
  vtkSMPropertyHelper(this, "PARCLastRenderTime").Set(statistics->GetRenderTime());
  vtkSMPropertyHelper(this, "PARCLastCastingTime").Set(statistics->GetCastingTime());
  vtkSMPropertyHelper(this, "PARCLastProjectionTime").Set(statistics->GetProjectionTime());
  vtkSMPropertyHelper(this, "PARCLastSampleCount").Set(statistics->GetSampleCount());
  vtkSMPropertyHelper(this, "PARCLastRayCount").Set(statistics->GetRayCount());
  vtkSMPropertyHelper(this, "PARCLastShadowRayCount").Set(statistics->GetShadowRayCount());
  vtkSMPropertyHelper(this, "PARCLastAccelerationMode").Set(statistics->GetAccelerationMode());
}

void vtkSMPARCVolumeRepresentationProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
