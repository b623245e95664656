// PARC for VTK: the CPU volume ray caster of the core (no OpenGL, no pipeline).
//
// One caster samples the global lattice (parcRay.h) inside whatever segments a
// SegmentSource gives it. Samples are visited in increasing lattice index, each at most
// once, with the same arithmetic whatever the source: a sample whose opacity is exactly 0
// changes nothing, so a source that leaves out only such samples gives a bit-identical
// image (DESIGN.md sections 1-2). The samples of a lattice range are taken in blocks of up
// to LatticeBlock::Size (FieldView::SampleLattice: no branch on the data, several lanes at
// once), each with the arithmetic of a single sample; a ray that stops early has taken at
// most a block's worth in vain, which the statistics do not count. When a sample's opacity
// and colour depend on its value alone (no mask, labels or varying gradient opacity), the
// composite function works on a block in stages: the opacities, then which lanes are
// composited before the ray stops (the compositor's own arithmetic), then only their
// colours, gradients and shading, four lanes at a time where it can, then the compositing.
// Each lane gets the bits it would get alone, so a stage changes speed, never the image.
// A block runs in code compiled for the baseline instruction set or, where the processor
// has it, for AVX2 without fused multiply-add (CastParameters::WideVectors): the same
// operations rounding alike, so the same bits.
//
// Ray functions (one functor each, dispatched in one switch):
// - Composite: front-to-back "over" with opacity correction
//   a' = 1 - (1 - a)^(dt / unit distance) (in float), gradient opacity, shading, early
//   termination.
// - Maximum / minimum intensity: the extreme scalar along the ray, then its colour and
//   (uncorrected) opacity.
// - Average intensity: the mean of the samples inside AverageRange, then colour/opacity.
// - Additive: sum of a' * colour and of a', clamped to 1 (emission only, no attenuation).
// - Isosurface: between consecutive lattice samples s0, s1 a value v is crossed when
//   (s0 < v) != (s1 < v); the crossing is found by linear interpolation of s0, s1 followed
//   by two regula-falsi steps on the interpolated field; each crossing is shaded with the
//   colour and opacity of v and composited front to back.
// - Slice: the ray's one sample where it crosses the plane (SliceOrigin, SliceNormal)
//   inside the field, the clipping planes and the cropping, off the lattice: the colour
//   there (shaded, without shadows) and its uncorrected opacity. No segment is asked for.
// Several volumes (SceneCaster): each volume's caster turns a ray into RayEvents, what the
// volume contributes where along the ray, and one compositor merges the events of all
// volumes front to back by (ray parameter, volume index). A composite or isosurface volume
// gives one event per contributing sample or surface crossing; a maximum, minimum or
// average intensity or additive volume gives its whole-ray result as one event, placed at
// its first sample with the extreme value, its first averaged sample or its first
// contributing sample; a slice volume its sample, at the plane. One volume alone gives the
// same bits as its own caster. The merge ends at the first event behind the stop of the
// ray: the ray parameter of the last event of a composite or isosurface volume whose own
// opacity reached its termination opacity there (the smallest such; the merged opacity has
// reached it by then, up to rounding). The volumes are cast one after another (isosurface,
// whole-ray, then composite volumes), and each composite or isosurface volume is cast only
// up to a little beyond the stop the volumes cast before it found: what lies behind a
// surface costs nothing, and the events the merge takes are the same. The last composite
// volume cast keeps no events: its samples are composited as it takes them, the others'
// events merged in between, and the ray stops where the merged opacity reaches the
// termination opacity.
// Shadows (paper section 5, DESIGN.md section 5): with Occluders set, each shaded
// contribution at world point x is lit by each light with ShadowAttenuation > 0 only as far
// as the light gets through: its diffuse and specular terms (when not zero) are scaled by
// 1 - ShadowAttenuation (1 - T). T is the product over the occluding volumes of their
// transmittance along the shadow ray from x towards the light (up to the light, for a
// positional light). Each volume samples the shadow ray on its own lattice t_k = k dt from
// x, k >= 1 (x itself is left out): a composite volume multiplies T by 1 - a' at each
// sample (a' its corrected opacity, gradient opacity included), an isosurface volume by
// 1 - opacity(v) at each crossing of an iso value v; maximum, minimum, average and
// additive volumes cast no shadow. A shadow ray stops once T < 1 - the volume's
// termination opacity. The lattice depends only on x and the light, so every segment
// source of the shadow rays gives the same T. Shadow rays cross a piece's ghost cells
// (CastParameters::OwnedLo/OwnedHi cut primary rays only).
// Independent components (SetComponents; vtkVolumeProperty::IndependentComponentsOn): the
// caster of component 0 casts for all. Each component c has its own field (the same
// memory, shifted by c values), transfer functions, shading and ComponentWeight w_c, and
// is sampled at the same lattice positions. As VTK's ray cast mappers combine them:
// - Composite: each sample's component opacities a_c (corrected, gradient opacity
//   included) become w_c a_c; a sample with sum_c w_c a_c = 0 changes nothing; otherwise
//   its premultiplied colour is sum_c w_c a_c rgb_c (rgb_c shaded with component c's own
//   gradient and material) and its opacity sum_c (w_c a_c)^2 / sum_c w_c a_c.
// - Maximum / minimum intensity: each component's own extreme along the ray, then colour
//   sum_c w_c a_c rgb_c and opacity min(1, sum_c w_c a_c).
// A component of weight 0 is not sampled. Shadows are not cast (no Occluders are used).
// Thread safety: Cast* are const and may run concurrently once Prepare has been called.
#ifndef parcRayCaster_h
#define parcRayCaster_h

