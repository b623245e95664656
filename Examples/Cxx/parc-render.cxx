// parc-render: renders a volume file with vtkPARCVolumeMapper to a PNG file and prints
// the statistics of the render (optionally as JSON, optionally side by side with
// vtkFixedPointVolumeRayCastMapper at the same sample distance).
#include "parcAccuracyStudy.h"
#include "parcRenderStudies.h"
#include "parcRenderTools.h"
#include "parcViewer.h"
#include "parcVolumeIO.h"
#include "vtkPARCMultiVolume.h"
#include "vtkPARCVolumeMapper.h"

#include <vtkCamera.h>
#include <vtkContourValues.h>
#include <vtkDataArray.h>
#include <vtkFixedPointVolumeRayCastMapper.h>
#include <vtkImageData.h>
#include <vtkImageResample.h>
#include <vtkLight.h>
#include <vtkNew.h>
#include <vtkPiecewiseFunction.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkSMPTools.h>
#include <vtkVolume.h>
#include <vtkVolumeProperty.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <iostream>
#include <utility>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace
{
using parctools::FixedPointLike;
using parctools::TimedRender;
using parctools::WarmUp;
using parcstudies::AutoTrialFrames;
using parcstudies::BudgetRotation;
using parcstudies::CompareAccelerationModes;
using parcstudies::EditCost;
using parcstudies::SampleCost;
using parcstudies::ShadowTable;
using parcstudies::SweepSupercells;
using parcstudies::ThreadScaling;
using parcstudies::VersusFixedPoint;

const char* Usage = R"(usage: parc-render VOLUME [options]
  VOLUME                .vti .mha .mhd .nii .nii.gz .nrrd .nhdr .vtk .slc or NAME_XxYxZ_TYPE.raw
  --output FILE.png     image to write (default: parc.png)
  --blend MODE          composite (default), mip, minip, average, additive, iso
  --tf NAME|FILE        transfer function: ramp, mri, ct-skin-bone, ct-bone, mip (default:
                        ramp, mip for mip/minip) or a file of "scalar opacity r g b" lines
  --iso VALUE           iso value for --blend iso (default: middle of the scalar range)
  --shade               shade with the headlight (on by default for iso)
  --shading-model M     exact (default) or quantized (quantized voxel normals, as
                        vtkFixedPointVolumeRayCastMapper shades)
  --specular-power P    the volume property's specular power (default VTK's, 10)
  --size N | WxH        image size in pixels (default 300)
  --azimuth DEG --elevation DEG --zoom F     camera around the volume (after a reset)
  --camera-position X,Y,Z [--focal-point X,Y,Z] [--view-up X,Y,Z]   explicit camera
  --parallel            parallel projection (default perspective)
  --sample-distance D   world units (default: half the smallest spacing)
  --image-sample-distance D  rays every D pixels (default 1; turns the mapper's
                        AutoAdjustSampleDistances off)
  --acceleration MODE   none, depth, color, both, walk (the supercells walked on the CPU,
                        no GL pass), auto (default)
  --supercell M,N,P     supercell size in cells (default: the mapper's 4,4,4, scaled by
                        Auto's search in auto)
  --compare-acceleration  also render with every acceleration mode, side by side: a table
                        of samples, cells, polygons, times, speedup and exactness
  --sweep-supercells S1,S2,...  also render with cubic supercells of these sizes (table)
  --repeat N            timed renders after the warm-up renders (default 1); the
                        warm-up includes the frames on which Auto tries each pass
  --compare-fixed-point also render with vtkFixedPointVolumeRayCastMapper
  --versus-fixed-point R  R rounds of interleaved renders (this mapper with acceleration
                        none and auto, with each shading model when shaded, and
                        vtkFixedPointVolumeRayCastMapper at the same sample distance):
                        minimum and median times (table)
  --sample-cost R       R interleaved rounds of the scene unshaded and shaded with each
                        shading model, acceleration none: casting ns per sample per
                        thread, and the extra ns per contributing shaded sample (table)
  --accuracy-curve R    what accuracy costs in time: every mapper (this one in each
                        acceleration mode and shading model, FixedPoint, GPU) at sample
                        distances 2 to --finest-distance D (default 1/16) voxel (the
                        smallest spacing) and image sample distances 1 and 2, R timed
                        interleaved frames each: median and spread, RMSE and maximum of the
                        8-bit image against this mapper's exact cast at --reference-distance
                        D (default 1/64 voxel; its convergence shown) and against the
                        mapper's own cast there, and the float RMSE (table; with --csv FILE
                        also rows appended to FILE, named by --scene NAME)
  --edit-cost R         R rounds of a transfer-function edit: the frame right after the
                        edit against the warm frame after it (minimum, median, ratio)
  --auto-trials R       R rounds of a fresh mapper in Auto: each frame until Auto has
                        settled (its mode and wall time), then 3 settled frames; the
                        slowest trial frame against the settled one (table)
  --thread-scaling R    R interleaved rounds of one thread and all threads per acceleration
                        mode: median frame times and their ratio (table)
  --threads N           threads for vtkSMPTools (default: all cores)
  --multisamples N      the window's multisampling (default 0, as VTK's volume tests set
                        it: VTK's default 8 costs every mapper alike, about 3.5 ms a frame
                        at 400^2 on llvmpipe, for nothing a volume image shows)
  --resample F          resample the volume by F along every axis first (trilinear; F^3
                        times the voxels, spacing divided by F)
  --budget RATE         a simulated 30-frame rotation (3 degrees a frame) at a desired
                        update rate of RATE frames per second, then a still frame, for this
                        mapper (Auto) and vtkFixedPointVolumeRayCastMapper, each with
                        AutoAdjustSampleDistances, rotations interleaved (A B A B): frame
                        times against the budget 1/RATE (table)
  --memory              print the bytes the mapper holds, per structure
  --bricked-copy        the mapper samples a copy of the scalars in bricks (BrickedCopy)
  --second VOLUME       a second volume in the same image (vtkPARCMultiVolume, input
                        port 1), its centre on the first's; with --second-blend MODE
                        (default composite), --second-tf NAME|FILE and --second-iso VALUE
                        like --blend, --tf and --iso (not with the FixedPoint options)
  --floor               a second volume: the paper's Figure 13 floor, a voxelized slab of
                        57x12x57 samples under the first volume (y up), as an isosurface
  --light X,Y,Z         a positional light at world point X,Y,Z (repeatable; replaces the
                        headlight; its cone is wide open and it does not fade with distance;
                        the lights share an intensity of 1)
  --shadows             the renderer uses shadows: every light casts them (attenuation 1)
  --shadow-table R      the paper's Table 3: R interleaved rounds of frames without and
                        with shadows for acceleration none, depth, colour and Auto (each
                        on primary and shadow rays): cells, casting and total times,
                        light-pass time, ratios beside the paper's (needs --light)
  --interactive         open a window on the volume instead: trackball interaction, keys
                        for blend mode, transfer function, shading, acceleration, image
                        sample distance and screenshots ('h' lists them), a status line
  --playback FILE       with --interactive: play a vtkInteractorEventRecorder log instead
                        of waiting for a user, then print the viewer's state (JSON)
  --screenshot-prefix P with --interactive: screenshots are written as P-N.png
  --progress            a progress line (set-up steps, casting) on stderr for every
                        render; without it, for renders over a second when stderr is
                        a terminal
  --json                print statistics as JSON
  --help
)";

