// vtkPARCVolumeMapper: the statistics of the last render (counts, times, the ray-cast
// image) and the memory the mapper holds.
#include "vtkPARCVolumeMapperInternals.h"

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
  const vtkIdType pixels = static_cast<vtkIdType>(in.ImageSize[0]) * in.ImageSize[1];
  rgba->SetNumberOfTuples(pixels);
  std::copy_n(in.Image.data(), 4 * pixels, rgba->GetPointer(0));
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
vtkIdType vtkPARCVolumeMapper::GetLastEmptyCellSampleCount()
{
  return static_cast<vtkIdType>(this->Internals->Stats.EmptyCellSamples);
}
vtkIdType vtkPARCVolumeMapper::GetLastRayCount()
{
  return static_cast<vtkIdType>(this->Internals->Stats.Rays);
}
vtkIdType vtkPARCVolumeMapper::GetLastGradientCount()
{
  return static_cast<vtkIdType>(this->Internals->Stats.GradientEvaluations);
}
vtkIdType vtkPARCVolumeMapper::GetLastGradientCacheSize()
{
  return static_cast<vtkIdType>(this->Internals->Stats.DifferenceCacheBytes);
}
vtkIdType vtkPARCVolumeMapper::GetLastShadowRayCount()
{
  return static_cast<vtkIdType>(this->Internals->Stats.ShadowRays);
}
vtkIdType vtkPARCVolumeMapper::GetLastShadowSampleCount()
{
  return static_cast<vtkIdType>(this->Internals->Stats.ShadowSamples);
}
vtkIdType vtkPARCVolumeMapper::GetLastShadowCellCount()
{
  return static_cast<vtkIdType>(this->Internals->Stats.ShadowCells);
}
int vtkPARCVolumeMapper::GetAutoTrialsRemaining()
{
  const bool searchesSizes = this->Internals->Settings.SearchSupercellSize; // the last render's
  return this->Internals->Sum<int>([searchesSizes](const vtkVolumeState& v) {
    if (v.Last.SettledByClassification)
    {
      return 0;
    }
    const parc::AutoTrials& trials = v.Plan.Auto;
    const bool againstNone =
      searchesSizes && v.Plan.Sizes.SearchesAgainstNone(trials.DepthMayBeatNoneAtTwiceTheSize());
    return trials.Remaining() + (againstNone ? 1 : 0);
  });
}

