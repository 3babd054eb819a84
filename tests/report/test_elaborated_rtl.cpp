// The cycle model uses the elaborated design (docs/resources.md): a unit the
// frame's design leaves out adds no pipeline stages, so the latency configured
// for it cannot change the frame's cycle count; for a frame that uses the unit
// it does. The image stays the same bits.
#include <gtest/gtest.h>

#include <string>

#include "cosim/engines/engines.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/engine.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

struct Frame {
  bittrue::FrameSetup setup;
  bittrue::VoxelMemory memory;
};

Frame frame(const std::string& mode, const std::string& projection) {
  const ref::Scene s = ref::parse_scene(
      "[volume]\nsource = \"phantom:shepp-logan?size=16\"\n"
      "[classification]\npoints = [ {value = 0, alpha = 0.0}, "
      "{value = 30, color = [0.9, 0.6, 0.4], alpha = 0.05}, "
      "{value = 200, color = [0.5, 0.8, 1.0], alpha = 0.7} ]\n"
      "[camera]\nprojection = \"" + projection + "\"\neye = [7.5, -30, 7.5]\n"
      "center = [7.5, 7.5, 7.5]\nheight = 20\n"
      "[render]\nwidth = 12\nheight = 12\nmode = \"" + mode + "\"\n"
      "[precision]\nprofile = \"vizard2\"\n",
      "rtl elaboration " + mode + " " + projection, ".");
  const cosim::SceneVolume sv = cosim::load_scene_volume(s);
  const ref::RenderInputs in = ref::make_render_inputs(s, sv.volume, sv.gradients, s.camera.pose);
  return {bittrue::make_frame_setup(s.precision, s, in),
          bittrue::make_voxel_memory(s.precision, sv.volume, sv.gradients)};
}

rtl::RtlResult run(const Frame& f, int classification, int shading, int ray_setup) {
  rtl::RtlConfig c = rtl::vizard2_baseline();
  c.pipeline.latency.classification = classification;
  c.pipeline.latency.shading = shading;
  c.pipeline.latency.ray_setup = ray_setup;
  return rtl::rtl_render(f.setup, f.memory, c);
}

TEST(ElaboratedRtl, MipSkipsClassificationAndShadingStages) {
  const Frame f = frame("mip", "perspective");
  const auto a = run(f, 2, 4, 24);
  const auto b = run(f, 9, 13, 24);
  EXPECT_EQ(a.stats.cycles, b.stats.cycles);
  EXPECT_EQ(a.image.pixels, b.image.pixels);
  // The same change costs cycles in a shaded frame, which has both units.
  const Frame g = frame("shaded", "perspective");
  EXPECT_LT(run(g, 2, 4, 24).stats.cycles, run(g, 9, 13, 24).stats.cycles);
}

TEST(ElaboratedRtl, UnshadedHasOneShadingStage) {
  const Frame f = frame("unshaded", "perspective");
  EXPECT_EQ(run(f, 2, 4, 24).stats.cycles, run(f, 2, 13, 24).stats.cycles);
  EXPECT_LT(run(f, 2, 4, 24).stats.cycles, run(f, 9, 4, 24).stats.cycles);
}

TEST(ElaboratedRtl, ParallelRaySetupHasNoRsqrtStages) {
  // A parallel frame's ray set-up is the configured latency less the rsqrt
  // unit's stages, floored at 1: every configured latency up to kRsqrtStages + 1
  // gives the same frame.
  const Frame f = frame("shaded", "parallel");
  const int k = rtl::pipeline::kRsqrtStages;
  EXPECT_EQ(run(f, 2, 4, 1).stats.cycles, run(f, 2, 4, k + 1).stats.cycles);
  EXPECT_LT(run(f, 2, 4, k + 1).stats.cycles, run(f, 2, 4, k + 40).stats.cycles);
}

}  // namespace
}  // namespace voxcast::test
