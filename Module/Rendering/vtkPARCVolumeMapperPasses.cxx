// vtkPARCVolumeMapper: the PARC passes of a render: each volume's classification and
// models, the acceleration mode (Auto's trials and supercell search), the view's passes
// and the lights' passes for shadow rays.
#include "vtkPARCVolumeMapperInternals.h"

namespace
{
/// Pixels along each edge of a light's PARC buffers (shadow rays).
constexpr int LightBufferSize = 256;

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
}

//------------------------------------------------------------------------------
std::vector<parc::SceneCaster::Member> vtkPARCVolumeMapper::vtkInternals::RunPasses(
  vtkRenderer* ren, const parc::vtk::PassView& view)
{
  std::vector<parc::SceneCaster::Member> members;
  for (const auto& entry : this->Rendered)
  {
    vtkVolumeState& volume = *entry.first;
    volume.Plan.Auto.Chosen = -1;
    const double start = vtkTimerLog::GetUniversalTime();
    volume.PrepareCells(this->Settings, entry.second);
    const parc::SegmentSource& source = volume.RunPasses(this->Settings, ren, entry.second, view);
    volume.ProjectionTime = vtkTimerLog::GetUniversalTime() - start;
    this->ProjectionTime += volume.ProjectionTime;
    members.push_back({ &volume.Caster, &source });
  }
  return members;
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::vtkInternals::SetUpShadows(vtkRenderer* ren)
{
  const AccelerationTraits requested = parc::mapper::TraitsOf(this->Settings.AccelerationMode);
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
  const parc::Vec3 frame = this->Frame.Origin;
  for (const auto& entry : this->Rendered)
  {
    vtkVolumeState& volume = *entry.first;
    if (!inShadows(volume))
    {
      continue;
    }
    parc::Occluders::Member member{ &volume.Caster, {} };
    // The walk answers any ray: shadow rays need no pass from the lights.
    for (std::size_t i = 0; shadows && (requested.Walk || requested.LightPasses) &&
         volume.Plan.GetGrid().GetNumberOfSupercells() > 0 && i < lights->size();
         ++i)
    {
      if (!castsShadows((*lights)[i]))
      {
        member.LightSources.push_back(nullptr);
        continue;
      }
      member.LightSources.push_back(requested.Walk
          ? &volume.Plan.GetWalk(volume.CoreVolume.WorldToIndex)
          : volume.LightSource(ren->GetRenderWindow(), *lights, i, frame, requested.LightPlanes,
              this->LightPasses));
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
      volume.Passes.GetUploadCount() != before[v].Uploads;
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
      parc::SupercellSearch& sizes = volume.Plan.Sizes;
      const bool againstNone = sizes.IsSearchingAgainstNone();
      sizes.Record(volume.Last.Candidate, volume.Plan.Auto.Settled, frame.Projection,
        frame.Casting, volume.Plan.Auto.DepthMayBeatNoneAtTwiceTheSize());
      if (againstNone && sizes.IsDone())
      {
        double projection = 0.0, casting = 0.0;
        const bool depthWon = sizes.BeatNone(projection, casting);
        volume.Plan.Auto.SettleAfterSearch(depthWon, projection, casting);
      }
    }
  }
}

//------------------------------------------------------------------------------
int vtkPARCVolumeMapper::vtkVolumeState::ChooseMode(
  const RenderSettings& settings, const parc::Camera& camera)
{
  vtkVolumeState& state = *this;
  const int requested = settings.AccelerationMode;
  if (requested != ACCELERATION_AUTO)
  {
    return requested;
  }
  const parc::SupercellGrid& grid = state.Plan.GetGrid();
  const std::size_t pc = grid.GetNumberOfContributing();
  if (pc == grid.GetNumberOfSupercells())
  {
    state.Last.SettledByClassification = true;
    return ACCELERATION_NONE; // every supercell may contribute: no pass can help
  }
  // Which pass pays off, if any, depends on the GL implementation (software GL makes the
  // passes dear), the data, the ray function and the view: measure.
  // The eye is the frame's origin.
  state.Plan.Auto.SetView(camera.Direction, parc::Length(state.CoreVolume.Centre()));
  // The search's frames take its pass; one against None is a trial (none while interacting).
  const parc::SupercellSearch& sizes = state.Plan.Sizes;
  if (settings.SearchSupercellSize && sizes.IsSearching() &&
    !(settings.Interactive && sizes.IsSearchingAgainstNone()))
  {
    return AutoCandidates[sizes.GetCandidate()];
  }
  // No trial during interaction: a trial of a slow mode would break the frame budget.
  return AutoCandidates[state.Plan.Auto.Choose(
    state.Plan.GetModelVersion(), pc, camera.Width, camera.Height, !settings.Interactive)];
}

//------------------------------------------------------------------------------
const parc::SegmentSource& vtkPARCVolumeMapper::vtkVolumeState::RunPasses(
  const RenderSettings& settings, vtkRenderer* ren, vtkVolume* vol,
  const parc::vtk::PassView& passView)
{
  vtkVolumeState& state = *this;
  const int requested = settings.AccelerationMode;
  vtkRenderWindow* window = ren->GetRenderWindow();
  FramePasses& last = state.Last;
  last = FramePasses();
  // A ray function without segments (a slice: one sample a ray): no pass can pay off.
  if (requested == ACCELERATION_NONE || !parc::TraitsOf(state.Parameters.Blend).UsesSegments ||
    !state.PrepareModels(settings, vol))
  {
    last.Candidate = parc::AutoTrials::None;
    state.ReleaseUnusedPasses(window, {});
    return state.Plan.GetSource(parc::AutoTrials::None);
  }
  const parc::SupercellGrid& grid = state.Plan.GetGrid();
  if (grid.GetNumberOfContributing() == 0)
  {
    last.Mode = requested;
    last.SettledByClassification = true;
    state.ReleaseUnusedPasses(window, {});
    return state.Plan.GetEmptySource(); // nothing can show: no pass, no sample
  }
  const int* dims = state.Field.GetDimensions();
  if (!passView.Camera.MayMeetBox(state.CoreVolume.IndexToWorld, parc::Vec3{ 0, 0, 0 },
        parc::Vec3(dims[0] - 1, dims[1] - 1, dims[2] - 1)))
  {
    last.Mode = requested;
    // Outside the view (another volume of the scene is not): no pass.
    return state.Plan.GetEmptySource();
  }
  const int mode = state.ChooseMode(settings, passView.Camera);
  if (mode == ACCELERATION_NONE)
  {
    last.Candidate = parc::AutoTrials::None;
    state.ReleaseUnusedPasses(window, {});
    return state.Plan.GetSource(parc::AutoTrials::None);
  }
  const AccelerationTraits passes = parc::mapper::TraitsOf(mode);
  if (passes.Walk)
  {
    last.Mode = mode;
    state.ReleaseUnusedPasses(window, passes);
    return state.Plan.GetWalk(state.CoreVolume.WorldToIndex);
  }
  const bool depth = passes.Depth;
  const bool color = passes.Planes;
  parc::vtk::PassDriver::Drawn drawn;
  bool ok = !depth || state.Passes.DrawDepth(window, state.Plan, state.CoreVolume, passView, drawn);
  if (ok && color)
  {
    const int axis = MajorAxis(state.CoreVolume.IndexToWorld, passView.Camera.Direction);
    ok = state.Passes.DrawPlanes(window, state.Plan, state.CoreVolume, passView, axis, drawn);
  }
  state.Drawn = drawn;
  if (!ok)
  {
    if (!state.FallbackWarned)
    {
      vtkWarningWithObjectMacro(settings.Reporter, "PARC passes are not available ("
          << state.Passes.GetLastError() << "); casting unaccelerated.");
      state.FallbackWarned = true;
    }
    state.Drawn = {};
    last.Candidate = parc::AutoTrials::None;
    return state.Plan.GetSource(parc::AutoTrials::None);
  }
  last.Mode = mode;
  last.Candidate = depth && color ? parc::AutoTrials::Both
    : depth                       ? parc::AutoTrials::Depth
                                  : parc::AutoTrials::Color;
  state.ReleaseUnusedPasses(window, passes);
  return state.Plan.GetSource(static_cast<parc::AutoTrials::Candidate>(last.Candidate));
}

//------------------------------------------------------------------------------
const parc::SegmentSource* vtkPARCVolumeMapper::vtkVolumeState::LightSource(
  vtkRenderWindow* window, const std::vector<parc::Light>& lights, std::size_t index,
  const parc::Vec3& frame, bool planes, LightPassWork& work)
{
  vtkVolumeState& state = *this;
  const parc::SupercellGrid& grid = state.Plan.GetGrid();
  if (grid.GetNumberOfContributing() == 0)
  {
    return &state.Plan.GetEmptySource(); // nothing in this volume can block a light
  }
  const parc::Light& light = lights[index];
  parc::LightFrame frameOfLight;
  if (!parc::MakeLightFrame(
        light, state.CoreVolume.IndexToWorld, state.Field.GetDimensions(), frameOfLight))
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
    axis < 0 ? state.Plan.GetModelVersion() : state.Plan.GetColorModelVersion(axis);
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
      key.push_back(state.CoreVolume.IndexToWorld(r, c) + (c == 3 ? frame[r] : 0.0));
    }
  }
  parc::AccelerationPlan::LightPasses& passes = state.Plan.GetLightPasses(index, lights.size());
  passes.Source.Offset = -1.0 * eye; // render frame -> the light's frame (eye at 0)
  if (passes.IsDrawnFrom(key))
  {
    return &passes.Source;
  }
  const double start = vtkTimerLog::GetUniversalTime();
  passes.Key.clear();
  const bool ok = state.Passes.DrawLight(
    window, state.Plan, frameOfLight, axis, LightBufferSize, passes.Source);
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
void vtkPARCVolumeMapper::vtkVolumeState::PrepareCells(
  const RenderSettings& settings, vtkVolume* vol)
{
  vtkVolumeState& state = *this;
  if (!state.Caster.ReadsContributingCells())
  {
    state.Caster.SetContributingCells(nullptr);
    state.Plan.ReleaseCells();
    return;
  }
  parc::ClassificationKey key = state.Key(settings, vol);
  std::fill_n(key.Size, 3, 0.0); // cells do not depend on the supercells
  if (!state.Plan.AreCellsClassifiedFrom(key))
  {
    settings.SetUpStep("classifying the cells", SetUpProgress::Cells);
    parc::ContributionRule rule;
    rule.Set(state.Parameters, state.Field.GetRange());
    state.Plan.ClassifyCellsFrom(key, state.Field, rule);
  }
  state.Caster.SetContributingCells(&state.Plan.GetContributingCells());
}

