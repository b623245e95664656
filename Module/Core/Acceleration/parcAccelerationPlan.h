// PARC for VTK: the acceleration plan of one volume (DESIGN.md section 9), shared by the
// mapper and the polygon-model filter: the range pyramid, the supercell classification
// with what it was made from, the polygon models of the passes with their versions, the
// segment sources the passes fill (and the lights' passes for shadow rays), Auto's
// measurements and its supercell search. No GL: the caller draws the models, says whether
// its GPU holds a model's version already, and fills the sources' buffers.
//
// The pyramid is remade when the field's version changes, the classification on every
// Classify; ClassifyFrom notes what the caller made it from (a ClassificationKey), and
// IsClassifiedFrom tells the caller whether its inputs changed since. Each classification
// makes a new model version; a model's vertices are built once per version, and only
// while the caller does not hold an uploaded copy.
#ifndef parcAccelerationPlan_h
#define parcAccelerationPlan_h

#include "parcBufferSources.h"
#include "parcClassification.h"
#include "parcLightFrusta.h"
#include "parcMath.h"
#include "parcPolygonModel.h"
#include "parcStatistics.h"
#include "parcSupercellGrid.h"
#include "parcSupercellWalk.h"

#include <cstddef>
#include <cstdint>

namespace parc
{

/// What Auto measures of a frame: its times and counts (see CastStatistics).
struct FrameMeasure
{
  double Projection = 0.0; ///< seconds of the passes
  /// Seconds of Projection spent setting up (classifying, building and uploading models,
  /// compiling shaders) on a frame that did.
  double SetUp = 0.0;
  double Casting = 0.0;    ///< seconds of casting (wall)
  double Samples = 0.0;
  double Contributing = 0.0;
  /// Samples left out in cells that cannot contribute (CastStatistics::EmptyCellSamples).
  double EmptyCells = 0.0;
  RayCostFit Timing;
};

/// Auto: the candidate passes are Depth, Color, Both and None (no pass). A candidate's
/// estimate is its fastest representative frame (projection + casting) for the current
/// classification and view or, from an earlier classification, that frame with its
/// projection scaled by the number of PC supercells (the models grow with it); both times
/// scale with the ray-image pixels. A candidate not measured yet gets a prediction from
/// the frames measured: None from the samples its rays would add (RayCostFit's
/// unaccelerated samples) at the measured cost of a non-contributing sample; Color from
/// Depth's projection times the ratio of colour to depth projection (learned, a prior
/// until measured) and Depth's casting less half the samples Color leaves out: outside the
/// PC supercells, so in empty cells (of little cost when the caster leaves out empty
/// cells: EmptyCellCostShare), else among the non-contributing ones; Both from
/// the projections of Depth and Color and the faster casting of the two. Each frame takes
/// the candidate with the least estimate or prediction (Depth first), so a candidate is
/// tried only when it is predicted to win: no trial of a mode that is surely slow. The
/// first frame that may try a candidate but chooses a measured one ends the trials: an
/// edit, a new image size or a new view brings none. After the view turns or moves
/// markedly, the next frame of a measured candidate replaces its estimate.
/// A frame that also set up (the first one, above all) gives its candidate a provisional
/// estimate: the frame without its set-up time, high by what a first draw costs more than
/// a warm one (shader variants compiled, buffers grown). It predicts the others like a
/// measured one, so that a candidate predicted faster is taken next instead of a second
/// frame of this one (a trial the settled mode may not need); the candidate's next frame
/// replaces it, and choosing it does not end the trials.
struct AutoTrials
{
  enum Candidate
  {
    Depth = 0,
    Color = 1,
    Both = 2,
    None = 3,
    Count = 4
  };
  /// A view change that makes the estimates stale: the view direction turns by more than
  /// this angle (cosine), or the volume's distance from the eye changes by this fraction.
  static constexpr double SameDirection = 0.985; // about 10 degrees
  static constexpr double SameDistance = 0.2;
  /// Colour projection time over depth projection time before one is measured (llvmpipe
  /// gave 1.6 to 3.9, median 1.9, on the benchmark's scenes).
  static constexpr double PriorColorProjectionRatio = 1.75;
  /// A non-contributing sample's share of the mean cost of a sample, when the frame's rays
  /// do not determine it.
  static constexpr double NonContributingShare = 0.5;
  /// A sample left out in an empty cell (located and its cell's bit read, never
  /// interpolated or classified) against one that is interpolated and contributes nothing:
  /// the part of a sample's work that locating it is, about a third.
  static constexpr double EmptyCellCostShare = 0.3;
  /// The share of a pass's projection left at twice the supercell size: its polygons go
  /// as the supercells' faces.
  static constexpr double ProjectionShareAtTwiceTheSize = 0.25;
  /// An estimate's model version that stands for the model of the next Choose.
  static constexpr std::uint64_t NextModel = 0;
  struct Estimate
  {
    bool Measured = false;
    bool Provisional = false; ///< from a frame that also set up
    std::uint64_t ModelVersion = 0; ///< of the measured frame
    std::uint64_t ViewVersion = 0;  ///< of the measured frame
    std::size_t Contributing = 0;   ///< PC supercells of that frame's classification
    double Rays = 0.0;              ///< ray-image pixels of that frame
    double Projection = 0.0, Casting = 0.0;
    double Samples = 0.0, ContributingSamples = 0.0; ///< of that frame
    double EmptyCellSamples = 0.0; ///< of that frame
  };
  int Size[2] = { 0, 0 }; ///< the ray image of the current frame
  Estimate Estimates[Count];
  int Chosen = -1; ///< the candidate of the current frame, or -1
  std::uint64_t ViewVersion = 0;
  Vec3 Direction;        ///< view direction at the last view change
  double Distance = 0.0; ///< the volume's distance from the eye then
  /// The latest representative frame's unaccelerated samples and the wall seconds one more
  /// non-contributing sample adds to it (0: not measured).
  double UnacceleratedSamples = 0.0, SampleSeconds = 0.0;
  double ColorProjectionRatio = PriorColorProjectionRatio;
  bool Settled = false; ///< the trials are over

