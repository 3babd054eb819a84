// The engines that render a frame of the fixed-point design, behind one
// interface: the bit-true reference (refmodel/bittrue) and the hls kernels.
// Both consume the same host set-up (FrameSetup, VoxelMemory).
#pragma once

#include <string>
#include <vector>

#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/precision/profile.hpp"
#include "refmodel/scene/scene.hpp"

namespace voxcast::cosim {

// A scene's volume as every engine needs it: loaded, checked against the
// scene (crop), with its gradient voxel property.
struct SceneVolume {
  ref::Volume volume;
  ref::GradientField gradients;
};
SceneVolume load_scene_volume(const ref::Scene& scene);

// Throws voxcast::Error naming the width if the scene's precision profile
// cannot hold the volume, or (hls = true) if the hls engine is not compiled
// for it.
void check_fixed_point(const ref::Scene& scene, const SceneVolume& sv, bool hls);

// The hls engine is compiled for a fixed set of profiles (the kernels take
// the profile as a template parameter, as a synthesized design would).
bool hls_supports(const PrecisionProfile& p);
std::string hls_supported_profiles();  // for error messages

// Renders with the hls kernels; throws voxcast::Error if the profile is not
// compiled in (naming the ones that are).
ref::QuantImage hls_render_image(const bittrue::FrameSetup& setup,
                                 const bittrue::VoxelMemory& memory, int threads = 0,
                                 ref::FrameStats* stats = nullptr);

// One pixel through the hls kernels with every unit's output recorded.
bittrue::RayTrace hls_trace_ray(const bittrue::FrameSetup& setup,
                                const bittrue::VoxelMemory& memory, int px, int py);

}  // namespace voxcast::cosim
