// A testbench of the kind a hardware team writes against the installed
// package: a phantom rendered by voxcast's synthesizable kernels (voxcast::hls,
// header-only, instantiated here) must equal the bit-true reference
// (voxcast::refmodel) on every pixel. Exit 0 when it does.
#include <cstdio>
#include <vector>

#include "hls/host_frame.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "refmodel/volume/gradients.hpp"
#include "refmodel/volume/loaders.hpp"

int main() {
  using namespace voxcast;
  const ref::Scene scene = ref::default_scene(
      {"render.width=24", "render.height=24", "precision.profile=balanced"});
  const ref::Volume volume = ref::load_volume(scene.volume.source, scene.base_dir, nullptr);
  ref::validate_against_volume(scene, volume);  // the scene's boxes inside the volume
  const ref::GradientField gradients = ref::compute_gradients(volume, scene.volume.gradient);
  const ref::RenderInputs in = ref::make_render_inputs(
      scene, volume, gradients, ref::frame_poses(scene.camera, 1).front());
  const bittrue::FrameSetup setup = bittrue::make_frame_setup(scene.precision, scene, in);
  const bittrue::VoxelMemory memory = bittrue::make_voxel_memory(scene.precision, volume, gradients);
  const ref::QuantImage bt = bittrue::bt_render_image(setup, memory, 1);

  int differ = -1;
  const bool compiled = hls::host::dispatch_profile(scene.precision, [&]<class P>() {
    const auto frame = hls::host::load_frame_state<P>(setup, "consumer");
    const hls::host::BitTrueBanks<P> banks(memory);
    const int w = setup.regs.width, h = setup.regs.height;
    std::vector<hls::OutputPixel<P>> fb(static_cast<std::size_t>(w * h));
    hls::RowStats stats;
    hls::render_rows<P>(*frame, banks, w, 0, h, fb.data(), &stats);
    differ = 0;
    for (int i = 0; i < w * h; ++i)
      for (int c = 0; c < 4; ++c)
        if (fb[static_cast<std::size_t>(i)].ch[c].to_uint64() !=
            bt.pixels[static_cast<std::size_t>(i)][static_cast<std::size_t>(c)])
          ++differ;
  });
  if (!compiled || differ != 0) {
    std::printf("consumer: hls and bit-true differ in %d channel values\n", differ);
    return 1;
  }
  std::printf("consumer: %dx%d, hls == bit-true on every pixel\n", setup.regs.width,
              setup.regs.height);
  return 0;
}
