#include "parcSegmentSource.h"

#include <limits>

namespace parc
{

void WholeRaySource::GetSegments(int, int, const Ray&, std::vector<Segment>& out) const
{
  constexpr double inf = std::numeric_limits<double>::infinity();
  out.push_back({ -inf, inf });
}

} // namespace parc
