#include "refmodel/math/geometry.hpp"

#include <algorithm>
#include <limits>

namespace voxcast::ref {

std::optional<Segment> clip(const Ray& ray, const Box& box, double t_min) {
  double t0 = t_min;
  double t1 = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double o = ray.origin[a];
    const double d = ray.direction[a];
    if (d == 0.0) {
      if (o < box.lo[a] || o > box.hi[a]) return std::nullopt;
      continue;
    }
    double ta = (box.lo[a] - o) / d;
    double tb = (box.hi[a] - o) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t0 <= t1)) return std::nullopt;
  return Segment{t0, t1};
}

}  // namespace voxcast::ref