struct Options
{
  std::string Volume, Output = "parc.png", Blend = "composite", TF, Acceleration = "auto";
  std::string Second, SecondBlend = "composite", SecondTF, Csv, Scene;
  double FinestDistance = 1.0 / 16.0, ReferenceDistance = 1.0 / 64.0, Resample = 1.0;
  double SecondIso = 0.0;
  bool HasSecondIso = false;
  double Iso = 0.0, Azimuth = 30.0, Elevation = 20.0, Zoom = 1.0, SampleDistance = 0.0;
  bool HasIso = false, Shade = false, Parallel = false, Compare = false, Json = false;
  bool HasPosition = false, HasFocal = false, CompareAcceleration = false, Memory = false;
  double BudgetRate = 0.0;
  int ShadowTableRounds = 0, Versus = 0, SampleCost = 0, Threads = 0, Accuracy = 0;
  int MultiSamples = 0;
  int EditCost = 0, ThreadScaling = 0, AutoTrials = 0;
  double Supercell[3] = { 4, 4, 4 };
  bool SupercellSet = false; ///< else the mapper's, which Auto scales
  std::vector<double> Sweep;
  double Position[3] = { 0, 0, 0 }, Focal[3] = { 0, 0, 0 }, ViewUp[3] = { 0, 0, 0 };
  bool HasViewUp = false, Interactive = false, Progress = false;
  double ImageSampleDistance = 0.0; ///< 0: the mapper's default
  std::string Playback, ScreenshotPrefix = "parc-view";
  int Width = 300, Height = 300, Repeat = 1;
  std::vector<std::array<double, 3>> Lights;
  bool Shadows = false, Floor = false, QuantizedNormals = false, BrickedCopy = false;
  double SpecularPower = -1.0; ///< below 0: the property's default
};