  /// Notes the view: direction, and the volume's distance from the eye.
  void SetView(const Vec3& direction, double distance);
  /// The candidate for this frame: the one with the least estimate or prediction (a
  /// prediction only when trials are allowed and not over; Depth when nothing is measured).
  int Choose(std::uint64_t modelVersion, std::size_t contributing, int width, int height,
    bool allowTrials = true);
  /// The times and counts of the frame Choose chose. A frame that was aborted does not
  /// count (representative false); one that also set up goes to RecordSetUp instead.
  void Record(std::uint64_t modelVersion, std::size_t contributing, const FrameMeasure& frame,
    bool representative);
  /// The same for a completed frame that also set up (frame.SetUp): a provisional estimate
  /// when its candidate has none, or only a provisional one of another view, model or
  /// image size.
  void RecordSetUp(
    std::uint64_t modelVersion, std::size_t contributing, const FrameMeasure& frame);
  /// Candidates not measured yet that are predicted to beat the measured ones (every
  /// candidate while none is measured; none once settled): the trials still to come.
  int Remaining() const;
  /// Whether Auto takes None as the fastest, with no trial to come, though the depth pass
  /// may beat it at twice the supercell size: both measured (the depth pass perhaps
  /// provisionally) at this model, view and image size, its casting plus
  /// ProjectionShareAtTwiceTheSize of its projection is less than None's frame.
  bool DepthMayBeatNoneAtTwiceTheSize() const;
  /// Ends the trials after a search of the depth pass against None (SupercellSearch):
  /// depthWon, the kept size's fastest frame (projection, casting) is the depth pass's
  /// estimate; else None's stands. Either holds for the model of the next frame, which
  /// classifies at the kept size, so that frames after the search replace it only when
  /// faster, as after any trial.
  void SettleAfterSearch(bool depthWon, double projection, double casting);

private:
  /// The estimate of a measured candidate for this frame, and its projection part.
  double Predict(const Estimate& e, std::uint64_t modelVersion, std::size_t contributing) const;
  double ProjectionOf(
    const Estimate& e, std::uint64_t modelVersion, std::size_t contributing) const;
  /// Whether e was measured at this model version, view and image size.
  bool IsCurrent(const Estimate& e, std::uint64_t modelVersion) const;
  /// The ray-image pixels of this frame over those of e's.
  double RaysScale(const Estimate& e) const;
  /// Notes the frame's unaccelerated samples and the cost of a non-contributing sample.
  void RecordSampleCost(const FrameMeasure& frame);
  /// The prediction for candidate c, not measured: false when there is none yet (Depth is
  /// measured first, and a frame without timed rays predicts nothing).
  bool PredictUnmeasured(int c, std::uint64_t modelVersion, std::size_t contributing,
    double& seconds) const;
  /// The least estimate or, with predictions, prediction (-inf for a candidate without
  /// one: it is tried); the candidate, or -1 when there is none.
  int Best(std::uint64_t modelVersion, std::size_t contributing, bool predictions,
    double* seconds = nullptr) const;
  std::uint64_t LastModelVersion = 0; ///< of the latest Choose
  std::size_t LastContributing = 0;
};

/// Auto's choice of the supercell size: the paper's trade-off of polygons against ray
/// steps (section 3), measured instead of guessed. Once Auto has settled on a pass
/// (candidate Depth, Color or Both of AutoTrials), the frames of that pass are timed
/// (projection and casting) at scale 1 of the caller's supercell size, then at twice the
/// scale, four times and so on while each is faster than the best so far; when twice is
/// not, at half the scale and below. The search ends at the first scale slower than the
/// best, which the volume keeps. A scale's time is the least of FramesPerScale
/// representative frames; a frame that set up (a new scale classifies and builds its
/// models) is not one. Supercell sizes change the segments, never the samples, so the
/// search changes times only. A large volume starts at a larger scale (Begin).
/// When Auto settles on None only because the depth pass's projection cost more than it
/// saved (AutoTrials::DepthMayBeatNoneAtTwiceTheSize), the depth pass is timed at twice
/// the scale and more, against None's frame: a scale that beats it is kept, else the
/// search ends at the start scale; its end settles Auto (AutoTrials::SettleAfterSearch).
class SupercellSearch
{
public:
  static constexpr double MinScale = 0.25; ///< the default 4 cells down to 1
  static constexpr double MaxScale = 8.0;  ///< and up to 32
  static constexpr int FramesPerScale = 2;
  /// The most supercells of the scale a search starts from.
  static constexpr double StartSupercells = 1 << 16;

