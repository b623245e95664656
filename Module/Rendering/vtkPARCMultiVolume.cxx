#include "vtkPARCMultiVolume.h"

#include "vtkAbstractVolumeMapper.h"
#include "vtkBoundingBox.h"
#include "vtkDataSet.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkRenderer.h"

vtkStandardNewMacro(vtkPARCMultiVolume);

//------------------------------------------------------------------------------
vtkPARCMultiVolume::vtkPARCMultiVolume() = default;
vtkPARCMultiVolume::~vtkPARCMultiVolume() = default;

//------------------------------------------------------------------------------
double* vtkPARCMultiVolume::GetBounds()
{
  vtkBoundingBox box;
  auto* mapper = vtkAbstractVolumeMapper::SafeDownCast(this->Mapper);
  for (const auto& entry : this->Volumes)
  {
    const int port = entry.first;
    vtkVolume* volume = entry.second;
    if (!mapper || !volume || port >= mapper->GetNumberOfInputPorts() ||
      mapper->GetNumberOfInputConnections(port) < 1)
    {
      continue;
    }
    mapper->GetInputAlgorithm(port, 0)->Update();
    vtkDataSet* data = vtkDataSet::SafeDownCast(mapper->GetInputDataObject(port, 0));
    if (!data || data->GetNumberOfPoints() < 1)
    {
      continue;
    }
    double b[6];
    data->GetBounds(b);
    vtkMatrix4x4* matrix = volume->GetMatrix();
    for (int corner = 0; corner < 8; ++corner)
    {
      const double p[4] = { b[corner & 1], b[2 + ((corner >> 1) & 1)], b[4 + ((corner >> 2) & 1)],
        1.0 };
      double q[4];
      matrix->MultiplyPoint(p, q);
      box.AddPoint(q[0] / q[3], q[1] / q[3], q[2] / q[3]);
    }
  }
  this->Matrix->Identity();
  if (box.IsValid())
  {
    box.GetBounds(this->Bounds);
  }
  else
  {
    vtkMath::UninitializeBounds(this->Bounds);
  }
  return this->Bounds;
}

//------------------------------------------------------------------------------
int vtkPARCMultiVolume::RenderVolumetricGeometry(vtkViewport* viewport)
{
  this->Update();
  if (!this->Mapper)
  {
    vtkErrorMacro("No mapper: set a vtkPARCVolumeMapper with SetMapper.");
    return 0;
  }
  if (!this->Mapper->GetDataObjectInput())
  {
    return 0;
  }
  this->Mapper->Render(static_cast<vtkRenderer*>(viewport), this);
  this->EstimatedRenderTime += this->Mapper->GetTimeToDraw();
  return 1;
}

//------------------------------------------------------------------------------
void vtkPARCMultiVolume::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