#include "parcCamera.h"
#include "parcCastParameters.h"
#include "parcCellMap.h"
#include "parcCompositor.h"
#include "parcOpacityCorrection.h"
#include "parcRay.h"
#include "parcScalarField.h"
#include "parcSegmentSource.h"
#include "parcStatistics.h"
#include "parcVolume.h"

#include <algorithm>
#include <cstdint>
#include <functional>
#include <limits>
#include <vector>

namespace parc
{

/// The most volumes a SceneCaster casts together.
constexpr std::size_t MaxSceneVolumes = 16;

class Occluders;

/// Scratch storage of one thread's shadow rays (reused from ray to ray).
struct ShadowScratch
{
  std::vector<Segment> Segments;
  std::vector<LatticeRange> Ranges;
};

/// The most independent components a caster combines (VTK's limit).
constexpr std::size_t MaxComponents = 4;

/// Other volumes' events for the samples of one composite volume to be composited between
/// (SceneCaster's last composite volume; RayCaster::CastRayMerged): the merge by (ray
/// parameter, volume index) without keeping that volume's events.
struct MergedEvents
{
  /// An event, with the first lattice index of the composite volume whose sample comes
  /// after it in the merge.
  struct Entry
  {
    long FirstAfter;
    RayEvent Event;
  };
  std::vector<Entry> Entries; ///< in merge order
  std::size_t Next = 0;       ///< the first not composited yet
  /// The composite volume's samples from this lattice index on lie behind the ray's stop.
  long End = std::numeric_limits<long>::max();

  /// Composites into out the events that come before lattice sample k, while out's opacity
  /// stays below termination; false once it does not.
  bool AddBefore(long k, EventCompositor& out, double termination)
  {
    for (; this->Next < this->Entries.size() && this->Entries[this->Next].FirstAfter <= k;
         ++this->Next)
    {
      if (!out.Below(termination))
      {
        return false;
      }
      out.Add(this->Entries[this->Next].Event);
    }
    return out.Below(termination);
  }
  /// The lattice index before which the next event is composited (End when none is left).
  long NextPosition() const
  {
    return this->Next < this->Entries.size() ? this->Entries[this->Next].FirstAfter
                                             : this->End;
  }
};

/// Casts rays through one scalar field.
class RayCaster
{
public:
  /// An independent component other than component 0 (see the file comment).
  struct Component
  {
    const RayCaster* Caster; ///< prepared on the component's field and parameters
    /// Where the component's values lie in memory relative to component 0's, in values.
    std::ptrdiff_t Shift;
  };
  /// Keeps volume (its field and parameters must outlive the casts) and derives the
  /// per-render constants. Returns false if the volume cannot be cast.
  bool Prepare(const Volume& volume);