  /// Starts from the smallest power-of-two scale (at least 1) at which a field of `cells`
  /// cells per axis holds at most StartSupercells supercells of `size` times the scale
  /// (and never tries one that makes more than SupercellGrid::MaxSupercells):
  /// the first passes then draw thousands of polygons, not millions (the first frame's
  /// pass costs more the more there are, and each polygon, on a software GL, about a
  /// kilobyte of the driver's memory), and the search finds smaller supercells where
  /// they pay.
  void Begin(const int cells[3], const double size[3]);

  /// The scale of the supercell size for the next frame.
  double GetScale() const { return this->Scale; }
  /// Whether a search is under way: its frames take its pass, GetCandidate().
  bool IsSearching() const { return this->State == Searching; }
  bool IsDone() const { return this->State == Done; }
  /// Whether a search of the depth pass against None is under way: Auto's choice of a pass
  /// is not known until it ends.
  bool IsSearchingAgainstNone() const { return this->IsSearching() && this->AgainstNone; }
  /// The same, or one starts on the next representative frame of None (depthMayBeatNone:
  /// AutoTrials::DepthMayBeatNoneAtTwiceTheSize).
  bool SearchesAgainstNone(bool depthMayBeatNone) const
  {
    return this->IsSearchingAgainstNone() || (this->State == Waiting && depthMayBeatNone);
  }
  int GetCandidate() const { return this->Candidate; }
  /// A representative frame of AutoTrials candidate `candidate` took `projection` and
  /// `casting` seconds at GetScale(); `settled`: Auto's trials of the modes are over;
  /// `depthMayBeatNone`: AutoTrials::DepthMayBeatNoneAtTwiceTheSize.
  void Record(int candidate, bool settled, double projection, double casting,
    bool depthMayBeatNone = false);
  /// Whether a search against None kept a larger scale, and its fastest frame's times.
  bool BeatNone(double& projection, double& casting) const;
  /// Forgets everything: the next settled pass searches again from scale 1 (or Begin's).
  void Reset() { *this = SupercellSearch(); }

private:
  /// Moves on to scale, or ends the search at the best scale when it is out of range
  /// (TurnOrEnd above the largest).
  void Try(double scale);
  /// After the first step up from the start, slower or out of range, tries the other way
  /// (not against None: larger sizes only); else ends the search at the best scale.
  void TurnOrEnd();

