// vtkPARCVolumeMapper: the preparation phase of a render: each input volume's field,
// mask, ray-function parameters (transfer functions, lights, clipping, cropping, the
// placement) and components.
#include "vtkPARCVolumeMapperInternals.h"

namespace
{
/// A sample distance must leave at most this many samples along the volume's diagonal.
constexpr double MaxSamplesPerDiagonal = 1e7;

/// The renderer's lights that are on, in the render frame (origin at frame). A light casts
/// shadows (its ShadowAttenuation) only when shadows is true. ambient is their ambient
/// light: the sum of their ambient colours times their intensities (black for vtkLight's
/// defaults), as vtkFixedPointVolumeRayCastMapper lights the ambient term.
void ConvertLights(vtkRenderer* ren, const parc::Vec3& frame, bool shadows,
  std::vector<parc::Light>& lights, parc::Vec3& ambient)
{
  lights.clear();
  ambient = parc::Vec3{ 0.0, 0.0, 0.0 };
  vtkLightCollection* collection = ren->GetLights();
  vtkCollectionSimpleIterator it;
  collection->InitTraversal(it);
  while (vtkLight* light = collection->GetNextLight(it))
  {
    if (!light->GetSwitch())
    {
      continue;
    }
    const double i = light->GetIntensity();
    const double* ambientColor = light->GetAmbientColor();
    ambient =
      ambient + parc::Vec3{ ambientColor[0] * i, ambientColor[1] * i, ambientColor[2] * i };
    if (i <= 0.0)
    {
      continue;
    }
    parc::Light l;
    l.Positional = light->GetPositional() != 0;
    double p[3], f[3];
    light->GetTransformedPosition(p);
    light->GetTransformedFocalPoint(f);
    l.Position = parc::Vec3{ p[0], p[1], p[2] } - frame;
    l.FocalPoint = parc::Vec3{ f[0], f[1], f[2] } - frame;
    const double* c = light->GetDiffuseColor();
    l.Color = { c[0] * i, c[1] * i, c[2] * i };
    const double* s = light->GetSpecularColor();
    l.SpecularColor = { s[0] * i, s[1] * i, s[2] * i };
    const double* a = light->GetAttenuationValues();
    l.Attenuation = { a[0], a[1], a[2] };
    l.ConeAngle = light->GetConeAngle();
    l.Exponent = light->GetExponent();
    l.ShadowAttenuation =
      shadows ? std::min(std::max(static_cast<double>(light->GetShadowAttenuation()), 0.0), 1.0)
              : 0.0;
    lights.push_back(l);
  }
}

/// The matrix from 0-based voxel indices of the image to the render frame (origin at frame).
/// A field of cell scalars has its voxels at the cells' centres: index i lies at the
/// image's index i + cellOffset (0.5; 0 for point scalars).
parc::Matrix4 IndexToFrame(
  vtkImageData* image, vtkVolume* vol, const parc::Vec3& frame, double cellOffset)
{
  parc::Matrix4 shift;
  shift(0, 3) = shift(1, 3) = shift(2, 3) = cellOffset;
  return parc::Translated(parc::Multiply(parc::vtk::ToMatrix4(vol->GetMatrix()),
                            parc::Multiply(parc::vtk::IndexToPhysical(image), shift)),
    -frame);
}

/// The planes of a vtkPlaneCollection, in the render frame (origin at frame).
void ConvertClippingPlanes(
  vtkPlaneCollection* planes, const parc::Vec3& frame, std::vector<parc::ClipPlane>& out)
{
  out.clear();
  if (!planes)
  {
    return;
  }
  vtkCollectionSimpleIterator it;
  planes->InitTraversal(it);
  while (vtkPlane* plane = planes->GetNextPlane(it))
  {
    const double* o = plane->GetOrigin();
    const double* n = plane->GetNormal();
    out.push_back({ parc::Vec3{ o[0], o[1], o[2] } - frame, { n[0], n[1], n[2] } });
  }
}

/// vtkVolumeMapper's cropping planes (the image's physical coordinates along its axes) in
/// voxel-index coordinates of the field (index 0 at the extent's start).
void ConvertCropping(vtkImageData* image, double cellOffset, const double planes[6], int flags,
  parc::Cropping& out)
{
  const double* origin = image->GetOrigin();
  const double* spacing = image->GetSpacing();
  const int* extent = image->GetExtent();
  for (int a = 0; a < 3; ++a)
  {
    double lo = (planes[2 * a] - origin[a]) / spacing[a] - extent[2 * a] - cellOffset;
    double hi = (planes[2 * a + 1] - origin[a]) / spacing[a] - extent[2 * a] - cellOffset;
    if (lo > hi) // negative spacing
    {
      std::swap(lo, hi);
    }
    out.Planes[2 * a] = lo;
    out.Planes[2 * a + 1] = hi;
  }
  out.RegionFlags = flags;
}

/// The world length of the diagonal of the volume's box (voxel-index box of dims).
double VolumeDiagonal(const parc::Matrix4& indexToWorld, const int dims[3])
{
  return parc::Length(indexToWorld.TransformVector(
    { dims[0] - 1.0, dims[1] - 1.0, dims[2] - 1.0 }));
}

/// The world length of a voxel's edge along index axis a.
double VoxelEdge(const parc::Matrix4& indexToWorld, int a)
{
  return parc::Length(parc::Vec3{ indexToWorld(0, a), indexToWorld(1, a), indexToWorld(2, a) });
}

/// The sample distance LockSampleDistanceToInputSpacing asks for: the average voxel edge
/// (world units) times min(1/2, cbrt(voxels) / 200).
double SpacingLockedSampleDistance(const parc::Matrix4& indexToWorld, std::size_t voxels)
{
  const double edge =
    (VoxelEdge(indexToWorld, 0) + VoxelEdge(indexToWorld, 1) + VoxelEdge(indexToWorld, 2)) / 3.0;
  return edge * std::min(0.5, std::cbrt(static_cast<double>(voxels)) / 200.0);
}

/// The input ports to render with the vtkVolume that gives each its property and transform:
/// port 0 with vol itself, or for a multi-volume every connected port that holds a volume.
std::vector<std::pair<int, vtkVolume*>> CollectInputs(vtkPARCVolumeMapper* mapper, vtkVolume* vol)
{
  std::vector<std::pair<int, vtkVolume*>> inputs;
  auto* multi = vtkMultiVolume::SafeDownCast(vol);
  if (!multi)
  {
    inputs.emplace_back(0, vol);
    return inputs;
  }
  auto* parcMulti = vtkPARCMultiVolume::SafeDownCast(vol);
  for (int port = 0; port < vtkPARCVolumeMapper::MaxInputPorts; ++port)
  {
    if (mapper->GetNumberOfInputConnections(port) < 1)
    {
      continue;
    }
    vtkVolume* volume = parcMulti ? parcMulti->FindVolumeOfPort(port) : multi->GetVolume(port);
    if (volume)
    {
      inputs.emplace_back(port, volume);
    }
  }
  return inputs;
}

}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::PrepareMask(
  vtkVolumeState& state, vtkVolumeProperty* property, std::string& fixes)
{
  parc::CastParameters& p = state.Parameters;
  const bool labelMap = this->MaskType == LabelMapMaskType;
  if (labelMap && this->MaskBlendFactor == 0.f)
  {
    return true; // the default functions everywhere, as VTK's GPU mapper draws it
  }
  if (labelMap && (!parc::TraitsOf(p.Blend).AppliesLabels || !state.Components.empty()))
  {
    vtkErrorMacro("A label-map mask applies to composite blending of one component; "
                  "nothing is drawn.");
    return false;
  }
  if (!labelMap && !parc::TraitsOf(p.Blend).AppliesMask)
  {
    vtkErrorMacro("A binary mask applies to composite, isosurface and additive blending; "
                  "nothing is drawn.");
    return false;
  }
  vtkDataArray* values = this->MaskInput->GetPointData()->GetScalars();
  const int* fieldDims = state.Field.GetDimensions();
  int dims[3];
  this->MaskInput->GetDimensions(dims);
  if (!values || !std::equal(dims, dims + 3, fieldDims))
  {
    vtkErrorMacro("The mask needs point scalars and the volume's dimensions ("
                  << fieldDims[0] << " x " << fieldDims[1] << " x " << fieldDims[2]
                  << "); nothing is drawn.");
    return false;
  }
  const vtkMTimeType time = std::max(this->MaskInput->GetMTime(), values->GetMTime());
  if (!state.MaskScalars.Matches(values, time))
  {
    std::size_t replaced = 0;
    std::string error;
    if (!parc::vtk::WrapScalars(values, dims, state.Mask, replaced, error))
    {
      vtkErrorMacro("The mask: " << error << " Nothing is drawn.");
      state.MaskScalars.Clear();
      return false;
    }
    state.MaskScalars.Wrapped(values, time);
  }
  p.Mask = &state.Mask;
  if (labelMap)
  {
    const std::string own = parc::vtk::ConvertLabels(
      property, state.Field.GetRange(), p, p.Labels, state.GradientUnit);
    parc::vtk::AppendSentence(fixes, own);
    p.MaskBlendFactor = this->MaskBlendFactor;
    if (p.Labels.empty())
    {
      p.Mask = nullptr; // no label has functions: the default ones everywhere
    }
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::PrepareVolumes(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  in.Rendered.clear();
  for (const auto& input : CollectInputs(this, vol))
  {
    vtkVolumeState& volume = in.At(input.first);
    volume.Stats = parc::CastStatistics();
    volume.ProjectionTime = 0.0;
    volume.Drawn = {};
    volume.Last = vtkVolumeState::FramePasses();
    if (!this->PrepareField(volume, input.second) ||
      !this->PrepareParameters(volume, ren, input.second))
    {
      in.Rendered.clear();
      return false;
    }
    this->PrepareBricks(volume);
    in.Rendered.emplace_back(&volume, input.second);
  }
  if (in.Rendered.empty())
  {
    vtkErrorMacro("The multi-volume holds no vtkVolume for a connected input port; nothing "
                  "is drawn.");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
namespace
{
/// A copy in bricks larger than this many times the values (a volume thinner than a brick
/// along some axis) is not made: it would gain nothing for its memory.
constexpr std::size_t MaxBrickedCopyRatio = 2;
}

void vtkPARCVolumeMapper::PrepareBricks(vtkVolumeState& state)
{
  std::vector<parc::ScalarField*> fields{ &state.Field };
  for (const auto& component : state.Components)
  {
    fields.push_back(&component->Field);
  }
  for (parc::ScalarField* field : fields)
  {
    if (!this->BrickedCopy || field->IsBricked())
    {
      field->SetBricked(this->BrickedCopy);
      continue;
    }
    if (state.BricksDeclined == state.Scalars.Version)
    {
      continue; // warned once for these scalars
    }
    const std::size_t values = parc::BrickGrid(field->GetDimensions()).NumberOfValues();
    if (values > MaxBrickedCopyRatio * field->GetNumberOfValues())
    {
      vtkWarningMacro("BrickedCopy: the scalars are too thin for bricks of "
        << parc::BrickGrid::Cells << "^3 cells (a copy would hold " << values << " values for "
        << field->GetNumberOfValues() << "); the rays sample the input's scalars.");
      state.BricksDeclined = state.Scalars.Version;
      continue;
    }
    this->ReportSetUp("copying the scalars into bricks", SetUpProgress::Bricks);
    if (!field->SetBricked(true))
    {
      vtkWarningMacro("BrickedCopy: no memory for a copy of the scalars in bricks ("
        << values << " values); the rays sample the input's scalars.");
      state.BricksDeclined = state.Scalars.Version;
    }
  }
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::PrepareField(vtkVolumeState& state, vtkVolume* prop)
{
  const int port = state.Port;
  vtkAlgorithm* producer =
    this->GetNumberOfInputConnections(port) > 0 ? this->GetInputAlgorithm(port, 0) : nullptr;
  if (!producer)
  {
    vtkErrorMacro("No input on port " << port << ": connect a vtkImageData to the mapper.");
    return false;
  }
  producer->Update();
  vtkDataObject* input = this->GetInputDataObject(port, 0);
  vtkImageData* image = vtkImageData::SafeDownCast(input);
  if (!image)
  {
    vtkErrorMacro("The input on port " << port << " is a "
                                        << (input ? input->GetClassName() : "null object")
                                        << ", not a vtkImageData: resample it onto an image "
                                           "first (vtkResampleToImage), then render that.");
    return false;
  }
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(image, this->ScalarMode,
    this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
  std::string error;
  if (!scalars)
  {
    vtkErrorMacro(<< (parc::vtk::CheckImage(image, error) ? "The input has no scalars to render."
                                                          : error + " Nothing is drawn."));
    return false;
  }
  // Cell scalars are a field of one voxel per cell, at the cells' centres (as VTK's GPU
  // mapper renders them): an image of one sample fewer along each axis.
  int dims[3];
  image->GetDimensions(dims);
  if (cellFlag)
  {
    for (int a = 0; a < 3; ++a)
    {
      dims[a] = std::max(dims[a] - 1, 1);
    }
  }
  if (!parc::vtk::CheckGrid(dims, image->GetSpacing(), error))
  {
    vtkErrorMacro(<< (cellFlag ? "The image's cells: " : "") << error << " Nothing is drawn.");
    return false;
  }
  state.CellOffset = cellFlag ? 0.5 : 0.0;
  state.GradientUnit = parc::vtk::GradientUnit(image);
  // Dependent components (vtkVolumeProperty::IndependentComponentsOff): opacity and
  // gradient from the last component, colour from the others.
  const int components = scalars->GetNumberOfComponents();
  vtkVolumeProperty* property = prop ? prop->GetProperty() : nullptr;
  const bool dependent = components > 1 && property && !property->GetIndependentComponents();
  if (dependent &&
    !(components == 2 || (components == 4 && scalars->GetDataType() == VTK_UNSIGNED_CHAR)))
  {
    vtkErrorMacro("Dependent components (IndependentComponentsOff) need 2 components (colour "
                  "and opacity) or 4 unsigned char ones (RGBA); these scalars have "
                  << components << " of type " << scalars->GetDataTypeAsString()
                  << ". Nothing is drawn.");
    return false;
  }
  if (components > static_cast<int>(parc::MaxComponents))
  {
    vtkErrorMacro("The scalars have " << components << " components; at most "
                                      << parc::MaxComponents
                                      << " are rendered, as by VTK's mappers. Nothing is drawn.");
    return false;
  }
  const int component = dependent ? components - 1 : 0;
  const vtkMTimeType time = std::max(image->GetMTime(), scalars->GetMTime());
  if (state.Scalars.Matches(scalars, time, component))
  {
    return true;
  }
  this->ReportSetUp("reading the scalars", SetUpProgress::Scalars);
  std::size_t replaced = 0;
  state.Scalars.Clear();
  state.Components.clear();
  if (!parc::vtk::WrapScalars(scalars, dims, state.Field, replaced, error, component))
  {
    vtkErrorMacro(<< error << " Nothing is drawn.");
    return false;
  }
  bool copied = state.Field.GetMemorySize() > 0;
  for (int c = 1; !dependent && c < components; ++c)
  {
    state.Components.push_back(std::make_unique<vtkVolumeState::ComponentState>());
    std::size_t others = 0;
    if (!parc::vtk::WrapScalars(scalars, dims, state.Components.back()->Field, others, error, c))
    {
      vtkErrorMacro(<< error << " Nothing is drawn.");
      state.Components.clear();
      return false;
    }
    copied = copied || others > 0;
  }
  if (components > 1 && copied)
  {
    vtkErrorMacro("Several components with non-finite values are not supported (a replaced "
                  "copy holds one component); nothing is drawn.");
    state.Components.clear();
    return false;
  }
  if (replaced > 0)
  {
    vtkWarningMacro(<< replaced
                    << " non-finite scalars were replaced: NaN and -inf by the smallest, +inf "
                       "by the largest finite value.");
  }
  parc::vtk::OwnedCellBox(image, state.CellOffset, state.OwnedLo, state.OwnedHi);
  state.Scalars.Wrapped(scalars, time, component);
  state.DependentComponents = dependent ? components : 0;
  int cells[3]; // another volume: another best size
  for (int a = 0; a < 3; ++a)
  {
    cells[a] = state.Field.GetDimensions()[a] - 1;
  }
  state.Plan.Sizes.Begin(cells, this->SupercellSize);
  return true;
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::ColorTableRange(
  vtkVolumeProperty* property, int component, double range[2]) const
{
  if (this->ColorRangeType != NATIVE)
  {
    return;
  }
  double native[2] = { 0.0, 0.0 };
  if (property->GetColorChannels(component) == 1)
  {
    property->GetGrayTransferFunction(component)->GetRange(native);
  }
  else
  {
    property->GetRGBTransferFunction(component)->GetRange(native);
  }
  if (native[0] < native[1] && std::isfinite(native[0]) && std::isfinite(native[1]))
  {
    std::copy_n(native, 2, range);
  }
}

namespace
{
/// The slice plane of property (a vtkPlane, in world coordinates) into p, relative to
/// frame as the core's world; false when there is none or it is degenerate.
bool ConvertSlicePlane(
  vtkVolumeProperty* property, const parc::Vec3& frame, parc::CastParameters& p)
{
  auto* plane = vtkPlane::SafeDownCast(property->GetSliceFunction());
  if (!plane)
  {
    return false;
  }
  const double* o = plane->GetOrigin();
  const double* n = plane->GetNormal();
  p.SliceOrigin = parc::Vec3(o[0], o[1], o[2]) - frame;
  p.SliceNormal = parc::Vec3(n[0], n[1], n[2]);
  return parc::HasUsableSlicePlane(p);
}
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::PrepareParameters(
  vtkVolumeState& state, vtkRenderer* ren, vtkVolume* vol)
{
  parc::CastParameters& p = state.Parameters;
  const int blend = this->GetInputBlendMode(state.Port);
  state.InputBlend = blend;
  if (!parc::vtk::ConvertBlendMode(blend, p.Blend))
  {
    vtkErrorMacro("Blend mode " << blend << " is not supported; nothing is drawn.");
    return false;
  }
  vtkVolumeProperty* property = vol->GetProperty();
  if (!property)
  {
    vtkErrorMacro("The volume of port " << state.Port << " has no property; nothing is drawn.");
    return false;
  }
  // With 2 dependent components the colour function maps the first one's range.
  double colorRange[2];
  std::copy_n(state.Field.GetRange(), 2, colorRange);
  if (state.DependentComponents == 2)
  {
    state.Scalars.Array->GetRange(colorRange, 0);
  }
  this->ColorTableRange(property, 0, colorRange);
  if (!state.Components.empty() && !parc::TraitsOf(p.Blend).CombinesComponents)
  {
    vtkErrorMacro("Independent components are rendered with composite, maximum or minimum "
                  "intensity blending, not blend mode "
                  << blend << "; nothing is drawn.");
    return false;
  }
  std::string fixes = parc::vtk::ConvertProperty(property, colorRange, p, 0, state.GradientUnit);
  p.ComponentWeight = state.Components.empty() ? 1.0 : property->GetComponentWeight(0);
  constexpr float UnsignedCharToUnit = 1.f / 255.f;
  p.ColorShiftCount = state.DependentComponents == 0 ? 0 : state.DependentComponents - 1;
  for (int c = 0; c < p.ColorShiftCount; ++c)
  {
    p.ColorShifts[c] = c - p.ColorShiftCount; // the components before the opacity's
  }
  p.DirectColorScale = UnsignedCharToUnit;
  if (property->GetTransferFunctionMode() == vtkVolumeProperty::TF_2D)
  {
    parc::vtk::AppendSentence(fixes,
      "2-D transfer functions are not supported: the 1-D colour and scalar opacity "
      "functions of the property are used.");
  }
  const auto notFinite = [](double v) { return !std::isfinite(v); };
  if (p.Blend == parc::BlendMode::IsoSurface &&
    (p.IsoValues.empty() || std::any_of(p.IsoValues.begin(), p.IsoValues.end(), notFinite)))
  {
    vtkErrorMacro("The isosurface blend mode needs at least one iso value, all finite "
                  "(vtkVolumeProperty::GetIsoSurfaceValues); nothing is drawn.");
    return false;
  }
  if (!(this->ImageSampleDistance >= 1.0 && this->ImageSampleDistance <= 64.0))
  {
    vtkErrorMacro("ImageSampleDistance " << this->ImageSampleDistance
                                         << " is not in [1, 64]; nothing is drawn.");
    return false;
  }
  p.AverageRange[0] = this->AverageIPScalarRange[0];
  p.AverageRange[1] = this->AverageIPScalarRange[1];
  std::copy_n(state.Field.GetRange(), 2, p.IntensityRange);
  p.TerminationOpacity = this->TerminationOpacity;
  p.Mask = nullptr;
  p.Labels.clear();
  if (state.Port == 0 && this->MaskInput && !this->PrepareMask(state, property, fixes))
  {
    return false;
  }

  // The core sees world coordinates minus the camera position, as the passes' views do.
  const parc::Vec3 frame = this->Internals->Frame.Origin;
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInputDataObject(state.Port, 0));
  state.CoreVolume = { &state.Field, &p };
  if (!state.CoreVolume.SetIndexToWorld(IndexToFrame(image, vol, frame, state.CellOffset)))
  {
    vtkErrorMacro("The volume's index-to-world transform is singular (zero scale?).");
    return false;
  }
  const parc::Matrix4& indexToWorld = state.CoreVolume.IndexToWorld;
  const double smallestStep = std::min(
    { VoxelEdge(indexToWorld, 0), VoxelEdge(indexToWorld, 1), VoxelEdge(indexToWorld, 2) });
  p.SampleDistance = this->SampleDistance > 0.0 ? this->SampleDistance : 0.5 * smallestStep;
  if (this->LockSampleDistanceToInputSpacing)
  {
    p.SampleDistance = SpacingLockedSampleDistance(indexToWorld, state.Field.GetNumberOfValues());
  }
  if (this->LastInteractive && this->InteractiveSampleDistance > p.SampleDistance)
  {
    p.SampleDistance = this->InteractiveSampleDistance;
  }
  const double diagonal = VolumeDiagonal(indexToWorld, state.Field.GetDimensions());
  if (std::isnan(this->SampleDistance) || !std::isfinite(p.SampleDistance) ||
    p.SampleDistance * MaxSamplesPerDiagonal < diagonal)
  {
    vtkErrorMacro("SampleDistance " << this->SampleDistance
                                    << " is not usable: it must be finite, and at least 1/"
                                    << MaxSamplesPerDiagonal << " of the volume's diagonal ("
                                    << diagonal
                                    << "), or <= 0 for half the smallest spacing; nothing is "
                                       "drawn.");
    return false;
  }
  if (state.Port == 0)
  {
    this->LastSampleDistance = p.SampleDistance;
  }
  ConvertClippingPlanes(this->ClippingPlanes, frame, p.ClipPlanes);
  if (p.Blend == parc::BlendMode::Slice && !ConvertSlicePlane(property, frame, p))
  {
    vtkErrorMacro("The slice blend mode needs a vtkPlane with a finite origin and a non-zero "
                  "normal as the property's SliceFunction; nothing is drawn.");
    return false;
  }
  p.OwnedLo = state.OwnedLo;
  p.OwnedHi = state.OwnedHi;
  p.Crop.Enabled = this->Cropping != 0;
  if (p.Crop.Enabled)
  {
    ConvertCropping(image, state.CellOffset, this->CroppingRegionPlanes,
      this->CroppingRegionFlags, p.Crop);
  }
  if (p.Shade)
  {
    const bool shadows = this->ShadowMode == SHADOWS_ON ||
      (this->ShadowMode == SHADOWS_FROM_RENDERER && ren->GetUseShadows());
    parc::Vec3 lightsAmbient;
    ConvertLights(ren, frame, shadows, p.Lights, lightsAmbient);
    p.AmbientLight =
      this->AmbientModel == AMBIENT_LIGHTS ? lightsAmbient : parc::Vec3{ 1.0, 1.0, 1.0 };
  }
  else
  {
    p.Lights.clear();
  }
  // The quantized normals are of one component: several are shaded exactly.
  state.PrepareShadingModel(
    this->ShadingModel == SHADING_QUANTIZED_NORMALS && state.Components.empty(),
    this->Internals->Frame);
  if (!state.Caster.Prepare(state.CoreVolume) || !this->PrepareComponents(state, property, fixes))
  {
    vtkErrorMacro("Invalid rendering parameters (sample distance " << p.SampleDistance
                                                                   << ", opacity unit distance "
                                                                   << p.OpacityUnitDistance
                                                                   << ").");
    return false;
  }
  if (!fixes.empty() && property->GetMTime() != state.FixesWarnedTime)
  {
    vtkWarningMacro(<< fixes);
    state.FixesWarnedTime = property->GetMTime();
  }
  return true;
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::PrepareComponents(
  vtkVolumeState& state, vtkVolumeProperty* property, std::string& fixes)
{
  std::vector<parc::RayCaster::Component> others;
  for (std::size_t i = 0; i < state.Components.size(); ++i)
  {
    const int c = static_cast<int>(i) + 1;
    vtkVolumeState::ComponentState& component = *state.Components[i];
    // Component 0's settings, with the component's own transfer functions and shading.
    parc::CastParameters& q = component.Parameters;
    q = state.Parameters;
    const double* range = component.Field.GetRange();
    double colorRange[2] = { range[0], range[1] };
    this->ColorTableRange(property, c, colorRange);
    const std::string own =
      parc::vtk::ConvertProperty(property, colorRange, q, c, state.GradientUnit);
    if (!own.empty())
    {
      parc::vtk::AppendSentence(fixes, "Component " + std::to_string(c) + ": " + own);
    }
    q.ComponentWeight = property->GetComponentWeight(c);
    std::copy_n(range, 2, q.IntensityRange);
    parc::Volume volume = state.CoreVolume; // placed alike
    volume.Field = &component.Field;
    volume.Parameters = &q;
    if (!component.Caster.Prepare(volume))
    {
      return false;
    }
    others.push_back({ &component.Caster, c });
  }
  return state.Caster.SetComponents(std::move(others));
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::vtkVolumeState::PrepareShadingModel(
  bool quantized, const parc::vtk::CameraFrame& frame)
{
  parc::CastParameters& p = this->Parameters;
  p.Shading = quantized ? parc::ShadingModel::QuantizedNormals : parc::ShadingModel::Exact;
  p.Normals = nullptr;
  if (!quantized)
  {
    this->Normals.Clear(); // only the model that uses them holds them
    return;
  }
  if (!p.Shade || !parc::LightsAllowQuantizedNormals(p))
  {
    return; // shaded exactly, or not at all
  }
  if (this->Normals.IsEmpty() || this->NormalsVersion != this->Scalars.Version)
  {
    this->Normals.Build(this->Field);
    this->NormalsVersion = this->Scalars.Version;
  }
  p.Normals = &this->Normals;
  // Towards the eye (the frame's origin) from the volume's centre; along the view
  // direction for a parallel projection.
  const parc::Vec3 centre = this->CoreVolume.Centre();
  p.ShadingViewDirection = frame.Parallel || !(parc::Length(centre) > 0.0)
    ? -frame.Direction
    : parc::Normalized(-centre);
}
