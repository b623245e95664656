#include "parcVTKConversion.h"

#include "vtkColorTransferFunction.h"
#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPiecewiseFunction.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVolumeMapper.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <new>
#include <numeric>
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

/// Converts a vtkPiecewiseFunction into the core's exact piecewise-linear function, of
/// x / unit where f is of x. Nodes with a non-finite scalar or value are left out and
/// values are clamped to [0, 1]; what was changed is appended to fixes, named by what.
void ConvertPiecewise(vtkPiecewiseFunction* f, const char* what, PiecewiseLinearFunction& out,
  std::string& fixes, double unit = 1.0)
{
  const int n = f ? f->GetSize() : 0;
  if (n == 0)
  {
    out.SetConstant(f ? f->GetValue(0.0) : 1.0);
    return;
  }
  std::vector<double> x, y;
  int dropped = 0, clamped = 0;
  auto add = [&](double s, double v) {
    if (!std::isfinite(s) || !std::isfinite(v))
    {
      ++dropped;
      return;
    }
    const double c = std::min(std::max(v, 0.0), 1.0);
    clamped += c != v;
    x.push_back(s / unit);
    y.push_back(c);
  };
  double node[4], next[4];
  for (int i = 0; i < n; ++i)
  {
    f->GetNodeValue(i, node);
    add(node[0], node[1]);
    if (i + 1 < n && (node[2] != 0.5 || node[3] != 0.0))
    {
      f->GetNodeValue(i + 1, next);
      for (int p = 1; p < NonLinearSegmentPieces; ++p)
      {
        const double s = node[0] + (next[0] - node[0]) * p / NonLinearSegmentPieces;
        add(s, f->GetValue(s));
      }
    }
  }
  if (dropped > 0 || clamped > 0)
  {
    AppendSentence(fixes, std::string("The ") + what + " function has " +
        std::to_string(dropped) + " non-finite and " + std::to_string(clamped) +
        " out-of-range [0, 1] values: left out and clamped.");
  }
  if (x.empty())
  {
    out.SetConstant(0.0);
    return;
  }
  if (dropped > 0) // a NaN scalar may have left the function's nodes out of order
  {
    std::vector<std::size_t> order(x.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(
      order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return x[a] < x[b]; });
    std::vector<double> sx, sy;
    for (std::size_t i : order)
    {
      sx.push_back(x[i]);
      sy.push_back(y[i]);
    }
    x.swap(sx);
    y.swap(sy);
  }
  out.SetNodes(std::move(x), std::move(y), f->GetClamping() != 0);
}

/// Clamps colour values to [0, 1] (NaN to 0); the number changed.
int ClampColors(std::vector<float>& rgb)
{
  int changed = 0;
  for (float& v : rgb)
  {
    const float c = v >= 0.f ? std::min(v, 1.f) : 0.f; // NaN to 0
    changed += !(c == v);
    v = c;
  }
  return changed;
}

/// The colour table of a gray function (when gray is given) or an RGB one over range: each
/// entry is the function's own value (GetValue, GetColor) at its scalar, so every setting
/// that changes them holds (clamping, midpoints and sharpness, colour spaces, below- and
/// above-range colours). Not GetTable: VTK 9.1's gives black at a colour function's first
/// node when the table starts below it.
void ConvertColor(vtkPiecewiseFunction* gray, vtkColorTransferFunction* color,
  const double range[2], ColorTable& out, std::string& fixes)
{
  std::vector<float> rgb(3 * ColorTableSize);
  const double lo = range[0];
  const double hi = range[1] > range[0] ? range[1] : range[0] + 1.0;
  for (int i = 0; i < ColorTableSize; ++i)
  {
    const double s = i + 1 < ColorTableSize ? lo + (hi - lo) * i / (ColorTableSize - 1) : hi;
    double value[3];
    if (gray)
    {
      value[0] = value[1] = value[2] = gray->GetValue(s);
    }
    else
    {
      color->GetColor(s, value);
    }
    std::copy_n(value, 3, &rgb[3 * i]);
  }
  if (const int changed = ClampColors(rgb))
  {
    AppendSentence(fixes, "The colour function has " + std::to_string(changed) +
        " NaN or out-of-range [0, 1] values in its table: clamped.");
  }
  out.SetTable(lo, hi, std::move(rgb));
}

template <typename T>
std::size_t WrapField(ScalarField& field, vtkDataArray* array, const int dims[3], int component)
{
  return field.Wrap(static_cast<const T*>(array->GetVoidPointer(0)) + component, dims,
    array->GetNumberOfComponents());
}
}

void AppendSentence(std::string& text, const std::string& sentence)
{
  if (!sentence.empty())
  {
    text += (text.empty() ? "" : " ") + sentence;
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
    case vtkVolumeMapper::SLICE_BLEND:
      out = BlendMode::Slice;
      return true;
    default:
      return false;
  }
}