  enum
  {
    Waiting,
    Searching,
    Done
  } State = Waiting;
  int Candidate = -1;
  double StartScale = 1.0;
  /// The least scale tried: MinScale, or more where smaller supercells would exceed
  /// SupercellGrid::MaxSupercells (Begin).
  double LeastScale = MinScale;
  double Scale = 1.0, BestScale = 1.0, BestSeconds = 0.0;
  double ScaleSeconds = 0.0; ///< the least frame of Scale so far
  double ScaleProjection = 0.0, BestProjection = 0.0; ///< the projection part of these
  int ScaleFrames = 0;       ///< frames of Scale so far
  bool Growing = true;
  /// A search of the depth pass against None's frame (larger sizes only: smaller ones only
  /// cost more projection).
  bool AgainstNone = false;
};

/// What a classification is made from, as its caller sees its inputs (the field's
/// version, the transfer functions, the ray function, the supercell size): a plan
/// classifies again only when its key changes (AccelerationPlan::IsClassifiedFrom).
struct ClassificationKey
{
  std::uint64_t FieldVersion = 0;
  const void* Functions = nullptr; ///< what holds the transfer functions; compared only
  std::uint64_t FunctionsTime = 0; ///< their latest modification
  int Blend = -1;                  ///< the caller's blend mode
  /// The label map's labels with functions, and the latest modification of their opacities.
  std::size_t Labels = 0;
  std::uint64_t LabelsTime = 0;
  double Average[2] = { 0, 0 }; ///< the average-intensity range
  double Size[3] = { 0, 0, 0 }; ///< the supercell size (0 for the cells' classification)
  bool operator==(const ClassificationKey& o) const;
  bool operator!=(const ClassificationKey& o) const { return !(*this == o); }
};

class AccelerationPlan
{
public:
  AccelerationPlan() = default;
  AccelerationPlan(const AccelerationPlan&) = delete; // its sources refer to each other
  AccelerationPlan& operator=(const AccelerationPlan&) = delete;

  /// Joins coplanar neighbouring faces in the models (fewer primitives; the depth pass is
  /// as tight on a large face as on a small one).
  void SetMergeFaces(bool merge);

  /// Makes the pyramid again if fieldVersion (the caller's count of the fields it wrapped)
  /// changed, then classifies the supercells of size (cells per axis; scaled up uniformly
  /// into fitted when it would make more than SupercellGrid::MaxSupercells) under rule.
  /// field must outlive the plan's use. False, the grid empty, for an invalid size.
  bool Classify(const ScalarField& field, std::uint64_t fieldVersion,
    const ContributionRule& rule, Interpolation interpolation, const double size[3],
    double fitted[3])
  {
    return this->Classify({ &field }, fieldVersion, { rule }, interpolation, size, fitted);
  }
  /// The same for a volume of independent components: one field and rule per component
  /// (fields of equal dimensions); a supercell is PC under any of them.
  bool Classify(const std::vector<const ScalarField*>& fields, std::uint64_t fieldVersion,
    const std::vector<ContributionRule>& rules, Interpolation interpolation,
    const double size[3], double fitted[3]);