[[noreturn]] void Fail(const std::string& message)
{
  std::cerr << "parc-render: " << message << std::endl;
  std::exit(2);
}

/// Whether --shading-model names the quantized normals (else exact shading).
bool ShadingModelNamed(const std::string& name)
{
  if (name != "exact" && name != "quantized")
  {
    Fail("--shading-model takes exact or quantized");
  }
  return name == "quantized";
}

double ToNumber(const std::string& option, const std::string& text)
{
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
  {
    Fail("option " + option + " needs a number, got '" + text + "'");
  }
  return v;
}

void ToTriple(const std::string& option, const std::string& text, double out[3])
{
  std::stringstream in(text);
  std::string part;
  for (int i = 0; i < 3; ++i)
  {
    if (!std::getline(in, part, ','))
    {
      Fail("option " + option + " needs X,Y,Z, got '" + text + "'");
    }
    out[i] = ToNumber(option, part);
  }
}

Options Parse(int argc, char* argv[])
{
  Options o;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc)
      {
        Fail("option " + a + " needs a value");
      }
      return argv[++i];
    };
    if (a == "--help" || a == "-h")
    {
      std::cout << Usage;
      std::exit(0);
    }
    else if (a == "--output") { o.Output = value(); }
    else if (a == "--blend") { o.Blend = value(); }
    else if (a == "--tf") { o.TF = value(); }
    else if (a == "--iso") { o.Iso = ToNumber(a, value()); o.HasIso = true; }
    else if (a == "--shade") { o.Shade = true; }
    else if (a == "--shading-model") { o.QuantizedNormals = ShadingModelNamed(value()); }
    else if (a == "--specular-power") { o.SpecularPower = ToNumber(a, value()); }
    else if (a == "--azimuth") { o.Azimuth = ToNumber(a, value()); }
    else if (a == "--elevation") { o.Elevation = ToNumber(a, value()); }
    else if (a == "--zoom") { o.Zoom = ToNumber(a, value()); }
    else if (a == "--camera-position") { ToTriple(a, value(), o.Position); o.HasPosition = true; }
    else if (a == "--focal-point") { ToTriple(a, value(), o.Focal); o.HasFocal = true; }
    else if (a == "--view-up") { ToTriple(a, value(), o.ViewUp); o.HasViewUp = true; }
    else if (a == "--interactive") { o.Interactive = true; }
    else if (a == "--progress") { o.Progress = true; }
    else if (a == "--image-sample-distance") { o.ImageSampleDistance = ToNumber(a, value()); }
    else if (a == "--playback") { o.Playback = value(); }
    else if (a == "--screenshot-prefix") { o.ScreenshotPrefix = value(); }
    else if (a == "--parallel") { o.Parallel = true; }
    else if (a == "--sample-distance") { o.SampleDistance = ToNumber(a, value()); }
    else if (a == "--acceleration") { o.Acceleration = value(); }
    else if (a == "--repeat") { o.Repeat = static_cast<int>(ToNumber(a, value())); }
    else if (a == "--compare-fixed-point") { o.Compare = true; }
    else if (a == "--budget") { o.BudgetRate = ToNumber(a, value()); }
    else if (a == "--versus-fixed-point") { o.Versus = static_cast<int>(ToNumber(a, value())); }
    else if (a == "--sample-cost") { o.SampleCost = static_cast<int>(ToNumber(a, value())); }
    else if (a == "--accuracy-curve") { o.Accuracy = static_cast<int>(ToNumber(a, value())); }
    else if (a == "--finest-distance") { o.FinestDistance = ToNumber(a, value()); }
    else if (a == "--reference-distance") { o.ReferenceDistance = ToNumber(a, value()); }
    else if (a == "--csv") { o.Csv = value(); }
    else if (a == "--resample") { o.Resample = ToNumber(a, value()); }
    else if (a == "--scene") { o.Scene = value(); }
    else if (a == "--edit-cost") { o.EditCost = static_cast<int>(ToNumber(a, value())); }
    else if (a == "--auto-trials") { o.AutoTrials = static_cast<int>(ToNumber(a, value())); }
    else if (a == "--thread-scaling") { o.ThreadScaling = static_cast<int>(ToNumber(a, value())); }
    else if (a == "--threads") { o.Threads = static_cast<int>(ToNumber(a, value())); }
    else if (a == "--multisamples") { o.MultiSamples = static_cast<int>(ToNumber(a, value())); }
    else if (a == "--memory") { o.Memory = true; }
    else if (a == "--bricked-copy") { o.BrickedCopy = true; }
    else if (a == "--supercell") { ToTriple(a, value(), o.Supercell); o.SupercellSet = true; }
    else if (a == "--compare-acceleration") { o.CompareAcceleration = true; }
    else if (a == "--sweep-supercells")
    {
      std::stringstream in(value());
      for (std::string part; std::getline(in, part, ',');)
      {
        o.Sweep.push_back(ToNumber(a, part));
      }
    }
    else if (a == "--json") { o.Json = true; }
    else if (a == "--light") { o.Lights.emplace_back(); ToTriple(a, value(), o.Lights.back().data()); }
    else if (a == "--shadows") { o.Shadows = true; }
    else if (a == "--second") { o.Second = value(); }
    else if (a == "--floor") { o.Floor = true; }
    else if (a == "--shadow-table") { o.ShadowTableRounds = static_cast<int>(ToNumber(a, value())); }
    else if (a == "--second-blend") { o.SecondBlend = value(); }
    else if (a == "--second-tf") { o.SecondTF = value(); }
    else if (a == "--second-iso") { o.SecondIso = ToNumber(a, value()); o.HasSecondIso = true; }
    else if (a == "--size")
    {
      const std::string v = value();
      const auto x = v.find('x');
      o.Width = static_cast<int>(ToNumber(a, v.substr(0, x)));
      o.Height = x == std::string::npos ? o.Width : static_cast<int>(ToNumber(a, v.substr(x + 1)));
    }
    else if (!a.empty() && a[0] == '-') { Fail("unknown option " + a + " (see --help)"); }
    else if (o.Volume.empty()) { o.Volume = a; }
    else { Fail("more than one volume given: " + a); }
  }
  if (o.Volume.empty())
  {
    Fail("no volume file given (see --help)");
  }
  if (o.Width < 1 || o.Height < 1 || o.Width > 8192 || o.Height > 8192)
  {
    Fail("--size must be between 1 and 8192");
  }
  if (o.Repeat < 1 || o.Zoom <= 0.0 || o.SampleDistance < 0.0)
  {
    Fail("--repeat must be >= 1, --zoom and --sample-distance > 0");
  }
  const std::filesystem::path folder = std::filesystem::path(o.Output).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder))
  {
    Fail("cannot write " + o.Output + ": no such folder " + folder.string());
  }
  if (o.ShadowTableRounds < 0 || o.ShadowTableRounds > 0 && o.Lights.empty())
  {
    Fail("--shadow-table takes a positive number and needs --light");
  }
  if (!(o.FinestDistance > 0.0) || !(o.ReferenceDistance > 0.0) ||
    o.ReferenceDistance >= o.FinestDistance)
  {
    Fail("--finest-distance and --reference-distance take positive distances, the "
         "reference the smaller");
  }
  if (!(o.Resample > 0.0))
  {
    Fail("--resample takes a positive factor");
  }
  if (!o.Playback.empty() && !o.Interactive)
  {
    Fail("--playback plays an interaction: it needs --interactive");
  }
  if (!o.Playback.empty() && !std::filesystem::is_regular_file(o.Playback))
  {
    Fail("no such interaction log: " + o.Playback);
  }
  if (o.ImageSampleDistance != 0.0 && !(o.ImageSampleDistance >= 1.0))
  {
    Fail("--image-sample-distance takes a distance of at least 1 pixel");
  }
  if (o.BudgetRate < 0.0)
  {
    Fail("--budget takes a positive rate in frames per second");
  }
  if (o.Versus < 0 || o.SampleCost < 0 || o.Threads < 0 || o.MultiSamples < 0 ||
    o.Accuracy < 0 || o.EditCost < 0 || o.ThreadScaling < 0 || o.AutoTrials < 0)
  {
    Fail("--versus-fixed-point, --sample-cost, --accuracy-curve, --edit-cost, "
         "--thread-scaling, --auto-trials and --threads take a positive number");
  }
  return o;
}

