// `voxcast burst-study`: the scene's samples counted in DDR4 bursts by layout,
// and one layout's fetches through the U250's channels. Reuse only drops
// fetches (ray and cache never fetch more than none), the results do not
// depend on the host's threads, one pipeline of one sample a clock is the
// bound when memory keeps up, and a bad layout or board is one error.
#include <gtest/gtest.h>

#include <string>

#include "cosim/explore/burst_study.hpp"
#include "refmodel/error.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace VOXCAST_UNITY_ID {

using voxcast::cosim::BurstStudyOptions;
using voxcast::cosim::BurstStudyResult;
using voxcast::cosim::run_burst_study;

// The default scene, small: a 32^3 phantom, 24x24 pixels, 32-bit voxels.
voxcast::ref::Scene small_default(int threads) {
  return voxcast::ref::load_scene_file(
      std::string(VOXCAST_SOURCE_DIR) + "/scenes/default.toml",
      {"volume.source=\"phantom:shepp-logan?size=32&aa=1\"", "volume.crop.hi=[31,31,20]",
       "camera.eye=[15.5,-37.5,65.0]", "camera.center=[15.5,15.5,15.5]", "render.width=24",
       "render.height=24", "precision.profile=vizard2",
       "render.threads=" + std::to_string(threads)});
}

TEST(BurstStudy, ReuseOnlyDropsFetchesAndThreadsChangeNothing) {
  const BurstStudyResult one = run_burst_study(small_default(1), {});
  const BurstStudyResult two = run_burst_study(small_default(2), {});
  EXPECT_EQ(one.voxel_bytes, 4);
  EXPECT_EQ(one.voxels_per_burst, 16);
  ASSERT_GT(one.samples, 0u);
  EXPECT_EQ(one.samples, two.samples);
  ASSERT_EQ(one.layouts.size(), 28u);  // 7 shapes x 2 bank-group maps x 2 row maps
  for (std::size_t i = 0; i < one.layouts.size(); ++i) {
    SCOPED_TRACE(one.layouts[i].name);
    const auto& none = one.layouts[i].reuse[0];
    const auto& ray = one.layouts[i].reuse[1];
    const auto& cache = one.layouts[i].reuse[2];
    // A cell touches one to eight bricks; reuse fetches a subset of them.
    EXPECT_GE(none.bursts_per_sample, 1.0);
    EXPECT_LE(none.bursts_per_sample, 8.0);
    EXPECT_LE(ray.bursts_per_sample, none.bursts_per_sample);
    EXPECT_LE(cache.bursts_per_sample, none.bursts_per_sample);
    for (std::size_t k = 0; k < 3; ++k) {
      EXPECT_EQ(one.layouts[i].reuse[k].bursts_per_sample,
                two.layouts[i].reuse[k].bursts_per_sample);
      EXPECT_EQ(one.layouts[i].reuse[k].row_hits, two.layouts[i].reuse[k].row_hits);
    }
  }
}

TEST(BurstStudy, OnePipelineBoundsTheChannelRunWhenTheCacheHolds) {
  BurstStudyOptions o;
  o.channel_layout = "4x2x2-skewed-blocks";
  o.pipelines = {1, 2};
  const BurstStudyResult r = run_burst_study(small_default(0), o);
  ASSERT_TRUE(r.has_channel_run);
  const auto& c = r.channel_run;
  EXPECT_EQ(c.board, "alveo_u250");
  EXPECT_DOUBLE_EQ(c.memory_mhz, 1e6 / 833.0);  // DDR4-2400's tCK, 0.833 ns in whole picoseconds
  // The run fetches what the table counts for this layout under the cache.
  for (const auto& l : r.layouts) {
    if (l.name != o.channel_layout) continue;
    EXPECT_NEAR(static_cast<double>(c.requests),
                l.reuse[2].bursts_per_sample * static_cast<double>(r.samples), 1e-6);
  }
  ASSERT_EQ(c.points.size(), 2u);
  for (const auto& p : c.points) {
    SCOPED_TRACE(p.pipelines);
    // N pipelines issue a sample each core clock: samples / (N x 300 MHz).
    EXPECT_NEAR(p.pipeline_us, static_cast<double>(r.samples) / (p.pipelines * 300.0), 1e-9);
    // A few hundred bursts keep no channel busy: the frame ends within the
    // last fetch's latency (well under a microsecond) of the last sample.
    EXPECT_GE(p.memory_us, 0.0);
    EXPECT_LE(p.frame_us, p.pipeline_us + 1.0);
    EXPECT_EQ(p.bound, "pipelines");
  }
}

TEST(BurstStudy, ABadLayoutOrBoardIsOneError) {
  BurstStudyOptions o;
  o.channel_layout = "3x3x3-skewed";
  try {
    run_burst_study(small_default(0), o);
    FAIL() << "no error";
  } catch (const voxcast::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no layout 3x3x3-skewed (the layouts: 16x1x1-plain"),
              std::string::npos)
        << e.what();
  }
  o.channel_layout = "4x2x2-skewed";
  o.board = "vizard2_pci";  // PC100 SDR: no bank groups, 8-byte accesses
  try {
    run_burst_study(small_default(0), o);
    FAIL() << "no error";
  } catch (const voxcast::Error& e) {
    EXPECT_NE(std::string(e.what()).find("board vizard2_pci's memory is not the DDR4 channel"),
              std::string::npos)
        << e.what();
  }
  o.cache_lines = 1000;
  EXPECT_THROW(run_burst_study(small_default(0), o), voxcast::Error);
}

}  // namespace VOXCAST_UNITY_ID
