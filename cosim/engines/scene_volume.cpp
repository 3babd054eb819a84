// Loading a scene's volume and checking it against the fixed-point design,
// shared by render, cosim and regress.
#include <algorithm>
#include <cmath>

#include "cosim/engines/engines.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::cosim {

SceneVolume load_scene_volume(const ref::Scene& scene) {
  SceneVolume sv{ref::load_volume(scene.volume.source, scene.base_dir,
                                  scene.volume.raw ? &*scene.volume.raw : nullptr,
                                  {.resample = scene.volume.resample}),
                 {}};
  ref::validate_against_volume(scene, sv.volume);
  sv.gradients = ref::compute_gradients(sv.volume, scene.volume.gradient);
  return sv;
}

void check_fixed_point(const ref::Scene& scene, const SceneVolume& sv, bool hls) {
  double max_gradient = 0.0;
  for (const glm::vec3& v : sv.gradients.g)
    max_gradient = std::max({max_gradient, std::abs(static_cast<double>(v.x)),
                             std::abs(static_cast<double>(v.y)), std::abs(static_cast<double>(v.z))});
  check_profile_fits(scene.precision, sv.volume, max_gradient);
  if (hls && !hls_supports(scene.precision))
    throw Error("precision profile " + scene.precision_name +
                " is not compiled into the hls engine (compiled: " + hls_supported_profiles() +
                ")");
}

}  // namespace voxcast::cosim