//------------------------------------------------------------------------------
parc::ClassificationKey vtkPARCVolumeMapper::vtkVolumeState::Key(
  const RenderSettings& settings, vtkVolume* vol) const
{
  parc::ClassificationKey key = parc::vtk::ClassificationKeyOf(vol->GetProperty(),
    this->Parameters, this->Scalars.Version, this->InputBlend, settings.AverageIPScalarRange);
  this->SupercellSizeOf(settings, key.Size);
  return key;
}

//------------------------------------------------------------------------------
bool vtkPARCVolumeMapper::vtkVolumeState::PrepareModels(
  const RenderSettings& settings, vtkVolume* vol)
{
  vtkVolumeState& state = *this;
  const parc::ClassificationKey key = state.Key(settings, vol);
  if (state.Plan.IsClassifiedFrom(key))
  {
    return state.Plan.GetGrid().GetNumberOfSupercells() > 0; // empty after a failed one
  }
  settings.SetUpStep("classifying the supercells", SetUpProgress::Supercells);
  // One rule per component: a supercell is PC where any component may contribute.
  std::vector<const parc::ScalarField*> fields{ &state.Field };
  std::vector<parc::ContributionRule> rules(1 + state.Components.size());
  rules[0].Set(state.Parameters, state.Field.GetRange());
  for (std::size_t c = 0; c < state.Components.size(); ++c)
  {
    const vtkVolumeState::ComponentState& component = *state.Components[c];
    fields.push_back(&component.Field);
    rules[c + 1].Set(component.Parameters, component.Field.GetRange());
  }
  const double* requested = key.Size;
  double size[3];
  if (!state.Plan.ClassifyFrom(key, fields, rules, state.Parameters.Interp, size))
  {
    vtkErrorWithObjectMacro(settings.Reporter,
      "Invalid supercell size (" << requested[0] << ", " << requested[1] << ", " << requested[2]
                                 << "): casting unaccelerated.");
    return false;
  }
  if (!std::equal(size, size + 3, requested))
  {
    vtkWarningWithObjectMacro(settings.Reporter,
      "Supercell size (" << requested[0] << ", " << requested[1] << ", " << requested[2]
        << ") would make "
        << parc::SupercellGrid::CountSupercells(state.Plan.GetGrid().GetCellDimensions(), requested)
        << " supercells, more than the " << parc::SupercellGrid::MaxSupercells
        << " allowed: using (" << size[0] << ", " << size[1] << ", " << size[2] << ").");
  }
  return true;
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::vtkVolumeState::SupercellSizeOf(
  const RenderSettings& settings, double size[3]) const
{
  const double scale = settings.SearchSupercellSize ? this->Plan.Sizes.GetScale() : 1.0;
  for (int a = 0; a < 3; ++a)
  {
    size[a] = scale * settings.SupercellSize[a];
  }
}
