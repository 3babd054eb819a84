// Small volumes and scenes with closed-form answers, shared by the render tests.
#pragma once

#include <cstdint>
#include <functional>

#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene.hpp"
#include "refmodel/volume/volume.hpp"

namespace voxcast::test {

// A volume whose stored value at (x, y, z) is f(x, y, z).
inline ref::Volume make_volume(int nx, int ny, int nz, int bits,
                               const std::function<std::uint16_t(int, int, int)>& f) {
  ref::Volume v;
  v.dims = {nx, ny, nz};
  v.bits = bits;
  v.source = "test volume";
  v.data.resize(v.voxel_count());
  for (int z = 0; z < nz; ++z)
    for (int y = 0; y < ny; ++y)
      for (int x = 0; x < nx; ++x) v.data[v.index(x, y, z)] = f(x, y, z);
  return v;
}

inline ref::Volume constant_volume(int n, std::uint16_t value) {
  return make_volume(n, n, n, 8, [=](int, int, int) { return value; });
}

// An unshaded scene with one transfer-function point (so every value maps to
// the same colour and alpha), ERT off, a parallel camera.
inline ref::Scene constant_alpha_scene(double alpha) {
  ref::Scene s;
  s.tf_points = {ref::TfPoint{0.0, {1.0, 1.0, 1.0}, alpha}};
  s.render.mode = ref::RenderMode::Unshaded;
  s.render.ert_threshold = 1.0;
  s.camera.projection = ref::Projection::Parallel;
  s.lights = {ref::Light{}};
  return s;
}

// Renders one ray of `scene` through pixel (px, py).
struct OneRay {
  glm::dvec4 rgba;
  ref::RayStats stats;
  ref::Segment segment;
};

inline OneRay cast_pixel(const ref::Scene& scene, const ref::Volume& volume, int px, int py) {
  const ref::GradientField g = ref::compute_gradients(volume, scene.volume.gradient);
  const ref::RenderInputs in = ref::make_render_inputs(scene, volume, g, scene.camera.pose);
  const ref::Ray ray = ref::primary_ray(in.camera, px, py);
  OneRay r;
  r.rgba = ref::cast_ray(in.volume, in.tf, in.shading, in.settings, ray, &r.stats);
  if (auto seg = ref::clip(ray, in.volume.world_box)) r.segment = *seg;
  return r;
}

}  // namespace voxcast::test
