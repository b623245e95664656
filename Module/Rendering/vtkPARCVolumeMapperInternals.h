// The private classes of vtkPARCVolumeMapper: the state of one input volume and the
// mapper's internals, shared by the files the mapper is written in.
#ifndef vtkPARCVolumeMapperInternals_h
#define vtkPARCVolumeMapperInternals_h

#include "vtkPARCVolumeMapper.h"

#include "parcAccelerationPlan.h"
#include "parcBufferSources.h"
#include "parcDriverMemory.h"
#include "parcEndOfRenderDraw.h"
#include "parcLightFrusta.h"
#include "parcPassDriver.h"
#include "parcPolygonModel.h"
#include "parcRayCaster.h"
#include "parcVTKConversion.h"
#include "vtkPARCMultiVolume.h"

#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMultiVolume.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkOpenGLRayCastImageDisplayHelper.h"
#include "vtkPlane.h"
#include "vtkPlaneCollection.h"
#include "vtkPiecewiseFunction.h"
#include "vtkPointData.h"
#include "vtkSmartPointer.h"
#include "vtkPropCollection.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkSMPTools.h"
#include "vtkSmartVolumeMapper.h"
#include "vtkTimerLog.h"
#include "vtkVolume.h"
#include "vtkVolumeProperty.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <utility>
#include <vector>

namespace parc
{
namespace mapper
{
/// The modes Auto tries, in the plan's candidate numbering (no pass last).
constexpr int AutoCandidates[parc::AutoTrials::Count] = {
  vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER, vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER,
  vtkPARCVolumeMapper::ACCELERATION_BOTH, vtkPARCVolumeMapper::ACCELERATION_NONE
};

/// What an acceleration mode draws and walks, in one place: RunPasses draws its passes,
/// ReleaseUnusedPasses frees the others, and SetUpShadows gives shadow rays its kind of
/// light pass.
struct AccelerationTraits
{
  bool Depth = false;  ///< draws the depth pass (near/far buffers)
  bool Planes = false; ///< draws the colour planes pass (bit planes)
  bool Walk = false;   ///< walks the supercells: no pass, for view and shadow rays alike
  /// Shadow rays use passes from the lights (not for None): colour planes, else depth.
  bool LightPasses = false;
  bool LightPlanes = false;
};

/// The traits of an acceleration mode (vtkPARCVolumeMapper::ACCELERATION_*; Auto's are
/// those of its light passes, its view passes being those of the mode it chooses).
constexpr AccelerationTraits TraitsOf(int mode)
{
  switch (mode)
  {
    case vtkPARCVolumeMapper::ACCELERATION_DEPTH_BUFFER:
      return { true, false, false, true, false };
    case vtkPARCVolumeMapper::ACCELERATION_COLOR_BUFFER:
      return { false, true, false, true, true };
    case vtkPARCVolumeMapper::ACCELERATION_BOTH:
      return { true, true, false, true, false };
    case vtkPARCVolumeMapper::ACCELERATION_AUTO:
      return { false, false, false, true, false };
    case vtkPARCVolumeMapper::ACCELERATION_SUPERCELL_WALK:
      return { false, false, true, false, false };
    default: // ACCELERATION_NONE
      return {};
  }
}

/// The render's progress as each set-up step begins (vtkPARCVolumeMapper::ReportSetUp).
namespace SetUpProgress
{
constexpr double Scalars = 0.05;    ///< wrapping (and scanning) new scalars
constexpr double Bricks = 0.1;      ///< copying the scalars into bricks (BrickedCopy)
constexpr double Cells = 0.2;       ///< classifying the cells for the caster
constexpr double Supercells = 0.35; ///< classifying the supercells, building the models
}
/// The progress text while rays are cast.
constexpr const char* CastingProgressText = "casting rays";

/// What the phases of one render read of the mapper, taken when the render begins: the
/// per-volume state and the internals' phases receive these, never the mapper.
struct RenderSettings
{
  int AccelerationMode = 0; ///< as requested (vtkPARCVolumeMapper::ACCELERATION_*)
  /// Auto chooses the supercell size (ACCELERATION_AUTO with AutoSupercellSize).
  bool SearchSupercellSize = false;
  double SupercellSize[3] = { 0, 0, 0 }; ///< as requested, in cells
  double AverageIPScalarRange[2] = { 0, 0 };
  /// An interactive render whose sample distances are adjusted to its budget.
  bool Interactive = false;
  double TerminationOpacity = 1.0;
  int NumberOfThreads = 0; ///< 0: vtkSMPTools' own
  /// The object errors and warnings name (the mapper), never called otherwise.
  vtkObject* Reporter = nullptr;
  /// A set-up step begins: its name and the render's progress (see SetUpProgress).
  std::function<void(const char* step, double progress)> SetUpStep;
  /// The fraction of the rays cast so far; false when the render is to stop.
  std::function<bool(double fraction)> CastProgress;
};

/// The lights' passes of one render: their time and the frusta rendered.
struct LightPassWork
{
  double Time = 0.0;
  int Frusta = 0;
};
}
}

