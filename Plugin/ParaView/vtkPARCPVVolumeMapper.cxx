#include "vtkPARCPVVolumeMapper.h"

#include "vtkObjectFactory.h"
#include "vtkPARCPVVolumeScene.h"

vtkStandardNewMacro(vtkPARCPVVolumeMapper);

vtkPARCPVVolumeMapper::vtkPARCPVVolumeMapper() = default;

vtkPARCPVVolumeMapper::~vtkPARCPVVolumeMapper() = default;

void vtkPARCPVVolumeMapper::SetScene(vtkPARCPVVolumeScene* scene)
{
  this->Scene = scene;
}

vtkPARCPVVolumeScene* vtkPARCPVVolumeMapper::GetScene()
{
  return this->Scene;
}

void vtkPARCPVVolumeMapper::Render(vtkRenderer* renderer, vtkVolume* volume)
{
  if (!this->Scene || !this->Scene->RenderTogether(renderer))
  {
    this->Superclass::Render(renderer, volume);
  }
}

void vtkPARCPVVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Scene: " << this->Scene.GetPointer() << "\n";
}
