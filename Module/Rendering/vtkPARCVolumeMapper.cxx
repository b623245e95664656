#include "vtkPARCVolumeMapperInternals.h"

#include <optional>

namespace
{
constexpr float DisplayDepth = 1e-6f; ///< window depth of the displayed image quad

/// The share of a render's allocated time a budgeted render aims at: the window's own work
/// after the renderers (swapping buffers: 0.02 s at 800^2 on llvmpipe) and the variation
/// between frames take the rest.
constexpr double BudgetShare = 0.7;

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
}

vtkStandardNewMacro(vtkPARCVolumeMapper);

//------------------------------------------------------------------------------
vtkPARCVolumeMapper::vtkPARCVolumeMapper()
  : Internals(new vtkInternals(this))
{
  this->SetNumberOfInputPorts(MaxInputPorts);
  this->Internals->DisplayHelper->PreMultipliedColorsOn();
}

//------------------------------------------------------------------------------
vtkPARCVolumeMapper::~vtkPARCVolumeMapper()
{
  this->SetMaskInput(nullptr);
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::SetOwnedExtent(vtkImageData* image, const int extent[6])
{
  parc::vtk::SetOwnedExtent(image, extent);
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::GetOwnedExtent(vtkImageData* image, int extent[6])
{
  return parc::vtk::OwnedExtent(image, extent);
}

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
    case ACCELERATION_BOTH:
      return "DepthAndColorBuffer";
    case ACCELERATION_SUPERCELL_WALK:
      return "SupercellWalk";
    default:
      return "Unknown";
  }
}

//------------------------------------------------------------------------------
const char* vtkPARCVolumeMapper::GetAmbientModelAsString(int model)
{
  switch (model)
  {
    case AMBIENT_MATERIAL:
      return "Material";
    case AMBIENT_LIGHTS:
      return "Lights";
    default:
      return "Unknown";
  }
}

//------------------------------------------------------------------------------
const char* vtkPARCVolumeMapper::GetShadingModelAsString(int model)
{
  switch (model)
  {
    case SHADING_EXACT:
      return "Exact";
    case SHADING_QUANTIZED_NORMALS:
      return "QuantizedNormals";
    default:
      return "Unknown";
  }
}

