#include "refmodel/scene/scene.hpp"

#include <algorithm>
#include <cmath>

#include "refmodel/error.hpp"

namespace voxcast::ref {

const char* to_string(Projection p) {
  return p == Projection::Perspective ? "perspective" : "parallel";
}
const char* to_string(RenderMode m) {
  switch (m) {
    case RenderMode::Shaded: return "shaded";
    case RenderMode::Unshaded: return "unshaded";
    case RenderMode::Mip: return "mip";
  }
  return "?";
}
const char* to_string(ClassificationMode m) {
  return m == ClassificationMode::Preintegrated ? "preintegrated" : "post";
}
const char* to_string(LightType t) {
  return t == LightType::Directional ? "directional" : "headlight";
}

TransferFunction stored_transfer_function(const Scene& scene, const Volume& volume) {
  return TransferFunction(scene.tf_points, scene.tf_interpolation, scene.material)
      .in_stored_units(volume);
}

void validate_against_volume(const Scene& scene, const Volume& volume) {
  if (!scene.volume.crop) return;
  static const char* const kAxis[3] = {"x", "y", "z"};
  const Crop& c = *scene.volume.crop;
  for (int a = 0; a < 3; ++a)
    if (c.hi[a] >= volume.dims[a])
      throw Error(scene.origin + ": volume.crop.hi[" + std::to_string(a) + "] = " +
                  std::to_string(c.hi[a]) + " is outside the volume (" + kAxis[a] + " has " +
                  std::to_string(volume.dims[a]) + " voxels, indices 0.." +
                  std::to_string(volume.dims[a] - 1) + ")");
}

std::vector<CameraPose> frame_poses(const CameraDesc& camera, int frames) {
  const std::size_t n = static_cast<std::size_t>(std::max(frames, 1));
  if (camera.path.size() < 2)
    return std::vector<CameraPose>(n, camera.path.empty() ? camera.pose : camera.path.front());
  // Uniform parameter over the keyframes: frame 0 is the first keyframe, the
  // last frame the last one, linear in between.
  const std::size_t segments = camera.path.size() - 1;
  std::vector<CameraPose> poses;
  poses.reserve(n);
  for (std::size_t f = 0; f < n; ++f) {
    const double u = n == 1 ? 0.0
                            : static_cast<double>(f) / static_cast<double>(n - 1) *
                                  static_cast<double>(segments);
    const std::size_t k = std::min(static_cast<std::size_t>(u), segments - 1);
    const double t = u - static_cast<double>(k);
    const CameraPose& a = camera.path[k];
    const CameraPose& b = camera.path[k + 1];
    poses.push_back({a.eye + t * (b.eye - a.eye), a.center + t * (b.center - a.center),
                     a.up + t * (b.up - a.up)});
  }
  return poses;
}

}  // namespace voxcast::ref