//------------------------------------------------------------------------------
double vtkPARCVolumeMapper::GetLastCastingTime()
{
  return this->Internals->CastingTime;
}
double vtkPARCVolumeMapper::GetLastProjectionTime()
{
  return this->Internals->ProjectionTime;
}
double vtkPARCVolumeMapper::GetLastLightProjectionTime()
{
  return this->Internals->LightPasses.Time;
}
int vtkPARCVolumeMapper::GetLastLightFrustumCount()
{
  return this->Internals->LightPasses.Frusta;
}
double vtkPARCVolumeMapper::GetLastRenderTime()
{
  return this->Internals->RenderTime;
}
int vtkPARCVolumeMapper::GetLastShadingModel()
{
  const auto& volumes = this->Internals->Volumes;
  return !volumes.empty() && volumes[0] && volumes[0]->Caster.UsesQuantizedNormals()
    ? SHADING_QUANTIZED_NORMALS
    : SHADING_EXACT;
}
int vtkPARCVolumeMapper::GetLastAccelerationMode()
{
  return this->GetLastInputAccelerationMode(0);
}
int vtkPARCVolumeMapper::GetLastInputAccelerationMode(int port)
{
  if (port < 0 || port >= MaxInputPorts)
  {
    vtkErrorMacro("Port " << port << " is not in [0, " << MaxInputPorts << ").");
    return ACCELERATION_NONE;
  }
  const auto& volumes = this->Internals->Volumes;
  return static_cast<std::size_t>(port) < volumes.size() && volumes[port]
    ? volumes[port]->Last.Mode
    : ACCELERATION_NONE;
}
vtkIdType vtkPARCVolumeMapper::GetLastPolygonCount()
{
  return this->Internals->Sum<vtkIdType>(
    [](const vtkVolumeState& v) { return static_cast<vtkIdType>(v.Drawn.Polygons); });
}
vtkIdType vtkPARCVolumeMapper::GetLastCellCount()
{
  return static_cast<vtkIdType>(this->Internals->Stats.Cells);
}
vtkIdType vtkPARCVolumeMapper::GetLastSupercellCount()
{
  return this->Internals->Sum<vtkIdType>(
    [](const vtkVolumeState& v) { return v.Plan.GetGrid().GetNumberOfSupercells(); });
}
vtkIdType vtkPARCVolumeMapper::GetLastContributingSupercellCount()
{
  return this->Internals->Sum<vtkIdType>(
    [](const vtkVolumeState& v) { return v.Plan.GetGrid().GetNumberOfContributing(); });
}
int vtkPARCVolumeMapper::GetLastPlaneCount()
{
  return this->Internals->Sum<int>([](const vtkVolumeState& v) { return v.Drawn.Planes; });
}
int vtkPARCVolumeMapper::GetLastPassCount()
{
  return this->Internals->Sum<int>([](const vtkVolumeState& v) { return v.Drawn.Passes; });
}
double vtkPARCVolumeMapper::GetLastClassificationTime()
{
  return this->Internals->Sum<double>(
    [](const vtkVolumeState& v) { return v.Plan.GetClassificationTime(); });
}
vtkIdType vtkPARCVolumeMapper::GetPyramidBuildCount()
{
  return this->Internals->Sum<vtkIdType>(
    [](const vtkVolumeState& v) { return static_cast<vtkIdType>(v.Plan.GetPyramidBuilds()); });
}
vtkIdType vtkPARCVolumeMapper::GetCellClassificationCount()
{
  return this->Internals->Sum<vtkIdType>([](const vtkVolumeState& v) {
    return static_cast<vtkIdType>(v.Plan.GetCellClassifications());
  });
}
vtkIdType vtkPARCVolumeMapper::GetClassificationCount()
{
  return this->Internals->Sum<vtkIdType>(
    [](const vtkVolumeState& v) { return static_cast<vtkIdType>(v.Plan.GetClassifications()); });
}
vtkIdType vtkPARCVolumeMapper::GetModelBuildCount()
{
  return this->Internals->Sum<vtkIdType>(
    [](const vtkVolumeState& v) { return static_cast<vtkIdType>(v.Plan.GetModelBuilds()); });
}
vtkIdType vtkPARCVolumeMapper::GetModelUploadCount()
{
  return this->Internals->Sum<vtkIdType>([](const vtkVolumeState& v) {
    return static_cast<vtkIdType>(v.Passes.GetUploadCount());
  });
}

//------------------------------------------------------------------------------
void vtkPARCVolumeMapper::PrintStatistics(ostream& os)
{
  vtkInternals& in = *this->Internals;
  os << "Ray image: " << in.ImageSize[0] << " x " << in.ImageSize[1] << "\n";
  for (const auto& entry : in.Rendered)
  {
    const vtkVolumeState& v = *entry.first;
    const char* indent = in.Rendered.size() > 1 ? "  " : "";
    if (in.Rendered.size() > 1)
    {
      os << "Port " << v.Port << ":\n";
    }
    os << indent << "Acceleration: " << GetAccelerationModeAsString(v.Last.Mode) << "\n"
       << indent << "Auto trials remaining: " << v.Plan.Auto.Remaining() << "\n"
       << indent << "Supercells: " << v.Plan.GetGrid().GetNumberOfSupercells() << " ("
       << v.Plan.GetGrid().GetNumberOfContributing() << " possibly contributing)\n"
       << indent << "Polygons: " << v.Drawn.Polygons << "\n"
       << indent << "Planes: " << v.Drawn.Planes << " in " << v.Drawn.Passes << " passes\n"
       << indent << "Samples: " << v.Stats.Samples << "\n";
  }
  os << "Rays: " << in.Stats.Rays << "\n"
     << "Segments: " << in.Stats.Segments << "\n"
     << "Samples: " << in.Stats.Samples << "\n"
     << "Contributing samples: " << in.Stats.ContributingSamples << "\n"
     << "Gradients: " << in.Stats.GradientEvaluations << " (cell differences loaded "
     << in.Stats.DifferenceLoads << ")\n"
     << "Cells considered: " << in.Stats.Cells << "\n"
     << "Shadow rays: " << in.Stats.ShadowRays << " (samples " << in.Stats.ShadowSamples
     << ", cells " << in.Stats.ShadowCells << ")\n"
     << "Casting time (s): " << in.CastingTime << "\n"
     << "Projection time (s): " << in.ProjectionTime << "\n"
     << "Light projection time (s): " << in.LightPasses.Time << " (" << in.LightPasses.Frusta
     << " light frusta)\n"
     << "Render time (s): " << in.RenderTime << "\n";
}

