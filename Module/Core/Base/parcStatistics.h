// PARC for VTK: the counters of a render, as data (summed over threads and volumes).
#ifndef parcStatistics_h
#define parcStatistics_h

#include <chrono>
#include <cstdint>

namespace parc
{

/// Seconds of a steady clock since start (the times the statistics and Auto measure).
inline double SecondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// A least-squares fit t = a + b s + c k of the casting time t of a ray against its
/// lattice samples s and contributing samples k, over a subset of a render's rays. It
/// measures what one more non-contributing sample costs (b), the samples a pass skips or
/// adds, for Auto's predictions. The one measurement among the counters: it never affects
/// an image.
struct RayCostFit
{
  /// The primary rays of every this many pixel columns (x = 0, ColumnStride, ...) are
  /// timed.
  static constexpr int ColumnStride = 4;
  /// Of the rays not cast in those columns, those of every this many pixel rows (y = 0,
  /// UncastRowStride, ...) are counted, each for UncastRowStride rays: their samples are
  /// only estimated, and clipping every such ray would cost a sparse scene's frame ~5%.
  static constexpr int UncastRowStride = 4;
  /// Sums over the timed rays of 1, s, k, t, s s, s k, k k, s t, k t.
  double Sums[9] = { 0, 0, 0, 0, 0, 0, 0, 0, 0 };
  /// The unaccelerated samples (CastStatistics) of the timed columns' rays, cast or not
  /// (those not cast estimated from every UncastRowStride-th row).
  double Unaccelerated = 0.0;

  /// A timed ray of s samples, k contributing, t seconds and u unaccelerated samples.
  void Add(double s, double k, double t, double u)
  {
    const double terms[9] = { 1.0, s, k, t, s * s, s * k, k * k, s * t, k * t };
    for (int i = 0; i < 9; ++i)
    {
      this->Sums[i] += terms[i];
    }
    this->Unaccelerated += u;
  }
  /// A counted ray of the timed columns that was not cast (no segment), of u unaccelerated
  /// samples (see UncastRowStride).
  void AddUncast(double u) { this->Unaccelerated += UncastRowStride * u; }
  /// Whether the primary ray of pixel column px is timed when it is cast.
  static bool TimesColumn(int px) { return px % ColumnStride == 0; }
  /// Whether the ray of pixel (px, py) is counted when it is not cast.
  static bool CountsUncast(int px, int py)
  {
    return TimesColumn(px) && py % UncastRowStride == 0;
  }
  RayCostFit& operator+=(const RayCostFit& o)
  {
    for (int i = 0; i < 9; ++i)
    {
      this->Sums[i] += o.Sums[i];
    }
    this->Unaccelerated += o.Unaccelerated;
    return *this;
  }
  double Rays() const { return this->Sums[0]; }
  /// Samples and thread-seconds of the timed rays.
  double Samples() const { return this->Sums[1]; }
  double Seconds() const { return this->Sums[3]; }
  /// b, the seconds one more non-contributing sample adds to a ray on one thread; false
  /// (b untouched) when the rays do not determine it: too few, or samples and contributing
  /// samples in a fixed proportion.
  bool SampleCost(double& b) const;
};

/// Counters of one render; summed over threads (order-independent integers, and the fit).
struct CastStatistics
{
  std::uint64_t Rays = 0;                ///< rays that met the volume's box
  std::uint64_t Segments = 0;            ///< segments handed to the caster
  std::uint64_t Samples = 0;             ///< scalar samples taken on the lattice
  std::uint64_t ContributingSamples = 0; ///< non-zero opacity, or isosurface crossings
  /// Samples the caster found in cells that cannot contribute
  /// (RayCaster::SetContributingCells): never interpolated when their whole group of lanes
  /// lies in such cells. A ray reads the map only where it crosses such cells
  /// (RayContext::ReadsMap): samples in such cells among cells that may contribute are
  /// interpolated and not counted here.
  std::uint64_t EmptyCellSamples = 0;
  std::uint64_t GradientEvaluations = 0;
  /// Cells whose voxel differences were loaded for gradients (the rest were cached).
  std::uint64_t DifferenceLoads = 0;
  /// Bytes of the caches of cell differences of the threads that may cast an image
  /// (RayCaster::CastImage; freed when the image is done).
  std::uint64_t DifferenceCacheBytes = 0;
  std::uint64_t Cells = 0; ///< cells crossed by the cast lattice ranges (paper, Table 2)
  /// Shadow rays: one per shaded contribution and shadow-casting light that lights it.
  std::uint64_t ShadowRays = 0;
  std::uint64_t ShadowSamples = 0; ///< lattice samples taken along shadow rays
  std::uint64_t ShadowCells = 0;   ///< cells crossed by them (paper, Table 3)
  /// Lattice samples the rays have from where they enter the field to where they leave it
  /// or their ray function stops them: the samples of a cast without acceleration (before
  /// cropping).
  std::uint64_t UnacceleratedSamples = 0;
  RayCostFit Timing; ///< of the primary rays of every RayCostFit::ColumnStride-th column

  CastStatistics& operator+=(const CastStatistics& o)
  {
    this->Rays += o.Rays;
    this->Segments += o.Segments;
    this->Samples += o.Samples;
    this->ContributingSamples += o.ContributingSamples;
    this->EmptyCellSamples += o.EmptyCellSamples;
    this->GradientEvaluations += o.GradientEvaluations;
    this->DifferenceLoads += o.DifferenceLoads;
    this->DifferenceCacheBytes += o.DifferenceCacheBytes;
    this->Cells += o.Cells;
    this->ShadowRays += o.ShadowRays;
    this->ShadowSamples += o.ShadowSamples;
    this->ShadowCells += o.ShadowCells;
    this->UnacceleratedSamples += o.UnacceleratedSamples;
    this->Timing += o.Timing;
    return *this;
  }
};

inline bool RayCostFit::SampleCost(double& b) const
{
  // The normal equations of (a, b, c): M x = r, solved by Cramer's rule.
  const double* q = this->Sums;
  const double m[3][3] = { { q[0], q[1], q[2] }, { q[1], q[4], q[5] }, { q[2], q[5], q[6] } };
  const double r[3] = { q[3], q[7], q[8] };
  const auto det = [](const double (&a)[3][3]) {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
      a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
      a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  };
  const double d = det(m);
  // Degenerate: fewer rays than unknowns, or s and k (nearly) proportional; the scale of
  // the determinant is that of the product of the diagonal.
  if (q[0] < 16.0 || !(d > 1e-9 * m[0][0] * m[1][1] * m[2][2]))
  {
    return false;
  }
  double mb[3][3];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      mb[i][j] = j == 1 ? r[i] : m[i][j];
    }
  }
  b = det(mb) / d;
  return true;
}

} // namespace parc

#endif
