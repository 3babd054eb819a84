#include "refmodel/bittrue/geometry_bound.hpp"

#include "refmodel/bittrue/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <optional>

namespace voxcast::bittrue {

namespace {

// M = |forward + u0·right + v0·up|, the corner pixels' direction length (1 for
// a parallel camera).
double corner_length(const ref::CameraFrame& cam) {
  if (cam.projection != ref::Projection::Perspective) return 1.0;
  const double u0 = (1.0 / cam.width - 1.0) * cam.half_width;
  const double v0 = (1.0 - 1.0 / cam.height) * cam.half_height;
  return std::sqrt(1.0 + u0 * u0 + v0 * v0);
}

// direction_error_bound for a pixel with x + y = `sum` whose direction has
// length |d| = 1/inv_len (in units of M).
double direction_error(const PrecisionProfile& p, const ref::CameraFrame& cam, double sum,
                       double inv_len) {
  const int df = p.dir_frac_bits;
  if (cam.projection == ref::Projection::Parallel) return std::ldexp(1.0, -(df + 1));
  const double dd = (1.0 + sum) * std::ldexp(1.0, -(df + 1));
  return (1.0 + std::sqrt(3.0)) * dd * inv_len + 4.0 * std::ldexp(1.0, -df);
}

double step_error(const PrecisionProfile& p, double du, const ref::Vec3& world_scale, double step) {
  const double ws_min = std::min({world_scale.x, world_scale.y, world_scale.z});
  return du * step / ws_min + (1.0 + du) * std::ldexp(1.0, -(p.dir_frac_bits + 1)) +
         std::ldexp(1.0, -(p.pos_frac_bits + 1));
}

double first_sample_error(const PrecisionProfile& p, double sum, double du,
                          const ref::Vec3& world_scale, double step, double k_in) {
  const double half_pf = std::ldexp(1.0, -(p.pos_frac_bits + 1));
  return std::sqrt(3.0) *
         ((1.0 + sum) * half_pf + k_in * step_error(p, du, world_scale, step) + half_pf);
}

}  // namespace

double direction_error_bound(const PrecisionProfile& p, const ref::CameraFrame& cam, int x,
                             int y) {
  const double u = (2.0 * (x + 0.5) / cam.width - 1.0) * cam.half_width;
  const double v = (1.0 - 2.0 * (y + 0.5) / cam.height) * cam.half_height;
  const double len = glm::length(cam.forward + u * cam.right + v * cam.up) / corner_length(cam);
  return direction_error(p, cam, static_cast<double>(x + y), 1.0 / len);
}

double origin_error_bound(const PrecisionProfile& p, int x, int y) {
  return (1.0 + x + y) * std::ldexp(1.0, -(p.pos_frac_bits + 1));
}

double step_error_bound(const PrecisionProfile& p, const ref::CameraFrame& cam,
                        const ref::Vec3& world_scale, double step, int x, int y) {
  return step_error(p, direction_error_bound(p, cam, x, y), world_scale, step);
}

double lever_bound(const ref::CameraFrame& cam, const ref::Box& world_box, double depth,
                   double step) {
  const double depth_far = ref::box_depth_range(cam, world_box).far;
  return corner_length(cam) * std::max(0.0, depth_far - depth) / step + 1.0;
}

double first_sample_error_bound(const PrecisionProfile& p, const ref::CameraFrame& cam,
                                const ref::Vec3& world_scale, double step, int x, int y,
                                double k_in) {
  return first_sample_error(p, static_cast<double>(x + y), direction_error_bound(p, cam, x, y),
                            world_scale, step, k_in);
}

double frame_first_sample_error_bound(const PrecisionProfile& p, const ref::CameraFrame& cam,
                                      const ref::Vec3& world_scale, const ref::Box& world_box,
                                      double depth, double step) {
  // Each pixel's own lever: its float ray's entry from the plane, in samples,
  // + 1 for the clip's truncations and the jitter (< 1 sample). A ray that
  // misses the box takes no sample (one that grazes it in fixed point enters
  // next to its hitting neighbour, at about its lever).
  double worst = 0.0;
  for (int y = 0; y < cam.height; ++y)
    for (int x = 0; x < cam.width; ++x) {
      const ref::Ray ray = ref::origin_plane_ray(cam, x, y, depth);
      const std::optional<ref::Segment> seg = ref::clip(ray, world_box);
      if (!seg) continue;
      const double k = seg->t_enter / step + 1.0;
      worst = std::max(worst, first_sample_error_bound(p, cam, world_scale, step, x, y, k));
    }
  return worst;
}

SamplePositionError frame_sample_position_error(const PrecisionProfile& p,
                                                const FrameRegisters& regs,
                                                const std::vector<Raw>& rsqrt_seed,
                                                const ref::CameraFrame& cam,
                                                const ref::Vec3& world_scale, double step,
                                                int max_side) {
  const auto stride_of = [&](int side) { return std::max(1, (side + max_side - 1) / max_side); };
  const int sx = stride_of(cam.width), sy = stride_of(cam.height);
  const auto axis = [](int n, int stride) {
    std::vector<int> v;
    for (int i = 0; i < n; i += stride) v.push_back(i);
    if (v.back() != n - 1) v.push_back(n - 1);
    return v;
  };
  SamplePositionError worst;
  for (const int y : axis(cam.height, sy))
    for (const int x : axis(cam.width, sx)) {
      const BtRay ray = bt_ray_setup(p, regs, rsqrt_seed, x, y);
      if (!ray.hit) continue;
      const ref::Ray f = ref::origin_plane_ray(cam, x, y, regs.origin_depth);
      const double last = static_cast<double>(ray.n - 1);
      for (int a = 0; a < 3; ++a) {
        const auto ia = static_cast<std::size_t>(a);
        const auto line = [&](double k) {
          return (f.origin[a] + k * step * f.direction[a]) / world_scale[a];
        };
        const double e0 = std::abs(ray.p0[ia] - line(ray.k_in));
        const double e1 = std::abs(ray.p0[ia] + last * ray.s[ia] - line(ray.k_in + last));
        const double e = std::max(e0, e1);
        if (e > worst.voxels) worst = {e, x, y};
      }
    }
  return worst;
}

}  // namespace voxcast::bittrue