//------------------------------------------------------------------------------
const char* vtkPARCVolumeMapper::GetShadowModeAsString(int mode)
{
  switch (mode)
  {
    case SHADOWS_FROM_RENDERER:
      return "FromRenderer";
    case SHADOWS_OFF:
      return "Off";
    case SHADOWS_ON:
      return "On";
    default:
      return "Unknown";
  }
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::Render(vtkRenderer* ren, vtkVolume* vol)
{
  // The phases: the settings and the camera's frame, read once; the volumes' fields and ray
  // functions; then for the camera the ray image's view, the depth of other geometry, each
  // volume's PARC passes, one cast of all volumes and Auto's bookkeeping (RenderRayImage);
  // last the image over the viewport.
  vtkInternals& in = *this->Internals;
  if (parc::vtk::InsideDualDepthPeeling(ren))
  {
    in.EndOfRender.Request(ren, vol); // drawn after the peels, over what they drew
    return;
  }
  const double renderStart = vtkTimerLog::GetUniversalTime();
  this->SetAbortExecute(0); // like an algorithm's execution, each render starts un-aborted
  in.Stats = parc::CastStatistics();
  in.CastingTime = in.ProjectionTime = 0.0;
  in.SetUpProgress = 0.0;
  in.ImageSize[0] = in.ImageSize[1] = 0; // no image until a cast fills one
  in.Budget = vol->GetAllocatedRenderTime();
  // The renderer's last render holds this mapper's last one and what else it drew then.
  in.PreviousRendererTime = ren->GetLastRenderTimeInSeconds();
  const bool interactive = in.Budget < 1.0 / this->InteractiveUpdateRate;
  in.AdjustSampleDistances = this->AutoAdjustSampleDistances ||
    (this->InteractiveAdjustSampleDistances && interactive);
  this->LastInteractive = in.AdjustSampleDistances && interactive;
  this->TakeSettings(ren);
  in.Frame = parc::vtk::ReadCameraFrame(ren);
  if (this->UseJittering && !in.JitteringWarned)
  {
    vtkWarningMacro("UseJittering is not supported: rays sample one exact lattice; ignored.");
    in.JitteringWarned = true;
  }
  if (this->PrepareVolumes(ren, vol))
  {
    this->InvokeEvent(vtkCommand::VolumeMapperRenderStartEvent, nullptr);
    this->RenderRayImage(ren);
    this->InvokeEvent(vtkCommand::VolumeMapperRenderEndEvent, nullptr);
    this->DisplayImage(ren, vol);
  }
  in.ReturnFreedMemory();
  in.RenderTime = vtkTimerLog::GetUniversalTime() - renderStart;
  this->TimeToDraw = in.RenderTime;
  if (in.ImageSize[0] > 0)
  {
    in.PreviousTime = in.RenderTime;
    in.PreviousProjection = in.ProjectionTime;
    in.PreviousCasting = in.CastingTime;
    in.PreviousImageStep = this->LastImageSampleDistance;
    in.PreviousSampleDistance = this->LastSampleDistance;
  }
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::ReportSetUp(const char* step, double progress)
{
  vtkInternals& in = *this->Internals;
  // Several volumes repeat the steps: the render's progress never goes back.
  in.SetUpProgress = std::max(in.SetUpProgress, progress);
  if (this->ReportProgress)
  {
    this->SetProgressText(step);
    this->UpdateProgress(in.SetUpProgress);
  }
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::TakeSettings(vtkRenderer* ren)
{
  RenderSettings& settings = this->Internals->Settings;
  settings.AccelerationMode = this->AccelerationMode;
  settings.SearchSupercellSize =
    this->AccelerationMode == ACCELERATION_AUTO && this->AutoSupercellSize;
  std::copy_n(this->SupercellSize, 3, settings.SupercellSize);
  std::copy_n(this->AverageIPScalarRange, 2, settings.AverageIPScalarRange);
  settings.Interactive = this->LastInteractive;
  settings.TerminationOpacity = this->TerminationOpacity;
  settings.NumberOfThreads = this->NumberOfThreads;
  settings.Reporter = this;
  settings.SetUpStep = [this](const char* step, double progress) {
    this->ReportSetUp(step, progress);
  };
  vtkRenderWindow* window = ren->GetRenderWindow();
  settings.CastProgress = [this, window](double fraction) {
    // As VTK's ray cast mappers report it (call data: the fraction done), and as an
    // algorithm does.
    if (this->ReportProgress)
    {
      this->InvokeEvent(vtkCommand::VolumeMapperRenderProgressEvent, &fraction);
      this->SetProgressText(CastingProgressText);
      this->UpdateProgress(
        this->Internals->SetUpProgress > 0.0 ? 0.5 + 0.5 * fraction : fraction);
    }
    return !this->GetAbortExecute() && !window->CheckAbortStatus();
  };
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::SetMaskInput(vtkImageData* mask)
{
  vtkSetObjectBodyMacro(MaskInput, vtkImageData, mask);
}

//------------------------------------------------------------------------------
double vtkPARCVolumeMapper::ChooseImageSampleDistance() const
{
  const vtkInternals& in = *this->Internals;
  if (!in.AdjustSampleDistances)
  {
    return this->ImageSampleDistance;
  }
  const double lo = this->MinimumImageSampleDistance;
  const double hi = std::max(lo, this->MaximumImageSampleDistance);
  if (!(in.PreviousTime > 0.0) || !(in.Budget > 0.0) || !(in.PreviousSampleDistance > 0.0))
  {
    return lo;
  }
  // The last render's time: the PARC passes grow with the rays (1 / step^2), the cast with
  // the rays times their samples (1 / the sample distance), the rest (display, set-up, the
  // renderer's other work) stays. The step that makes that model fit a share of the
  // budget, for this render's sample distance.
  const double samples = in.PreviousSampleDistance / std::max(this->LastSampleDistance, 1e-300);
  const double scaled = in.PreviousProjection + in.PreviousCasting * samples;
  const double whole = std::max(in.PreviousTime, in.PreviousRendererTime);
  const double fixed = std::max(0.0, whole - in.PreviousProjection - in.PreviousCasting);
  const double room = BudgetShare * in.Budget - fixed;
  if (!(room > 0.0))
  {
    return hi;
  }
  const double step = in.PreviousImageStep * std::sqrt(scaled / room);
  return std::min(std::max(step, lo), hi);
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::SetRequestedRenderMode(int mode)
{
  if (mode != this->RequestedRenderMode)
  {
    this->RequestedRenderMode = mode;
    this->Modified();
  }
  if (mode != vtkSmartVolumeMapper::DefaultRenderMode &&
    mode != vtkSmartVolumeMapper::RayCastRenderMode && !this->Internals->RenderModeWarned)
  {
    vtkWarningMacro("Render mode " << mode << " requested: this mapper casts rays on the CPU "
                                    "(GL only accelerates them); it renders as RayCast.");
    this->Internals->RenderModeWarned = true;
  }
}

//------------------------------------------------------------------------------
int vtkPARCVolumeMapper::GetLastUsedRenderMode()
{
  return this->Internals->ImageSize[0] > 0 ? vtkSmartVolumeMapper::RayCastRenderMode
                                           : vtkSmartVolumeMapper::InvalidRenderMode;
}

//------------------------------------------------------------------------------
int vtkPARCVolumeMapper::IsRenderSupported(vtkRenderWindow*, vtkVolumeProperty*)
{
  if (this->GetNumberOfInputConnections(0) == 0)
  {
    return 0;
  }
  this->GetInputAlgorithm(0, 0)->Update();
  vtkImageData* image = vtkImageData::SafeDownCast(this->GetInputDataObject(0, 0));
  if (!image)
  {
    return 0;
  }
  int cellFlag = 0;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(image, this->ScalarMode,
    this->ArrayAccessMode, this->ArrayId, this->ArrayName, cellFlag);
  std::string error;
  return scalars && cellFlag == 0 && parc::vtk::CheckImage(image, error) &&
      parc::vtk::IsSupportedScalarType(scalars->GetDataType())
    ? 1
    : 0;
}

//------------------------------------------------------------------------------

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::RenderRayImage(vtkRenderer* ren)
{
  vtkInternals& in = *this->Internals;
  this->LastImageSampleDistance = this->ChooseImageSampleDistance();
  parc::vtk::PassView view;
  if (!in.MakeView(ren, this->LastImageSampleDistance, view))
  {
    return;
  }
  const float* depth = this->IntermixIntersectingGeometry && HasOtherGeometry(ren)
    ? in.ReadGeometryDepth(ren, view.Camera)
    : nullptr;
  const std::vector<vtkInternals::SetUpWork> before = in.CountSetUpWork();
  const std::vector<parc::SceneCaster::Member> members = in.RunPasses(ren, view);
  in.SetUpShadows(ren);
  const bool completed = in.Cast(view.Camera, depth, members);
  this->LastNumberOfThreads = in.CastThreads;
  in.RecordAuto(before, completed, in.Settings.SearchSupercellSize && !in.Settings.Interactive);
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::vtkInternals::MakeView(
  vtkRenderer* ren, double step, parc::vtk::PassView& view)
{
  int width, height;
  ren->GetTiledSize(&width, &height);
  if (width < 1 || height < 1)
  {
    return false;
  }
  if (!parc::vtk::MakePassView(ren, this->Frame, std::max(1, static_cast<int>(width / step)),
        std::max(1, static_cast<int>(height / step)), view))
  {
    vtkErrorWithObjectMacro(this->Settings.Reporter, "The camera's projection is singular.");
    return false;
  }
  return true;
}

//------------------------------------------------------------------------------
const float* vtkPARCVolumeMapper::vtkInternals::ReadGeometryDepth(
  vtkRenderer* ren, const parc::Camera& rays)
{
  int width, height, x0, y0;
  ren->GetTiledSizeAndOrigin(&width, &height, &x0, &y0);
  std::vector<float> screen(static_cast<std::size_t>(width) * height);
  ren->GetRenderWindow()->GetZbufferData(x0, y0, x0 + width - 1, y0 + height - 1, screen.data());
  this->Depth.resize(static_cast<std::size_t>(rays.Width) * rays.Height);
  for (int py = 0; py < rays.Height; ++py)
  {
    const int sy = std::min(height - 1, static_cast<int>((py + 0.5) * height / rays.Height));
    for (int px = 0; px < rays.Width; ++px)
    {
      const int sx = std::min(width - 1, static_cast<int>((px + 0.5) * width / rays.Width));
      this->Depth[static_cast<std::size_t>(py) * rays.Width + px] =
        screen[static_cast<std::size_t>(sy) * width + sx];
    }
  }
  return this->Depth.data();
}

//------------------------------------------------------------------------------
std::vector<vtkPARCVolumeMapper::vtkInternals::SetUpWork>
vtkPARCVolumeMapper::vtkInternals::CountSetUpWork() const
{
  std::vector<SetUpWork> work;
  for (const auto& entry : this->Rendered)
  {
    const vtkVolumeState& volume = *entry.first;
    work.push_back(
      { volume.Plan.GetModelBuilds(), volume.Passes.GetUploadCount(), volume.SetUpTime() });
  }
  return work;
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::vtkInternals::Cast(const parc::Camera& rays, const float* depth,
  const std::vector<parc::SceneCaster::Member>& members)
{
  this->Image.resize(4 * static_cast<std::size_t>(rays.Width) * rays.Height);
  this->ImageSize[0] = rays.Width;
  this->ImageSize[1] = rays.Height;
  const double start = vtkTimerLog::GetUniversalTime();
  bool completed = false;
  auto cast = [&]() {
    this->CastThreads = vtkSMPTools::GetEstimatedNumberOfThreads();
    if (members.size() == 1)
    {
      vtkVolumeState& volume = *this->Rendered[0].first;
      completed = volume.Caster.CastImage(
        rays, depth, *members[0].Source, this->Image.data(), volume.Stats,
        this->Settings.CastProgress);
      return;
    }
    if (!this->Scene.SetMembers(members, this->Settings.TerminationOpacity))
    {
      vtkErrorWithObjectMacro(this->Settings.Reporter,
        "" << members.size() << " volumes in one scene; at most " << parc::MaxSceneVolumes
           << " render together.");
      std::fill(this->Image.begin(), this->Image.end(), 0.f);
      return;
    }
    completed = this->Scene.CastImage(
      rays, depth, this->Image.data(), this->MemberStats, this->Settings.CastProgress);
    for (std::size_t v = 0; v < members.size(); ++v)
    {
      this->Rendered[v].first->Stats = this->MemberStats[v];
    }
  };
  if (this->Settings.NumberOfThreads > 0)
  {
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ this->Settings.NumberOfThreads }, cast);
  }
  else
  {
    cast();
  }
  this->CastingTime = vtkTimerLog::GetUniversalTime() - start;
  for (const auto& entry : this->Rendered)
  {
    this->Stats += entry.first->Stats;
  }
  return completed;
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::vtkInternals::ReturnFreedMemory()
{
  std::uint64_t work = 0;
  for (const auto& volume : this->Volumes)
  {
    if (volume)
    {
      const parc::AccelerationPlan& plan = volume->Plan;
      work += plan.GetPyramidBuilds() + plan.GetClassifications() + plan.GetModelBuilds() +
        plan.GetCellClassifications() + volume->Passes.GetUploadCount() +
        volume->Passes.GetReleaseCount() + volume->Scalars.Version;
    }
  }
  if (work != this->SetUpWorkReturned)
  {
    this->SetUpWorkReturned = work;
#if defined(__GLIBC__)
    malloc_trim(0);
#endif
  }
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::SetSupercellSize(double x, double y, double z)
{
  const double size[3] = { x, y, z };
  this->SetSupercellSize(size);
}

void vtkPARCVolumeMapper::SetSupercellSize(const double size[3])
{
  if (!std::equal(size, size + 3, this->SupercellSize) || this->AutoSupercellSize)
  {
    std::copy_n(size, 3, this->SupercellSize);
    this->AutoSupercellSize = 0;
    this->Modified();
  }
}

double* vtkPARCVolumeMapper::GetLastSupercellSize()
{
  const auto& volumes = this->Internals->Volumes;
  const bool classified =
    !volumes.empty() && volumes[0] && volumes[0]->Plan.GetGrid().GetNumberOfSupercells() > 0;
  std::copy_n(classified ? volumes[0]->Plan.GetGrid().GetSize() : this->SupercellSize, 3,
    this->LastSupercellSize);
  return this->LastSupercellSize;
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::DisplayImage(vtkRenderer* ren, vtkVolume* vol)
{
  vtkInternals& in = *this->Internals;
  if (in.ImageSize[0] < 1 || in.ImageSize[1] < 1)
  {
    return;
  }
  const vtkIdType values = 4 * static_cast<vtkIdType>(in.ImageSize[0]) * in.ImageSize[1];
  in.Display.resize(static_cast<std::size_t>(values));
  const float* image = in.Image.data();
  unsigned char* display = in.Display.data();
  const parc::vtk::FinalColor finalColor(this->FinalColorWindow, this->FinalColorLevel);
  if (!finalColor.IsUsable() && !in.WindowWarned)
  {
    vtkWarningMacro("FinalColorWindow 0 is not usable: the final colours are not adjusted.");
    in.WindowWarned = true;
  }
  vtkSMPTools::For(0, values / 4, [=](vtkIdType begin, vtkIdType end) {
    for (vtkIdType p = begin; p < end; ++p)
    {
      finalColor.ToBytes(image + 4 * p, display + 4 * p);
    }
  });
  int origin[2] = { 0, 0 };
  // Measured when the texture is (re)allocated: a warm frame's transient memory is not the
  // display's.
  std::optional<parc::vtk::DriverMemory::Scope> measured;
  if (in.ImageSize[0] != in.DisplayedSize[0] || in.ImageSize[1] != in.DisplayedSize[1])
  {
    measured.emplace(in.DisplayDriver);
    in.DisplayedSize[0] = in.ImageSize[0];
    in.DisplayedSize[1] = in.ImageSize[1];
  }
  in.DisplayHelper->RenderTexture(vol, ren, in.ImageSize, in.ImageSize, in.ImageSize, origin,
    DisplayDepth, in.Display.data());
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->DisplayHelper->ReleaseGraphicsResources(window);
  this->Internals->DisplayDriver = parc::vtk::DriverMemory();
  this->Internals->DisplayedSize[0] = this->Internals->DisplayedSize[1] = 0;
  for (const auto& volume : this->Internals->Volumes)
  {
    if (volume)
    {
      volume->Passes.ReleaseGraphicsResources(window);
      volume->Plan.ReleaseLightPasses(); // drawn in the window's context: remade when needed
    }
  }
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::SetInputBlendMode(int port, int blendMode)
{
  if (port < 0 || port >= MaxInputPorts)
  {
    vtkErrorMacro("Port " << port << " is not in [0, " << MaxInputPorts << ").");
    return;
  }
  if (port == 0)
  {
    this->SetBlendMode(blendMode);
    return;
  }
  if (this->InputBlendModes[port] != blendMode)
  {
    this->InputBlendModes[port] = blendMode;
    this->Modified();
  }
}

int vtkPARCVolumeMapper::GetInputBlendMode(int port)
{
  if (port < 0 || port >= MaxInputPorts)
  {
    vtkErrorMacro("Port " << port << " is not in [0, " << MaxInputPorts << ").");
    return COMPOSITE_BLEND;
  }
  return port == 0 ? this->BlendMode : this->InputBlendModes[port];
}

//------------------------------------------------------------------------------
int vtkPARCVolumeMapper::FillInputPortInformation(int port, vtkInformation* info)
{
  if (!this->Superclass::FillInputPortInformation(port, info))
  {
    return 0;
  }
  // Any data set passes the pipeline, so that a vtkRectilinearGrid or an unstructured grid
  // gets the mapper's error, which names a way out (PrepareField), not the pipeline's.
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  if (port > 0)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "AccelerationMode: " << GetAccelerationModeAsString(this->AccelerationMode)
     << "\n";
  os << indent << "ShadingModel: " << GetShadingModelAsString(this->ShadingModel) << "\n";
  os << indent << "AmbientModel: " << GetAmbientModelAsString(this->AmbientModel) << "\n";
  os << indent << "ShadowMode: " << GetShadowModeAsString(this->ShadowMode) << "\n";
  os << indent << "ColorRangeType: " << (this->ColorRangeType == NATIVE ? "NATIVE" : "SCALAR")
     << "\n";
  os << indent << "SupercellSize: " << this->SupercellSize[0] << ", " << this->SupercellSize[1]
     << ", " << this->SupercellSize[2] << "\n";
  os << indent << "AutoSupercellSize: " << this->AutoSupercellSize << "\n";
  os << indent << "SampleDistance: " << this->SampleDistance << "\n";
  os << indent << "ImageSampleDistance: " << this->ImageSampleDistance << "\n";
  os << indent << "TerminationOpacity: " << this->TerminationOpacity << "\n";
  os << indent << "BrickedCopy: " << this->BrickedCopy << "\n";
  os << indent << "IntermixIntersectingGeometry: " << this->IntermixIntersectingGeometry << "\n";
  os << indent << "LastSampleDistance: " << this->LastSampleDistance << "\n";
  os << indent << "AutoAdjustSampleDistances: " << this->AutoAdjustSampleDistances << "\n";
  os << indent << "InteractiveAdjustSampleDistances: " << this->InteractiveAdjustSampleDistances
     << "\n";
  os << indent << "MinimumImageSampleDistance: " << this->MinimumImageSampleDistance << "\n";
  os << indent << "MaximumImageSampleDistance: " << this->MaximumImageSampleDistance << "\n";
  os << indent << "InteractiveSampleDistance: " << this->InteractiveSampleDistance << "\n";
  os << indent << "InteractiveUpdateRate: " << this->InteractiveUpdateRate << "\n";
  os << indent << "LastImageSampleDistance: " << this->LastImageSampleDistance << "\n";
  os << indent << "LastInteractive: " << this->LastInteractive << "\n";
  os << indent << "LockSampleDistanceToInputSpacing: " << this->LockSampleDistanceToInputSpacing
     << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "LastNumberOfThreads: " << this->LastNumberOfThreads << "\n";
  os << indent << "UseJittering: " << this->UseJittering << "\n";
  os << indent << "UseDepthPass: " << this->UseDepthPass << "\n";
  os << indent << "MaskInput: " << this->MaskInput << "\n";
  os << indent << "MaskType: " << this->MaskType << "\n";
  os << indent << "MaskBlendFactor: " << this->MaskBlendFactor << "\n";
  os << indent << "ReportProgress: " << this->ReportProgress << "\n";
  os << indent << "MaxMemoryInBytes: " << this->MaxMemoryInBytes << "\n";
  os << indent << "MaxMemoryFraction: " << this->MaxMemoryFraction << "\n";
  os << indent << "InterpolationMode: " << this->InterpolationMode << "\n";
  os << indent << "FinalColorWindow: " << this->FinalColorWindow << "\n";
  os << indent << "FinalColorLevel: " << this->FinalColorLevel << "\n";
  os << indent << "RequestedRenderMode: " << this->RequestedRenderMode << "\n";
}
