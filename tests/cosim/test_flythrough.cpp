// `voxcast flythrough`: the camera path on the cycle model. The frames are the
// hls engine's pixels, the path's ends are its keyframes, each frame's timing
// is the rtl engine's for its pose, the readback schedule follows from the
// frames' cycles, and nothing depends on the host's thread count.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>


#include "cosim/engines/engines.hpp"
#include "cosim/explore/flythrough.hpp"
#include "cosim/reports/image_io.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/error.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/scene_config.hpp"

namespace VOXCAST_UNITY_ID {

using voxcast::cosim::FlythroughOptions;
using voxcast::cosim::FlythroughResult;
using voxcast::cosim::run_flythrough;

// The shipped endoscopy flight, small enough for a unit test: a 32^3 tube,
// 20x20 pixels, one sample per voxel.
voxcast::ref::Scene small_endoscopy(int threads) {
  return voxcast::ref::load_scene_file(
      std::string(VOXCAST_SOURCE_DIR) + "/scenes/endoscopy.toml",
      {"volume.source=\"phantom:tube?size=32&aa=1\"", "render.width=20", "render.height=20",
       "render.oversampling=1", "render.threads=" + std::to_string(threads),
       // The keyframes are in voxels of the 128^3 tube (h = 63.5): the same
       // normalised points in the 32^3 tube (h = 15.5).
       "camera.path[0].eye=[10.85,15.5,4.65]", "camera.path[0].center=[10.85,15.5,19.53]",
       "camera.path[1].eye=[10.85,15.5,13.95]", "camera.path[1].center=[10.85,15.5,21.7]",
       "camera.path[2].eye=[13.12,15.5,20.98]", "camera.path[2].center=[18.6,15.5,26.46]",
       "camera.path[3].eye=[18.6,15.5,23.25]", "camera.path[3].center=[26.35,15.5,23.25]",
       "camera.path[4].eye=[26.35,15.5,23.25]", "camera.path[4].center=[34.1,15.5,23.25]"});
}

std::filesystem::path out_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("voxcast_fly_" + name);
  std::filesystem::remove_all(d);
  return d;
}

FlythroughResult fly(const voxcast::ref::Scene& scene, const std::string& name, int frames) {
  FlythroughOptions o;
  o.out_dir = out_dir(name).string();
  o.frames = frames;
  return run_flythrough(scene, o);
}

TEST(Flythrough, FramesAreTheHlsPixelsAlongThePath) {
  const auto scene = small_endoscopy(0);
  const FlythroughResult r = fly(scene, "hls", 3);
  ASSERT_EQ(r.frames.size(), 3u);
  // Uniform parameter over the keyframes: the first and last frames are the
  // first and last keyframes, the middle one is keyframe 2 (u = 2 of 4).
  EXPECT_EQ(r.frames[0].pose.eye, scene.camera.path[0].eye);
  EXPECT_EQ(r.frames[1].pose.eye, scene.camera.path[2].eye);
  EXPECT_EQ(r.frames[2].pose.center, scene.camera.path[4].center);

  const auto sv = voxcast::cosim::load_scene_volume(scene);
  const auto memory = voxcast::bittrue::make_voxel_memory(scene.precision, sv.volume, sv.gradients);
  for (const auto& f : r.frames) {
    const auto in = voxcast::ref::make_render_inputs(scene, sv.volume, sv.gradients, f.pose);
    const auto setup = voxcast::bittrue::make_frame_setup(scene.precision, scene, in);
    const auto hls = voxcast::cosim::hls_render_image(setup, memory);
    const std::string expected = (out_dir("hls_expected") += std::to_string(f.index) + ".png").string();
    voxcast::cosim::write_image(expected, hls.to_image(), scene.render.background);
    const auto a = voxcast::cosim::read_image(f.image);
    const auto b = voxcast::cosim::read_image(expected);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
      ASSERT_EQ(a.pixels[i], b.pixels[i]) << "frame " << f.index << " pixel " << i;
    // The frame's timing is the rtl engine's for this pose and the scene's
    // [rtl] card, simulated on its own: the same cycles and row outcomes.
    const auto alone = voxcast::rtl::rtl_render(setup, memory, voxcast::rtl::rtl_config(scene.rtl));
    EXPECT_EQ(f.stats.cycles, alone.stats.cycles) << "frame " << f.index;
    EXPECT_EQ(f.stats.samples_issued, alone.stats.samples_issued) << "frame " << f.index;
    EXPECT_EQ(f.stats.activates(), alone.stats.activates()) << "frame " << f.index;
    EXPECT_EQ(f.stats.row_hits(), alone.stats.row_hits()) << "frame " << f.index;
    // The card's clock is the DIMMs' 100 MHz (2001 paper, §2.3), and no frame
    // beats one READ per DIMM per sample on a command bus of one command a clock.
    EXPECT_DOUBLE_EQ(f.stats.clock_mhz, 100.0);
    EXPECT_GE(f.stats.cycles, f.stats.samples_issued) << "frame " << f.index;
    EXPECT_EQ(f.stats.rays, 400u);
  }
  // The camera moves: the frames are not one frame's timing repeated.
  EXPECT_NE(r.frames[0].stats.samples_issued, r.frames[2].stats.samples_issued);
}