  /// One ray: the premultiplied RGBA result. Scratch vectors are reused by the caller.
  /// firstHit (optional) receives the ray parameter of the first contributing composite or
  /// additive sample or the first isosurface crossing (+inf if none or other blend modes).
  /// events (optional) receives the ray's events in ray order (see the file comment); a
  /// composite or isosurface ray still stops where its own opacity reaches the
  /// termination opacity, which the merged opacity has reached by then.
  /// shadows (optional) is the thread's scratch for shadow rays (a ray without one makes
  /// its own when it casts shadow rays).
  void CastRay(const RayQuery& query, const SegmentSource& source,
    std::vector<Segment>& segments, std::vector<LatticeRange>& ranges, float rgba[4],
    CastStatistics& stats, double* firstHit = nullptr,
    std::vector<RayEvent>* events = nullptr, ShadowScratch* shadows = nullptr) const;

  /// A composite ray (no components) like CastRay, with merge's events composited in
  /// between its samples (from merge.Next on) and its samples from merge.End on left out:
  /// out receives what was composited until the ray stopped or its samples ended (to
  /// composite the rest into); the events after that are left from merge.Next on. No
  /// events are kept.
  void CastRayMerged(const RayQuery& query, const SegmentSource& source,
    std::vector<Segment>& segments, std::vector<LatticeRange>& ranges, MergedEvents& merge,
    EventCompositor& out, CastStatistics& stats, ShadowScratch* shadows = nullptr) const;

  /// The components 1, 2, ... of a field of independent components, this caster being
  /// component 0 (see the file comment); empty (the default) for one component. Each must
  /// be prepared on a field of this one's dimensions and scalar type, with the same blend
  /// mode (composite, maximum or minimum intensity), sample distance, world-to-index
  /// matrix, clipping and cropping. Returns false, keeping none, otherwise.
  bool SetComponents(std::vector<Component> components);
  const std::vector<Component>& GetComponents() const { return this->Components; }

  /// The cells of the field that may contribute, as RangePyramid::MapCells gives them
  /// under this caster's parameters, or null (the default): composite rays then leave out
  /// the samples of the other cells, whose opacity is 0, without interpolating them (the
  /// same image). Used for a composite volume of one component and linear interpolation
  /// whose values lie next to each other, a map covering the field; it must outlive the
  /// casts.
  void SetContributingCells(const CellMap* cells) { this->Cells = cells; }
  /// Whether this caster's rays read the map of SetContributingCells (prepared, with its
  /// components set): the volumes that skip no sample need none.
  bool ReadsContributingCells() const;

  /// What shades this volume's contributions in shadow (see the file comment); null (the
  /// default) casts no shadow ray. It must outlive the casts.
  void SetOccluders(const Occluders* occluders) { this->Shadows = occluders; }
  const Occluders* GetOccluders() const { return this->Shadows; }
  /// This volume's transmittance along a shadow ray (query.Path from the shaded point
  /// towards the light, TMax at the light or +inf), sampled where source says light may
  /// be blocked; samples and cells are counted as shadow samples and cells in stats.
  float Transmittance(const RayQuery& query, const SegmentSource& source,
    ShadowScratch& scratch, CastStatistics& stats) const;
  /// The lattice samples of ray (world coordinates) between where it enters and leaves the
  /// field inside the clipping planes: what casting it without acceleration would take.
  std::uint64_t UnacceleratedSamples(const Ray& ray) const;

  /// A whole image into rgba (4 floats a pixel, rows bottom to top), in parallel over
  /// tiles with vtkSMPTools; depth (may be null) holds each pixel's window depth of the
  /// opaque geometry. progress(fraction) is called between bands of rows from the calling
  /// thread; when it returns false the cast stops, the rest of the image stays zero and
  /// CastImage returns false.
  bool CastImage(const Camera& view, const float* depth, const SegmentSource& source,
    float* rgba, CastStatistics& stats,
    const std::function<bool(double)>& progress = nullptr) const;