/// The value named name in names; fails with the list of names otherwise.
int Lookup(const std::vector<std::pair<std::string, int>>& names, const std::string& name,
  const std::string& what)
{
  std::string list;
  for (const auto& n : names)
  {
    if (n.first == name)
    {
      return n.second;
    }
    list += (list.empty() ? "" : ", ") + n.first;
  }
  Fail("unknown " + what + " " + name + " (" + list + ")");
}

int BlendMode(const std::string& name)
{
  return Lookup({ { "composite", vtkVolumeMapper::COMPOSITE_BLEND },
                  { "mip", vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND },
                  { "minip", vtkVolumeMapper::MINIMUM_INTENSITY_BLEND },
                  { "average", vtkVolumeMapper::AVERAGE_INTENSITY_BLEND },
                  { "additive", vtkVolumeMapper::ADDITIVE_BLEND },
                  { "iso", vtkVolumeMapper::ISOSURFACE_BLEND } },
    name, "blend mode");
}

int AccelerationMode(const std::string& name)
{
  return Lookup({ { "none", vtkPARCVolumeMapper::ACCELERATION_NONE },
                  { "depth", vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER },
                  { "color", vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER },
                  { "both", vtkPARCVolumeMapper::ACCELERATION_BOTH },
                  { "walk", vtkPARCVolumeMapper::ACCELERATION_SUPERCELL_WALK },
                  { "auto", vtkPARCVolumeMapper::ACCELERATION_AUTO } },
    name, "acceleration mode");
}




}