using parc::mapper::AutoCandidates;
using parc::mapper::AccelerationTraits;
using parc::mapper::LightPassWork;
using parc::mapper::RenderSettings;
using parc::mapper::CastingProgressText;
namespace SetUpProgress = parc::mapper::SetUpProgress;

//------------------------------------------------------------------------------
/// One input volume (one input port): its field, ray function, caster and PARC
/// acceleration, with the classification and models cached until their inputs change.
class vtkPARCVolumeMapper::vtkVolumeState
{
public:
  int Port = 0;
  /// The port's blend mode (vtkVolumeMapper's), of the last PrepareParameters.
  int InputBlend = -1;
  parc::ScalarField Field;
  /// 0.5 when Field holds cell scalars (its voxels at the cells' centres), else 0.
  double CellOffset = 0.0;
  /// World units the gradient opacity functions measure gradients per (GradientUnit).
  double GradientUnit = 1.0;
  /// The box of Field (voxel-index coordinates) that is not ghost cells.
  parc::Vec3 OwnedLo, OwnedHi;
  /// The number of dependent components (2 or 4: colour from the others), or 0.
  int DependentComponents = 0;
  /// What Field was wrapped from (its Version: what the pyramid and the classification
  /// were made from).
  parc::vtk::WrappedScalars Scalars;
  /// The Scalars.Version for which BrickedCopy warned that no copy was made (0: none).
  std::uint64_t BricksDeclined = 0;
  /// The binary mask's values (port 0), and what they were wrapped from.
  parc::ScalarField Mask;
  parc::vtk::WrappedScalars MaskScalars;
  vtkMTimeType FixesWarnedTime = 0; ///< the property whose conversion fixes were reported
  /// The quantized normals of Field (ShadingModel QuantizedNormals), and the field
  /// version they were made from.
  parc::NormalVolume Normals;
  std::uint64_t NormalsVersion = 0;
  parc::CastParameters Parameters;
  /// Components 1, 2, ... of independent components (vtkVolumeProperty::
  /// IndependentComponentsOn), each with its own field (the values of that
  /// component), parameters and caster; empty for one component.
  struct ComponentState
  {
    parc::ScalarField Field;
    parc::CastParameters Parameters;
    parc::RayCaster Caster;
  };
  std::vector<std::unique_ptr<ComponentState>> Components;
  /// Field, Parameters and the placement as the caster is prepared on them, of the last
  /// PrepareParameters. Its world is the render frame (world minus the camera position):
  /// every world quantity the core sees is in that frame.
  parc::Volume CoreVolume;
  parc::RayCaster Caster;
  parc::CastStatistics Stats; ///< of the last render
  /// What the last frame's rays took, set once by RunPasses.
  struct FramePasses
  {
    int Mode = ACCELERATION_NONE; ///< as GetLastInputAccelerationMode reports it
    /// The AutoTrials candidate whose segments the rays took (-1: the walk's, or none).
    int Candidate = -1;
    /// The classification decided the mode without Auto's measurements (no supercell, or
    /// every one, may contribute): no trial is to come.
    bool SettledByClassification = false;
  };
  FramePasses Last;

