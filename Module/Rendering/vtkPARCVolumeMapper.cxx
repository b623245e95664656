#include "vtkPARCVolumeMapperInternals.h"

namespace
{
constexpr float DisplayDepth = 1e-6f; ///< window depth of the displayed image quad

/// Pixels along each edge of a light's PARC buffers (shadow rays).
constexpr int LightBufferSize = 256;

/// Relative difference under which what a light's passes were made from counts as unchanged.
constexpr double LightKeyTolerance = 1e-9;

/// The share of a render's allocated time a budgeted render aims at: the window's own work
/// after the renderers (swapping buffers: 0.02 s at 800^2 on llvmpipe) and the variation
/// between frames take the rest.
constexpr double BudgetShare = 0.7;

/// The volume axis whose direction (indexToWorld's column) is closest to direction, the
/// view's (or a light's towards the volume): its planes are crossed in order by every ray.
int MajorAxis(const parc::Matrix4& indexToWorld, const parc::Vec3& direction)
{
  int best = 2;
  double bestCosine = -1.0;
  for (int a = 0; a < 3; ++a)
  {
    const parc::Vec3 axis =
      parc::Normalized({ indexToWorld(0, a), indexToWorld(1, a), indexToWorld(2, a) });
    const double c = std::fabs(parc::Dot(axis, direction));
    if (c > bestCosine)
    {
      bestCosine = c;
      best = a;
    }
  }
  return best;
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
  // The phases: the volumes' fields and ray functions; then for the camera the ray image's
  // view, the depth of other geometry, each volume's PARC passes, one cast of all volumes
  // and Auto's bookkeeping (CastImage); last the image over the viewport.
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
  in.ImageSize[0] = in.ImageSize[1] = 0; // no image until a cast fills one
  in.Budget = vol->GetAllocatedRenderTime();
  // The renderer's last render holds this mapper's last one and what else it drew then.
  in.PreviousRendererTime = ren->GetLastRenderTimeInSeconds();
  const bool interactive = in.Budget < 1.0 / this->InteractiveUpdateRate;
  in.AdjustSampleDistances = this->AutoAdjustSampleDistances ||
    (this->InteractiveAdjustSampleDistances && interactive);
  this->LastInteractive = in.AdjustSampleDistances && interactive;
  if (this->UseJittering && !in.JitteringWarned)
  {
    vtkWarningMacro("UseJittering is not supported: rays sample one exact lattice; ignored.");
    in.JitteringWarned = true;
  }
  if (this->PrepareVolumes(ren, vol))
  {
    this->InvokeEvent(vtkCommand::VolumeMapperRenderStartEvent, nullptr);
    this->CastImage(ren);
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
void vtkPARCVolumeMapper::CastImage(vtkRenderer* ren)
{
  vtkInternals& in = *this->Internals;
  vtkPARCRasterizer::View view;
  if (!in.MakeView(this, ren, view))
  {
    return;
  }
  const float* depth = this->IntermixIntersectingGeometry && HasOtherGeometry(ren)
    ? in.ReadGeometryDepth(ren, view.Camera)
    : nullptr;
  const std::vector<vtkInternals::SetUpWork> before = in.CountSetUpWork();
  const std::vector<parc::SceneCaster::Member> members = in.RunPasses(this, ren, view);
  in.SetUpShadows(this, ren);
  const bool completed = in.Cast(this, ren, view.Camera, depth, members);
  in.RecordAuto(before, completed,
    this->AccelerationMode == ACCELERATION_AUTO && this->AutoSupercellSize &&
      !this->LastInteractive);
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::vtkInternals::MakeView(
  vtkPARCVolumeMapper* self, vtkRenderer* ren, vtkPARCRasterizer::View& view)
{
  int width, height;
  ren->GetTiledSize(&width, &height);
  if (width < 1 || height < 1)
  {
    return false;
  }
  const double step = self->ChooseImageSampleDistance();
  self->LastImageSampleDistance = step;
  if (!parc::vtk::MakePassView(ren, std::max(1, static_cast<int>(width / step)),
        std::max(1, static_cast<int>(height / step)), view))
  {
    vtkErrorWithObjectMacro(self, "The camera's projection is singular.");
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
      { volume.Plan.GetModelBuilds(), volume.Rasterizer->GetUploadCount(), volume.SetUpTime() });
  }
  return work;
}

//------------------------------------------------------------------------------
std::vector<parc::SceneCaster::Member> vtkPARCVolumeMapper::vtkInternals::RunPasses(
  vtkPARCVolumeMapper* self, vtkRenderer* ren, const vtkPARCRasterizer::View& view)
{
  std::vector<parc::SceneCaster::Member> members;
  for (const auto& entry : this->Rendered)
  {
    vtkVolumeState& volume = *entry.first;
    volume.Plan.Auto.Chosen = -1;
    const double start = vtkTimerLog::GetUniversalTime();
    self->PrepareCells(volume, entry.second);
    const parc::SegmentSource& source = volume.RunPasses(self, ren, entry.second, view);
    volume.ProjectionTime = vtkTimerLog::GetUniversalTime() - start;
    this->ProjectionTime += volume.ProjectionTime;
    members.push_back({ &volume.Caster, &source });
  }
  return members;
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::vtkInternals::SetUpShadows(vtkPARCVolumeMapper* self, vtkRenderer* ren)
{
  const auto castsShadows = [](const parc::Light& light) { return light.ShadowAttenuation > 0.0; };
  // Volumes of independent components neither cast nor receive shadows.
  const auto inShadows = [](const vtkVolumeState& volume) { return volume.Components.empty(); };
  // The lights of the shaded volumes (every shaded volume has all of the renderer's).
  const std::vector<parc::Light>* lights = nullptr;
  for (const auto& entry : this->Rendered)
  {
    const std::vector<parc::Light>& own = entry.first->Parameters.Lights;
    if (inShadows(*entry.first) && std::any_of(own.begin(), own.end(), castsShadows))
    {
      lights = &own;
    }
  }
  const bool shadows = lights != nullptr;
  this->LightPasses = LightPassWork();
  std::vector<parc::Occluders::Member> occluders;
  const parc::Vec3 frame = parc::vtk::FrameOrigin(ren);
  for (const auto& entry : this->Rendered)
  {
    vtkVolumeState& volume = *entry.first;
    if (!inShadows(volume))
    {
      continue;
    }
    parc::Occluders::Member member{ &volume.Caster, {} };
    // The walk answers any ray: shadow rays need no pass from the lights.
    const bool walk = self->AccelerationMode == ACCELERATION_SUPERCELL_WALK;
    for (std::size_t i = 0; shadows && self->AccelerationMode != ACCELERATION_NONE &&
         volume.Plan.GetGrid().GetNumberOfSupercells() > 0 && i < lights->size();
         ++i)
    {
      if (!castsShadows((*lights)[i]))
      {
        member.LightSources.push_back(nullptr);
        continue;
      }
      const bool planes = self->AccelerationMode == ACCELERATION_COLOR_BUFFER;
      member.LightSources.push_back(walk
          ? &volume.Plan.GetWalk(volume.CoreVolume.WorldToIndex)
          : volume.LightSource(ren->GetRenderWindow(), *lights, i, frame, planes, this->LightPasses));
    }
    occluders.push_back(std::move(member));
  }
  this->Shadows.SetMembers(shadows ? std::move(occluders) : std::vector<parc::Occluders::Member>());
  for (const auto& entry : this->Rendered)
  {
    entry.first->Caster.SetOccluders(shadows && inShadows(*entry.first) ? &this->Shadows : nullptr);
  }
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::vtkInternals::Cast(vtkPARCVolumeMapper* self, vtkRenderer* ren,
  const parc::Camera& rays, const float* depth,
  const std::vector<parc::SceneCaster::Member>& members)
{
  this->Image.resize(4 * static_cast<std::size_t>(rays.Width) * rays.Height);
  this->ImageSize[0] = rays.Width;
  this->ImageSize[1] = rays.Height;
  vtkRenderWindow* window = ren->GetRenderWindow();
  auto progress = [self, window](double fraction) {
    // As VTK's ray cast mappers report it (call data: the fraction done), and as an
    // algorithm does.
    if (self->ReportProgress)
    {
      self->InvokeEvent(vtkCommand::VolumeMapperRenderProgressEvent, &fraction);
      self->UpdateProgress(fraction);
    }
    return !self->GetAbortExecute() && !window->CheckAbortStatus();
  };
  const double start = vtkTimerLog::GetUniversalTime();
  bool completed = false;
  auto cast = [&]() {
    self->LastNumberOfThreads = vtkSMPTools::GetEstimatedNumberOfThreads();
    if (members.size() == 1)
    {
      vtkVolumeState& volume = *this->Rendered[0].first;
      completed = volume.Caster.CastImage(
        rays, depth, *members[0].Source, this->Image.data(), volume.Stats, progress);
      return;
    }
    if (!this->Scene.SetMembers(members, self->TerminationOpacity))
    {
      vtkErrorWithObjectMacro(self, "" << members.size() << " volumes in one scene; at most "
                                       << parc::MaxSceneVolumes << " render together.");
      std::fill(this->Image.begin(), this->Image.end(), 0.f);
      return;
    }
    completed = this->Scene.CastImage(rays, depth, this->Image.data(), this->MemberStats, progress);
    for (std::size_t v = 0; v < members.size(); ++v)
    {
      this->Rendered[v].first->Stats = this->MemberStats[v];
    }
  };
  if (self->NumberOfThreads > 0)
  {
    vtkSMPTools::LocalScope(vtkSMPTools::Config{ self->NumberOfThreads }, cast);
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
void vtkPARCVolumeMapper::vtkInternals::RecordAuto(
  const std::vector<SetUpWork>& before, bool completed, bool searchSizes)
{
  // Each volume's estimate takes its own projection and its share of the casting, in
  // proportion to its samples.
  for (std::size_t v = 0; v < this->Rendered.size(); ++v)
  {
    vtkVolumeState& volume = *this->Rendered[v].first;
    const double share = this->Stats.Samples > 0
      ? static_cast<double>(volume.Stats.Samples) / static_cast<double>(this->Stats.Samples)
      : 1.0 / static_cast<double>(this->Rendered.size());
    const bool setUp = volume.Plan.GetModelBuilds() != before[v].ModelBuilds ||
      volume.Rasterizer->GetUploadCount() != before[v].Uploads;
    parc::FrameMeasure frame;
    frame.Projection = volume.ProjectionTime;
    frame.SetUp = volume.SetUpTime() - before[v].Seconds;
    frame.Casting = share * this->CastingTime;
    frame.Samples = static_cast<double>(volume.Stats.Samples);
    frame.Contributing = static_cast<double>(volume.Stats.ContributingSamples);
    frame.EmptyCells = static_cast<double>(volume.Stats.EmptyCellSamples);
    frame.Timing = volume.Stats.Timing;
    const std::uint64_t version = volume.Plan.GetModelVersion();
    const std::size_t contributing = volume.Plan.GetGrid().GetNumberOfContributing();
    if (completed && setUp)
    {
      volume.Plan.Auto.RecordSetUp(version, contributing, frame);
    }
    else
    {
      volume.Plan.Auto.Record(version, contributing, frame, completed);
    }
    if (searchSizes && completed && !setUp)
    {
      const int* candidate = std::find(
        AutoCandidates, AutoCandidates + parc::AutoTrials::Count, volume.LastMode);
      volume.Plan.Sizes.Record(static_cast<int>(candidate - AutoCandidates),
        volume.Plan.Auto.Settled, frame.Projection + frame.Casting);
    }
  }
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
        plan.GetCellClassifications() + volume->Rasterizer->GetUploadCount() +
        volume->FieldVersion;
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
int vtkPARCVolumeMapper::vtkVolumeState::ChooseMode(
  const vtkPARCVolumeMapper* self, int requested, const parc::Camera& camera)
{
  vtkVolumeState& in = *this;
  if (requested != ACCELERATION_AUTO)
  {
    return requested;
  }
  const parc::SupercellGrid& grid = in.Plan.GetGrid();
  const std::size_t pc = grid.GetNumberOfContributing();
  if (pc == grid.GetNumberOfSupercells())
  {
    in.ModeSettledByClassification = true;
    return ACCELERATION_NONE; // every supercell may contribute: no pass can help
  }
  // Which pass pays off, if any, depends on the GL implementation (software GL makes the
  // passes dear), the data, the ray function and the view: measure.
  const int* dims = in.Field.GetDimensions();
  const parc::Vec3 centre = in.IndexToFrame.TransformPoint( // the eye is the frame's origin
    { 0.5 * (dims[0] - 1), 0.5 * (dims[1] - 1), 0.5 * (dims[2] - 1) });
  in.Plan.Auto.SetView(camera.Direction, parc::Length(centre));
  if (self->AutoSupercellSize && in.Plan.Sizes.IsSearching())
  {
    return AutoCandidates[in.Plan.Sizes.GetCandidate()]; // the search's frames take its pass
  }
  // No trial during interaction: a trial of a slow mode would break the frame budget.
  return AutoCandidates[in.Plan.Auto.Choose(
    in.Plan.GetModelVersion(), pc, camera.Width, camera.Height, !self->LastInteractive)];
}

//------------------------------------------------------------------------------
const parc::SegmentSource& vtkPARCVolumeMapper::vtkVolumeState::RunPasses(
  vtkPARCVolumeMapper* self, vtkRenderer* ren, vtkVolume* vol,
  const vtkPARCRasterizer::View& passView)
{
  vtkVolumeState& in = *this;
  const int requested = self->AccelerationMode;
  vtkRenderWindow* window = ren->GetRenderWindow();
  in.LastMode = ACCELERATION_NONE;
  in.ModeSettledByClassification = false;
  // A slice takes one sample a ray and asks for no segments: no pass can pay off.
  if (requested == ACCELERATION_NONE || in.Parameters.Blend == parc::BlendMode::Slice ||
    !self->PrepareModels(in, vol))
  {
    in.ReleaseUnusedPasses(window, false, false);
    return in.WholeRays;
  }
  const parc::SupercellGrid& grid = in.Plan.GetGrid();
  if (grid.GetNumberOfContributing() == 0)
  {
    in.LastMode = requested;
    in.ModeSettledByClassification = true;
    in.ReleaseUnusedPasses(window, false, false);
    return in.NoRays; // nothing can show: no pass, no sample
  }
  const int* dims = in.Field.GetDimensions();
  if (!passView.Camera.MayMeetBox(
        in.IndexToFrame, parc::Vec3{ 0, 0, 0 }, parc::Vec3(dims[0] - 1, dims[1] - 1, dims[2] - 1)))
  {
    in.LastMode = requested;
    return in.NoRays; // outside the view (another volume of the scene is not): no pass
  }
  const int mode = in.ChooseMode(self, requested, passView.Camera);
  if (mode == ACCELERATION_NONE)
  {
    in.ReleaseUnusedPasses(window, false, false);
    return in.WholeRays;
  }
  if (mode == ACCELERATION_SUPERCELL_WALK)
  {
    in.LastMode = mode;
    in.ReleaseUnusedPasses(window, false, false, true);
    return in.Plan.GetWalk(in.CoreVolume.WorldToIndex);
  }
  const parc::Matrix4& indexToWorld = in.IndexToFrame;
  const bool depth = mode == ACCELERATION_DEPTH_BUFFER || mode == ACCELERATION_BOTH;
  const bool color = mode == ACCELERATION_COLOR_BUFFER || mode == ACCELERATION_BOTH;
  bool ok = true;
  if (depth)
  {
    const std::uint64_t version = in.Plan.GetModelVersion();
    const parc::PolygonModel& model =
      in.Plan.GetDepthModel(in.Rasterizer->HasModel(window, vtkPARCRasterizer::Pass::Depth, version));
    std::vector<float> nearFar = in.DepthSource.ReleaseBuffer();
    ok = in.Rasterizer->RenderDepth(window, model, version, indexToWorld, passView, nearFar);
    if (in.Rasterizer->HasModel(window, vtkPARCRasterizer::Pass::Depth, version))
    {
      in.Plan.ReleaseDepthVertices();
    }
    in.DepthSource.Set(passView.Camera, std::move(nearFar), &grid, in.CoreVolume.WorldToIndex);
    in.PolygonCount += static_cast<vtkIdType>(in.Plan.GetDepthQuads());
  }
  if (ok && color)
  {
    const int axis = MajorAxis(indexToWorld, passView.Camera.Direction);
    const std::uint64_t version = in.Plan.GetColorModelVersion(axis);
    const parc::PolygonModel& model =
      in.Plan.GetColorModel(axis, in.Rasterizer->HasModel(window, vtkPARCRasterizer::Pass::Planes, version));
    std::vector<std::uint32_t> bits = in.PlaneSource.ReleaseBuffer();
    int words = 0;
    std::vector<parc::Vec3> starts, directions;
    passView.Camera.RayBounds(in.CoreVolume.WorldToIndex, starts, directions);
    ok = in.Rasterizer->RenderPlanes(window, model, version, indexToWorld, passView,
      parc::RayAxisSign(model, starts, directions), bits, words, in.PassCount);
    if (in.Rasterizer->HasModel(window, vtkPARCRasterizer::Pass::Planes, version))
    {
      in.Plan.ReleaseColorVertices(axis);
    }
    in.PlaneSource.Set(passView.Camera, std::move(bits), words, &grid, axis, model.FirstPlane,
      in.CoreVolume.WorldToIndex);
    in.PlaneCount = model.PlaneCount;
    in.PolygonCount += static_cast<vtkIdType>(in.Plan.GetColorQuads(axis));
  }
  if (!ok)
  {
    if (!in.FallbackWarned)
    {
      vtkWarningWithObjectMacro(self, "PARC passes are not available ("
          << in.Rasterizer->GetLastError() << "); casting unaccelerated.");
      in.FallbackWarned = true;
    }
    in.PolygonCount = 0;
    in.PlaneCount = in.PassCount = 0;
    return in.WholeRays;
  }
  in.LastMode = mode;
  in.ReleaseUnusedPasses(window, depth, color);
  if (mode == ACCELERATION_BOTH)
  {
    return in.Both;
  }
  return depth ? static_cast<const parc::SegmentSource&>(in.DepthSource) : in.PlaneSource;
}

//------------------------------------------------------------------------------
const parc::SegmentSource* vtkPARCVolumeMapper::vtkVolumeState::LightSource(
  vtkRenderWindow* window, const std::vector<parc::Light>& lights, std::size_t index,
  const parc::Vec3& frame, bool planes, LightPassWork& work)
{
  vtkVolumeState& in = *this;
  const parc::SupercellGrid& grid = in.Plan.GetGrid();
  if (grid.GetNumberOfContributing() == 0)
  {
    return &in.NoRays; // nothing in this volume can block a light
  }
  const parc::Light& light = lights[index];
  parc::LightFrame frameOfLight;
  if (!parc::MakeLightFrame(light, in.IndexToFrame, in.Field.GetDimensions(), frameOfLight))
  {
    return nullptr;
  }
  const parc::Vec3& eye = frameOfLight.Eye; // render frame
  // Colour planes along the axis nearest the light's view of the box (its centre), or depth.
  const auto towardsCentre = [&frameOfLight]() {
    parc::Vec3 centre;
    for (const parc::Vec3& corner : frameOfLight.Corners)
    {
      centre = centre + (1.0 / frameOfLight.Corners.size()) * corner;
    }
    return centre;
  };
  const int axis = planes ? MajorAxis(frameOfLight.IndexToLight, towardsCentre()) : -1;
  const std::uint64_t version =
    axis < 0 ? in.Plan.GetModelVersion() : in.Plan.GetColorModelVersion(axis);
  // What the passes depend on, in world coordinates.
  std::vector<double> key = { light.Positional ? 1.0 : 0.0, static_cast<double>(version),
    static_cast<double>(LightBufferSize), static_cast<double>(axis) };
  for (const parc::Vec3& x : { light.Position + frame, light.FocalPoint + frame, eye + frame })
  {
    key.insert(key.end(), { x.X, x.Y, x.Z });
  }
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      key.push_back(in.IndexToFrame(r, c) + (c == 3 ? frame[r] : 0.0));
    }
  }
  if (in.LightBuffers.size() < lights.size())
  {
    in.LightBuffers.resize(lights.size());
  }
  LightPasses& passes = in.LightBuffers[index];
  passes.Source.Offset = -1.0 * eye; // render frame -> the light's frame (eye at 0)
  // The same world quantities come back through the render frame with rounding.
  const auto same = [](double a, double b) {
    return std::fabs(a - b) <= LightKeyTolerance * std::max({ 1.0, std::fabs(a), std::fabs(b) });
  };
  if (passes.Key.size() == key.size() &&
    std::equal(key.begin(), key.end(), passes.Key.begin(), same))
  {
    return &passes.Source;
  }
  const double start = vtkTimerLog::GetUniversalTime();
  passes.Key.clear();
  const bool uploaded = in.LightRasterizer->HasModel(
    window, planes ? vtkPARCRasterizer::Pass::Planes : vtkPARCRasterizer::Pass::Depth, version);
  const parc::PolygonModel& model =
    planes ? in.Plan.GetColorModel(axis, uploaded) : in.Plan.GetDepthModel(uploaded);
  const bool ok = in.LightRasterizer->RenderLight(
    window, model, version, frameOfLight, LightBufferSize, &grid, passes.Source);
  work.Time += vtkTimerLog::GetUniversalTime() - start;
  work.Frusta += static_cast<int>(passes.Source.GetFrustumCount());
  if (!ok || passes.Source.GetFrustumCount() == 0)
  {
    return nullptr;
  }
  passes.Key = std::move(key);
  return &passes.Source;
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::PrepareCells(vtkVolumeState& in, vtkVolume* vol)
{
  if (!in.Caster.ReadsContributingCells())
  {
    in.Caster.SetContributingCells(nullptr);
    in.Plan.ReleaseCells();
    in.CellsClassified = ClassificationKey();
    return;
  }
  ClassificationKey key = in.Key(this, vol);
  std::fill_n(key.Size, 3, 0.0); // cells do not depend on the supercells
  if (!(key == in.CellsClassified))
  {
    in.CellsClassified = key;
    parc::ContributionRule rule;
    rule.Set(in.Parameters, in.Field.GetRange());
    in.Plan.ClassifyCells(in.Field, in.FieldVersion, rule);
  }
  in.Caster.SetContributingCells(&in.Plan.GetContributingCells());
}

//------------------------------------------------------------------------------
ClassificationKey vtkPARCVolumeMapper::vtkVolumeState::Key(
  vtkPARCVolumeMapper* self, vtkVolume* vol) const
{
  const vtkVolumeState& in = *this;
  ClassificationKey key;
  key.FieldVersion = in.FieldVersion;
  key.Property = vol->GetProperty();
  key.PropertyTime = vol->GetProperty()->GetMTime();
  key.Blend = self->GetInputBlendMode(in.Port);
  key.Labels = in.Parameters.Labels.size();
  for (const parc::LabelFunctions& label : in.Parameters.Labels)
  {
    if (vtkPiecewiseFunction* opacity = vol->GetProperty()->GetLabelScalarOpacity(label.Label))
    {
      key.LabelsTime = std::max(key.LabelsTime, opacity->GetMTime());
    }
  }
  std::copy_n(self->AverageIPScalarRange, 2, key.Average);
  self->SupercellSizeOf(in, key.Size);
  return key;
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::PrepareModels(vtkVolumeState& in, vtkVolume* vol)
{
  const ClassificationKey key = in.Key(this, vol);
  if (key == in.Classified)
  {
    return in.Plan.GetGrid().GetNumberOfSupercells() > 0; // empty after a failed one
  }
  in.Classified = key;
  // One rule per component: a supercell is PC where any component may contribute.
  std::vector<const parc::ScalarField*> fields{ &in.Field };
  std::vector<parc::ContributionRule> rules(1 + in.Components.size());
  rules[0].Set(in.Parameters, in.Field.GetRange());
  for (std::size_t c = 0; c < in.Components.size(); ++c)
  {
    const vtkVolumeState::ComponentState& component = *in.Components[c];
    fields.push_back(&component.Field);
    rules[c + 1].Set(component.Parameters, component.Field.GetRange());
  }
  double requested[3], size[3];
  this->SupercellSizeOf(in, requested);
  if (!in.Plan.Classify(fields, in.FieldVersion, rules, in.Parameters.Interp, requested, size))
  {
    vtkErrorMacro("Invalid supercell size (" << requested[0] << ", " << requested[1] << ", "
                                             << requested[2] << "): casting unaccelerated.");
    return false;
  }
  if (!std::equal(size, size + 3, requested))
  {
    vtkWarningMacro("Supercell size (" << requested[0] << ", " << requested[1] << ", "
      << requested[2] << ") would make "
      << parc::SupercellGrid::CountSupercells(in.Plan.GetGrid().GetCellDimensions(), requested)
      << " supercells, more than the " << parc::SupercellGrid::MaxSupercells
      << " allowed: using (" << size[0] << ", " << size[1] << ", " << size[2] << ").");
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::SupercellSizeOf(const vtkVolumeState& in, double size[3]) const
{
  const double scale = this->AccelerationMode == ACCELERATION_AUTO && this->AutoSupercellSize
    ? in.Plan.Sizes.GetScale()
    : 1.0;
  for (int a = 0; a < 3; ++a)
  {
    size[a] = scale * this->SupercellSize[a];
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
  // The final colour window and level, as VTK's ray cast mappers apply them to the
  // premultiplied colours: rgb * scale + bias * alpha, within [0, alpha].
  const bool windowLevel = !(this->FinalColorWindow == 1.f && this->FinalColorLevel == 0.5f);
  if (windowLevel && this->FinalColorWindow == 0.f && !in.WindowWarned)
  {
    vtkWarningMacro("FinalColorWindow 0 is not usable: the final colours are not adjusted.");
    in.WindowWarned = true;
  }
  const bool adjust = windowLevel && this->FinalColorWindow != 0.f;
  const float scale = adjust ? 1.f / this->FinalColorWindow : 1.f;
  const float bias = adjust ? 0.5f - this->FinalColorLevel / this->FinalColorWindow : 0.f;
  vtkSMPTools::For(0, values / 4, [=](vtkIdType begin, vtkIdType end) {
    for (vtkIdType p = begin; p < end; ++p)
    {
      const float* rgba = image + 4 * p;
      const float a = std::min(std::max(rgba[3], 0.f), 1.f);
      for (int c = 0; c < 4; ++c)
      {
        float v = rgba[c];
        if (adjust && c < 3)
        {
          v = std::min(std::max(v * scale + bias * a, 0.f), a);
        }
        v = std::min(std::max(v, 0.f), 1.f);
        display[4 * p + c] = static_cast<unsigned char>(v * 255.f + 0.5f);
      }
    }
  });
  int origin[2] = { 0, 0 };
  in.DisplayHelper->RenderTexture(vol, ren, in.ImageSize, in.ImageSize, in.ImageSize, origin,
    DisplayDepth, in.Display.data());
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Internals->DisplayHelper->ReleaseGraphicsResources(window);
  for (const auto& volume : this->Internals->Volumes)
  {
    if (volume)
    {
      volume->Rasterizer->ReleaseGraphicsResources(window);
      volume->LightRasterizer->ReleaseGraphicsResources(window);
      volume->LightBuffers.clear(); // drawn in the window's context: remade when needed
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