/// Reads a volume file; fails with the reader's message.
void Read(const std::string& path, vtkImageData* image)
{
  std::string error;
  if (!parcio::ReadVolume(path, image, error))
  {
    Fail(error);
  }
}

/// The property of a volume rendered with blend: the transfer function tf (a default for
/// the blend mode when empty), the iso value (the middle of the range unless given), shaded
/// when asked and always for isosurfaces.
void SetUpProperty(vtkImageData* image, int blend, const std::string& tf, bool hasIso,
  double isoValue, bool shade, vtkVolumeProperty* property)
{
  double range[2];
  image->GetScalarRange(range);
  const bool extreme = blend == vtkVolumeMapper::MAXIMUM_INTENSITY_BLEND ||
    blend == vtkVolumeMapper::MINIMUM_INTENSITY_BLEND;
  std::string error;
  if (!parcio::LoadTransferFunction(tf.empty() ? (extreme ? "mip" : "ramp") : tf, range,
        property, error))
  {
    Fail(error);
  }
  property->SetInterpolationTypeToLinear();
  const double iso = hasIso ? isoValue : 0.5 * (range[0] + range[1]);
  if (blend == vtkVolumeMapper::ISOSURFACE_BLEND)
  {
    property->GetIsoSurfaceValues()->SetValue(0, iso);
    property->GetScalarOpacity()->AddPoint(iso, 1.0);
  }
  property->SetShade(shade || blend == vtkVolumeMapper::ISOSURFACE_BLEND);
}

/// --interactive: the viewer on the scene set up; with --playback, its state afterwards as
/// JSON (the camera to full precision, so that a fresh render can be compared).
int Interact(const Options& o, int blend, int acceleration, vtkRenderWindow* window,
  vtkRenderer* renderer, vtkPARCVolumeMapper* mapper, vtkVolumeProperty* property,
  vtkImageData* image)
{
  window->SetOffScreenRendering(0);
  parcviewer::Settings settings;
  settings.Playback = o.Playback;
  settings.ScreenshotPrefix = o.ScreenshotPrefix;
  settings.SetUp = [&o, image](int b, const std::string& tf, vtkVolumeProperty* p) {
    SetUpProperty(image, b, tf, o.HasIso, o.Iso, false, p);
  };
  parcviewer::State state;
  state.Blend = blend;
  state.TF = o.TF;
  state.Shading = o.Shade ? (o.QuantizedNormals ? 2 : 1) : 0;
  state.Acceleration = acceleration;
  const parcviewer::Frames frames = parcviewer::Run(settings, window, renderer, mapper, property, state);
  if (!o.Playback.empty())
  {
    vtkCamera* c = renderer->GetActiveCamera();
    const auto triple = [](const double* v) {
      char text[128];
      std::snprintf(text, sizeof(text), "[%.17g, %.17g, %.17g]", v[0], v[1], v[2]);
      return std::string(text);
    };
    std::cout << "{\n  \"frames\": " << frames.All << ",\n  \"interactive_frames\": "
              << frames.Interactive << ",\n  \"blend\": " << state.Blend
              << ",\n  \"tf\": \"" << state.TF << "\",\n  \"shading\": " << state.Shading
              << ",\n  \"acceleration\": " << state.Acceleration
              << ",\n  \"image_sample_distance\": " << state.ImageSampleDistance
              << ",\n  \"last_interactive\": " << mapper->GetLastInteractive()
              << ",\n  \"last_image_sample_distance\": " << mapper->GetLastImageSampleDistance()
              << ",\n  \"camera_position\": " << triple(c->GetPosition())
              << ",\n  \"focal_point\": " << triple(c->GetFocalPoint())
              << ",\n  \"view_up\": " << triple(c->GetViewUp()) << "\n}" << std::endl;
  }
  return 0;
}

