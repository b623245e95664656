#include "parcRenderStudies.h"

#include "parcRenderTools.h"
#include "vtkPARCMultiVolume.h"
#include "vtkPARCVolumeMapper.h"

#include <vtkCamera.h>
#include <vtkPiecewiseFunction.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSMPTools.h>
#include <vtkSmartPointer.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <utility>
#include <string>
#include <vector>

namespace parcstudies
{
using parctools::CopyMapper;
using parctools::FixedPointLike;
using parctools::MinMedian;
using parctools::RayImage;
using parctools::TimedRender;
using parctools::WarmUp;

namespace
{
/// Averages of repeated renders of one configuration, and its float ray-cast image.
struct Measurement
{
  std::string Mode;
  long long Samples = 0, Cells = 0, Polygons = 0, Supercells = 0, Contributing = 0;
  long long ShadowRays = 0, ShadowCells = 0;
  int Planes = 0, Passes = 0;
  double Projection = 0.0, Casting = 0.0, Total = 0.0, Wall = 0.0;
  std::vector<float> Image;
};

Measurement Measure(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper, int repeat)
{
  WarmUp(window, mapper);
  Measurement m;
  for (int r = 0; r < repeat; ++r)
  {
    m.Wall += TimedRender(window) / repeat;
    m.Projection += mapper->GetLastProjectionTime() / repeat;
    m.Casting += mapper->GetLastCastingTime() / repeat;
    m.Total += mapper->GetLastRenderTime() / repeat;
  }
  m.Mode = vtkPARCVolumeMapper::GetAccelerationModeAsString(mapper->GetLastAccelerationMode());
  m.Samples = mapper->GetLastSampleCount();
  m.Cells = mapper->GetLastCellCount();
  m.ShadowRays = mapper->GetLastShadowRayCount();
  m.ShadowCells = mapper->GetLastShadowCellCount();
  m.Polygons = mapper->GetLastPolygonCount();
  m.Supercells = mapper->GetLastSupercellCount();
  m.Contributing = mapper->GetLastContributingSupercellCount();
  m.Planes = mapper->GetLastPlaneCount();
  m.Passes = mapper->GetLastPassCount();
  m.Image = RayImage(mapper);
  return m;
}
}

void CompareAccelerationModes(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper, int repeat)
{
  const int modes[] = { vtkPARCVolumeMapper::ACCELERATION_NONE,
    vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER, vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER,
    vtkPARCVolumeMapper::ACCELERATION_BOTH, vtkPARCVolumeMapper::ACCELERATION_SUPERCELL_WALK,
    vtkPARCVolumeMapper::ACCELERATION_AUTO };
  std::vector<Measurement> rows;
  for (int mode : modes)
  {
    mapper->SetAccelerationMode(mode);
    rows.push_back(Measure(window, mapper, repeat));
    if (mode == vtkPARCVolumeMapper::ACCELERATION_AUTO)
    {
      rows.back().Mode = "Auto: " + rows.back().Mode;
    }
  }
  std::printf("| mode | samples | cells | shadow rays | shadow cells | polygons | planes/passes "
              "| projection (s) | casting (s) | total (s) | speedup | identical |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Measurement& m : rows)
  {
    const bool same = m.Image == rows[0].Image;
    std::printf("| %s | %lld | %lld | %lld | %lld | %lld | %d/%d | %.4f | %.4f | %.4f | %.2fx | %s |\n",
      m.Mode.c_str(), m.Samples, m.Cells, m.ShadowRays, m.ShadowCells, m.Polygons, m.Planes,
      m.Passes, m.Projection, m.Casting, m.Total, rows[0].Total / m.Total, same ? "yes" : "NO");
  }
  std::printf("PC supercells: %lld of %lld (%.2f%%); classification took %.4f s\n",
    rows[1].Contributing, rows[1].Supercells,
    100.0 * rows[1].Contributing / std::max(1LL, rows[1].Supercells),
    mapper->GetLastClassificationTime());
}




void ShadowTable(vtkRenderWindow* window, vtkRenderer* renderer, vtkVolume* prop,
  vtkPARCVolumeMapper* parc, int rounds)
{
  const int modes[] = { vtkPARCVolumeMapper::ACCELERATION_NONE,
    vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER, vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER,
    vtkPARCVolumeMapper::ACCELERATION_AUTO };
  constexpr int Modes = 4, AutoRow = 3;
  struct Row
  {
    vtkSmartPointer<vtkPARCVolumeMapper> Mapper;
    std::string Name;
    std::vector<double> Casting, Total[2]; ///< primary casting; totals without and with shadows
    long long Cells = 0, ShadowCells = 0, ShadowRays = 0;
    double LightPasses = 0.0;
    std::vector<float> Image[2];
  };
  std::vector<Row> rows(Modes);
  const auto render = [&](Row& row, int shadows) {
    renderer->SetUseShadows(shadows);
    prop->SetMapper(row.Mapper);
    window->Render();
  };
  for (int i = 0; i < Modes; ++i)
  {
    rows[i].Mapper = CopyMapper(parc, modes[i]);
    for (int shadows = 1; shadows >= 0; --shadows) // the first shadowed frame builds the light passes
    {
      render(rows[i], shadows);
      rows[i].LightPasses = std::max(rows[i].LightPasses, rows[i].Mapper->GetLastLightProjectionTime());
      WarmUp(window, rows[i].Mapper);
    }
  }
  for (int r = 0; r < rounds; ++r)
  {
    for (Row& row : rows)
    {
      for (int shadows = 0; shadows < 2; ++shadows)
      {
        render(row, shadows);
        vtkPARCVolumeMapper* m = row.Mapper;
        row.Total[shadows].push_back(m->GetLastRenderTime());
        if (shadows == 0)
        {
          row.Casting.push_back(m->GetLastCastingTime());
          row.Cells = m->GetLastCellCount();
        }
        else
        {
          row.ShadowCells = m->GetLastShadowCellCount();
          row.ShadowRays = m->GetLastShadowRayCount();
        }
        if (r == 0)
        {
          row.Image[shadows] = RayImage(m);
        }
      }
      row.Name = vtkPARCVolumeMapper::GetAccelerationModeAsString(row.Mapper->GetLastAccelerationMode());
    }
  }
  rows[AutoRow].Name = "Auto: " + rows[AutoRow].Name;
  prop->SetMapper(parc);
  renderer->SetUseShadows(1);
  struct Medians
  {
    double Casting, Primary, Shadowed;
  };
  const auto medians = [](const Row& row) {
    return Medians{ MinMedian(row.Casting).second, MinMedian(row.Total[0]).second,
      MinMedian(row.Total[1]).second + row.LightPasses };
  };
  std::printf("| PARC | primary cells (10^3) | primary casting (s) | primary total (s) | shadow "
              "rays | shadow cells (10^3) | light passes (s) | total with shadows (s) | identical "
              "|\n|---|---|---|---|---|---|---|---|---|\n");
  for (const Row& row : rows)
  {
    const Medians m = medians(row);
    const bool same = row.Image[0] == rows[0].Image[0] && row.Image[1] == rows[0].Image[1];
    std::printf("| %s | %.0f | %.4f | %.4f | %lld | %.0f | %.4f | %.4f | %s |\n", row.Name.c_str(),
      1e-3 * row.Cells, m.Casting, m.Primary, row.ShadowRays, 1e-3 * row.ShadowCells,
      row.LightPasses, m.Shadowed, same ? "yes" : "NO");
  }
  // The paper's Table 3 (depth PARC against none, 300^2 and 600^2), seconds.
  constexpr double Paper[2][2][3] = { { { 33.38, 35.61, 66.04 }, { 7.72, 10.06, 26.31 } },
    { { 132.04, 141.29, 260.45 }, { 29.72, 40.29, 99.74 } } };
  const auto paperRatio = [&](int size, int column) {
    if (column == 3) // the shadows' share: total with shadows minus primary total
    {
      return (Paper[size][0][2] - Paper[size][0][1]) / (Paper[size][1][2] - Paper[size][1][1]);
    }
    return Paper[size][0][column] / Paper[size][1][column];
  };
  const Medians none = medians(rows[0]);
  const int* size = window->GetSize();
  const int nearest = size[0] * size[1] < 450 * 450 ? 0 : 1; // the paper's 300^2 or 600^2
  std::printf("\n| none / PARC (medians) | DepthBuffer | ColorBuffer | %s | paper, 300^2 | paper, "
              "600^2 | goal: 1.5x the paper's at %d^2 |\n|---|---|---|---|---|---|---|\n",
    rows[AutoRow].Name.c_str(), nearest == 0 ? 300 : 600);
  const char* names[4] = { "primary casting", "primary total", "total with shadows",
    "the shadows' share (with shadows minus primary)" };
  for (int c : { 0, 1, 3, 2 })
  {
    const auto ratio = [&](const Medians& m) {
      switch (c)
      {
        case 0: return none.Casting / m.Casting;
        case 1: return none.Primary / m.Primary;
        case 2: return none.Shadowed / m.Shadowed;
        default: return (none.Shadowed - none.Primary) / (m.Shadowed - m.Primary);
      }
    };
    std::printf("| %s | %.2fx | %.2fx | %.2fx | %.2fx | %.2fx | %.2fx |\n", names[c],
      ratio(medians(rows[1])), ratio(medians(rows[2])), ratio(medians(rows[3])), paperRatio(0, c),
      paperRatio(1, c), 1.5 * paperRatio(nearest, c));
  }
  std::printf("%d interleaved rounds (each mode without, then with shadows) after warm-up; "
              "light passes: the first shadowed frame's\n", rounds);
}

void VersusFixedPoint(vtkRenderWindow* window, vtkVolume* volume, vtkPARCVolumeMapper* parc,
  vtkImageData* image, int rounds)
{
  std::vector<vtkSmartPointer<vtkVolumeMapper>> mappers;
  std::vector<std::string> names;
  const bool shaded = volume->GetProperty()->GetShade() != 0;
  for (const int model : { vtkPARCVolumeMapper::SHADING_EXACT,
         vtkPARCVolumeMapper::SHADING_QUANTIZED_NORMALS })
  {
    if (model == vtkPARCVolumeMapper::SHADING_QUANTIZED_NORMALS && !shaded)
    {
      break;
    }
    const std::string suffix = shaded
      ? std::string(", ") + vtkPARCVolumeMapper::GetShadingModelAsString(model) + " shading"
      : "";
    for (const int mode : { vtkPARCVolumeMapper::ACCELERATION_NONE,
           vtkPARCVolumeMapper::ACCELERATION_AUTO })
    {
      const auto m = CopyMapper(parc, mode);
      m->SetShadingModel(model);
      mappers.push_back(m);
      names.push_back(std::string(mode == vtkPARCVolumeMapper::ACCELERATION_AUTO
                          ? "PARC, Auto"
                          : "PARC, acceleration none") +
        suffix);
    }
  }
  mappers.push_back(FixedPointLike(parc, image));
  names.push_back("vtkFixedPointVolumeRayCastMapper");
  for (vtkVolumeMapper* m : mappers)
  {
    volume->SetMapper(m);
    if (auto* p = vtkPARCVolumeMapper::SafeDownCast(m))
    {
      WarmUp(window, p);
    }
    window->Render();
  }
  std::vector<std::vector<double>> times(mappers.size());
  for (int r = 0; r < rounds; ++r)
  {
    for (std::size_t i = 0; i < mappers.size(); ++i)
    {
      volume->SetMapper(mappers[i]);
      times[i].push_back(TimedRender(window));
    }
  }
  volume->SetMapper(parc);
  const double fixedMedian = MinMedian(times.back()).second;
  std::printf("| mapper | min (s) | median (s) | FixedPoint median / median |\n|---|---|---|---|\n");
  for (std::size_t i = 0; i < mappers.size(); ++i)
  {
    const auto t = MinMedian(times[i]);
    std::printf("| %s | %.4f | %.4f | %.2fx |\n", names[i].c_str(), t.first, t.second,
      fixedMedian / t.second);
  }
  auto* automatic = vtkPARCVolumeMapper::SafeDownCast(mappers[1]);
  std::printf("Auto used %s; %d interleaved rounds after warm-up\n",
    vtkPARCVolumeMapper::GetAccelerationModeAsString(automatic->GetLastAccelerationMode()), rounds);
}

void BudgetRotation(vtkRenderWindow* window, vtkRenderer* renderer, vtkVolume* volume,
  vtkPARCVolumeMapper* parc, vtkImageData* image, double rate)
{
  constexpr int Frames = 30;
  constexpr double DegreesPerFrame = 3.0;
  constexpr double StillRate = 0.0001; // vtkRenderWindowInteractor's still update rate
  const double budget = 1.0 / rate;
  const auto automatic = CopyMapper(parc, vtkPARCVolumeMapper::ACCELERATION_AUTO);
  vtkNew<vtkFixedPointVolumeRayCastMapper> fixed;
  fixed->SetInputData(image);
  fixed->SetBlendMode(parc->GetBlendMode());
  fixed->SetLockSampleDistanceToInputSpacing(0);
  fixed->SetSampleDistance(parc->GetLastSampleDistance());
  vtkVolumeMapper* mappers[2] = { automatic, fixed };
  const char* names[2] = { "PARC, Auto", "vtkFixedPointVolumeRayCastMapper" };
  vtkCamera* camera = renderer->GetActiveCamera();
  vtkNew<vtkCamera> start;
  start->DeepCopy(camera);
  window->SetDesiredUpdateRate(StillRate);
  for (vtkVolumeMapper* m : mappers)
  {
    volume->SetMapper(m);
    if (auto* p = vtkPARCVolumeMapper::SafeDownCast(m))
    {
      WarmUp(window, p);
    }
    window->Render();
  }
  constexpr int Rounds = 2;
  std::vector<double> times[2], steps, still[2];
  for (int r = 0; r < Rounds; ++r)
  {
    for (int i = 0; i < 2; ++i)
    {
      volume->SetMapper(mappers[i]);
      camera->DeepCopy(start);
      window->SetDesiredUpdateRate(StillRate);
      window->Render();
      for (int f = 0; f < Frames; ++f)
      {
        camera->DeepCopy(start);
        camera->Azimuth(DegreesPerFrame * (f + 1));
        window->SetDesiredUpdateRate(rate);
        times[i].push_back(TimedRender(window));
        if (i == 0)
        {
          steps.push_back(automatic->GetLastImageSampleDistance());
        }
      }
      window->SetDesiredUpdateRate(StillRate);
      still[i].push_back(TimedRender(window));
    }
  }
  camera->DeepCopy(start);
  volume->SetMapper(parc);
  std::printf("| mapper | budget (s) | median frame (s) | slowest frame (s) | frames over the "
              "budget | over 1.5x | still frame (s) |\n|---|---|---|---|---|---|---|\n");
  for (int i = 0; i < 2; ++i)
  {
    const auto t = MinMedian(times[i]);
    const double slowest = *std::max_element(times[i].begin(), times[i].end());
    const auto over = [&](double factor) {
      return std::count_if(times[i].begin(), times[i].end(),
        [&](double x) { return x > factor * budget; });
    };
    std::printf("| %s | %.3f | %.4f | %.4f | %ld of %d | %ld | %.4f |\n", names[i], budget,
      t.second, slowest, static_cast<long>(over(1.0)), Rounds * Frames,
      static_cast<long>(over(1.5)), MinMedian(still[i]).second);
  }
  std::printf("PARC's image sample distance while rotating: median %.2f, from %.2f to %.2f; "
              "its frames used %s\n",
    MinMedian(steps).second, *std::min_element(steps.begin(), steps.end()),
    *std::max_element(steps.begin(), steps.end()),
    vtkPARCVolumeMapper::GetAccelerationModeAsString(automatic->GetLastAccelerationMode()));
}

void SampleCost(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper, vtkVolumeProperty* property,
  int rounds)
{
  const int mode = mapper->GetAccelerationMode();
  const int shade = property->GetShade();
  const int model = mapper->GetShadingModel();
  mapper->SetAccelerationModeToNone();
  // Unshaded, shaded exactly, shaded with quantized normals.
  constexpr int Configurations = 3;
  std::vector<double> casting[Configurations];
  vtkIdType samples = 0, contributing[Configurations] = { 0, 0, 0 }, gradients = 0;
  for (int r = 0; r <= rounds; ++r) // round 0 warms up
  {
    for (int c = 0; c < Configurations; ++c)
    {
      property->SetShade(c > 0);
      mapper->SetShadingModel(c == 2 ? vtkPARCVolumeMapper::SHADING_QUANTIZED_NORMALS
                                     : vtkPARCVolumeMapper::SHADING_EXACT);
      window->Render();
      if (r > 0)
      {
        casting[c].push_back(mapper->GetLastCastingTime());
      }
      samples = c == 0 ? mapper->GetLastSampleCount() : samples;
      contributing[c] = mapper->GetLastContributingSampleCount();
      gradients = c == 1 ? mapper->GetLastGradientCount() : gradients;
    }
  }
  property->SetShade(shade);
  mapper->SetShadingModel(model);
  mapper->SetAccelerationMode(mode);
  const int threads = vtkSMPTools::GetEstimatedNumberOfThreads();
  double minimum[Configurations];
  for (int c = 0; c < Configurations; ++c)
  {
    minimum[c] = MinMedian(casting[c]).first;
  }
  const double perSample = 1e9 * minimum[0] * threads / std::max<vtkIdType>(samples, 1);
  auto perShaded = [&](int c) {
    return 1e9 * (minimum[c] - minimum[0]) * threads / std::max<vtkIdType>(contributing[c], 1);
  };
  std::printf("| casting, unshaded (s) | shaded, exact (s) | shaded, quantized normals (s) | "
              "samples | contributing | gradients (exact) | ns per sample per thread "
              "(unshaded) | extra ns per contributing shaded sample per thread: exact | "
              "quantized normals |\n|---|---|---|---|---|---|---|---|---|\n");
  std::printf("| %.4f | %.4f | %.4f | %lld | %lld | %lld | %.1f | %.1f | %.1f |\n", minimum[0],
    minimum[1], minimum[2], static_cast<long long>(samples),
    static_cast<long long>(contributing[1]), static_cast<long long>(gradients), perSample,
    perShaded(1), perShaded(2));
  std::printf("minimum casting times of %d interleaved rounds, %d threads\n", rounds, threads);
}


void EditCost(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper, vtkVolumeProperty* property,
  int rounds)
{
  WarmUp(window, mapper);
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity();
  double node[4];
  opacity->GetNodeValue(opacity->GetSize() / 2, node);
  const double range = mapper->GetInput()->GetScalarRange()[1] - mapper->GetInput()->GetScalarRange()[0];
  std::vector<double> edited, warm;
  std::vector<std::string> modes;
  for (int r = 0; r < rounds; ++r)
  {
    double moved[4] = { node[0] + (r % 2 == 0 ? 0.01 : 0.0) * range, node[1], node[2], node[3] };
    opacity->SetNodeValue(opacity->GetSize() / 2, moved);
    edited.push_back(TimedRender(window));
    modes.push_back(vtkPARCVolumeMapper::GetAccelerationModeAsString(mapper->GetLastAccelerationMode()));
    warm.push_back(TimedRender(window));
  }
  const auto e = MinMedian(edited), w = MinMedian(warm);
  std::printf("| frame | min (s) | median (s) |\n|---|---|---|\n| right after an edit | %.4f | "
              "%.4f |\n| warm, the next | %.4f | %.4f |\n",
    e.first, e.second, w.first, w.second);
  std::printf("edit frame / warm frame (medians): %.2fx; modes of the edit frames:", e.second / w.second);
  for (const std::string& m : modes)
  {
    std::printf(" %s", m.c_str());
  }
  std::printf("\n");
}

void AutoTrialFrames(vtkRenderWindow* window, vtkVolume* volume, vtkPARCVolumeMapper* mapper,
  int rounds)
{
  constexpr int MaxFrames = 12, SettledFrames = 3;
  std::printf("| round | frames: mode (s) | first frame (s) | settled (s) | slowest trial "
              "/ settled |\n|---|---|---|---|---|\n");
  std::vector<double> ratios;
  for (int r = 0; r < rounds; ++r)
  {
    const auto fresh = CopyMapper(mapper, vtkPARCVolumeMapper::ACCELERATION_AUTO);
    volume->SetMapper(fresh);
    std::vector<double> times;
    std::string frames;
    int settledAfter = -1;
    for (int f = 0; f < MaxFrames; ++f)
    {
      if (settledAfter >= 0 && static_cast<int>(times.size()) - settledAfter >= SettledFrames)
      {
        break;
      }
      times.push_back(TimedRender(window));
      frames += std::string(f > 0 ? ", " : "") +
        vtkPARCVolumeMapper::GetAccelerationModeAsString(fresh->GetLastAccelerationMode()) +
        " (" + std::to_string(times.back()).substr(0, 6) + ")";
      if (settledAfter < 0 && fresh->GetAutoTrialsRemaining() == 0)
      {
        settledAfter = static_cast<int>(times.size());
      }
    }
    if (settledAfter < 0)
    {
      settledAfter = static_cast<int>(times.size());
    }
    const double settled =
      MinMedian(std::vector<double>(times.begin() + settledAfter, times.end())).second;
    const double slowest = settledAfter > 1
      ? *std::max_element(times.begin() + 1, times.begin() + settledAfter)
      : settled;
    ratios.push_back(slowest / settled);
    std::printf("| %d | %s | %.4f | %.4f | %.2fx |\n", r + 1, frames.c_str(), times[0], settled,
      ratios.back());
  }
  std::printf("slowest trial frame / settled frame: at most %.2fx over %d rounds (the first "
              "frame, which builds, not counted)\n",
    *std::max_element(ratios.begin(), ratios.end()), rounds);
  volume->SetMapper(mapper);
}

void ThreadScaling(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper, int rounds)
{
  const int all = vtkSMPTools::GetEstimatedNumberOfThreads();
  const int modes[] = { vtkPARCVolumeMapper::ACCELERATION_NONE,
    vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER, vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER,
    vtkPARCVolumeMapper::ACCELERATION_BOTH, vtkPARCVolumeMapper::ACCELERATION_SUPERCELL_WALK,
    vtkPARCVolumeMapper::ACCELERATION_AUTO };
  std::printf("| mode | 1 thread, median (s) | %d threads, median (s) | speedup | casting, 1 "
              "thread (s) | casting, %d threads (s) | casting speedup | passes, 1 thread (s) | "
              "passes, %d threads (s) |\n|---|---|---|---|---|---|---|---|---|\n",
    all, all, all);
  for (int mode : modes)
  {
    mapper->SetAccelerationMode(mode);
    WarmUp(window, mapper);
    std::vector<double> frames[2], casting[2], passes[2];
    for (int r = 0; r < rounds; ++r)
    {
      for (int i = 0; i < 2; ++i)
      {
        vtkSMPTools::Initialize(i == 0 ? 1 : all);
        frames[i].push_back(TimedRender(window));
        casting[i].push_back(mapper->GetLastCastingTime());
        passes[i].push_back(mapper->GetLastProjectionTime());
      }
    }
    double median[3][2];
    for (int i = 0; i < 2; ++i)
    {
      median[0][i] = MinMedian(frames[i]).second;
      median[1][i] = MinMedian(casting[i]).second;
      median[2][i] = MinMedian(passes[i]).second;
    }
    const std::string used =
      vtkPARCVolumeMapper::GetAccelerationModeAsString(mapper->GetLastAccelerationMode());
    std::printf("| %s | %.4f | %.4f | %.2fx | %.4f | %.4f | %.2fx | %.4f | %.4f |\n",
      (mode == vtkPARCVolumeMapper::ACCELERATION_AUTO ? "Auto: " + used : used).c_str(),
      median[0][0], median[0][1], median[0][0] / median[0][1], median[1][0], median[1][1],
      median[1][0] / median[1][1], median[2][0], median[2][1]);
  }
  vtkSMPTools::Initialize(all);
}

void SweepSupercells(vtkRenderWindow* window, vtkPARCVolumeMapper* mapper,
  const std::vector<double>& sizes, int repeat)
{
  std::printf("| supercell | PC supercells | polygons | samples | projection (s) | casting (s) "
              "| total (s) | mode |\n|---|---|---|---|---|---|---|---|\n");
  for (double s : sizes)
  {
    mapper->SetSupercellSize(s, s, s);
    const Measurement m = Measure(window, mapper, repeat);
    std::printf("| %g | %lld of %lld (%.1f%%) | %lld | %lld | %.4f | %.4f | %.4f | %s |\n", s,
      m.Contributing, m.Supercells, 100.0 * m.Contributing / std::max(1LL, m.Supercells),
      m.Polygons, m.Samples, m.Projection, m.Casting, m.Total, m.Mode.c_str());
  }
}
}
