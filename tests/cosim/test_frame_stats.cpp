// The counts every engine reports (ref::FrameStats, docs/pipeline.md §9), one
// test per count, on scenes where each count has a closed form and no ray
// grazes the box, so ref, bittrue, hls and rtl must all give it.
//
// The scene: the box phantom at 16^3 (voxels 4..11 hold 200, the rest 0; the
// rendered box is the voxel centres [0, 15]^3) seen by a parallel camera
// along +y from y = -20, 16x16 pixels over a 32x32 view: pixel i's ray runs
// at x (and z) = 7.5 + (2i + 1 - 16) = 2i - 7.5, so pixels 4..11 on each axis
// cross the box (x = 0.5 .. 14.5, half a voxel inside its faces) and the
// others pass at least 1.5 voxels outside: 8 x 8 = 64 of 256 rays hit. A hit
// ray's samples lie at y = 0, 1, .., 15 (n = 16 at one sample per voxel).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "cosim/engines/engines.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/engine.hpp"
#include "tests/common/voxcast_cli.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

constexpr std::uint64_t kRays = 16 * 16;
constexpr std::uint64_t kHits = 8 * 8;

// Alpha 0.9 per voxel at every value: each hit ray's opacity after k + 1
// samples is 1 - 0.1^(k+1), which first reaches the ERT threshold 0.98 at
// k = 1 (0.9 < 0.98 <= 0.99).
const char* const kOpaque =
    "classification.points=[{value=0, color=[1,1,1], alpha=0.9}, "
    "{value=255, color=[1,1,1], alpha=0.9}]";

std::string scene_text() {
  return "[volume]\nsource = \"phantom:box?size=16\"\n"
         "[classification]\npoints = [{value = 0, alpha = 0.0}, {value = 255, alpha = 0.0}]\n"
         "[camera]\nprojection = \"parallel\"\neye = [7.5, -20, 7.5]\ncenter = [7.5, 7.5, 7.5]\n"
         "up = [0, 0, 1]\nheight = 32\n"
         "[render]\nwidth = 16\nheight = 16\nmode = \"unshaded\"\noversampling = 1\n"
         "ert_threshold = 0.98\n";
}

ref::Scene box_scene(const ref::Overrides& o) {
  return ref::parse_scene(scene_text(), "frame stats box", ".", o);
}

struct Counts {
  ref::FrameStats ref, bittrue, hls, rtl;
  rtl::RtlStats card;  // the cycle model's own counts
};

Counts count(const ref::Overrides& o) {
  const ref::Scene s = box_scene(o);
  const cosim::SceneVolume sv = cosim::load_scene_volume(s);
  const ref::RenderInputs in = ref::make_render_inputs(s, sv.volume, sv.gradients, s.camera.pose);
  const bittrue::FrameSetup setup = bittrue::make_frame_setup(s.precision, s, in);
  const bittrue::VoxelMemory mem = bittrue::make_voxel_memory(s.precision, sv.volume, sv.gradients);
  Counts c;
  ref::render_image(in, 2, &c.ref);
  bittrue::bt_render_image(setup, mem, 2, &c.bittrue);
  cosim::hls_render_image(setup, mem, 2, &c.hls);
  c.card = rtl::rtl_render(setup, mem, rtl::vizard2_baseline()).stats;
  c.rtl = rtl::frame_stats(c.card);
  return c;
}

ref::FrameStats stats(std::uint64_t hit, std::uint64_t early, std::uint64_t samples,
                      std::uint64_t skipped = 0) {
  ref::FrameStats f;
  f.rays = kRays;
  f.rays_hit = hit;
  f.rays_terminated_early = early;
  f.samples = samples;
  f.samples_skipped = skipped;
  return f;
}

Counts expect_every_engine(const ref::Overrides& o, const ref::FrameStats& want) {
  const Counts c = count(o);
  EXPECT_EQ(c.ref, want) << "ref";
  EXPECT_EQ(c.bittrue, want) << "bittrue";
  EXPECT_EQ(c.hls, want) << "hls";
  EXPECT_EQ(c.rtl, want) << "rtl";
  return c;
}

TEST(FrameStats, RaysHitAreThePixelsWhoseRayCrossesTheBox) {
  // Transparent: every hit ray takes all 16 samples.
  expect_every_engine({}, stats(kHits, 0, 16 * kHits));
  // Looking away (rays go forward only): no ray hits, no sample is taken.
  expect_every_engine({"camera.center=[7.5, -40, 7.5]"}, stats(0, 0, 0));
}

