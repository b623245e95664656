// PARC for VTK: the counters of a render, as data (summed over threads and volumes).
#ifndef parcStatistics_h
#define parcStatistics_h

#include <cstdint>

namespace parc
{

/// Counters of one render; summed over threads (order-independent integers).
struct CastStatistics
{
  std::uint64_t Rays = 0;                ///< rays that met the volume's box
  std::uint64_t Segments = 0;            ///< segments handed to the caster
  std::uint64_t Samples = 0;             ///< scalar samples taken on the lattice
  std::uint64_t ContributingSamples = 0; ///< non-zero opacity, or isosurface crossings
  std::uint64_t GradientEvaluations = 0;
  /// Cells whose voxel differences were loaded for gradients (the rest were cached).
  std::uint64_t DifferenceLoads = 0;
  std::uint64_t Cells = 0; ///< cells crossed by the cast lattice ranges (paper, Table 2)
  /// Shadow rays: one per shaded contribution and shadow-casting light that lights it.
  std::uint64_t ShadowRays = 0;
  std::uint64_t ShadowSamples = 0; ///< lattice samples taken along shadow rays
  std::uint64_t ShadowCells = 0;   ///< cells crossed by them (paper, Table 3)

  CastStatistics& operator+=(const CastStatistics& o)
  {
    this->Rays += o.Rays;
    this->Segments += o.Segments;
    this->Samples += o.Samples;
    this->ContributingSamples += o.ContributingSamples;
    this->GradientEvaluations += o.GradientEvaluations;
    this->DifferenceLoads += o.DifferenceLoads;
    this->Cells += o.Cells;
    this->ShadowRays += o.ShadowRays;
    this->ShadowSamples += o.ShadowSamples;
    this->ShadowCells += o.ShadowCells;
    return *this;
  }
};

} // namespace parc

#endif
