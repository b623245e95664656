#include "vtkPARCPVPolygonModelFilter.h"

#include "vtkContourValues.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPiecewiseFunction.h"
#include "vtkVolumeProperty.h"

vtkStandardNewMacro(vtkPARCPVPolygonModelFilter);

vtkPARCPVPolygonModelFilter::vtkPARCPVPolygonModelFilter()
{
  vtkNew<vtkVolumeProperty> property;
  this->SetVolumeProperty(property);
}

vtkPARCPVPolygonModelFilter::~vtkPARCPVPolygonModelFilter() = default;

void vtkPARCPVPolygonModelFilter::SetScalarOpacityFunction(vtkPiecewiseFunction* function)
{
  // Null: the property creates VTK's default function when asked for it.
  this->GetVolumeProperty()->SetScalarOpacity(function);
  this->Modified();
}

void vtkPARCPVPolygonModelFilter::SetNumberOfIsosurfaces(int number)
{
  this->GetVolumeProperty()->GetIsoSurfaceValues()->SetNumberOfContours(number);
  this->Modified();
}

void vtkPARCPVPolygonModelFilter::SetIsosurfaceValue(int i, double value)
{
  this->GetVolumeProperty()->GetIsoSurfaceValues()->SetValue(i, value);
  this->Modified();
}

void vtkPARCPVPolygonModelFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
