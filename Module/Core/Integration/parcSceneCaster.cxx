#include "parcRayCaster.h"
#include "parcTileCasting.h"

#include <algorithm>
#include <limits>
#include <numeric>

namespace parc
{
using namespace casting;

namespace
{
/// Lattice steps beyond a scene ray's stop that its composite and isosurface volumes are
/// still cast (SceneCaster::CastRay).
constexpr double StopMarginSteps = 2.0;

/// The first lattice index k of member `member` (sample distance dt) whose sample at ray
/// parameter k dt comes after an event at t of member `from` in the merge by (ray
/// parameter, member index); the lattice position is computed as the caster computes it.
long FirstSampleAfter(double t, std::size_t from, double dt, std::size_t member)
{
  const auto after = [&](long k) {
    const double tk = k * dt;
    return tk > t || (tk == t && member > from);
  };
  constexpr double Limit = 4503599627370496.0; // 2^52: lattice indices stay exact
  long k = static_cast<long>(std::max(-Limit, std::min(std::floor(t / dt), Limit)));
  while (!after(k))
  {
    ++k;
  }
  while (after(k - 1))
  {
    --k;
  }
  return k;
}
}

bool SceneCaster::SetMembers(std::vector<Member> members, double terminationOpacity)
{
  if (members.size() > MaxSceneVolumes)
  {
    return false;
  }
  this->Members = std::move(members);
  this->TerminationOpacity = terminationOpacity;
  this->CastOrder.resize(this->Members.size());
  std::iota(this->CastOrder.begin(), this->CastOrder.end(), std::size_t(0));
  const auto rank = [this](std::size_t v) {
    return TraitsOf(this->Members[v].Caster->GetParameters()->Blend).CastRank;
  };
  std::stable_sort(this->CastOrder.begin(), this->CastOrder.end(),
    [&rank](std::size_t a, std::size_t b) { return rank(a) < rank(b); });
  this->Streamed = this->Members.size();
  if (!this->CastOrder.empty())
  {
    const RayCaster& last = *this->Members[this->CastOrder.back()].Caster;
    if (TraitsOf(last.GetParameters()->Blend).StreamsInScene && last.GetComponents().empty() &&
      last.GetParameters()->TerminationOpacity == terminationOpacity)
    {
      this->Streamed = this->CastOrder.back();
    }
  }
  return true;
}

bool SceneCaster::Skips(std::size_t v, int px, int py) const
{
  const Member& m = this->Members[v];
  return !m.Caster->CastsEveryRay() && !m.Source->MayHaveSegments(px, py);
}

bool SceneCaster::Skips(std::size_t v, const RayQuery& query) const
{
  return query.HasPixel && this->Skips(v, query.Pixel[0], query.Pixel[1]);
}

void SceneCaster::MergeEvents(
  const std::vector<std::vector<RayEvent>>& events, double stop, MergedEvents& merged) const
{
  const std::size_t n = this->Members.size();
  const bool streams = this->Streamed < n;
  const double dt =
    streams ? this->Members[this->Streamed].Caster->GetParameters()->SampleDistance : 1.0;
  merged.Entries.clear();
  merged.Next = 0;
  merged.End = streams && stop < std::numeric_limits<double>::infinity()
    ? FirstSampleAfter(stop, this->Streamed, dt, this->Streamed)
    : std::numeric_limits<long>::max();
  // Each member's events are in ray order.
  std::size_t next[MaxSceneVolumes] = {};
  for (;;)
  {
    std::size_t best = n;
    for (std::size_t v = 0; v < n; ++v)
    {
      if (next[v] < events[v].size() &&
        (best == n || events[v][next[v]].T < events[best][next[best]].T))
      {
        best = v;
      }
    }
    if (best == n || events[best][next[best]].T > stop)
    {
      break;
    }
    const RayEvent& e = events[best][next[best]++];
    merged.Entries.push_back(
      { streams ? FirstSampleAfter(e.T, best, dt, this->Streamed) : 0, e });
  }
}

void SceneCaster::CastRay(const RayQuery& query, std::vector<Segment>& segments,
  std::vector<LatticeRange>& ranges, SceneScratch& scratch, float rgba[4],
  CastStatistics* stats, ShadowScratch* shadows) const
{
  std::vector<std::vector<RayEvent>>& events = scratch.Events;
  events.resize(this->Members.size());
  float own[4];
  double stop = std::numeric_limits<double>::infinity(); // see the header's file comment
  RayQuery clamped = query;
  // A volume that can stop the ray is cast two lattice steps beyond the stop: every sample
  // at or before it, and the sample after it that an isosurface crossing before it is
  // found with. The others give their whole-ray result.
  auto clampFor = [&](const CastParameters& p) {
    clamped.Path.TMax = TraitsOf(p.Blend).StopsRays
      ? std::min(query.Path.TMax, stop + StopMarginSteps * p.SampleDistance)
      : query.Path.TMax;
  };
  for (const std::size_t v : this->CastOrder)
  {
    events[v].clear();
    if (v == this->Streamed || this->Skips(v, query))
    {
      continue;
    }
    const Member& m = this->Members[v];
    const CastParameters& p = *m.Caster->GetParameters();
    clampFor(p);
    m.Caster->CastRay(
      clamped, *m.Source, segments, ranges, own, stats[v], nullptr, &events[v], shadows);
    if (TraitsOf(p.Blend).StopsRays && !events[v].empty() && !(own[3] < p.TerminationOpacity))
    {
      stop = std::min(stop, events[v].back().T);
    }
  }
  MergedEvents& merged = scratch.Merged;
  this->MergeEvents(events, stop, merged);
  EventCompositor compositor;
  if (this->Streamed < this->Members.size() && !this->Skips(this->Streamed, query))
  {
    const Member& m = this->Members[this->Streamed];
    clampFor(*m.Caster->GetParameters());
    m.Caster->CastRayMerged(
      clamped, *m.Source, segments, ranges, merged, compositor, stats[this->Streamed], shadows);
  }
  // The events after the streamed volume's samples, or all of them.
  merged.AddBefore(std::numeric_limits<long>::max(), compositor, this->TerminationOpacity);
  compositor.Finish(rgba);
}

bool SceneCaster::CastImage(const Camera& view, const float* depth, float* rgba,
  std::vector<CastStatistics>& stats, const std::function<bool(double)>& progress) const
{
  const std::size_t n = this->Members.size();
  auto castOne = [&](const RayQuery& query, RayScratch& scratch, float* pixel) {
    scratch.MemberStats.resize(n);
    this->CastRay(query, scratch.Segments, scratch.Ranges, scratch.Scene, pixel,
      scratch.MemberStats.data(), &scratch.Shadows);
  };
  auto mayHave = [&](int px, int py) {
    for (std::size_t v = 0; v < n; ++v)
    {
      if (!this->Skips(v, px, py))
      {
        return true;
      }
    }
    return false;
  };
  stats.assign(n, CastStatistics());
  auto skipOne = [](int, int, RayScratch&) {}; // Auto's fit is the single volume's
  auto reduce = [&stats](const RayScratch& scratch) {
    for (std::size_t v = 0; v < scratch.MemberStats.size(); ++v)
    {
      stats[v] += scratch.MemberStats[v];
    }
  };
  return CastTiles(view, depth, castOne, mayHave, skipOne, rgba, reduce, progress);
}

} // namespace parc
