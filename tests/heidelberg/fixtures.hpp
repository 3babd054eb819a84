// Volumes and scenes with closed-form answers for VIRIM's tests.
#pragma once

#include <cstdint>
#include <functional>
#include <random>

#include "refmodel/scene/scene.hpp"
#include "refmodel/volume/volume.hpp"
#include "tests/refmodel/render_fixtures.hpp"  // make_volume

namespace voxcast::test {

inline ref::Volume random_volume(int nx, int ny, int nz, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> d(0, 255);
  return make_volume(nx, ny, nz, 8, [&](int, int, int) { return static_cast<std::uint16_t>(d(rng)); });
}

// A Heidelberg scene whose LUT is the identity ramp: density = value / 255.
inline ref::Scene heidelberg_scene(int W, int D, int H) {
  ref::Scene s;
  s.algorithm = ref::Algorithm::Heidelberg;
  s.tf_points = {ref::TfPoint{0.0, {1.0, 1.0, 1.0}, 0.0}, ref::TfPoint{255.0, {1.0, 1.0, 1.0}, 1.0}};
  s.render.width = W;
  s.render.height = H;
  s.heidelberg.depth = D;
  s.render.threads = 1;
  return s;
}

// The view every VIRIM unit is checked on beyond the aligned cases: turned
// 37 degrees about an oblique axis, zoomed, translated, in perspective, over
// a 24 x 22 x 20 view cube of oblique_volume().
inline ref::Scene oblique_heidelberg_scene() {
  ref::Scene s = heidelberg_scene(24, 22, 20);
  s.heidelberg.axis = {0.3, -0.5, 1.0};
  s.heidelberg.angle_deg = 37.0;
  s.heidelberg.zoom = 1.3;
  s.heidelberg.translation = {1.25, -0.5, 2.0};
  s.heidelberg.perspective = 40.0;
  return s;
}
inline ref::Volume oblique_volume() { return random_volume(20, 18, 16, 7); }

}  // namespace voxcast::test