  // PARC: the classification and models, remade only when their inputs (the plan's keys)
  // change.
  parc::AccelerationPlan Plan;
  /// What the classification of this volume depends on, now.
  parc::ClassificationKey Key(const RenderSettings& settings, vtkVolume* vol) const;
  /**
   * The supercell size of the volume's next classification: the requested one, scaled by
   * Auto's search (RenderSettings::SearchSupercellSize).
   */
  void SupercellSizeOf(const RenderSettings& settings, double size[3]) const;
  /**
   * Classifies the volume's cells for its caster when their inputs changed (composite
   * volumes of one component, linear interpolation), in every acceleration mode: the
   * caster leaves out the samples of cells that cannot contribute.
   */
  void PrepareCells(const RenderSettings& settings, vtkVolume* vol);
  /** Classifies and builds the volume's polygon models when their inputs changed. */
  bool PrepareModels(const RenderSettings& settings, vtkVolume* vol);
  /// Draws the plan's passes (the view's and the lights').
  parc::vtk::PassDriver Passes;
  bool FallbackWarned = false;
  parc::vtk::PassDriver::Drawn Drawn; ///< what the last render's view passes drew
  double ProjectionTime = 0.0;        ///< of the last render

  /// Seconds the plan and the passes spent so far setting up (Auto's RecordSetUp).
  double SetUpTime() const
  {
    return this->Plan.GetSetUpTime() + this->Passes.GetSetUpTime();
  }
  /// Frees the buffers and GL objects of the passes, and the walk's flags, that a settled
  /// mode (used) does not use (Auto keeps them while it still has modes to try).
  void ReleaseUnusedPasses(vtkRenderWindow* window, const AccelerationTraits& used)
  {
    if (this->Plan.Auto.Remaining() > 0 && this->Plan.Auto.Chosen >= 0)
    {
      return;
    }
    this->Plan.ReleasePassBuffers(used.Depth, used.Planes);
    this->Passes.ReleaseUnused(window, used.Depth, used.Planes);
    if (!used.Walk)
    {
      this->Plan.ReleaseWalk();
    }
  }

  /// Bytes held per structure (see GetMemorySize).
  std::vector<std::pair<const char*, std::size_t>> Memory() const;

  /// The shading model's part of Parameters (after the lights and the placement): the
  /// quantized normals (made again when the field changed) and the view direction they are
  /// shaded for (from the camera's frame), or exact shading.
  void PrepareShadingModel(bool quantized, const parc::vtk::CameraFrame& frame);
  /// The mode Auto resolves to for the current classification, ray function and view.
  int ChooseMode(const RenderSettings& settings, const parc::Camera& camera);
  /// The segment source of shadow rays towards light `index` (lit from lights, in the
  /// render frame whose world origin is frame): the light's plane passes (planes) or depth
  /// passes, run again only when the light, the volume's transform, its model or that kind
  /// changed; null when they cannot run (the whole ray is cast).
  const parc::SegmentSource* LightSource(vtkRenderWindow* window,
    const std::vector<parc::Light>& lights, std::size_t index, const parc::Vec3& frame,
    bool planes, LightPassWork& work);
  /// Runs the PARC passes of the requested mode; the segment source the caster uses.
  const parc::SegmentSource& RunPasses(const RenderSettings& settings, vtkRenderer* ren,
    vtkVolume* vol, const parc::vtk::PassView& view);
};

//------------------------------------------------------------------------------
class vtkPARCVolumeMapper::vtkInternals
{
public:
  /// What this render reads of the mapper (the phases below read nothing else of it).
  RenderSettings Settings;
  /// The renderer's camera as this render began (its position is the render frame's
  /// origin: every world quantity the core sees is in that frame).
  parc::vtk::CameraFrame Frame;
  /// Per input port, made when the port is first rendered.
  std::vector<std::unique_ptr<vtkVolumeState>> Volumes;
  /// The volumes of the current render with their props, in port order.
  std::vector<std::pair<vtkVolumeState*, vtkVolume*>> Rendered;
  parc::SceneCaster Scene;
  /// What shadows the rendered volumes when a light casts shadows (see ShadowMembers).
  parc::Occluders Shadows;
  std::vector<parc::CastStatistics> MemberStats;
  std::vector<float> Image;
  int ImageSize[2] = { 0, 0 };
  std::vector<float> Depth;
  std::vector<unsigned char> Display;
  parc::CastStatistics Stats; ///< summed over the rendered volumes
  double CastingTime = 0.0;
  /// The progress ReportSetUp last reported in this render, 0 while nothing was set up;
  /// once something was, casting reports the second half of the render's progress.
  double SetUpProgress = 0.0;
  double ProjectionTime = 0.0;
  LightPassWork LightPasses; ///< the shadow rays' light passes (part of the render)
  double RenderTime = 0.0;
  vtkNew<vtkOpenGLRayCastImageDisplayHelper> DisplayHelper;
  /// What the GL implementation holds for the image's display, measured when the
  /// image's size changes (the passes measure their own).
  parc::vtk::DriverMemory DisplayDriver;
  int DisplayedSize[2] = { 0, 0 }; ///< of the image when DisplayDriver last measured
  /// The volume's allocated render time for this render (render-time budgets).
  double Budget = 0.0;
  /// Whether this render adjusts the sample distances to the budget (AutoAdjust-, or
  /// InteractiveAdjustSampleDistances in an interactive render).
  bool AdjustSampleDistances = false;
  /// The last render that cast: its time, the parts of it in the PARC passes and the cast,
  /// its image sample distance and sample distance (port 0), from which the next render's
  /// image sample distance is estimated.
  double PreviousTime = 0.0, PreviousProjection = 0.0, PreviousCasting = 0.0;
  double PreviousRendererTime = 0.0; ///< the renderer's whole last render
  double PreviousImageStep = 1.0, PreviousSampleDistance = 0.0;
  bool JitteringWarned = false, RenderModeWarned = false, WindowWarned = false;
  /// The renders asked for inside VTK's dual depth peeling, drawn when the renderer ends.
  parc::vtk::EndOfRenderDraw EndOfRender;