  /// Makes the pyramid again if fieldVersion changed, then maps the cells of field that
  /// may contribute under rule (RangePyramid::MapCells), for the caster to leave out the
  /// samples of the others. False, the map empty, for a field without cells.
  bool ClassifyCells(
    const ScalarField& field, std::uint64_t fieldVersion, const ContributionRule& rule);
  /// The map of the last ClassifyCells (empty after ReleaseCells or a new pyramid).
  const CellMap& GetContributingCells() const { return this->Cells; }
  void ReleaseCells()
  {
    this->Cells = CellMap();
    this->CellsKey = ClassificationKey();
  }

  /// Whether the supercells were classified last from key (ClassifyFrom), successfully or
  /// not.
  bool IsClassifiedFrom(const ClassificationKey& key) const { return key == this->SupercellsKey; }
  /// Classify, noting key as what it was made from (key.FieldVersion and key.Size are its
  /// field version and size).
  bool ClassifyFrom(const ClassificationKey& key, const std::vector<const ScalarField*>& fields,
    const std::vector<ContributionRule>& rules, Interpolation interpolation, double fitted[3]);
  /// Whether the cells were classified last from key (ClassifyCellsFrom).
  bool AreCellsClassifiedFrom(const ClassificationKey& key) const { return key == this->CellsKey; }
  /// ClassifyCells, noting key as what it was made from.
  bool ClassifyCellsFrom(
    const ClassificationKey& key, const ScalarField& field, const ContributionRule& rule);

  const SupercellGrid& GetGrid() const { return this->Grid; }
  /// Counts the classifications: the version of the models.
  std::uint64_t GetModelVersion() const { return this->ModelVersion; }
  /// The version of the colour model along axis: distinct for each axis and classification.
  std::uint64_t GetColorModelVersion(int axis) const { return 4 * this->ModelVersion + axis; }

  /// The depth model of the current classification, its vertices built unless uploaded
  /// (the caller's GPU holds this version and needs none).
  const PolygonModel& GetDepthModel(bool uploaded) { return this->Ensure(this->Depth, -1, uploaded); }
  /// The colour model along axis, likewise.
  const PolygonModel& GetColorModel(int axis, bool uploaded)
  {
    return this->Ensure(this->Color[axis], axis, uploaded);
  }
  /// Quads of the pass's model (known also when its vertices were released).
  std::size_t GetDepthQuads() const { return this->Depth.Quads; }
  std::size_t GetColorQuads(int axis) const { return this->Color[axis].Quads; }
  /// The walk of the current classification (SupercellWalk), its flags derived once per
  /// classification, for rays mapped by worldToIndex.
  const SupercellWalk& GetWalk(const Matrix4& worldToIndex);
  /// Frees the walk's flags (a mode that does not walk).
  void ReleaseWalk() { this->Walk.Clear(); }

  /// The segment sources of the view's passes: the caller's GL passes fill their buffers
  /// (Set) and take them back to fill again (ReleaseBuffer).
  DepthBufferSource& GetDepthSource() { return this->DepthSource; }
  PlaneBufferSource& GetPlaneSource() { return this->PlaneSource; }
  /// What the rays of a frame whose passes are `passes` read: the depth pass, the colour
  /// pass, both intersected, or the whole rays (AutoTrials::None: no pass).
  const SegmentSource& GetSource(AutoTrials::Candidate passes) const;
  /// The source of rays that meet nothing that can show: no segment.
  const SegmentSource& GetEmptySource() const { return this->NoRays; }
  /// Frees the buffers of the passes a settled mode does not draw.
  void ReleasePassBuffers(bool depth, bool planes);

