#include "vtkPARCPolygonModelFilter.h"

#include "parcAccelerationPlan.h"
#include "parcVTKConversion.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkCellData.h"
#include "vtkVolumeProperty.h"

#include <string>

namespace
{
void AddStatistic(vtkFieldData* fd, const char* name, double value)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  fd->AddArray(a);
}
}

class vtkPARCPolygonModelFilter::vtkInternals
{
public:
  parc::ScalarField Field;
  parc::vtk::WrappedScalars Scalars; ///< what Field was wrapped from
  /// The pyramid is kept while the field is the same, the classification while its key is.
  parc::AccelerationPlan Plan;
  vtkNew<vtkVolumeProperty> DefaultProperty;
};

vtkStandardNewMacro(vtkPARCPolygonModelFilter);
vtkCxxSetObjectMacro(vtkPARCPolygonModelFilter, VolumeProperty, vtkVolumeProperty);

//------------------------------------------------------------------------------
vtkPARCPolygonModelFilter::vtkPARCPolygonModelFilter()
  : Internals(new vtkInternals)
{
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

//------------------------------------------------------------------------------
vtkPARCPolygonModelFilter::~vtkPARCPolygonModelFilter()
{
  this->SetVolumeProperty(nullptr);
}

//------------------------------------------------------------------------------
vtkMTimeType vtkPARCPolygonModelFilter::GetMTime()
{
  vtkMTimeType time = this->Superclass::GetMTime();
  if (this->VolumeProperty)
  {
    time = std::max(time, this->VolumeProperty->GetMTime());
    if (this->LabelMap)
    {
      time = std::max(time, parc::vtk::LabelOpacitiesMTime(this->VolumeProperty));
    }
  }
  return time;
}

//------------------------------------------------------------------------------
int vtkPARCPolygonModelFilter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkImageData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkPARCPolygonModelFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkImageData* image = vtkImageData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  vtkInternals& in = *this->Internals;
  std::string error;
  if (!parc::vtk::CheckImage(image, error))
  {
    vtkErrorMacro(<< error);
    return 1;
  }
  vtkDataArray* scalars = this->GetInputArrayToProcess(0, inputVector);
  if (!scalars)
  {
    vtkErrorMacro("The input has no point scalars to classify.");
    return 1;
  }
  parc::CastParameters p;
  if (!parc::vtk::ConvertBlendMode(this->BlendMode, p.Blend))
  {
    vtkErrorMacro("Blend mode " << this->BlendMode << " is not supported.");
    return 1;
  }
  const vtkMTimeType time = std::max(image->GetMTime(), scalars->GetMTime());
  if (!in.Scalars.Matches(scalars, time))
  {
    int dims[3];
    image->GetDimensions(dims);
    std::size_t replaced = 0;
    in.Scalars.Clear();
    if (!parc::vtk::WrapScalars(scalars, dims, in.Field, replaced, error))
    {
      vtkErrorMacro(<< error);
      return 1;
    }
    in.Scalars.Wrapped(scalars, time);
  }
  this->UpdateProgress(0.25);

  vtkVolumeProperty* property =
    this->VolumeProperty ? this->VolumeProperty : in.DefaultProperty.Get();
  parc::vtk::ConvertProperty(property, in.Field.GetRange(), p, 0, parc::vtk::GradientUnit(image));
  if (this->LabelMap)
  {
    if (!parc::TraitsOf(p.Blend).AppliesLabels)
    {
      vtkErrorMacro("A label map applies to composite blending.");
      return 1;
    }
    parc::vtk::ConvertLabels(
      property, in.Field.GetRange(), p, p.Labels, parc::vtk::GradientUnit(image));
  }
  p.AverageRange[0] = this->AverageIPScalarRange[0];
  p.AverageRange[1] = this->AverageIPScalarRange[1];
  parc::ClassificationKey key = parc::vtk::ClassificationKeyOf(
    property, p, in.Scalars.Version, this->BlendMode, this->AverageIPScalarRange);
  std::copy_n(this->SupercellSize, 3, key.Size);
  if (!in.Plan.IsClassifiedFrom(key))
  {
    parc::ContributionRule rule;
    rule.Set(p, in.Field.GetRange());
    double fitted[3];
    in.Plan.ClassifyFrom(key, { &in.Field }, { rule }, p.Interp, fitted);
  }
  const parc::SupercellGrid& grid = in.Plan.GetGrid();
  if (grid.GetNumberOfSupercells() == 0 ||
    !std::equal(this->SupercellSize, this->SupercellSize + 3, grid.GetSize()))
  {
    vtkErrorMacro("Invalid supercell size (" << this->SupercellSize[0] << ", "
                                             << this->SupercellSize[1] << ", "
                                             << this->SupercellSize[2]
                                             << "): sizes must be positive and finite, and "
                                                "make at most 2^28 supercells.");
    return 1;
  }
  this->UpdateProgress(0.5);

  in.Plan.SetMergeFaces(this->MergeFaces != 0);
  const parc::PolygonModel& model = this->Model == COLOR_MODEL
    ? in.Plan.GetColorModel(this->MajorAxis, false)
    : in.Plan.GetDepthModel(false);
  this->UpdateProgress(0.75);

  const parc::Matrix4 indexToPhysical = parc::vtk::IndexToPhysical(image);
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(model.Vertices.size()));
  for (std::size_t v = 0; v < model.Vertices.size(); ++v)
  {
    const parc::Vec3 x = indexToPhysical.TransformPoint(model.Vertices[v]);
    points->SetPoint(static_cast<vtkIdType>(v), x.X, x.Y, x.Z);
  }
  vtkNew<vtkCellArray> quads;
  quads->AllocateExact(static_cast<vtkIdType>(model.GetNumberOfQuads()),
    static_cast<vtkIdType>(model.Vertices.size()));
  for (std::size_t q = 0; q < model.GetNumberOfQuads(); ++q)
  {
    const vtkIdType ids[4] = { static_cast<vtkIdType>(4 * q), static_cast<vtkIdType>(4 * q + 1),
      static_cast<vtkIdType>(4 * q + 2), static_cast<vtkIdType>(4 * q + 3) };
    quads->InsertNextCell(4, ids);
  }
  output->SetPoints(points);
  output->SetPolys(quads);
  if (this->Model == COLOR_MODEL)
  {
    vtkNew<vtkIntArray> planes;
    planes->SetName("PlaneIndex");
    planes->SetNumberOfValues(static_cast<vtkIdType>(model.Planes.size()));
    std::copy(model.Planes.begin(), model.Planes.end(), planes->GetPointer(0));
    output->GetCellData()->AddArray(planes);
  }
  const parc::ModelStatistics stats = parc::ComputeStatistics(in.Plan.GetGrid(), model);
  vtkFieldData* fd = output->GetFieldData();
  AddStatistic(fd, "Cells", static_cast<double>(stats.Cells));
  AddStatistic(fd, "Supercells", static_cast<double>(stats.Supercells));
  AddStatistic(fd, "ContributingSupercells", static_cast<double>(stats.ContributingSupercells));
  AddStatistic(fd, "ContributingPercent", stats.ContributingPercent);
  AddStatistic(fd, "Polygons", static_cast<double>(stats.Polygons));
  // The filter's work so far: a new model or axis of the same classification adds none.
  AddStatistic(fd, "Classifications", static_cast<double>(in.Plan.GetClassifications()));
  AddStatistic(fd, "PyramidBuilds", static_cast<double>(in.Plan.GetPyramidBuilds()));
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkPARCPolygonModelFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VolumeProperty: " << this->VolumeProperty << "\n";
  os << indent << "BlendMode: " << this->BlendMode << "\n";
  os << indent << "AverageIPScalarRange: " << this->AverageIPScalarRange[0] << ", "
     << this->AverageIPScalarRange[1] << "\n";
  os << indent << "SupercellSize: " << this->SupercellSize[0] << ", " << this->SupercellSize[1]
     << ", " << this->SupercellSize[2] << "\n";
  os << indent << "Model: " << (this->Model == COLOR_MODEL ? "Color" : "Depth") << "\n";
  os << indent << "MajorAxis: " << this->MajorAxis << "\n";
  os << indent << "MergeFaces: " << this->MergeFaces << "\n";
  os << indent << "LabelMap: " << this->LabelMap << "\n";
}
