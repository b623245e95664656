#include "vtkPARCVolumeRepresentation.h"

#include "vtkDataObject.h"
#include "vtkExtentTranslator.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkOutlineSource.h"
#include "vtkPARCPVVolumeMapper.h"
#include "vtkPARCPVVolumeScene.h"
#include "vtkPVRenderView.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkVolumeProperty.h"

#include <algorithm>

vtkStandardNewMacro(vtkPARCVolumeRepresentation);

vtkPARCVolumeRepresentation::vtkPARCVolumeRepresentation()
{
  // The superclass connects whatever mapper VolumeMapper holds when it renders.
  auto mapper = vtkSmartPointer<vtkPARCPVVolumeMapper>::New();
  // ParaView's lookup table spans the whole data set's range: the colour table follows it,
  // and the ranks, whose pieces' ranges differ, agree.
  mapper->SetColorRangeType(vtkPARCVolumeMapper::NATIVE);
  this->VolumeMapper = mapper;
}

vtkPARCVolumeRepresentation::~vtkPARCVolumeRepresentation()
{
  if (vtkPARCPVVolumeScene* scene = this->GetScene()) // still in a view's scene
  {
    scene->RemoveMember(this);
  }
}

vtkPARCVolumeMapper* vtkPARCVolumeRepresentation::GetPARCMapper()
{
  return vtkPARCVolumeMapper::SafeDownCast(this->VolumeMapper);
}

vtkPARCPVVolumeMapper* vtkPARCVolumeRepresentation::GetSceneMemberMapper()
{
  return vtkPARCPVVolumeMapper::SafeDownCast(this->VolumeMapper);
}

vtkPARCPVVolumeScene* vtkPARCVolumeRepresentation::GetScene()
{
  return this->GetSceneMemberMapper()->GetScene();
}

vtkPARCVolumeMapper* vtkPARCVolumeRepresentation::GetRenderingMapper()
{
  vtkPARCPVVolumeScene* scene = this->GetScene();
  return scene && scene->GetPortOf(this) >= 0 ? scene->GetMapper() : this->GetPARCMapper();
}

bool vtkPARCVolumeRepresentation::AddToView(vtkView* view)
{
  auto* renderView = vtkPVRenderView::SafeDownCast(view);
  if (!renderView || !this->Superclass::AddToView(view))
  {
    return false;
  }
  vtkPARCPVVolumeScene* scene = vtkPARCPVVolumeScene::Of(renderView->GetRenderer());
  scene->AddMember(this);
  this->GetSceneMemberMapper()->SetScene(scene);
  return true;
}

bool vtkPARCVolumeRepresentation::RemoveFromView(vtkView* view)
{
  if (vtkPARCPVVolumeScene* scene = this->GetScene())
  {
    scene->RemoveMember(this);
    this->GetSceneMemberMapper()->SetScene(nullptr);
  }
  return this->Superclass::RemoveFromView(view);
}

void vtkPARCVolumeRepresentation::SetAccelerationMode(int mode)
{
  this->GetPARCMapper()->SetAccelerationMode(mode);
}

void vtkPARCVolumeRepresentation::SetSupercellSize(double x, double y, double z)
{
  // ParaView sets every property, this one too: the size is where Auto's search starts
  // unless PARCAutoSupercellSize is off.
  vtkPARCVolumeMapper* mapper = this->GetPARCMapper();
  const vtkTypeBool automatic = mapper->GetAutoSupercellSize();
  mapper->SetSupercellSize(x, y, z);
  mapper->SetAutoSupercellSize(automatic);
}

void vtkPARCVolumeRepresentation::SetAutoSupercellSize(bool automatic)
{
  this->GetPARCMapper()->SetAutoSupercellSize(automatic);
}

void vtkPARCVolumeRepresentation::SetSampleDistance(double distance)
{
  this->GetPARCMapper()->SetSampleDistance(distance);
}

void vtkPARCVolumeRepresentation::SetNumberOfThreads(int threads)
{
  this->GetPARCMapper()->SetNumberOfThreads(threads);
}

void vtkPARCVolumeRepresentation::SetBrickedCopy(bool bricked)
{
  this->GetPARCMapper()->SetBrickedCopy(bricked);
}

void vtkPARCVolumeRepresentation::SetShadows(bool shadows)
{
  const int mode =
    shadows ? vtkPARCVolumeMapper::SHADOWS_ON : vtkPARCVolumeMapper::SHADOWS_FROM_RENDERER;
  if (this->GetPARCMapper()->GetShadowMode() != mode)
  {
    this->GetPARCMapper()->SetShadowMode(mode);
    this->MarkModified(); // the pieces' border layers change (RequestUpdateExtent)
  }
}

double vtkPARCVolumeRepresentation::GetLastRenderTime()
{
  return this->GetRenderingMapper()->GetLastRenderTime();
}

double vtkPARCVolumeRepresentation::GetLastCastingTime()
{
  return this->GetRenderingMapper()->GetLastCastingTime();
}

double vtkPARCVolumeRepresentation::GetLastProjectionTime()
{
  return this->GetRenderingMapper()->GetLastProjectionTime();
}

vtkIdType vtkPARCVolumeRepresentation::GetLastSampleCount()
{
  return this->GetRenderingMapper()->GetLastSampleCount();
}

vtkIdType vtkPARCVolumeRepresentation::GetLastRayCount()
{
  return this->GetRenderingMapper()->GetLastRayCount();
}

vtkIdType vtkPARCVolumeRepresentation::GetLastShadowRayCount()
{
  return this->GetRenderingMapper()->GetLastShadowRayCount();
}

