#include "parcSegmentSource.h"

#include <limits>

namespace parc
{

void WholeRaySource::Segments(const RayQuery&, std::vector<Segment>& out) const
{
  constexpr double inf = std::numeric_limits<double>::infinity();
  out.push_back({ -inf, inf });
}

} // namespace parc
