#include "parcEndOfRenderDraw.h"

#include "vtkCallbackCommand.h"
#include "vtkDualDepthPeelingPass.h"
#include "vtkInformation.h"
#include "vtkInformationObjectBaseVectorKey.h"
#include "vtkOpenGLRenderPass.h"
#include "vtkProp.h"
#include "vtkPropCollection.h"
#include "vtkRenderer.h"
#include "vtkVolume.h"

namespace parc
{
namespace vtk
{
namespace
{
/// Whether prop carries a dual depth peeling pass among its render passes.
bool MarkedByDualDepthPeeling(vtkProp* prop)
{
  vtkInformation* keys = prop->GetPropertyKeys();
  vtkInformationObjectBaseVectorKey* passes = vtkOpenGLRenderPass::RenderPasses();
  if (!keys || !keys->Has(passes))
  {
    return false;
  }
  for (int i = 0; i < keys->Length(passes); ++i)
  {
    if (vtkDualDepthPeelingPass::SafeDownCast(keys->Get(passes, i)))
    {
      return true;
    }
  }
  return false;
}
}

bool InsideDualDepthPeeling(vtkRenderer* renderer)
{
  if (!renderer || !renderer->GetUseDepthPeeling() || !renderer->GetUseDepthPeelingForVolumes())
  {
    return false;
  }
  vtkPropCollection* props = renderer->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (MarkedByDualDepthPeeling(prop))
    {
      return true;
    }
  }
  return false;
}

EndOfRenderDraw::EndOfRenderDraw(Draw draw)
  : DrawVolume(std::move(draw))
{
  this->Callback->SetClientData(this);
  this->Callback->SetCallback(&EndOfRenderDraw::OnEndEvent);
}

EndOfRenderDraw::~EndOfRenderDraw()
{
  for (const Entry& entry : this->Entries)
  {
    if (entry.Renderer)
    {
      entry.Renderer->RemoveObserver(entry.Tag);
    }
  }
}

void EndOfRenderDraw::Request(vtkRenderer* renderer, vtkVolume* volume)
{
  for (Entry& entry : this->Entries)
  {
    if (entry.Renderer == renderer)
    {
      entry.Volume = volume;
      entry.Pending = true;
      return;
    }
  }
  Entry entry;
  entry.Renderer = renderer;
  entry.Volume = volume;
  entry.Tag = renderer->AddObserver(vtkCommand::EndEvent, this->Callback);
  entry.Pending = true;
  this->Entries.push_back(entry);
}

void EndOfRenderDraw::OnEndEvent(vtkObject* caller, unsigned long, void* self, void*)
{
  auto* draws = static_cast<EndOfRenderDraw*>(self);
  for (Entry& entry : draws->Entries)
  {
    if (entry.Renderer == caller && entry.Pending)
    {
      entry.Pending = false;
      if (entry.Volume)
      {
        draws->DrawVolume(entry.Renderer, entry.Volume);
      }
    }
  }
}
}
}