  /// The ray-parameter interval of ray inside the field's box, [TMin, TMax] and the
  /// clipping planes (cropping may cut it further).
  bool ClipRay(const Ray& ray, double& tEnter, double& tExit) const;
  /// Whether every ray that meets the field has a result (BlendTraits::CastsEveryRay).
  bool CastsEveryRay() const { return this->Params && TraitsOf(this->Params->Blend).CastsEveryRay; }

  const CastParameters* GetParameters() const { return this->Params; }
  const ScalarField* GetField() const { return this->Field; }
  const Matrix4& GetWorldToIndex() const { return this->WorldToIndex; }
  /// Whether samples need gradients: exact shading, or a gradient opacity that is not
  /// constant.
  bool NeedsGradient() const { return this->Constants.GradientNeeded; }
  /// Whether shaded samples use the quantized normals (see CastParameters::Shading).
  bool UsesQuantizedNormals() const { return this->Constants.QuantizedNormals; }
  /// Whether the rays prefetch the voxels ahead of their samples (see
  /// CastParameters::PrefetchMinBytes).
  bool PrefetchesVoxels() const { return this->Constants.PrefetchSamples > 0; }
  /// Bytes of the quantized normals' shading table (0 for exact shading).
  std::size_t GetShadingTableMemorySize() const
  {
    return this->Constants.NormalShading.capacity() * sizeof(ShadingFactors) +
      this->Constants.GreyNormalShading.capacity() * sizeof(float);
  }