  explicit vtkInternals(vtkPARCVolumeMapper* self)
    : EndOfRender([self](vtkRenderer* ren, vtkVolume* vol) { self->Render(ren, vol); })
  {
  }

  /// Bytes held per structure (see GetMemorySize).
  std::vector<std::pair<const char*, std::size_t>> Memory() const;

  // The phases of a render after the volumes are prepared (see Render).
  /// The ray image's view for the renderer's camera, step pixels to a ray; false (nothing
  /// to cast) when the viewport is empty or the projection singular.
  bool MakeView(vtkRenderer* ren, double step, parc::vtk::PassView& view);
  /// The window depth of the other geometry under each ray-image pixel.
  const float* ReadGeometryDepth(vtkRenderer* ren, const parc::Camera& rays);
  /// What set-up work the volumes have done so far: a frame that did some does not count
  /// for Auto.
  struct SetUpWork
  {
    std::uint64_t ModelBuilds, Uploads;
    double Seconds; ///< of the plan's and the rasterizer's set-up so far
  };
  std::vector<SetUpWork> CountSetUpWork() const;
  /// Runs each volume's PARC passes: the volumes with the segment source each casts with.
  std::vector<parc::SceneCaster::Member> RunPasses(
    vtkRenderer* ren, const parc::vtk::PassView& view);
  /// Every rendered volume shadows every shaded one when a shaded volume has a light that
  /// casts shadows (each caster's occluders are set, or cleared).
  void SetUpShadows(vtkRenderer* ren);
  /// Casts the ray image; false when aborted.
  bool Cast(const parc::Camera& rays, const float* depth,
    const std::vector<parc::SceneCaster::Member>& members);
  int CastThreads = 0; ///< the threads the last cast could use
  /// Gives each volume's Auto the times of this frame, and its supercell search when
  /// searchSizes (Auto chooses the size, and the frame is not interactive).
  void RecordAuto(const std::vector<SetUpWork>& before, bool completed, bool searchSizes);
  /// After a render that set anything up (pyramids, classifications, models, uploads:
  /// their temporaries freed) or freed a pass it no longer draws, gives the allocator's
  /// free pages back to the system. glibc keeps them otherwise, and a process rendering a
  /// large volume would hold 1.5-2 times what the mapper holds.
  void ReturnFreedMemory();
  std::uint64_t SetUpWorkReturned = 0; ///< the set-up work counted at the last return

  vtkVolumeState& At(int port)
  {
    if (static_cast<std::size_t>(port) >= this->Volumes.size())
    {
      this->Volumes.resize(port + 1);
    }
    if (!this->Volumes[port])
    {
      this->Volumes[port].reset(new vtkVolumeState);
      this->Volumes[port]->Port = port;
    }
    return *this->Volumes[port];
  }
  /// Sums f(volume) over the volumes of the last render.
  template <class T, class F>
  T Sum(F&& f) const
  {
    T total = 0;
    for (const auto& entry : this->Rendered)
    {
      total += f(*entry.first);
    }
    return total;
  }
};

#endif
