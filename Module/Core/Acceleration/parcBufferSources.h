// PARC for VTK: segment sources fed by the buffers of the GL passes (no GL here).
//
// A primary ray (a query with its pixel) reads its own pixel. A ray without a pixel is
// answered only when it lies on one of the camera's rays (Camera::IsAlongRays: a shadow
// ray towards the eye of a light's camera, in either direction); it reads the up to 2 x 2
// pixels whose centres surround its image point and takes the union of what they hold, and
// the parts of the line outside the camera's near/far depth range count as covered. Any
// other ray gets the whole line. The pixel-less answer is conservative for the lines the
// pass itself was drawn conservatively for (a pass drawn for pixel centres covers the lines
// through pixel centres).
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

class DepthBufferSource final : public SegmentSource
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
  const Camera& GetView() const { return this->View; }

  void Segments(const RayQuery& query, std::vector<Segment>& out) const override;
  bool MayHaveSegments(int px, int py) const override;

  /// The segment of one pixel's ray; false when the ray meets no PC supercell.
  bool PixelSegment(int px, int py, const Ray& ray, Segment& segment) const;

private:
  /// Segments for a ray without a pixel (see the file comment).
  void LineSegments(const Ray& ray, std::vector<Segment>& out) const;

  Camera View; ///< of the pass
  std::vector<float> NearFar;
  const SupercellGrid* Grid = nullptr;
  Matrix4 WorldToIndex;
  double StartEps = 0.0; ///< voxel-index tolerance of "the ray starts inside"
};

class PlaneBufferSource final : public SegmentSource
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
  const Camera& GetView() const { return this->View; }

  void Segments(const RayQuery& query, std::vector<Segment>& out) const override;
  bool MayHaveSegments(int px, int py) const override;

  /// The plane indices set for one pixel (tests and statistics).
  void PixelPlanes(int px, int py, std::vector<int>& planes) const;

private:
  /// The WordsPerPixel words of pixel (px, py).
  const std::uint32_t* PixelWords(int px, int py) const;
  /// The slabs of the set planes of words (WordsPerPixel of them) along ray.
  void EmitSlabs(const std::uint32_t* words, const Ray& ray, std::vector<Segment>& out) const;

  Camera View; ///< of the pass
  std::vector<std::uint32_t> Bits;
  int WordsPerPixel = 0;
  const SupercellGrid* Grid = nullptr;
  int Axis = 0;
  int FirstPlane = 0;
  Matrix4 WorldToIndex;
};

/// The segments of planes clipped to the depth source's [near, far].
class BothSource final : public SegmentSource
{
public:
  BothSource(const DepthBufferSource& depth, const PlaneBufferSource& planes)
    : Depth(depth)
    , Planes(planes)
  {
  }
  void Segments(const RayQuery& query, std::vector<Segment>& out) const override;
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