  /// A directional light as the shading uses it: colours times the material's
  /// coefficients, in float like every per-sample shading step.
  struct DirectionalLight
  {
    Vec3f ToLight;  ///< unit vector towards the light
    Vec3f Diffuse;  ///< diffuse coefficient times the light's colour
    Vec3f Specular; ///< specular coefficient times the light's colour
    std::size_t Index;       ///< in CastParameters::Lights
    Vec3 ShadowDirection;    ///< ToLight in double: the direction of shadow rays
    float ShadowAttenuation; ///< > 0 when the light casts shadows (with Occluders)
  };
  /// The diffuse and specular factors of the directional lights for one quantized normal
  /// (the fourth entries are 0).
  struct alignas(16) ShadingFactors
  {
    float Diffuse[4];
    float Specular[4];
  };
  /// A positional light with what does not change during a render.
  struct PositionalLight
  {
    const Light* Source;
    Vec3 SpotDirection;   ///< unit vector from the light to its focal point
    double CosCone = -1.; ///< cosine of the spot cone (spots only)
    std::size_t Index;    ///< in CastParameters::Lights
  };
  /// What Prepare derives from the parameters once per render for every ray.
  struct RenderConstants
  {
    /// The correction of a sample's opacity for the sample distance dt (compositing ray
    /// functions: the exponent dt / unit distance); additive blending takes the scale
    /// dt / unit distance instead, average intensity neither.
    OpacityCorrection Correction;
    float OpacityScale = 1.f;
    float ComponentWeight = 1.f; ///< CastParameters::ComponentWeight
    bool GradientNeeded = false;
    bool GradientOpacityConstant = false; ///< then every sample's factor is GradientOpacityValue
    float GradientOpacityValue = 1.f;
    /// A sample's opacity depends on its value alone (no labels, mask or varying gradient
    /// opacity): the caster evaluates a block's opacities together.
    bool OpacityByValue = false;
    /// ... and so does its colour: the composite function works in stages over a block.
    bool ColorByValue = false;
    /// The rays' loops run compiled for wide vectors (CastParameters::WideVectors, where
    /// the processor has them).
    bool WideVectors = false;
    /// Lattice samples ahead of a block whose voxels it prefetches
    /// (CastParameters::PrefetchMinBytes; 0: none).
    int PrefetchSamples = 0;
    /// Shaded samples are shaded several at a time: exact shading, directional lights only
    /// (at most 8, none casting shadows).
    bool ShadeLanesTogether = false;
    /// The opacity function is 0 at every sample value s <= ZeroOpacityBelow or s >=
    /// ZeroOpacityAbove (floats on the safe side of its first and last non-zero value).
    float ZeroOpacityBelow = 0.f;
    float ZeroOpacityAbove = 0.f;
    double IntensityScale = 1.0; ///< 1 / the width of CastParameters::IntensityRange, or 0
    /// World gradient = GradientToWorld (row-major 3x3) times the voxel-index gradient: the
    /// transpose of the world-to-index matrix's linear part.
    float GradientToWorld[9] = { 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f };
    /// GradientToWorld's columns, each with a fourth entry 0 (a register each).
    alignas(16) float GradientToWorldColumns[3][4] = { { 1.f, 0.f, 0.f, 0.f },
      { 0.f, 1.f, 0.f, 0.f }, { 0.f, 0.f, 1.f, 0.f } };
    int IntegerSpecularPower = -1; ///< SpecularPower when it is a small whole number
    float SpecularPower = 10.f;    ///< CastParameters::SpecularPower
    /// Whether every directional light's diffuse and specular factors are the same for
    /// red, green and blue (white lights): one channel's shading serves all three.
    bool GreyLights = false;
    /// The ambient factor per channel (Ambient times AmbientLight), and 0: red, green,
    /// blue as one register.
    alignas(16) float Ambient[4] = { 0.f, 0.f, 0.f, 0.f };
    std::vector<DirectionalLight> DirectionalLights;
    std::vector<PositionalLight> PositionalLights;
    std::vector<double> SortedIsoValues;
    /// Per sorted iso value v, when there are only a few, the smallest float at least v: a
    /// float sample lies below v exactly when it lies below that float.
    std::vector<float> IsoThresholds;
    /// Whether shaded samples use the quantized normals (CastParameters::Shading), shaded
    /// by one of the two tables below.
    bool QuantizedNormals = false;
    /// Per normal code, its shading factors; empty for exact shading and under white
    /// lights.
    std::vector<ShadingFactors> NormalShading;
    /// Per normal code, its (diffuse, specular) pair when every factor is the same for
    /// red, green and blue (white lights: a quarter of the bytes, fewer operations); else
    /// empty.
    std::vector<float> GreyNormalShading;
  };

private:
  /// The lattice ranges of query.Path to cast: its part inside the field, the clipping
  /// planes and the cropping where source gives segments (sourceSegments of them); tEnter
  /// and tExit are where the ray enters and leaves the field inside the planes. False when
  /// the ray misses the field (source is not asked). owned: within CastParameters'
  /// owned box too (primary rays; shadow rays cross the ghost cells as well).
  bool RangesOf(const RayQuery& query, const SegmentSource& source,
    std::vector<Segment>& segments, std::vector<LatticeRange>& ranges, Vec3& indexOrigin,
    Vec3& indexDirection, std::size_t& sourceSegments, double& tEnter, double& tExit,
    bool owned = true) const;
  /// differences (optional): a thread's cache of cell differences for gradients, a power
  /// of two of them, shared by the rays of one image. merge and merged (optional, together):
  /// CastRayMerged's.
  template <class View>
  void CastRayIn(const View& field, const RayQuery& query, const SegmentSource& source,
    std::vector<Segment>& segments, std::vector<LatticeRange>& ranges, float rgba[4],
    CastStatistics& stats, double* firstHit, std::vector<RayEvent>* events,
    std::vector<CellDifferences>* differences, ShadowScratch* shadows,
    MergedEvents* merge = nullptr, EventCompositor* merged = nullptr) const;
  /// CastRayIn of the slice ray function (intervals: scratch for the cropping).
  template <class View>
  void CastSliceIn(const View& field, const RayQuery& query, std::vector<Segment>& intervals,
    float rgba[4], CastStatistics& stats, double* firstHit,
    std::vector<RayEvent>* events) const;
  template <class View>
  float TransmittanceIn(const View& field, const RayQuery& query, const SegmentSource& source,
    ShadowScratch& scratch, CastStatistics& stats) const;
  template <class View>
  bool CastImageIn(const View& field, const Camera& view, const float* depth,
    const SegmentSource& source, float* rgba, CastStatistics& stats,
    const std::function<bool(double)>& progress) const;
  /// The cells of each thread's cache of cell differences for the rays of view.
  std::size_t DifferenceCacheCellsFor(const Camera& view) const;

