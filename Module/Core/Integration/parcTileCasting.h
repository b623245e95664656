// Casting an image in tiles of pixels over VTK's SMP tools, for the single-volume and
// the scene caster: each thread's scratch, the pixels' rays, progress by bands of tile
// rows. Internal to the casters.
#ifndef parc_TileCasting_h
#define parc_TileCasting_h

#include "parcRayCaster.h"

#include <vtkSMPThreadLocal.h>
#include <vtkSMPTools.h>

#include <algorithm>
#include <functional>
#include <vector>

namespace parc::casting
{

constexpr int TileSize = 16;        ///< ray-image pixels per tile edge
constexpr int TileRowsPerBand = 4;  ///< tile rows cast between two progress reports

/// Scratch storage of one thread's rays.
struct RayScratch
{
  std::vector<Segment> Segments;
  std::vector<LatticeRange> Ranges;
  SceneScratch Scene; ///< SceneCaster
  CastStatistics Stats;
  std::vector<CastStatistics> MemberStats; ///< per volume (SceneCaster)
  std::vector<CellDifferences> Differences; ///< of one volume's cells (RayCaster)
  ShadowScratch Shadows;
};

/// The ray of pixel (px, py), ending at the opaque geometry of depth (optional).
inline Ray PixelRay(const Camera& view, const float* depth, int px, int py)
{
  Ray ray = view.MakeRay(px, py);
  const std::size_t pixel = static_cast<std::size_t>(py) * view.Width + px;
  if (depth && depth[pixel] < 1.f)
  {
    ray.TMax = std::min(ray.TMax, view.DepthToParameter(ray, px, py, depth[pixel]));
  }
  return ray;
}

/// Casts the tiles of one band of rows; vtkSMPTools functor.
template <class Cast, class MayHave, class Skip>
struct TileCaster
{
  const Cast& CastOne;       ///< casts one ray: (query, scratch, rgba)
  const MayHave& MayHaveRay; ///< (px, py): false when the pixel's ray surely gets nothing
  const Skip& SkipOne;       ///< (px, py, scratch): for each pixel whose ray is not cast
  const Camera& View;
  const float* Depth;
  float* Image;
  int TilesX;
  int FirstTileRow;
  vtkSMPThreadLocal<RayScratch> Local;

  void Initialize() {}
  void operator()(vtkIdType begin, vtkIdType end)
  {
    RayScratch& scratch = this->Local.Local();
    for (vtkIdType tile = begin; tile < end; ++tile)
    {
      const int tx = static_cast<int>(tile % this->TilesX);
      const int ty = this->FirstTileRow + static_cast<int>(tile / this->TilesX);
      const int x1 = std::min((tx + 1) * TileSize, this->View.Width);
      const int y1 = std::min((ty + 1) * TileSize, this->View.Height);
      for (int py = ty * TileSize; py < y1; ++py)
      {
        for (int px = tx * TileSize; px < x1; ++px)
        {
          float* rgba = this->Image + 4 * (static_cast<std::size_t>(py) * this->View.Width + px);
          if (!this->MayHaveRay(px, py))
          {
            std::fill_n(rgba, 4, 0.f);
            this->SkipOne(px, py, scratch);
            continue;
          }
          const Ray ray = PixelRay(this->View, this->Depth, px, py);
          this->CastOne(RayQuery::AtPixel(ray, px, py), scratch, rgba);
        }
      }
    }
  }
  void Reduce() {}
};

/// Casts a whole image in bands of tile rows (see RayCaster::CastImage); reduce(scratch)
/// gathers each thread's statistics.
template <class Cast, class MayHave, class Skip, class Reduce>
inline bool CastTiles(const Camera& view, const float* depth, const Cast& castOne,
  const MayHave& mayHave, const Skip& skipOne, float* rgba, const Reduce& reduce,
  const std::function<bool(double)>& progress)
{
  // Every pixel of a cast band is written by its tile (zero when no ray is cast).
  const int tilesX = (view.Width + TileSize - 1) / TileSize;
  const int tilesY = (view.Height + TileSize - 1) / TileSize;
  bool completed = true;
  TileCaster<Cast, MayHave, Skip> caster{ castOne, mayHave, skipOne, view, depth, rgba, tilesX,
    0, {} };
  for (int row = 0; row < tilesY; row += TileRowsPerBand)
  {
    const int rows = std::min(TileRowsPerBand, tilesY - row);
    caster.FirstTileRow = row;
    vtkSMPTools::For(0, static_cast<vtkIdType>(tilesX) * rows, 1, caster);
    if (progress && !progress(static_cast<double>(row + rows) / tilesY))
    {
      const std::size_t castRows = std::min(view.Height, (row + rows) * TileSize);
      std::fill(rgba + 4 * castRows * view.Width,
        rgba + 4 * static_cast<std::size_t>(view.Height) * view.Width, 0.f);
      completed = false;
      break;
    }
  }
  for (auto& scratch : caster.Local)
  {
    reduce(scratch);
  }
  return completed;
}

} // namespace parc::casting

#endif
