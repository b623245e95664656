#include "vtkPARCPVVolumeScene.h"

#include "vtkCommand.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseKey.h"
#include "vtkObjectFactory.h"
#include "vtkPARCMultiVolume.h"
#include "vtkPARCVolumeMapper.h"
#include "vtkPARCVolumeRepresentation.h"
#include "vtkPVLODVolume.h"
#include "vtkRenderer.h"

#include <algorithm>

vtkStandardNewMacro(vtkPARCPVVolumeScene);
vtkInformationKeyMacro(vtkPARCPVVolumeScene, SCENE, ObjectBase);

namespace
{
/// What a member's mapper is set to that the scene's mapper takes over: the settings of the
/// "PARC Volume" representation and ParaView's cropping.
void CopySettings(vtkPARCVolumeMapper* from, vtkPARCVolumeMapper* to)
{
  to->SetAccelerationMode(from->GetAccelerationMode());
  to->SetSupercellSize(from->GetSupercellSize());
  to->SetAutoSupercellSize(from->GetAutoSupercellSize());
  to->SetSampleDistance(from->GetSampleDistance());
  to->SetNumberOfThreads(from->GetNumberOfThreads());
  to->SetBrickedCopy(from->GetBrickedCopy());
  to->SetShadowMode(from->GetShadowMode());
  to->SetColorRangeType(from->GetColorRangeType());
  to->SetCropping(from->GetCropping());
  to->SetCroppingRegionFlags(from->GetCroppingRegionFlags());
  to->SetCroppingRegionPlanes(from->GetCroppingRegionPlanes());
}
}

vtkPARCPVVolumeScene::vtkPARCPVVolumeScene()
{
  this->Volumes->SetMapper(this->Mapper);
}

vtkPARCPVVolumeScene::~vtkPARCPVVolumeScene()
{
  if (this->Renderer)
  {
    this->Renderer->RemoveObserver(this->StartObserver);
  }
}

vtkPARCPVVolumeScene* vtkPARCPVVolumeScene::Of(vtkRenderer* renderer)
{
  vtkInformation* info = renderer->GetInformation();
  if (auto* scene = vtkPARCPVVolumeScene::SafeDownCast(info->Get(SCENE())))
  {
    return scene;
  }
  vtkNew<vtkPARCPVVolumeScene> scene;
  scene->Renderer = renderer;
  scene->StartObserver = renderer->AddObserver(
    vtkCommand::StartEvent, scene.GetPointer(), &vtkPARCPVVolumeScene::StartRender);
  info->Set(SCENE(), scene); // the renderer's information holds the scene
  return scene;
}

void vtkPARCPVVolumeScene::AddMember(vtkPARCVolumeRepresentation* member)
{
  if (std::find(this->Members.begin(), this->Members.end(), member) == this->Members.end())
  {
    this->Members.push_back(member);
  }
}

void vtkPARCPVVolumeScene::RemoveMember(vtkPARCVolumeRepresentation* member)
{
  this->Members.erase(
    std::remove(this->Members.begin(), this->Members.end(), member), this->Members.end());
  this->Release(0);
  if (this->Members.empty() && this->PeelingForVolumesSuspended && this->Renderer)
  {
    this->Renderer->SetUseDepthPeelingForVolumes(true);
    this->PeelingForVolumesSuspended = false;
  }
}

void vtkPARCPVVolumeScene::StartRender()
{
  this->RenderedInThisRender = false;
  if (!this->Members.empty() && this->Renderer && this->Renderer->GetUseDepthPeelingForVolumes())
  {
    this->Renderer->SetUseDepthPeelingForVolumes(false);
    this->PeelingForVolumesSuspended = true;
  }
}

void vtkPARCPVVolumeScene::Release(int firstPort)
{
  for (int port = firstPort; port < vtkPARCVolumeMapper::MaxInputPorts; ++port)
  {
    this->Mapper->SetInputConnection(port, nullptr);
    this->Volumes->RemoveVolume(port);
  }
  this->LastPorts.resize(std::min<std::size_t>(this->LastPorts.size(), firstPort));
}

std::vector<vtkPARCVolumeRepresentation*> vtkPARCPVVolumeScene::VisibleMembers() const
{
  std::vector<vtkPARCVolumeRepresentation*> visible;
  for (auto* member : this->Members)
  {
    if (member->GetVisibility() && member->GetActor()->GetVisibility() &&
      member->GetPARCMapper()->GetDataObjectInput())
    {
      visible.push_back(member);
    }
  }
  return visible;
}

bool vtkPARCPVVolumeScene::RenderTogether(vtkRenderer* renderer)
{
  if (this->RenderedInThisRender)
  {
    return true;
  }
  const std::vector<vtkPARCVolumeRepresentation*> visible = this->VisibleMembers();
  if (visible.size() < 2)
  {
    this->Release(0);
    return false;
  }
  const int ports = std::min<int>(visible.size(), vtkPARCVolumeMapper::MaxInputPorts);
  if (static_cast<int>(visible.size()) > ports)
  {
    vtkWarningMacro("Only the first " << ports << " of " << visible.size()
                                      << " PARC volumes of the view are rendered.");
  }
  CopySettings(visible[0]->GetPARCMapper(), this->Mapper);
  this->Release(ports);
  for (int port = 0; port < ports; ++port)
  {
    vtkPARCVolumeMapper* own = visible[port]->GetPARCMapper();
    this->Mapper->SetInputDataObject(port, own->GetDataObjectInput());
    if (port == 0)
    {
      this->Mapper->SetBlendMode(own->GetBlendMode());
    }
    else
    {
      this->Mapper->SetInputBlendMode(port, own->GetBlendMode());
    }
    this->Volumes->SetVolume(visible[port]->GetActor(), port);
  }
  this->LastPorts.assign(visible.begin(), visible.begin() + ports);
  this->RenderedInThisRender = true;
  this->Volumes->RenderVolumetricGeometry(renderer);
  return true;
}

int vtkPARCPVVolumeScene::GetPortOf(vtkPARCVolumeRepresentation* member) const
{
  const auto found = std::find(this->LastPorts.begin(), this->LastPorts.end(), member);
  return found == this->LastPorts.end() ? -1 : static_cast<int>(found - this->LastPorts.begin());
}

vtkPARCVolumeMapper* vtkPARCPVVolumeScene::GetMapper()
{
  return this->Mapper;
}

void vtkPARCPVVolumeScene::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Members: " << this->Members.size() << "\n";
  os << indent << "Rendered together last: " << this->LastPorts.size() << "\n";
}
