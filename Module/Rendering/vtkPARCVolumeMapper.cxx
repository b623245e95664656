#include "vtkPARCVolumeMapper.h"

#include "parcRayCaster.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkContourValues.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRayCastImageDisplayHelper.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkPropCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkTimerLog.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
constexpr int ColorTableSize = 1024;
constexpr int NonLinearSegmentPieces = 32; ///< pieces for a node with midpoint/sharpness
constexpr float DisplayDepth = 1e-6f;      ///< window depth of the displayed image quad

/// Converts a vtkPiecewiseFunction into the core's exact piecewise-linear function.
void ConvertPiecewise(vtkPiecewiseFunction* f, parc::PiecewiseLinearFunction& out)
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

void ConvertColor(vtkVolumeProperty* property, const double range[2], parc::ColorTable& out)
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

void ConvertLights(vtkRenderer* ren, std::vector<parc::Light>& lights)
{
  lights.clear();
  vtkLightCollection* collection = ren->GetLights();
  vtkCollectionSimpleIterator it;
  collection->InitTraversal(it);
  while (vtkLight* light = collection->GetNextLight(it))
  {
    if (!light->GetSwitch() || light->GetIntensity() <= 0.0)
    {
      continue;
    }
    parc::Light l;
    l.Positional = light->GetPositional() != 0;
    double p[3], f[3];
    light->GetTransformedPosition(p);
    light->GetTransformedFocalPoint(f);
    l.Position = { p[0], p[1], p[2] };
    l.FocalPoint = { f[0], f[1], f[2] };
    const double* c = light->GetDiffuseColor();
    const double i = light->GetIntensity();
    l.Color = { c[0] * i, c[1] * i, c[2] * i };
    const double* a = light->GetAttenuationValues();
    l.Attenuation = { a[0], a[1], a[2] };
    l.ConeAngle = light->GetConeAngle();
    l.Exponent = light->GetExponent();
    lights.push_back(l);
  }
}

parc::Matrix4 ToMatrix4(vtkMatrix4x4* m)
{
  parc::Matrix4 out;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      out(r, c) = m->GetElement(r, c);
    }
  }
  return out;
}

/// The matrix from 0-based voxel indices of the image to world coordinates.
parc::Matrix4 IndexToWorld(vtkImageData* image, vtkVolume* vol)
{
  parc::Matrix4 indexToData = ToMatrix4(image->GetIndexToPhysicalMatrix());
  const int* extent = image->GetExtent();
  parc::Matrix4 shift;
  shift(0, 3) = extent[0];
  shift(1, 3) = extent[2];
  shift(2, 3) = extent[4];
  return parc::Multiply(ToMatrix4(vol->GetMatrix()), parc::Multiply(indexToData, shift));
}

/// True when the renderer draws any visible prop besides volumes.
bool HasOtherGeometry(vtkRenderer* ren)
{
  vtkPropCollection* props = ren->GetViewProps();
  vtkCollectionSimpleIterator it;
  props->InitTraversal(it);
  while (vtkProp* prop = props->GetNextProp(it))
  {
    if (prop->GetVisibility() && !vtkVolume::SafeDownCast(prop))
    {
      return true;
    }
  }
  return false;
}

template <typename T>
std::size_t AssignField(parc::ScalarField& field, vtkDataArray* array, const int dims[3])
{
  return field.Assign(static_cast<const T*>(array->GetVoidPointer(0)), dims,
    array->GetNumberOfComponents());
}
}

//------------------------------------------------------------------------------
class vtkPARCVolumeMapper::vtkInternals
{
public:
  parc::ScalarField Field;
  vtkMTimeType FieldTime = 0;
  vtkDataArray* FieldArray = nullptr;
  parc::CastParameters Parameters;
  parc::RayCaster Caster;
  std::vector<float> Image;
  int ImageSize[2] = { 0, 0 };
  std::vector<float> Depth;
  std::vector<unsigned char> Display;
  parc::CastStatistics Stats;
  double CastingTime = 0.0;
  double ProjectionTime = 0.0;
  double RenderTime = 0.0;
  int LastMode = ACCELERATION_NONE;
  vtkNew<vtkOpenGLRayCastImageDisplayHelper> DisplayHelper;
};