//------------------------------------------------------------------------------
std::vector<std::pair<const char*, std::size_t>>
vtkPARCVolumeMapper::vtkVolumeState::Memory() const
{
  std::size_t bricks = this->Field.GetBrickedMemorySize();
  for (const auto& component : this->Components)
  {
    bricks += component->Field.GetBrickedMemorySize();
  }
  return { { "scalar copy", this->Field.GetMemorySize() }, { "bricked copy", bricks },
    { "mask copy", this->Mask.GetMemorySize() },
    { "quantized normals", this->Normals.GetMemorySize() },
    { "normal shading table", this->Caster.GetShadingTableMemorySize() },
    { "range pyramid", this->Plan.GetPyramidMemorySize() },
    { "supercell flags", this->Plan.GetGrid().GetMemorySize() },
    { "depth model", this->Plan.GetDepthModelMemorySize() },
    { "colour models", this->Plan.GetColorModelsMemorySize() },
    { "supercell walk", this->Plan.GetWalkMemorySize() },
    { "depth buffer", this->Plan.GetDepthBufferMemorySize() },
    { "bit-plane buffer", this->Plan.GetPlaneBufferMemorySize() },
    { "OpenGL models and targets", this->Passes.GetMemorySize() },
    { "OpenGL implementation, beyond them (measured)", this->Passes.GetDriverMemorySize() },
    { "light buffers", this->Plan.GetLightPassesMemorySize() },
    { "gradients' cell caches (while casting)", this->Stats.DifferenceCacheBytes } };
}

std::vector<std::pair<const char*, std::size_t>> vtkPARCVolumeMapper::vtkInternals::Memory() const
{
  // The volumes' structures summed over the volumes, then the image's.
  std::vector<std::pair<const char*, std::size_t>> memory;
  for (const auto& volume : this->Volumes)
  {
    if (!volume)
    {
      continue;
    }
    const auto own = volume->Memory();
    if (memory.empty())
    {
      memory = own;
      continue;
    }
    for (std::size_t i = 0; i < own.size(); ++i)
    {
      memory[i].second += own[i].second;
    }
  }
  memory.insert(memory.end(),
    { { "ray-cast image", this->Image.capacity() * sizeof(float) },
      { "opaque depth", this->Depth.capacity() * sizeof(float) },
      { "display image", this->Display.capacity() },
      { "OpenGL implementation, display (measured)", this->DisplayDriver.GetMemorySize() } });
  return memory;
}

vtkIdType vtkPARCVolumeMapper::GetMemorySize()
{
  std::size_t total = 0;
  for (const auto& entry : this->Internals->Memory())
  {
    total += entry.second;
  }
  return static_cast<vtkIdType>(total);
}

void vtkPARCVolumeMapper::PrintMemory(ostream& os)
{
  for (const auto& entry : this->Internals->Memory())
  {
    os << "Memory, " << entry.first << " (bytes): " << entry.second << "\n";
  }
  os << "Memory, total (bytes): " << this->GetMemorySize() << "\n";
}
