// PARC for VTK: segment sources fed by the buffers of the GL passes (no GL here).
//
// DepthBufferSource turns each pixel's near/far view depths (the smallest and largest
// depth along the view direction of the depth-model faces covering the pixel, dilated so
// that grazing rays are covered) into one ray segment. A ray whose start lies in a PC
// supercell (eye or view plane inside the model) starts at its beginning instead
// (paper, section 3). PlaneBufferSource turns each pixel's bit set of colour-model planes
// into the slabs of supercells the ray may meet (paper, section 4): zero words are skipped,
// then zero bits, and runs of set bits become one segment. BothSource intersects the two.
#ifndef parcBufferSources_h
#define parcBufferSources_h

#include "parcCamera.h"
#include "parcSegmentSource.h"
#include "parcSupercellGrid.h"

#include <cstdint>
#include <vector>

namespace parc
{

class DepthBufferSource : public SegmentSource
{
public:
  /// Depth values that mark "no face" (the pass clears to it); above any real depth.
  static constexpr float Empty = 3.0e38f;

  /// nearFar holds (near, -far) per pixel, rows bottom to top, as the GL pass writes them.
  /// grid and worldToIndex locate rays that start inside the model.
  void Set(const Camera& view, std::vector<float> nearFar, const SupercellGrid* grid,
    const Matrix4& worldToIndex);
  /// Gives the buffer back (to be filled again without reallocating); the source is empty.
  std::vector<float> ReleaseBuffer() { return std::move(this->NearFar); }
  /// Memory held by the buffer, in bytes.
  std::size_t GetMemorySize() const { return this->NearFar.capacity() * sizeof(float); }

  void GetSegments(int px, int py, const Ray& ray, std::vector<Segment>& out) const override;
  bool MayHaveSegments(int px, int py) const override;

  /// The segment of one pixel; false when the ray meets no PC supercell.
  bool PixelSegment(int px, int py, const Ray& ray, Segment& segment) const;

private:
  Camera View; ///< of the pass
  std::vector<float> NearFar;
  const SupercellGrid* Grid = nullptr;
  Matrix4 WorldToIndex;
  double StartEps = 0.0; ///< voxel-index tolerance of "the ray starts inside"
};

class PlaneBufferSource : public SegmentSource
{
public:
  /// bits holds wordsPerPixel 32-bit words per pixel; bit p of the pixel's set is plane p
  /// (supercell index firstPlane + p along axis).
  void Set(const Camera& view, std::vector<std::uint32_t> bits, int wordsPerPixel,
    const SupercellGrid* grid, int axis, int firstPlane, const Matrix4& worldToIndex);
  /// Gives the buffer back (to be filled again without reallocating); the source is empty.
  std::vector<std::uint32_t> ReleaseBuffer() { return std::move(this->Bits); }
  /// Memory held by the buffer, in bytes.
  std::size_t GetMemorySize() const { return this->Bits.capacity() * sizeof(std::uint32_t); }

  void GetSegments(int px, int py, const Ray& ray, std::vector<Segment>& out) const override;
  bool MayHaveSegments(int px, int py) const override;

  /// The plane indices set for one pixel (tests and statistics).
  void PixelPlanes(int px, int py, std::vector<int>& planes) const;

private:
  Camera View; ///< of the pass
  std::vector<std::uint32_t> Bits;
  int WordsPerPixel = 0;
  const SupercellGrid* Grid = nullptr;
  int Axis = 0;
  int FirstPlane = 0;
  Matrix4 WorldToIndex;
};

/// The segments of planes clipped to the depth source's [near, far].
class BothSource : public SegmentSource
{
public:
  BothSource(const DepthBufferSource& depth, const PlaneBufferSource& planes)
    : Depth(depth)
    , Planes(planes)
  {
  }
  void GetSegments(int px, int py, const Ray& ray, std::vector<Segment>& out) const override;
  bool MayHaveSegments(int px, int py) const override
  {
    return this->Depth.MayHaveSegments(px, py) && this->Planes.MayHaveSegments(px, py);
  }

private:
  const DepthBufferSource& Depth;
  const PlaneBufferSource& Planes;
};

} // namespace parc

#endif