TEST(FrameStats, RaysTerminatedEarlyOnAnOpaqueVolume) {
  // ERT after sample 1 of 16: every hit ray ends early, after 2 samples.
  expect_every_engine({kOpaque}, stats(kHits, kHits, 2 * kHits));
  // Cropped to y = 0..1 the rays have 2 samples: ERT at the last one is not early.
  expect_every_engine({kOpaque, "volume.crop.lo=[0, 0, 0]", "volume.crop.hi=[15, 1, 15]"},
                      stats(kHits, 0, 2 * kHits));
  // No ERT: with the threshold at 1, and in MIP.
  expect_every_engine({kOpaque, "render.ert_threshold=1.0"}, stats(kHits, 0, 16 * kHits));
  expect_every_engine({kOpaque, "render.mode=\"mip\""}, stats(kHits, 0, 16 * kHits));
}

TEST(FrameStats, SamplesAreTheStepsAcrossTheBox) {
  // n = floor(15 / step) + 1: 16 at one sample per voxel, 31 at two.
  expect_every_engine({"render.ert_threshold=1.0"}, stats(kHits, 0, 16 * kHits));
  expect_every_engine({"render.ert_threshold=1.0", "render.oversampling=2"},
                      stats(kHits, 0, 31 * kHits));
}

// Leaping with 4-cell blocks: block b covers voxels 4b .. 4b+4 along an axis,
// so blocks 0..2 reach into the box (voxels 4..11) and block 3 (voxels 12..15)
// is empty wherever the transfer function is 0 at 0. A hit ray at x = 2i - 7.5
// lies in block 3 for i = 10, 11 (x = 12.5, 14.5): of the 64 hit rays, the 28
// with x or z in block 3 skip all 16 samples; the other 36 read y = 0..11 and
// skip y = 12..15.
constexpr std::uint64_t kInBlock3 = 8 * 8 - 6 * 6;
constexpr std::uint64_t kOthers = kHits - kInBlock3;

TEST(FrameStats, SamplesSkippedAreTheEmptyBlocksSamples) {
  const ref::Overrides leap{"render.space_leaping=true", "render.leap_block=4",
                            "render.ert_threshold=1.0",
                            "classification.points=[{value=0, color=[1,1,1], alpha=0.0}, "
                            "{value=100, color=[1,1,1], alpha=0.4}, "
                            "{value=255, color=[1,1,1], alpha=0.4}]"};
  expect_every_engine(leap, stats(kHits, 0, 12 * kOthers, 16 * kInBlock3 + 4 * kOthers));
  // With ERT at 0.978 the 16 rays through the box (x, z = 4.5 .. 10.5) reach
  // the threshold at their 8th box sample, y = 11 (1 - 0.6^7 = 0.972 < 0.978
  // <= 1 - 0.6^8 = 0.983): they end early with y = 12..15 neither read nor
  // skipped, though the card's issue stage may have leapt them already.
  ref::Overrides ert = leap;
  ert.push_back("render.ert_threshold=0.978");
  const std::uint64_t box_rays = 4 * 4;
  const Counts c = expect_every_engine(
      ert, stats(kHits, box_rays, 12 * kOthers, 16 * kInBlock3 + 4 * (kOthers - box_rays)));
  // It had, for every box ray: ERT at the last sample the card issued, still
  // early, with 4 samples leapt beyond it.
  EXPECT_EQ(c.card.samples_skipped_discarded, 4 * box_rays);
}

TEST(FrameStats, RenderPrintsTheSameHitAndTerminationShareForHlsAndRef) {
  // The opaque scene from the command line: 64/256 = 25.00% hit, all of them
  // end early.
  const auto dir = std::filesystem::temp_directory_path() / "voxcast_frame_stats_cli";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const auto toml = dir / "box.toml";
  std::ofstream(toml) << scene_text();
  auto rays_line = [&](const std::string& engine) {
    const Command r = run_voxcast("render " + toml.string() + " --engine " + engine + " -o " +
                                  (dir / (engine + ".png")).string() + " --set '" + kOpaque + "'");
    EXPECT_EQ(r.status, 0) << r.output;
    const std::size_t at = r.output.find("rays     ");
    return at == std::string::npos ? r.output : r.output.substr(at, r.output.find('\n', at) - at);
  };
  const std::string ref_line = rays_line("ref");
  EXPECT_EQ(ref_line, "rays     25.00% hit the volume, 25.00% terminated early, 128 samples");
  EXPECT_EQ(rays_line("hls"), ref_line);
}

}  // namespace VOXCAST_UNITY_ID
}  // namespace voxcast::test