  /// The passes of one light for shadow rays (parcLightFrusta.h), and what they were
  /// drawn from: the light and the volume in world coordinates, the model's version.
  struct LightPasses
  {
    std::vector<double> Key;
    LightBufferSource Source;
    /// Whether they were drawn from key (the same world quantities come back through the
    /// render frame with rounding: equal within LightKeyTolerance).
    bool IsDrawnFrom(const std::vector<double>& key) const;
  };
  /// Relative difference under which a light pass's key counts as unchanged.
  static constexpr double LightKeyTolerance = 1e-9;
  /// The passes of light `index` of `lights` lights.
  LightPasses& GetLightPasses(std::size_t index, std::size_t lights);
  /// Frees every light's passes (drawn in a GL context that is going away).
  void ReleaseLightPasses() { this->Lights.clear(); }

  /// Frees a model's vertices once the caller's GPU holds them.
  void ReleaseDepthVertices() { Release(this->Depth); }
  void ReleaseColorVertices(int axis) { Release(this->Color[axis]); }

  /// Work done so far (statistics).
  std::uint64_t GetPyramidBuilds() const { return this->PyramidBuilds; }
  std::uint64_t GetClassifications() const { return this->Classifications; }
  std::uint64_t GetModelBuilds() const { return this->ModelBuilds; }
  std::uint64_t GetCellClassifications() const { return this->CellClassifications; }
  /// Seconds of the last classification.
  double GetClassificationTime() const { return this->ClassificationTime; }
  /// Seconds spent so far building pyramids, classifying and building models.
  double GetSetUpTime() const { return this->SetUpTime; }

  /// Bytes held by the pyramid, the supercell flags, the depth model and the colour models.
  std::size_t GetPyramidMemorySize() const;
  std::size_t GetDepthModelMemorySize() const { return this->Depth.Model.GetMemorySize(); }
  std::size_t GetColorModelsMemorySize() const;
  std::size_t GetWalkMemorySize() const { return this->Walk.GetMemorySize(); }
  std::size_t GetDepthBufferMemorySize() const { return this->DepthSource.GetMemorySize(); }
  std::size_t GetPlaneBufferMemorySize() const { return this->PlaneSource.GetMemorySize(); }
  std::size_t GetLightPassesMemorySize() const;

  AutoTrials Auto; ///< Auto's measurements for this volume
  SupercellSearch Sizes; ///< Auto's choice of the supercell size for this volume

private:
  struct PassModel
  {
    PolygonModel Model;
    std::size_t Quads = 0;
    bool Current = false; ///< built for the current classification
  };
  /// Builds the pyramids of fields unless they are of fieldVersion already.
  void EnsurePyramids(const std::vector<const ScalarField*>& fields, std::uint64_t fieldVersion);
  /// Marks every model stale under a new version (a new classification or face merging).
  void NewModelVersion();
  /// Builds pass's model (axis -1: the depth model) unless it is current and either has its
  /// vertices or is uploaded.
  const PolygonModel& Ensure(PassModel& pass, int axis, bool uploaded);
  static void Release(PassModel& pass);

  bool MergeFaces = true;
  std::vector<RangePyramid> Pyramids; ///< one per field
  std::uint64_t PyramidFieldVersion = 0;
  SupercellGrid Grid;
  CellMap Cells; ///< ClassifyCells' map, into Pyramids[0]
  ClassificationKey SupercellsKey, CellsKey; ///< of ClassifyFrom and ClassifyCellsFrom
  PassModel Depth;
  PassModel Color[3]; ///< per major axis
  SupercellWalk Walk;
  DepthBufferSource DepthSource;
  PlaneBufferSource PlaneSource;
  const BothSource Both{ DepthSource, PlaneSource }; ///< refers to the two: no copies
  const WholeRaySource WholeRays;
  const EmptySource NoRays;
  std::vector<LightPasses> Lights;
  bool WalkCurrent = false; ///< the walk's flags are of the current classification
  std::uint64_t ModelVersion = 0;
  std::uint64_t PyramidBuilds = 0, Classifications = 0, ModelBuilds = 0;
  std::uint64_t CellClassifications = 0;
  double ClassificationTime = 0.0;
  double SetUpTime = 0.0;
};

} // namespace parc

#endif
