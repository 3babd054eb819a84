// `voxcast flythrough`: the camera path on the cycle model. The frames are the
// hls engine's pixels, the path's ends are its keyframes, the modelled rate is
// the clock over the cycles, and nothing depends on the host's thread count.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <OpenImageIO/imageio.h>

#include "cosim/engines.hpp"
#include "cosim/flythrough.hpp"
#include "cosim/image_io.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/error.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"

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
    // The modelled rate is the core clock (100 MHz) over the frame's cycles.
    EXPECT_GT(f.stats.cycles, 0u);
    EXPECT_NEAR(f.stats.fps() * static_cast<double>(f.stats.cycles), 100e6, 1e-3);
    EXPECT_EQ(f.stats.rays, 400u);
  }
}

TEST(Flythrough, WritesTheAnimationTableAndReport) {
  const FlythroughResult r = fly(small_endoscopy(0), "files", 4);
  auto in = OIIO::ImageInput::open(r.animation);
  ASSERT_TRUE(in) << OIIO::geterror();
  int subimages = 0;
  while (in->seek_subimage(subimages, 0)) ++subimages;
  EXPECT_EQ(subimages, 4);
  std::ifstream csv(r.csv);
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 1 + 4);  // header + one row per frame
  EXPECT_TRUE(std::filesystem::exists(r.json));
  // The 32^3 volume of one-byte voxels crosses the 33 MHz, 32-bit bus once.
  EXPECT_EQ(r.host.volume.bytes, 32u * 32u * 32u);
  // The readback on the clocked PCI model takes the closed form's clocks (the
  // core feeds the crossing faster than the bus drains it), and each frame's
  // readback is hidden exactly when it ends before the next frame has
  // rendered (double-buffered frame buffer); the last has no next frame.
  EXPECT_EQ(r.clocked_readback.cycles, r.host.image.cycles);
  ASSERT_EQ(r.readback.size(), r.frames.size());
  for (std::size_t f = 0; f < r.readback.size(); ++f) {
    const auto& rb = r.readback[f];
    EXPECT_EQ(rb.render_cycles, static_cast<std::int64_t>(r.frames[f].stats.cycles));
    EXPECT_DOUBLE_EQ(rb.readback_s, r.host.image.seconds);
    EXPECT_GE(rb.readback_start_s, rb.render_end_s);
    if (f + 1 < r.readback.size())
      EXPECT_EQ(rb.hidden, rb.readback_end_s <= r.readback[f + 1].render_end_s) << f;
    else
      EXPECT_FALSE(rb.hidden);
  }
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