TEST(Flythrough, WritesTheAnimationTableAndReport) {
  const FlythroughResult r = fly(small_endoscopy(0), "files", 4);
  EXPECT_EQ(voxcast::cosim::read_image_info(r.animation).subimages, 4);
  // header + one row per frame, whose cycles column is the frame's.
  std::ifstream csv(r.csv);
  std::string header;
  ASSERT_TRUE(std::getline(csv, header));
  EXPECT_EQ(header.rfind("frame,eye_x,eye_y,eye_z,center_x,center_y,center_z,cycles,", 0), 0u) << header;
  std::size_t rows = 0;
  for (std::string line; std::getline(csv, line); ++rows) {
    ASSERT_LT(rows, r.frames.size()) << line;
    std::istringstream fields(line);
    std::string cell;
    for (int column = 0; column <= 7; ++column) std::getline(fields, cell, ',');
    EXPECT_EQ(cell, std::to_string(r.frames[rows].stats.cycles)) << line;
  }
  EXPECT_EQ(rows, 4u);
  EXPECT_TRUE(std::filesystem::exists(r.json));
  // The 32^3 volume of one-byte voxels crosses the 33 MHz, 32-bit bus once.
  EXPECT_EQ(r.host.volume.bytes, 32u * 32u * 32u);
  // The 20x20 RGBA8 readback: 400 data phases in posted-write bursts of 64,
  // 7 transactions of address 1 + initial latency 2 + idle 1 (docs/performance.md
  // §4), and the clocked PCI model takes exactly as long (the core feeds the
  // crossing faster than the bus drains it).
  EXPECT_EQ(r.host.image.cycles, 400 + 7 * 4);
  EXPECT_EQ(r.clocked_readback.cycles, r.host.image.cycles);
  // Double-buffered: every frame renders for longer than a readback (checked
  // first), so no frame waits for its buffer, frames render back to back, each
  // readback is hidden behind the next frame, and the last ends one readback
  // after the last frame.
  ASSERT_EQ(r.readback.size(), r.frames.size());
  double rendered = 0.0;
  for (std::size_t f = 0; f < r.readback.size(); ++f) {
    const double render_s = static_cast<double>(r.frames[f].stats.cycles) * 10e-9;
    ASSERT_GT(render_s, r.host.image.seconds) << f;
    const auto& rb = r.readback[f];
    EXPECT_EQ(rb.stall_s, 0.0) << f;
    EXPECT_NEAR(rb.render_start_s, rendered, 1e-12) << f;
    rendered += render_s;
    EXPECT_DOUBLE_EQ(rb.readback_s, r.host.image.seconds) << f;
    EXPECT_EQ(rb.hidden, f + 1 < r.readback.size()) << f;
  }
  EXPECT_NEAR(r.readback.back().readback_end_s, rendered + r.host.image.seconds, 1e-12);
}

TEST(Flythrough, SameCyclesAndPixelsForAnyThreadCount) {
  const FlythroughResult one = fly(small_endoscopy(1), "t1", 3);
  const FlythroughResult two = fly(small_endoscopy(2), "t2", 3);
  for (std::size_t f = 0; f < one.frames.size(); ++f) {
    EXPECT_EQ(one.frames[f].stats.cycles, two.frames[f].stats.cycles) << f;
    EXPECT_EQ(one.frames[f].stats.samples, two.frames[f].stats.samples) << f;
    const auto a = voxcast::cosim::read_image(one.frames[f].image);
    const auto b = voxcast::cosim::read_image(two.frames[f].image);
    EXPECT_EQ(a.pixels, b.pixels) << f;
  }
}

TEST(Flythrough, RefusesASceneWithoutAPathAndASingleFrame) {
  const auto no_path = voxcast::ref::load_scene_file(
      std::string(VOXCAST_SOURCE_DIR) + "/scenes/mip.toml", {"render.width=8", "render.height=8"});
  try {
    fly(no_path, "nopath", 3);
    FAIL() << "no error";
  } catch (const voxcast::Error& e) {
    EXPECT_NE(std::string(e.what()).find("camera.path has 0 keyframe(s)"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(fly(small_endoscopy(0), "one", 1), voxcast::Error);
}

}  // namespace
