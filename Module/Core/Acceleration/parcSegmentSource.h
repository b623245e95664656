// PARC for VTK: the one interface between acceleration and integration.
#ifndef parcSegmentSource_h
#define parcSegmentSource_h

#include "parcRay.h"

#include <vector>

namespace parc
{

/// A source of ray segments: the one interface between acceleration (depth buffers, bit
/// planes, the segment oracle) and the caster. Unaccelerated casting is the one-segment
/// source. Implementations must be safe to call from several threads at once.
class SegmentSource
{
public:
  virtual ~SegmentSource() = default;
  /// Appends to out the segments of the ray through ray-image pixel (px, py).
  virtual void GetSegments(int px, int py, const Ray& ray, std::vector<Segment>& out) const = 0;
  /// False when the ray through pixel (px, py) surely gets no segment: it is not even made.
  virtual bool MayHaveSegments(int /*px*/, int /*py*/) const { return true; }
};

/// Unaccelerated casting: the whole ray is one segment.
class WholeRaySource : public SegmentSource
{
public:
  void GetSegments(int px, int py, const Ray& ray, std::vector<Segment>& out) const override;
};

/// Nothing may contribute anywhere: no segment at all.
class EmptySource : public SegmentSource
{
public:
  void GetSegments(int, int, const Ray&, std::vector<Segment>&) const override {}
  bool MayHaveSegments(int, int) const override { return false; }
};

} // namespace parc

#endif
