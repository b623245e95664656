// PARC for VTK: the one interface between acceleration and integration.
#ifndef parcSegmentSource_h
#define parcSegmentSource_h

#include "parcRay.h"

#include <vector>

namespace parc
{

/// What a segment source is asked: a ray, keyed by the ray itself, with an optional pixel
/// hint. A ray of the image the source was made for (a primary ray) passes its pixel, and a
/// buffer source answers with one look-up; any other ray (a shadow ray towards a light, a
/// test's ray) passes none, and the source finds what it knows of the ray by itself.
struct RayQuery
{
  Ray Path;              ///< the ray, world coordinates
  bool HasPixel = false; ///< whether Pixel is given
  int Pixel[2] = { 0, 0 }; ///< the image pixel (x, y) whose centre ray Path is

  /// A primary ray: the ray through the centre of pixel (px, py).
  static RayQuery AtPixel(const Ray& ray, int px, int py) { return { ray, true, { px, py } }; }
  /// Any ray, without a pixel.
  static RayQuery Anywhere(const Ray& ray) { return { ray, false, { 0, 0 } }; }
};

/// A source of ray segments: the one interface between acceleration (depth buffers, bit
/// planes, the segment oracle) and the caster. Unaccelerated casting is the one-segment
/// source. Every source answers every query conservatively: no contributing sample of the
/// ray lies outside the segments. Implementations must be safe to call from several
/// threads at once.
class SegmentSource
{
public:
  virtual ~SegmentSource() = default;
  /// Appends to out the ray-parameter segments of query.Path that may hold contributing
  /// samples (in any order; they may overlap).
  virtual void Segments(const RayQuery& query, std::vector<Segment>& out) const = 0;
  /// False when the primary ray through pixel (px, py) surely gets no segment: it is not
  /// even made.
  virtual bool MayHaveSegments(int /*px*/, int /*py*/) const { return true; }
};

/// Unaccelerated casting: the whole ray is one segment.
class WholeRaySource : public SegmentSource
{
public:
  void Segments(const RayQuery& query, std::vector<Segment>& out) const override;
};

/// Nothing may contribute anywhere: no segment at all.
class EmptySource : public SegmentSource
{
public:
  void Segments(const RayQuery&, std::vector<Segment>&) const override {}
  bool MayHaveSegments(int, int) const override { return false; }
};

} // namespace parc

#endif