vtkStandardNewMacro(vtkPARCVolumeMapper);

//------------------------------------------------------------------------------
vtkPARCVolumeMapper::vtkPARCVolumeMapper()
  : Internals(new vtkInternals)
{
  this->Internals->DisplayHelper->PreMultipliedColorsOn();
}

//------------------------------------------------------------------------------
vtkPARCVolumeMapper::~vtkPARCVolumeMapper() = default;

//------------------------------------------------------------------------------
const char* vtkPARCVolumeMapper::GetAccelerationModeAsString(int mode)
{
  switch (mode)
  {
    case ACCELERATION_NONE:
      return "None";
    case ACCELERATION_DEPTH_BUFFER:
      return "DepthBuffer";
    case ACCELERATION_COLOR_BUFFER:
      return "ColorBuffer";
    case ACCELERATION_AUTO:
      return "Auto";
    default:
      return "Unknown";
  }
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  const double renderStart = vtkTimerLog::GetUniversalTime();
  this->SetAbortExecute(0); // like an algorithm's execution, each render starts un-aborted
  in.Stats = parc::CastStatistics();
  in.CastingTime = in.ProjectionTime = 0.0;
  in.ImageSize[0] = in.ImageSize[1] = 0;
  in.Image.clear();

  if (!this->PrepareField() || !this->PrepareParameters(ren, vol))
  {
    in.RenderTime = vtkTimerLog::GetUniversalTime() - renderStart;
    return;
  }
  this->InvokeEvent(vtkCommand::VolumeMapperRenderStartEvent, nullptr);
  this->CastImage(ren);
  this->InvokeEvent(vtkCommand::VolumeMapperRenderEndEvent, nullptr);
  this->DisplayImage(ren, vol);
  in.RenderTime = vtkTimerLog::GetUniversalTime() - renderStart;
  this->TimeToDraw = in.RenderTime;
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::PrepareField()
{
  vtkInternals& in = *this->Internals;
  vtkAlgorithm* producer = this->GetInputAlgorithm();
  if (!producer)
  {
    vtkErrorMacro("No input: connect a vtkImageData to the mapper.");
    return false;
  }
  producer->Update();
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInput());
  if (!image)
  {
    vtkErrorMacro("The input is not a vtkImageData.");
    return false;
  }
  int dims[3];
  image->GetDimensions(dims);
  if (dims[0] < 2 || dims[1] < 2 || dims[2] < 2)
  {
    vtkErrorMacro("The input has dimensions " << dims[0] << " x " << dims[1] << " x " << dims[2]
                                               << ": at least 2 samples are needed along each "
                                                  "axis to cast rays; nothing is drawn.");
    return false;
  }
  const double* spacing = image->GetSpacing();
  for (int a = 0; a < 3; ++a)
  {
    if (spacing[a] == 0.0 || !std::isfinite(spacing[a]))
    {
      vtkErrorMacro("The input spacing (" << spacing[0] << ", " << spacing[1] << ", "
                                          << spacing[2] << ") must be finite and non-zero.");
      return false;
    }
  }
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(image, this->ScalarMode,
    this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
  if (!scalars)
  {
    vtkErrorMacro("The input has no scalars to render.");
    return false;
  }
  if (cellFlag)
  {
    vtkErrorMacro("Cell scalars are not supported: use point scalars.");
    return false;
  }
  const vtkMTimeType time = std::max(image->GetMTime(), scalars->GetMTime());
  if (scalars == in.FieldArray && time == in.FieldTime)
  {
    return true;
  }
  if (scalars->GetNumberOfComponents() > 1)
  {
    vtkWarningMacro("The scalars have " << scalars->GetNumberOfComponents()
                                        << " components; only the first is rendered.");
  }
  std::size_t replaced = 0;
  try
  {
    switch (scalars->GetDataType())
    {
      case VTK_CHAR:
      case VTK_SIGNED_CHAR:
        replaced = AssignField<signed char>(in.Field, scalars, dims);
        break;
      case VTK_UNSIGNED_CHAR:
        replaced = AssignField<unsigned char>(in.Field, scalars, dims);
        break;
      case VTK_SHORT:
        replaced = AssignField<short>(in.Field, scalars, dims);
        break;
      case VTK_UNSIGNED_SHORT:
        replaced = AssignField<unsigned short>(in.Field, scalars, dims);
        break;
      case VTK_INT:
        replaced = AssignField<int>(in.Field, scalars, dims);
        break;
      case VTK_UNSIGNED_INT:
        replaced = AssignField<unsigned int>(in.Field, scalars, dims);
        break;
      case VTK_FLOAT:
        replaced = AssignField<float>(in.Field, scalars, dims);
        break;
      case VTK_DOUBLE:
        replaced = AssignField<double>(in.Field, scalars, dims);
        break;
      default:
        vtkErrorMacro("Unsupported scalar type " << scalars->GetDataTypeAsString()
                                                 << ": use (unsigned) char, short, int, float "
                                                    "or double.");
        in.FieldArray = nullptr;
        return false;
    }
  }
  catch (const std::bad_alloc&)
  {
    vtkErrorMacro("Not enough memory to convert " << scalars->GetNumberOfTuples()
                                                  << " scalars; nothing is drawn.");
    in.FieldArray = nullptr;
    return false;
  }
  if (replaced > 0)
  {
    vtkWarningMacro(<< replaced
                    << " non-finite scalars were replaced: NaN and -inf by the smallest, +inf "
                       "by the largest finite value.");
  }
  in.FieldArray = scalars;
  in.FieldTime = time;
  return true;
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::PrepareParameters(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  parc::CastParameters& p = in.Parameters;
  switch (this->BlendMode)
  {
    case COMPOSITE_BLEND:
      p.Blend = parc::BlendMode::Composite;
      break;
    case MAXIMUM_INTENSITY_BLEND:
      p.Blend = parc::BlendMode::MaximumIntensity;
      break;
    case MINIMUM_INTENSITY_BLEND:
      p.Blend = parc::BlendMode::MinimumIntensity;
      break;
    case AVERAGE_INTENSITY_BLEND:
      p.Blend = parc::BlendMode::AverageIntensity;
      break;
    case ADDITIVE_BLEND:
      p.Blend = parc::BlendMode::Additive;
      break;
    case ISOSURFACE_BLEND:
      p.Blend = parc::BlendMode::IsoSurface;
      break;
    default:
      vtkErrorMacro("Blend mode " << this->BlendMode << " is not supported; nothing is drawn.");
      return false;
  }
  if (this->Cropping)
  {
    vtkWarningMacro("Cropping is not supported and is ignored.");
  }
  vtkVolumeProperty* property = vol->GetProperty();
  p.Interp = property->GetInterpolationType() == VTK_NEAREST_INTERPOLATION
    ? parc::Interpolation::Nearest
    : parc::Interpolation::Linear;
  ConvertPiecewise(property->GetScalarOpacity(0), p.Opacity);
  ConvertColor(property, in.Field.GetRange(), p.Color);
  p.UseGradientOpacity = property->HasGradientOpacity(0) && !property->GetDisableGradientOpacity(0);
  if (p.UseGradientOpacity)
  {
    ConvertPiecewise(property->GetGradientOpacity(0), p.GradientOpacity);
  }
  p.OpacityUnitDistance = property->GetScalarOpacityUnitDistance(0);
  p.Shade = property->GetShade(0) &&
    (p.Blend == parc::BlendMode::Composite || p.Blend == parc::BlendMode::IsoSurface);
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
  p.AverageRange[0] = this->AverageIPScalarRange[0];
  p.AverageRange[1] = this->AverageIPScalarRange[1];
  p.TerminationOpacity = this->TerminationOpacity;

  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInput());
  const parc::Matrix4 indexToWorld = IndexToWorld(image, vol);
  if (!parc::Invert(indexToWorld, p.WorldToIndex))
  {
    vtkErrorMacro("The volume's index-to-world transform is singular (zero scale?).");
    return false;
  }
  double smallestStep = VTK_DOUBLE_MAX;
  for (int a = 0; a < 3; ++a)
  {
    const parc::Vec3 axis{ indexToWorld(0, a), indexToWorld(1, a), indexToWorld(2, a) };
    smallestStep = std::min(smallestStep, parc::Length(axis));
  }
  p.SampleDistance = this->SampleDistance > 0.0 ? this->SampleDistance : 0.5 * smallestStep;
  this->LastSampleDistance = p.SampleDistance;
  if (p.Shade)
  {
    ConvertLights(ren, p.Lights);
  }
  else
  {
    p.Lights.clear();
  }
  if (!in.Caster.Prepare(&in.Field, &p))
  {
    vtkErrorMacro("Invalid rendering parameters (sample distance " << p.SampleDistance
                                                                   << ", opacity unit distance "
                                                                   << p.OpacityUnitDistance
                                                                   << ").");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::CastImage(vtkRenderer* ren)
{
  vtkInternals& in = *this->Internals;
  int width, height, x0, y0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  parc::ViewGeometry view;
  view.Width = std::max(1, static_cast<int>(width / this->ImageSampleDistance));
  view.Height = std::max(1, static_cast<int>(height / this->ImageSampleDistance));
  if (width < 1 || height < 1)
  {
    return;
  }
  vtkCamera* camera = ren->GetActiveCamera();
  vtkMatrix4x4* worldToNDC =
    camera->GetCompositeProjectionTransformMatrix(ren->GetTiledAspectRatio(), -1, 1);
  if (!parc::Invert(ToMatrix4(worldToNDC), view.NDCToWorld))
  {
    vtkErrorMacro("The camera's projection is singular.");
    return;
  }
  view.Parallel = camera->GetParallelProjection() != 0;
  const double* eye = camera->GetPosition();
  view.Eye = { eye[0], eye[1], eye[2] };

  const std::size_t pixels = static_cast<std::size_t>(view.Width) * view.Height;
  const float* depth = nullptr;
  if (this->IntermixIntersectingGeometry && HasOtherGeometry(ren))
  {
    std::vector<float> screen(static_cast<std::size_t>(width) * height);
    ren->GetRenderWindow()->GetZbufferData(x0, y0, x0 + width - 1, y0 + height - 1, screen.data());
    in.Depth.resize(pixels);
    for (int py = 0; py < view.Height; ++py)
    {
      const int sy = std::min(height - 1, static_cast<int>((py + 0.5) * height / view.Height));
      for (int px = 0; px < view.Width; ++px)
      {
        const int sx = std::min(width - 1, static_cast<int>((px + 0.5) * width / view.Width));
        in.Depth[static_cast<std::size_t>(py) * view.Width + px] =
          screen[static_cast<std::size_t>(sy) * width + sx];
      }
    }
    depth = in.Depth.data();
  }

  in.LastMode = ACCELERATION_NONE;
  if (this->AccelerationMode == ACCELERATION_DEPTH_BUFFER ||
    this->AccelerationMode == ACCELERATION_COLOR_BUFFER)
  {
    vtkWarningMacro("Acceleration mode " << GetAccelerationModeAsString(this->AccelerationMode)
                                         << " is not available yet; casting unaccelerated.");
  }
  const parc::WholeRaySource wholeRays;
  in.Image.resize(4 * pixels);
  in.ImageSize[0] = view.Width;
  in.ImageSize[1] = view.Height;
  vtkRenderWindow* window = ren->GetRenderWindow();
  auto progress = [this, window](double fraction) {
    this->UpdateProgress(fraction);
    return !this->GetAbortExecute() && !window->CheckAbortStatus();
  };
  const double castStart = vtkTimerLog::GetUniversalTime();
  in.Caster.CastImage(view, depth, wholeRays, in.Image.data(), in.Stats, progress);
  in.CastingTime = vtkTimerLog::GetUniversalTime() - castStart;
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::DisplayImage(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  if (in.ImageSize[0] < 1 || in.ImageSize[1] < 1)
  {
    return;
  }
  in.Display.resize(in.Image.size());
  for (std::size_t i = 0; i < in.Image.size(); ++i)
  {
    const float v = std::min(std::max(in.Image[i], 0.f), 1.f);
    in.Display[i] = static_cast<unsigned char>(v * 255.f + 0.5f);
  }
  int origin[2] = { 0, 0 };
  in.DisplayHelper->RenderTexture(vol, ren, in.ImageSize, in.ImageSize, in.ImageSize, origin,
    DisplayDepth, in.Display.data());
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->DisplayHelper->ReleaseGraphicsResources(window);
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::GetLastRayCastImage(vtkImageData* image)
{
  if (!image)
  {
    return;
  }
  const vtkInternals& in = *this->Internals;
  image->Initialize();
  image->SetDimensions(in.ImageSize[0], in.ImageSize[1], 1);
  vtkNew<vtkFloatArray> rgba;
  rgba->SetName("RGBA");
  rgba->SetNumberOfComponents(4);
  rgba->SetNumberOfTuples(static_cast<vtkIdType>(in.ImageSize[0]) * in.ImageSize[1]);
  std::copy(in.Image.begin(), in.Image.end(), rgba->GetPointer(0));
  image->GetPointData()->SetScalars(rgba);
}

vtkIdType vtkPARCVolumeMapper::GetLastSampleCount()
{
  return static_cast<vtkIdType>(this->Internals->Stats.Samples);
}
vtkIdType vtkPARCVolumeMapper::GetLastContributingSampleCount()
{
  return static_cast<vtkIdType>(this->Internals->Stats.ContributingSamples);
}
vtkIdType vtkPARCVolumeMapper::GetLastRayCount()
{
  return static_cast<vtkIdType>(this->Internals->Stats.Rays);
}
vtkIdType vtkPARCVolumeMapper::GetLastGradientCount()
{
  return static_cast<vtkIdType>(this->Internals->Stats.GradientEvaluations);
}
double vtkPARCVolumeMapper::GetLastCastingTime()
{
  return this->Internals->CastingTime;
}
double vtkPARCVolumeMapper::GetLastProjectionTime()
{
  return this->Internals->ProjectionTime;
}
double vtkPARCVolumeMapper::GetLastRenderTime()
{
  return this->Internals->RenderTime;
}
int vtkPARCVolumeMapper::GetLastAccelerationMode()
{
  return this->Internals->LastMode;
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::PrintStatistics(ostream& os)
{
  const vtkInternals& in = *this->Internals;
  os << "Ray image: " << in.ImageSize[0] << " x " << in.ImageSize[1] << "\n"
     << "Acceleration: " << GetAccelerationModeAsString(in.LastMode) << "\n"
     << "Rays: " << in.Stats.Rays << "\n"
     << "Segments: " << in.Stats.Segments << "\n"
     << "Samples: " << in.Stats.Samples << "\n"
     << "Contributing samples: " << in.Stats.ContributingSamples << "\n"
     << "Gradients: " << in.Stats.GradientEvaluations << "\n"
     << "Casting time (s): " << in.CastingTime << "\n"
     << "Projection time (s): " << in.ProjectionTime << "\n"
     << "Render time (s): " << in.RenderTime << "\n";
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "AccelerationMode: " << GetAccelerationModeAsString(this->AccelerationMode)
     << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << "\n";
  os << indent << "TerminationOpacity: " << this->TerminationOpacity << "\n";
  os << indent << "IntermixIntersectingGeometry: " << this->IntermixIntersectingGeometry << "\n";
  os << indent << "LastSampleDistance: " << this->LastSampleDistance << "\n";
}