const char* vtkPARCVolumeRepresentation::GetLastAccelerationModeAsString()
{
  vtkPARCPVVolumeScene* scene = this->GetScene();
  const int port = scene ? scene->GetPortOf(this) : -1;
  return vtkPARCVolumeMapper::GetAccelerationModeAsString(port >= 0
      ? scene->GetMapper()->GetLastInputAccelerationMode(port)
      : this->GetPARCMapper()->GetLastAccelerationMode());
}

int vtkPARCVolumeRepresentation::BorderLayers()
{
  vtkInformation* array = this->GetInputArrayInformation(0);
  const bool cells = array && array->Has(vtkDataObject::FIELD_ASSOCIATION()) &&
    array->Get(vtkDataObject::FIELD_ASSOCIATION()) == vtkDataObject::FIELD_ASSOCIATION_CELLS;
  vtkVolumeProperty* property = this->Property;
  const bool gradients = property->GetShade() ||
    (property->HasGradientOpacity() && !property->GetDisableGradientOpacity());
  return cells ? 2 : (gradients ? 1 : 0);
}

void vtkPARCVolumeRepresentation::SetShade(bool shade)
{
  const int before = this->BorderLayers();
  this->Superclass::SetShade(shade);
  if (this->BorderLayers() != before)
  {
    this->MarkModified(); // the pieces' border layers change (RequestUpdateExtent)
  }
}

int vtkPARCVolumeRepresentation::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestUpdateExtent(request, inputVector, outputVector))
  {
    return 0;
  }
  using Pipeline = vtkStreamingDemandDrivenPipeline;
  this->ReadsOwnedPiece = false;
  this->Layers = -1;
  vtkInformation* in = inputVector[0]->GetNumberOfInformationObjects() == 1
    ? inputVector[0]->GetInformationObject(0)
    : nullptr;
  if (!in || !in->Has(Pipeline::WHOLE_EXTENT()) || !in->Has(Pipeline::UPDATE_NUMBER_OF_PIECES()) ||
    in->Get(Pipeline::UPDATE_NUMBER_OF_PIECES()) <= 1)
  {
    return 1; // the whole volume in one piece
  }
  int whole[6], read[6] = { 0, -1, 0, -1, 0, -1 };
  in->Get(Pipeline::WHOLE_EXTENT(), whole);
  vtkNew<vtkExtentTranslator> translator;
  if (translator->PieceToExtentThreadSafe(in->Get(Pipeline::UPDATE_PIECE_NUMBER()),
        in->Get(Pipeline::UPDATE_NUMBER_OF_PIECES()), 0, whole, this->OwnedExtent,
        vtkExtentTranslator::BLOCK_MODE, 0))
  {
    // Shadow rays leave the piece: with shadows every rank reads the whole volume.
    const bool shadows =
      this->GetPARCMapper()->GetShadowMode() == vtkPARCVolumeMapper::SHADOWS_ON;
    const int layers = this->BorderLayers();
    this->Layers = shadows ? -1 : layers;
    if (!shadows && layers == 0)
    {
      // The piece as the pipeline splits it: asked for as it is, the source does not read
      // it again (its extent, the rank's own, shares its border voxels with the next).
      this->ReadsOwnedPiece = true;
      return 1;
    }
    for (int a = 0; a < 3; ++a)
    {
      read[2 * a] = shadows ? whole[2 * a] : std::max(whole[2 * a], this->OwnedExtent[2 * a] - layers);
      read[2 * a + 1] =
        shadows ? whole[2 * a + 1] : std::min(whole[2 * a + 1], this->OwnedExtent[2 * a + 1] + layers);
    }
  }
  in->Set(Pipeline::UPDATE_EXTENT(), read, 6);
  in->Set(Pipeline::UPDATE_PIECE_NUMBER(), 0);
  in->Set(Pipeline::UPDATE_NUMBER_OF_PIECES(), 1);
  in->Set(Pipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
  this->ReadsOwnedPiece = true;
  return 1;
}

int vtkPARCVolumeRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkSmartPointer<vtkImageData> piece;
  vtkImageData* input = inputVector[0]->GetNumberOfInformationObjects() == 1
    ? vtkImageData::GetData(inputVector[0], 0)
    : nullptr;
  const bool ghosts = input && input->HasAnyGhostCells();
  const bool owned = input && !ghosts && this->ReadsOwnedPiece;
  int ownedExtent[6];
  if (ghosts || owned)
  {
    piece.TakeReference(input->NewInstance()); // a vtkUniformGrid stays one
    piece->ShallowCopy(input);
  }
  if (owned)
  {
    const int* extent = input->GetExtent();
    if (this->Layers == 0) // the piece as split: all of it is the rank's
    {
      std::copy_n(extent, 6, this->OwnedExtent);
    }
    for (int a = 0; a < 3; ++a) // the part of the owned extent the source gave
    {
      ownedExtent[2 * a] = std::max(extent[2 * a], this->OwnedExtent[2 * a]);
      ownedExtent[2 * a + 1] = std::min(extent[2 * a + 1], this->OwnedExtent[2 * a + 1]);
    }
    vtkPARCVolumeMapper::SetOwnedExtent(piece, ownedExtent);
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
  if (owned) // the ranks' images are ordered by the bounds of the cells they own
  {
    vtkNew<vtkImageData> box;
    box->CopyStructure(input);
    box->SetExtent(ownedExtent);
    this->OutlineSource->SetBounds(box->GetBounds());
    this->OutlineSource->GetBounds(this->DataBounds);
    this->OutlineSource->Update();
  }
  return 1;
}

void vtkPARCVolumeRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PARC mapper:\n";
  this->GetPARCMapper()->PrintSelf(os, indent.GetNextIndent());
}