bool CheckImage(vtkImageData* image, std::string& error)
{
  return CheckGrid(image->GetDimensions(), image->GetSpacing(), error);
}

bool CheckGrid(const int dims[3], const double spacing[3], std::string& error)
{
  std::ostringstream message;
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
  {
    message << "The input has dimensions " << dims[0] << " x " << dims[1] << " x " << dims[2]
            << ": at least 2 samples are needed along each axis to cast rays.";
    error = message.str();
    return false;
  }
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

bool IsSupportedScalarType(int vtkType)
{
  switch (vtkType)
  {
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
    case VTK_UNSIGNED_CHAR:
    case VTK_SHORT:
    case VTK_UNSIGNED_SHORT:
    case VTK_INT:
    case VTK_UNSIGNED_INT:
    case VTK_FLOAT:
    case VTK_DOUBLE:
      return true;
    default:
      return false;
  }
}

bool WrapScalars(vtkDataArray* scalars, const int dims[3], ScalarField& field,
  std::size_t& replaced, std::string& error, int component)
{
  replaced = 0;
  const vtkIdType points =
    static_cast<vtkIdType>(dims[0]) * static_cast<vtkIdType>(dims[1]) * dims[2];
  if (scalars->GetNumberOfTuples() < points)
  {
    error = "The scalars have " + std::to_string(scalars->GetNumberOfTuples()) +
      " tuples, fewer than the image's " + std::to_string(points) + " points.";
    return false;
  }
  try
  {
    switch (scalars->GetDataType())
    {
      case VTK_CHAR:
      case VTK_SIGNED_CHAR:
        replaced = WrapField<signed char>(field, scalars, dims, component);
        return true;
      case VTK_UNSIGNED_CHAR:
        replaced = WrapField<unsigned char>(field, scalars, dims, component);
        return true;
      case VTK_SHORT:
        replaced = WrapField<short>(field, scalars, dims, component);
        return true;
      case VTK_UNSIGNED_SHORT:
        replaced = WrapField<unsigned short>(field, scalars, dims, component);
        return true;
      case VTK_INT:
        replaced = WrapField<int>(field, scalars, dims, component);
        return true;
      case VTK_UNSIGNED_INT:
        replaced = WrapField<unsigned int>(field, scalars, dims, component);
        return true;
      case VTK_FLOAT:
        replaced = WrapField<float>(field, scalars, dims, component);
        return true;
      case VTK_DOUBLE:
        replaced = WrapField<double>(field, scalars, dims, component);
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

std::string ConvertProperty(vtkVolumeProperty* property, const double range[2],
  CastParameters& p, int component, double gradientUnit)
{
  std::string fixes;
  const int c = component;
  p.Interp = property->GetInterpolationType() == VTK_NEAREST_INTERPOLATION
    ? Interpolation::Nearest
    : Interpolation::Linear;
  ConvertPiecewise(property->GetScalarOpacity(c), "scalar opacity", p.Opacity, fixes);
  const bool gray = property->GetColorChannels(c) == 1;
  ConvertColor(gray ? property->GetGrayTransferFunction(c) : nullptr,
    gray ? nullptr : property->GetRGBTransferFunction(c), range, p.Color, fixes);
  p.UseGradientOpacity = property->HasGradientOpacity(c) && !property->GetDisableGradientOpacity(c);
  if (p.UseGradientOpacity)
  {
    ConvertPiecewise(
      property->GetGradientOpacity(c), "gradient opacity", p.GradientOpacity, fixes, gradientUnit);
  }
  p.OpacityUnitDistance = property->GetScalarOpacityUnitDistance(c);
  p.Shade = property->GetShade(c) &&
    (p.Blend == BlendMode::Composite || p.Blend == BlendMode::IsoSurface ||
      p.Blend == BlendMode::Slice);
  p.Ambient = property->GetAmbient(c);
  p.Diffuse = property->GetDiffuse(c);
  p.Specular = property->GetSpecular(c);
  p.SpecularPower = property->GetSpecularPower(c);
  p.IsoValues.clear();
  vtkContourValues* iso = property->GetIsoSurfaceValues();
  for (int i = 0; i < iso->GetNumberOfContours(); ++i)
  {
    p.IsoValues.push_back(iso->GetValue(i));
  }
  return fixes;
}

std::string ConvertLabels(vtkVolumeProperty* property, const double range[2],
  const CastParameters& p, std::vector<LabelFunctions>& out, double gradientUnit)
{
  std::string fixes;
  out.clear();
  for (const int label : property->GetLabelMapLabels()) // sorted
  {
    if (label <= 0)
    {
      continue; // label 0 has the default functions
    }
    LabelFunctions f;
    f.Label = label;
    f.Opacity = p.Opacity;
    f.Color = p.Color;
    f.UseGradientOpacity = p.UseGradientOpacity;
    f.GradientOpacity = p.GradientOpacity;
    if (vtkPiecewiseFunction* opacity = property->GetLabelScalarOpacity(label))
    {
      ConvertPiecewise(opacity, "label scalar opacity", f.Opacity, fixes);
    }
    if (vtkColorTransferFunction* color = property->GetLabelColor(label))
    {
      ConvertColor(nullptr, color, range, f.Color, fixes);
    }
    if (vtkPiecewiseFunction* gradient = property->GetLabelGradientOpacity(label))
    {
      f.UseGradientOpacity = true;
      ConvertPiecewise(
        gradient, "label gradient opacity", f.GradientOpacity, fixes, gradientUnit);
    }
    out.push_back(std::move(f));
  }
  return fixes;
}

vtkMTimeType LabelOpacitiesMTime(vtkVolumeProperty* property)
{
  vtkMTimeType time = 0;
  for (const int label : property->GetLabelMapLabels())
  {
    vtkPiecewiseFunction* opacity = label > 0 ? property->GetLabelScalarOpacity(label) : nullptr;
    if (opacity)
    {
      time = std::max(time, opacity->GetMTime());
    }
  }
  return time;
}

ClassificationKey ClassificationKeyOf(vtkVolumeProperty* property, const CastParameters& p,
  std::uint64_t fieldVersion, int blend, const double average[2])
{
  ClassificationKey key;
  key.FieldVersion = fieldVersion;
  key.Functions = property;
  key.FunctionsTime = property->GetMTime();
  key.Blend = blend;
  key.Labels = p.Labels.size();
  key.LabelsTime = p.Labels.empty() ? 0 : LabelOpacitiesMTime(property);
  std::copy_n(average, 2, key.Average);
  return key;
}

double GradientUnit(vtkImageData* image)
{
  const double* spacing = image->GetSpacing();
  return (std::fabs(spacing[0]) + std::fabs(spacing[1]) + std::fabs(spacing[2])) / 3.0;
}

bool OwnedExtent(vtkImageData* image, int extent[6])
{
  vtkIntArray* owned = vtkIntArray::SafeDownCast(
    image->GetFieldData()->GetAbstractArray(OwnedExtentArrayName));
  if (!owned || owned->GetNumberOfValues() != 6)
  {
    return false;
  }
  std::copy_n(owned->GetPointer(0), 6, extent);
  return true;
}

void SetOwnedExtent(vtkImageData* image, const int extent[6])
{
  vtkNew<vtkIntArray> owned;
  owned->SetName(OwnedExtentArrayName);
  owned->SetNumberOfValues(6);
  std::copy_n(extent, 6, owned->GetPointer(0));
  image->GetFieldData()->AddArray(owned); // replaces an array of that name
}

void OwnedCellBox(vtkImageData* image, double cellOffset, Vec3& lo, Vec3& hi)
{
  constexpr double Infinity = std::numeric_limits<double>::infinity();
  lo = { -Infinity, -Infinity, -Infinity };
  hi = { Infinity, Infinity, Infinity };
  vtkUnsignedCharArray* ghosts = image->GetCellGhostArray();
  int cells[3];
  image->GetCellDims(cells);
  const vtkIdType count = vtkIdType{ cells[0] } * cells[1] * cells[2];
  if (!ghosts || ghosts->GetNumberOfTuples() != count || !image->HasAnyGhostCells())
  {
    int owned[6];
    if (OwnedExtent(image, owned))
    {
      const int* extent = image->GetExtent();
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = owned[2 * a] - extent[2 * a] - cellOffset;
        hi[a] = owned[2 * a + 1] - extent[2 * a] - cellOffset;
      }
    }
    return;
  }
  const unsigned char* flags = ghosts->GetPointer(0);
  int first[3] = { cells[0], cells[1], cells[2] }, last[3] = { -1, -1, -1 };
  vtkIdType id = 0;
  for (int k = 0; k < cells[2]; ++k)
  {
    for (int j = 0; j < cells[1]; ++j)
    {
      for (int i = 0; i < cells[0]; ++i, ++id)
      {
        if (!(flags[id] & vtkDataSetAttributes::DUPLICATECELL))
        {
          const int ijk[3] = { i, j, k };
          for (int a = 0; a < 3; ++a)
          {
            first[a] = std::min(first[a], ijk[a]);
            last[a] = std::max(last[a], ijk[a]);
          }
        }
      }
    }
  }
  for (int a = 0; a < 3; ++a)
  {
    lo[a] = first[a] - cellOffset;
    hi[a] = last[a] + 1 - cellOffset;
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