  const ScalarField* Field = nullptr;
  const CastParameters* Params = nullptr;
  Matrix4 WorldToIndex;
  /// The centre of the field's box, in world coordinates (Volume::Centre).
  Vec3 FieldCentre;
  RenderConstants Constants;
  /// The map of SetContributingCells when it applies to this caster's rays, or null.
  const CellMap* ContributingCells() const;

  const Occluders* Shadows = nullptr;
  std::vector<Component> Components;
  const CellMap* Cells = nullptr;
};

/// The volumes that shadow a scene's shaded contributions, each with a segment source per
/// light for its shadow rays (PARC buffers rendered from the light, or the whole ray).
class Occluders
{
public:
  struct Member
  {
    const RayCaster* Caster; ///< prepared
    /// Per light (the index into CastParameters::Lights): where this volume may block the
    /// light; null for the whole ray.
    std::vector<const SegmentSource*> LightSources;
  };
  void SetMembers(std::vector<Member> members) { this->Members = std::move(members); }
  const std::vector<Member>& GetMembers() const { return this->Members; }

  /// The transmittance along shadowRay (from a shaded point towards light `light`; see the
  /// file comment), the product over the members in their order; counts one shadow ray.
  float Transmittance(const Ray& shadowRay, std::size_t light, ShadowScratch& scratch,
    CastStatistics& stats) const;

private:
  std::vector<Member> Members;
  WholeRaySource WholeRay;
};

/// Scratch storage of one thread's scene rays (reused from ray to ray).
struct SceneScratch
{
  std::vector<std::vector<RayEvent>> Events; ///< per member
  MergedEvents Merged;
};

/// Several volumes cast together into one image (see the file comment): every ray meets
/// every volume, each through its own segment source.
class SceneCaster
{
public:
  struct Member
  {
    const RayCaster* Caster;     ///< prepared
    const SegmentSource* Source; ///< where the volume's samples may contribute
  };
  /// The members (at most MaxSceneVolumes, else false), in the order that breaks ties
  /// between events at one ray parameter. terminationOpacity: the merged opacity at which a
  /// ray stops.
  bool SetMembers(std::vector<Member> members, double terminationOpacity);

  /// One ray's premultiplied RGBA; stats has one entry per member; shadows (optional)
  /// like RayCaster::CastRay's.
  void CastRay(const RayQuery& query, std::vector<Segment>& segments,
    std::vector<LatticeRange>& ranges, SceneScratch& scratch, float rgba[4],
    CastStatistics* stats, ShadowScratch* shadows = nullptr) const;
  /// A whole image, like RayCaster::CastImage; stats receives one entry per member.
  bool CastImage(const Camera& view, const float* depth, float* rgba,
    std::vector<CastStatistics>& stats,
    const std::function<bool(double)>& progress = nullptr) const;

private:
  std::vector<Member> Members;
  /// Whether member v has nothing on the ray of pixel (px, py) (its source says so), or
  /// on query's ray when it has a pixel.
  bool Skips(std::size_t v, int px, int py) const;
  bool Skips(std::size_t v, const RayQuery& query) const;
  /// Merges the events of every member but Streamed by (ray parameter, member index), up
  /// to stop, into merged (Streamed's dt places them between its samples).
  void MergeEvents(const std::vector<std::vector<RayEvent>>& events, double stop,
    MergedEvents& merged) const;

  /// The order the members are cast in: isosurface volumes (their own opacity can stop a
  /// ray, usually soonest and cheapest), the whole-ray ones, then the composite ones, each
  /// group in member order.
  std::vector<std::size_t> CastOrder;
  /// The member whose samples are composited with the other members' events merged in
  /// between instead of becoming events (RayCaster::CastRayMerged): the last one cast,
  /// when it is a composite volume of one component that stops at TerminationOpacity;
  /// else the number of members.
  std::size_t Streamed = 0;
  double TerminationOpacity = 1.0;
};

} // namespace parc

#endif
