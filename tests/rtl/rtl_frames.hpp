// Small frames for the rtl engine's tests: a phantom, a scene in TOML, the
// host set-up (FrameSetup + VoxelMemory) every engine reads.
#pragma once

#include <memory>
#include <string>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "refmodel/volume/gradients.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::test {

struct RtlFrame {
  ref::Scene scene;
  std::shared_ptr<ref::Volume> volume;
  std::shared_ptr<ref::GradientField> gradients;
  bittrue::FrameSetup setup;
  bittrue::VoxelMemory memory;
};

// A phantom of edge `size` seen from an oblique eye, 3 opacity points; `extra`
// TOML lines override (e.g. "precision.profile=vizard2").
inline RtlFrame make_rtl_frame(const std::string& phantom, int size, int image,
                               const ref::Overrides& overrides = {}) {
  const double c = (size - 1) / 2.0;
  const std::string text =
      "[volume]\nsource = \"phantom:" + phantom + "?size=" + std::to_string(size) +
      "\"\n[classification]\npoints = [ {value = 0, alpha = 0.0}, "
      "{value = 30, color = [0.9, 0.6, 0.4], alpha = 0.05}, "
      "{value = 200, color = [0.5, 0.8, 1.0], alpha = 0.7} ]\n"
      "[camera]\neye = [" + std::to_string(c + 0.3 * size) + ", " + std::to_string(-1.2 * size) +
      ", " + std::to_string(c + 0.4 * size) + "]\ncenter = [" + std::to_string(c) + ", " +
      std::to_string(c) + ", " + std::to_string(c) + "]\nfov_deg = 45\nheight = " +
      std::to_string(1.2 * size) + "\n[render]\nwidth = " + std::to_string(image) +
      "\nheight = " + std::to_string(image) + "\noversampling = 1.5\n"
      "[[lights]]\ntype = \"directional\"\ndirection = [1, -1, 1]\nintensity = 0.6\n"
      "[[lights]]\ntype = \"headlight\"\nintensity = 0.6\n";
  RtlFrame f;
  f.scene = ref::parse_scene(text, "rtl test " + phantom, ".", overrides);
  f.volume = std::make_shared<ref::Volume>(ref::make_phantom(phantom, size, 1));
  f.gradients = std::make_shared<ref::GradientField>(
      ref::compute_gradients(*f.volume, f.scene.volume.gradient));
  const ref::RenderInputs in =
      ref::make_render_inputs(f.scene, *f.volume, *f.gradients, f.scene.camera.pose);
  f.setup = bittrue::make_frame_setup(f.scene.precision, f.scene, in);
  f.memory = bittrue::make_voxel_memory(f.scene.precision, *f.volume, *f.gradients);
  return f;
}

}  // namespace voxcast::test