int main(int argc, char* argv[])
{
  const Options o = Parse(argc, argv);
  if (o.Threads > 0)
  {
    vtkSMPTools::Initialize(o.Threads);
  }
  const int blend = BlendMode(o.Blend);
  const int acceleration = AccelerationMode(o.Acceleration);
  if (o.Floor && !o.Second.empty())
  {
    Fail("--floor and --second both name the second volume");
  }
  if ((o.Floor || !o.Second.empty()) && (o.Compare || o.Versus > 0 || o.SampleCost > 0 || o.Accuracy > 0 ||
                             o.EditCost > 0))
  {
    Fail("--second and --floor do not go with --compare-fixed-point, --versus-fixed-point, "
         "--sample-cost, --accuracy-curve or --edit-cost");
  }
  vtkNew<vtkImageData> image;
  Read(o.Volume, image);
  if (o.Resample != 1.0)
  {
    vtkNew<vtkImageResample> resample;
    resample->SetInputData(image);
    resample->SetInterpolationModeToLinear();
    for (int axis = 0; axis < 3; ++axis)
    {
      resample->SetAxisMagnificationFactor(axis, o.Resample);
    }
    resample->Update();
    image->DeepCopy(resample->GetOutput());
  }
  vtkNew<vtkVolumeProperty> property;
  SetUpProperty(image, blend, o.TF, o.HasIso, o.Iso, o.Shade, property);
  if (o.SpecularPower >= 0.0)
  {
    property->SetSpecularPower(o.SpecularPower);
  }

  vtkNew<vtkPARCVolumeMapper> mapper;
  mapper->SetInputData(image);
  mapper->SetBlendMode(blend);
  mapper->SetAccelerationMode(acceleration);
  if (o.SupercellSet)
  {
    mapper->SetSupercellSize(o.Supercell);
  }
  mapper->SetSampleDistance(o.SampleDistance);
  mapper->SetBrickedCopy(o.BrickedCopy);
  mapper->SetShadingModel(o.QuantizedNormals ? vtkPARCVolumeMapper::SHADING_QUANTIZED_NORMALS
                                             : vtkPARCVolumeMapper::SHADING_EXACT);
  if (o.ImageSampleDistance > 0.0)
  {
    mapper->SetAutoAdjustSampleDistances(0);
    mapper->SetImageSampleDistance(o.ImageSampleDistance);
  }
  vtkNew<vtkVolume> volume;
  volume->SetMapper(mapper);
  volume->SetProperty(property);

  vtkNew<vtkRenderer> renderer;
  // A second volume: both through one vtkPARCMultiVolume; a file's centre on the first's,
  // the floor under the first.
  vtkNew<vtkImageData> secondImage;
  vtkNew<vtkVolumeProperty> secondProperty;
  vtkNew<vtkVolume> secondVolume;
  vtkNew<vtkPARCMultiVolume> multiVolume;
  if (!o.Second.empty() || o.Floor)
  {
    int secondBlend = vtkVolumeMapper::ISOSURFACE_BLEND;
    if (o.Floor)
    {
      parcio::MakeFloor(image->GetBounds(), secondImage);
      constexpr double Grey[3] = { 0.85, 0.85, 0.8 };
      parcio::SetUpSurfaceProperty(parcio::FloorIsoValue, Grey, secondProperty);
    }
    else
    {
      Read(o.Second, secondImage);
      secondBlend = BlendMode(o.SecondBlend);
      SetUpProperty(secondImage, secondBlend, o.SecondTF, o.HasSecondIso, o.SecondIso, o.Shade,
        secondProperty);
      const double* a = image->GetCenter();
      const double* b = secondImage->GetCenter();
      secondVolume->SetPosition(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    }
    mapper->SetInputDataObject(1, secondImage);
    mapper->SetInputBlendMode(1, secondBlend);
    secondVolume->SetProperty(secondProperty);
    multiVolume->SetMapper(mapper);
    multiVolume->SetVolume(volume, 0);
    multiVolume->SetVolume(secondVolume, 1);
  }
  vtkVolume* shown = o.Floor || !o.Second.empty() ? multiVolume.Get() : volume.Get();
  renderer->AddVolume(shown);
  renderer->SetBackground(0.0, 0.0, 0.0);
  renderer->SetUseShadows(o.Shadows ? 1 : 0);
  for (const auto& position : o.Lights)
  {
    vtkNew<vtkLight> light;
    light->SetLightTypeToSceneLight();
    light->SetPositional(1);
    light->SetConeAngle(180.0);
    light->SetPosition(position.data());
    light->SetFocalPoint(image->GetCenter());
    light->SetIntensity(1.0 / o.Lights.size());
    renderer->AddLight(light);
  }
  // VTK's render windows here are X windows, also off screen: without a display VTK aborts.
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    Fail("no X display (DISPLAY is not set): run it on a desktop or under Xvfb "
         "(scripts/xvfb.sh parc-render ...)");
  }
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(o.MultiSamples);
  window->SetSize(o.Width, o.Height);
  window->AddRenderer(renderer);

  vtkCamera* camera = renderer->GetActiveCamera();
  camera->SetParallelProjection(o.Parallel ? 1 : 0);
  renderer->ResetCamera();
  if (o.HasPosition)
  {
    camera->SetPosition(o.Position);
    if (o.HasFocal)
    {
      camera->SetFocalPoint(o.Focal);
    }
    if (o.HasViewUp)
    {
      camera->SetViewUp(o.ViewUp);
    }
  }
  else
  {
    camera->Azimuth(o.Azimuth);
    camera->Elevation(o.Elevation);
    camera->OrthogonalizeViewUp();
  }
  camera->Zoom(o.Zoom);
  renderer->ResetCameraClippingRange();
  std::unique_ptr<parctools::ProgressLine> progress;
  if (o.Progress || isatty(STDERR_FILENO))
  {
    progress = std::make_unique<parctools::ProgressLine>(window, mapper, o.Progress);
  }
  if (o.Interactive)
  {
    return Interact(o, blend, acceleration, window, renderer, mapper, property, image);
  }

  WarmUp(window, mapper);
  double wall = 0.0, casting = 0.0, total = 0.0;
  for (int r = 0; r < o.Repeat; ++r)
  {
    wall += TimedRender(window);
    casting += mapper->GetLastCastingTime();
    total += mapper->GetLastRenderTime();
  }
  wall /= o.Repeat;
  casting /= o.Repeat;
  total /= o.Repeat;

  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->Update();
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(o.Output.c_str());
  writer->SetInputConnection(grab->GetOutputPort());
  writer->Write();
  if (writer->GetErrorCode() != 0)
  {
    Fail("cannot write " + o.Output);
  }

  double fixedWall = -1.0;
  // vtkFixedPointVolumeRayCastMapper has no isosurface or average-intensity mode.
  const bool fixedSupports = blend != vtkVolumeMapper::ISOSURFACE_BLEND &&
    blend != vtkVolumeMapper::AVERAGE_INTENSITY_BLEND;
  if (o.Compare && fixedSupports)
  {
    volume->SetMapper(FixedPointLike(mapper, image));
    window->Render();
    fixedWall = 0.0;
    for (int r = 0; r < o.Repeat; ++r)
    {
      fixedWall += TimedRender(window);
    }
    fixedWall /= o.Repeat;
  }

  const std::string accel =
    vtkPARCVolumeMapper::GetAccelerationModeAsString(mapper->GetLastAccelerationMode());
  const vtkIdType samples = mapper->GetLastSampleCount();
  if (o.CompareAcceleration || !o.Sweep.empty() || o.Versus > 0 || o.SampleCost > 0 ||
    o.Accuracy > 0 || o.EditCost > 0 || o.ThreadScaling > 0)
  {
    volume->SetMapper(mapper);
  }
  if (o.Memory)
  {
    mapper->PrintMemory(std::cout);
    std::cout << "Input scalars (bytes): "
              << image->GetPointData()->GetScalars()->GetActualMemorySize() * 1024 << "\n";
  }
  if (o.Versus > 0)
  {
    VersusFixedPoint(window, volume, mapper, image, o.Versus);
  }
  if (o.BudgetRate > 0.0)
  {
    BudgetRotation(window, renderer, volume, mapper, image, o.BudgetRate);
  }
  if (o.SampleCost > 0)
  {
    SampleCost(window, mapper, property, o.SampleCost);
  }
  if (o.Accuracy > 0)
  {
    parcaccuracy::Settings study;
    study.Rounds = o.Accuracy;
    study.FinestDistance = o.FinestDistance;
    study.ReferenceDistance = o.ReferenceDistance;
    study.Csv = o.Csv;
    study.Scene = o.Scene.empty() ? std::filesystem::path(o.Volume).filename().string() : o.Scene;
    parcaccuracy::Study(study, window, volume, mapper, image);
  }
  if (o.EditCost > 0)
  {
    EditCost(window, mapper, property, o.EditCost);
  }
  if (o.ThreadScaling > 0)
  {
    ThreadScaling(window, mapper, o.ThreadScaling);
  }
  if (o.AutoTrials > 0)
  {
    AutoTrialFrames(window, volume, mapper, o.AutoTrials);
  }
  if (o.ShadowTableRounds > 0)
  {
    ShadowTable(window, renderer, shown, mapper, o.ShadowTableRounds);
  }
  if (o.CompareAcceleration)
  {
    CompareAccelerationModes(window, mapper, o.Repeat);
  }
  if (!o.Sweep.empty())
  {
    mapper->SetAccelerationMode(acceleration);
    SweepSupercells(window, mapper, o.Sweep, o.Repeat);
  }
  if (o.Json)
  {
    const double* supercell = mapper->GetLastSupercellSize();
    std::cout << "{\n  \"volume\": \"" << o.Volume << "\",\n  \"image\": [" << o.Width << ", "
              << o.Height << "],\n  \"blend\": \"" << o.Blend << "\",\n  \"acceleration\": \""
              << accel << "\",\n  \"sample_distance\": " << mapper->GetLastSampleDistance()
              << ",\n  \"dimensions\": [" << image->GetDimensions()[0] << ", "
              << image->GetDimensions()[1] << ", " << image->GetDimensions()[2]
              << "],\n  \"spacing\": [" << image->GetSpacing()[0] << ", "
              << image->GetSpacing()[1] << ", " << image->GetSpacing()[2] << "]"
              << ",\n  \"samples\": " << samples
              << ",\n  \"contributing_samples\": " << mapper->GetLastContributingSampleCount()
              << ",\n  \"empty_cell_samples\": " << mapper->GetLastEmptyCellSampleCount()
              << ",\n  \"rays\": " << mapper->GetLastRayCount()
              << ",\n  \"casting_time\": " << casting
              << ",\n  \"projection_time\": " << mapper->GetLastProjectionTime()
              << ",\n  \"supercell_size\": [" << supercell[0] << ", " << supercell[1] << ", "
              << supercell[2] << "]"
              << ",\n  \"render_time\": " << total << ",\n  \"wall_time\": " << wall;
    if (o.Compare && fixedSupports)
    {
      std::cout << ",\n  \"fixed_point_wall_time\": " << fixedWall;
    }
    std::cout << "\n}" << std::endl;
    return 0;
  }
  std::printf("%-12s %-9s %-10s %-12s %12s %10s %10s %10s\n", "mapper", "image", "blend",
    "acceleration", "samples", "cast (s)", "total (s)", "wall (s)");
  char size[32];
  std::snprintf(size, sizeof(size), "%dx%d", o.Width, o.Height);
  std::printf("%-12s %-9s %-10s %-12s %12lld %10.3f %10.3f %10.3f\n", "PARC", size,
    o.Blend.c_str(), accel.c_str(), static_cast<long long>(samples), casting, total,
    wall);
  if (o.Compare && fixedSupports)
  {
    std::printf("%-12s %-9s %-10s %-12s %12s %10s %10s %10.3f\n", "FixedPoint", size,
      o.Blend.c_str(), "-", "-", "-", "-", fixedWall);
  }
  else if (o.Compare)
  {
    std::printf("%-12s %-9s %-10s (no such blend mode in vtkFixedPointVolumeRayCastMapper)\n",
      "FixedPoint", size, o.Blend.c_str());
  }
  std::printf("sample distance %.4g world units, %s projection, image written to %s\n",
    mapper->GetLastSampleDistance(), o.Parallel ? "parallel" : "perspective", o.Output.c_str());
  return 0;
}
