#include "parcVTKConversion.h"

#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkPiecewiseFunction.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <cmath>
#include <new>
#include <sstream>
#include <vector>

namespace parc
{
namespace vtk
{

namespace
{
constexpr int ColorTableSize = 1024;
constexpr int NonLinearSegmentPieces = 32; ///< pieces for a node with midpoint/sharpness

/// Converts a vtkPiecewiseFunction into the core's exact piecewise-linear function.
void ConvertPiecewise(vtkPiecewiseFunction* f, PiecewiseLinearFunction& out)
{
  const int n = f ? f->GetSize() : 0;
  if (n == 0)
  {
    out.SetConstant(f ? f->GetValue(0.0) : 1.0);
    return;
  }
  std::vector<double> x, y;
  double node[4], next[4];
  for (int i = 0; i < n; ++i)
  {
    f->GetNodeValue(i, node);
    x.push_back(node[0]);
    y.push_back(node[1]);
    if (i + 1 < n && (node[2] != 0.5 || node[3] != 0.0))
    {
      f->GetNodeValue(i + 1, next);
      for (int p = 1; p < NonLinearSegmentPieces; ++p)
      {
        const double s = node[0] + (next[0] - node[0]) * p / NonLinearSegmentPieces;
        x.push_back(s);
        y.push_back(f->GetValue(s));
      }
    }
  }
  out.SetNodes(std::move(x), std::move(y), f->GetClamping() != 0);
}

void ConvertColor(vtkVolumeProperty* property, const double range[2], ColorTable& out)
{
  std::vector<float> rgb(3 * ColorTableSize);
  const double lo = range[0];
  const double hi = range[1] > range[0] ? range[1] : range[0] + 1.0;
  if (property->GetColorChannels() == 1)
  {
    std::vector<float> gray(ColorTableSize);
    property->GetGrayTransferFunction()->GetTable(lo, hi, ColorTableSize, gray.data());
    for (int i = 0; i < ColorTableSize; ++i)
    {
      rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = gray[i];
    }
  }
  else
  {
    property->GetRGBTransferFunction()->GetTable(lo, hi, ColorTableSize, rgb.data());
  }
  out.SetTable(lo, hi, std::move(rgb));
}

template <typename T>
std::size_t WrapField(ScalarField& field, vtkDataArray* array, const int dims[3])
{
  return field.Wrap(static_cast<const T*>(array->GetVoidPointer(0)), dims,
    array->GetNumberOfComponents());
}
}

bool ConvertBlendMode(int vtkBlendMode, BlendMode& out)
{
  switch (vtkBlendMode)
  {
    case vtkVolumeMapper::COMPOSITE_BLEND:
      out = BlendMode::Composite;
      return true;
    case vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND:
      out = BlendMode::MaximumIntensity;
      return true;
    case vtkVolumeMapper::MINIMUM_INTENSITY_BLEND:
      out = BlendMode::MinimumIntensity;
      return true;
    case vtkVolumeMapper::AVERAGE_INTENSITY_BLEND:
      out = BlendMode::AverageIntensity;
      return true;
    case vtkVolumeMapper::ADDITIVE_BLEND:
      out = BlendMode::Additive;
      return true;
    case vtkVolumeMapper::ISOSURFACE_BLEND:
      out = BlendMode::IsoSurface;
      return true;
    default:
      return false;
  }
}

bool CheckImage(vtkImageData* image, std::string& error)
{
  std::ostringstream message;
  int dims[3];
  image->GetDimensions(dims);
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
  {
    message << "The input has dimensions " << dims[0] << " x " << dims[1] << " x " << dims[2]
            << ": at least 2 samples are needed along each axis to cast rays.";
    error = message.str();
    return false;
  }
  const double* spacing = image->GetSpacing();
  for (int a = 0; a < 3; ++a)
  {
    if (spacing[a] == 0.0 || !std::isfinite(spacing[a]))
    {
      message << "The input spacing (" << spacing[0] << ", " << spacing[1] << ", "
              << spacing[2] << ") must be finite and non-zero.";
      error = message.str();
      return false;
    }
  }
  return true;
}

bool WrapScalars(vtkDataArray* scalars, const int dims[3], ScalarField& field,
  std::size_t& replaced, std::string& error)
{
  replaced = 0;
  try
  {
    switch (scalars->GetDataType())
    {
      case VTK_CHAR:
      case VTK_SIGNED_CHAR:
        replaced = WrapField<signed char>(field, scalars, dims);
        return true;
      case VTK_UNSIGNED_CHAR:
        replaced = WrapField<unsigned char>(field, scalars, dims);
        return true;
      case VTK_SHORT:
        replaced = WrapField<short>(field, scalars, dims);
        return true;
      case VTK_UNSIGNED_SHORT:
        replaced = WrapField<unsigned short>(field, scalars, dims);
        return true;
      case VTK_INT:
        replaced = WrapField<int>(field, scalars, dims);
        return true;
      case VTK_UNSIGNED_INT:
        replaced = WrapField<unsigned int>(field, scalars, dims);
        return true;
      case VTK_FLOAT:
        replaced = WrapField<float>(field, scalars, dims);
        return true;
      case VTK_DOUBLE:
        replaced = WrapField<double>(field, scalars, dims);
        return true;
      default:
        error = std::string("Unsupported scalar type ") + scalars->GetDataTypeAsString() +
          ": use (unsigned) char, short, int, float or double.";
        return false;
    }
  }
  catch (const std::bad_alloc&)
  {
    error = "Not enough memory to convert " + std::to_string(scalars->GetNumberOfTuples()) +
      " scalars.";
    return false;
  }
}

void ConvertProperty(vtkVolumeProperty* property, const double range[2], CastParameters& p)
{
  p.Interp = property->GetInterpolationType() == VTK_NEAREST_INTERPOLATION
    ? Interpolation::Nearest
    : Interpolation::Linear;
  ConvertPiecewise(property->GetScalarOpacity(0), p.Opacity);
  ConvertColor(property, range, p.Color);
  p.UseGradientOpacity = property->HasGradientOpacity(0) && !property->GetDisableGradientOpacity(0);
  if (p.UseGradientOpacity)
  {
    ConvertPiecewise(property->GetGradientOpacity(0), p.GradientOpacity);
  }
  p.OpacityUnitDistance = property->GetScalarOpacityUnitDistance(0);
  p.Shade = property->GetShade(0) &&
    (p.Blend == BlendMode::Composite || p.Blend == BlendMode::IsoSurface);
  p.Ambient = property->GetAmbient(0);
  p.Diffuse = property->GetDiffuse(0);
  p.Specular = property->GetSpecular(0);
  p.SpecularPower = property->GetSpecularPower(0);
  p.IsoValues.clear();
  vtkContourValues* iso = property->GetIsoSurfaceValues();
  for (int i = 0; i < iso->GetNumberOfContours(); ++i)
  {
    p.IsoValues.push_back(iso->GetValue(i));
  }
}

Matrix4 ToMatrix4(vtkMatrix4x4* m)
{
  Matrix4 out;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out(r, c) = m->GetElement(r, c);
    }
  }
  return out;
}

Matrix4 IndexToPhysical(vtkImageData* image)
{
  const Matrix4 indexToData = ToMatrix4(image->GetIndexToPhysicalMatrix());
  const int* extent = image->GetExtent();
  Matrix4 shift;
  shift(0, 3) = extent[0];
  shift(1, 3) = extent[2];
  shift(2, 3) = extent[4];
  return Multiply(indexToData, shift);
}

} // namespace vtk
} // namespace parc
