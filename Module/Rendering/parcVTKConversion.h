// PARC for VTK: conversions from VTK objects to the core's types, shared by the mapper and
// the polygon-model filter (private to the module, not wrapped).
#ifndef parcVTKConversion_h
#define parcVTKConversion_h

#include "parcAccelerationPlan.h"
#include "parcRayCaster.h"

#include "vtkDataArray.h"
#include "vtkSmartPointer.h"
#include "vtkType.h"

#include <algorithm>
#include <cstdint>
#include <string>

class vtkImageData;
class vtkMatrix4x4;
class vtkVolumeProperty;

namespace parc
{
namespace vtk
{

/// Appends sentence to text, a space between them (nothing for an empty sentence): how the
/// conversions collect what they fixed.
void AppendSentence(std::string& text, const std::string& sentence);

/// The core blend mode of a vtkVolumeMapper blend mode; false for unsupported ones.
bool ConvertBlendMode(int vtkBlendMode, BlendMode& out);

/// Makes field read one component of scalars (point data of an image of dims) in place,
/// without a copy (scalars must stay alive while field is used; only non-finite
/// floating-point values make a copy, of that component alone). Returns false with a
/// message in error for unsupported types, fewer tuples than the image has points, or too
/// little memory; replaced receives the number of non-finite values replaced.
bool WrapScalars(vtkDataArray* scalars, const int dims[3], ScalarField& field,
  std::size_t& replaced, std::string& error, int component = 0);

/// What a field was last wrapped from (WrapScalars): the array, the latest modification of
/// it and its image, the component; Version counts the fields wrapped, what pyramids and
/// classifications are keyed by (an array switched back can be older than the last one).
struct WrappedScalars
{
  vtkSmartPointer<vtkDataArray> Array; ///< null while no field is wrapped
  vtkMTimeType Time = 0;
  int Component = 0;
  std::uint64_t Version = 0;
  /// Whether the field is wrapped from these scalars already.
  bool Matches(vtkDataArray* scalars, vtkMTimeType time, int component = 0) const
  {
    return this->Array && scalars == this->Array && time == this->Time &&
      component == this->Component;
  }
  /// The field was wrapped from these scalars: a new version.
  void Wrapped(vtkDataArray* scalars, vtkMTimeType time, int component = 0)
  {
    this->Array = scalars;
    this->Time = time;
    this->Component = component;
    ++this->Version;
  }
  /// The field is not wrapped (a wrap failed).
  void Clear() { this->Array = nullptr; }
};

/// How a premultiplied float RGBA ray image becomes the bytes shown, as VTK's ray cast
/// mappers show it: the final colour window and level applied to the colours (rgb * scale
/// + bias * alpha, within [0, alpha]; window 1 and level 0.5 change nothing), every
/// channel clamped to [0, 1] and rounded to 8 bits.
class FinalColor
{
public:
  /// window 0 is not usable: the colours are then not adjusted (IsUsable false).
  FinalColor(float window, float level)
    : Adjust(!(window == 1.f && level == 0.5f) && window != 0.f)
    , Scale(this->Adjust ? 1.f / window : 1.f)
    , Bias(this->Adjust ? 0.5f - level / window : 0.f)
    , Usable(window != 0.f)
  {
  }
  bool IsUsable() const { return this->Usable; }
  /// The bytes of one pixel.
  void ToBytes(const float rgba[4], unsigned char out[4]) const
  {
    const float a = std::min(std::max(rgba[3], 0.f), 1.f);
    for (int c = 0; c < 4; ++c)
    {
      float v = rgba[c];
      if (this->Adjust && c < 3)
      {
        v = std::min(std::max(v * this->Scale + this->Bias * a, 0.f), a);
      }
      v = std::min(std::max(v, 0.f), 1.f);
      out[c] = static_cast<unsigned char>(v * 255.f + 0.5f);
    }
  }

private:
  bool Adjust;
  float Scale, Bias;
  bool Usable;
};

/// Whether WrapScalars takes scalars of this VTK type.
bool IsSupportedScalarType(int vtkType);

/// Checks that an image can be cast (dims >= 2, finite non-zero spacing); false with a
/// message otherwise.
bool CheckImage(vtkImageData* image, std::string& error);
/// The same for a grid of dims samples with spacing (an image's, or its cells').
bool CheckGrid(const int dims[3], const double spacing[3], std::string& error);

/// The transfer functions, interpolation, shading coefficients and iso values of
/// a component of property, for a field of the given value range. Blend must be set in p
/// already (it decides whether shading applies). Values no transfer function can mean are
/// made usable the same way for every acceleration mode: nodes with a NaN or infinite
/// scalar or value are left out, opacities are clamped to [0, 1] and colours to [0, 1]
/// (NaN to 0). The gradient opacity function maps the gradient's magnitude in scalar units
/// per gradientUnit world units, as VTK's mappers define it with the mean voxel spacing
/// (GradientUnit); p's function is made one of the world gradient. Returns a description of
/// what was changed, empty when nothing was.
std::string ConvertProperty(vtkVolumeProperty* property, const double range[2],
  CastParameters& p, int component = 0, double gradientUnit = 1.0);

/// The functions of the labels (> 0) of property's label map into out, sorted: each
/// label's own scalar opacity, colour and gradient opacity where it has them, p's (already
/// converted for the field's range) where it has not. Returns what was fixed, as
/// ConvertProperty does.
std::string ConvertLabels(vtkVolumeProperty* property, const double range[2],
  const CastParameters& p, std::vector<LabelFunctions>& out, double gradientUnit = 1.0);

/// The latest modification of the scalar opacities of the labels (> 0) of property's label
/// map (vtkVolumeProperty::GetMTime does not include them); 0 without any.
vtkMTimeType LabelOpacitiesMTime(vtkVolumeProperty* property);

/// What a classification of the field of version fieldVersion is made from: property's
/// transfer functions (and those of p's labels), the caller's VTK blend mode and its
/// average-intensity range. Its supercell size is left 0 for the caller to set.
ClassificationKey ClassificationKeyOf(vtkVolumeProperty* property, const CastParameters& p,
  std::uint64_t fieldVersion, int blend, const double average[2]);

/// The length the gradient opacity functions of VTK's volume mappers measure gradients
/// per: the mean of image's voxel spacing (world units).
double GradientUnit(vtkImageData* image);

/// The name of the field-data array that holds the point extent a piece owns
/// (vtkPARCVolumeMapper::SetOwnedExtent).
constexpr const char* OwnedExtentArrayName = "vtkPARCOwnedExtent";
/// The point extent image's field data names as owned (OwnedExtentArrayName); false when
/// it names none. SetOwnedExtent names one.
bool OwnedExtent(vtkImageData* image, int extent[6]);
void SetOwnedExtent(vtkImageData* image, const int extent[6]);
/// The box of voxel-index coordinates (0 at the extent's start, minus cellOffset as for a
/// field of cell scalars) covered by the cells of image that are not ghost cells (no
/// DUPLICATECELL in its cell ghost array) or, without ghost cells, by the cells of its
/// owned extent (OwnedExtent): the cells a piece of a distributed volume owns, when it
/// also holds its neighbours' cells at its border. Infinite (the whole field) when image
/// has neither; empty (lo > hi) when every cell is a ghost.
void OwnedCellBox(vtkImageData* image, double cellOffset, Vec3& lo, Vec3& hi);
Matrix4 ToMatrix4(vtkMatrix4x4* m);
/// The matrix from 0-based voxel indices of the image to its physical coordinates.
Matrix4 IndexToPhysical(vtkImageData* image);

} // namespace vtk
} // namespace parc

#endif
