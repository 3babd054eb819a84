// The DDR4 card (rtl_model/pipeline/burst_card.hpp, docs/sdram.md §10): the
// U250 board's frames equal the hls engine's bit for bit for 1, 2 and 4
// pipelines; the pipelines' and the channels' closed-form bounds hold;
// frames are deterministic; rtl.pipelines is checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "hls/host_frame.hpp"
#include "hls/vizard2_top.hpp"
#include "refmodel/error.hpp"
#include "rtl_frames.hpp"
#include "rtl_model/board/board.hpp"
#include "rtl_model/board/board_config.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/scene_config.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

const char* const kU250 = "rtl.board=\"alveo_u250\"";

// The hls engine's image: hls::cast_ray for every pixel on the host's bank
// memory (what cosim's hls engine runs, one thread).
ref::QuantImage hls_image(const RtlFrame& f) {
  ref::QuantImage img(f.setup.regs.width, f.setup.regs.height, 8);
  const auto run = [&]<class P>() {
    const auto frame = hls::host::load_frame_state<P>(f.setup, "test");
    const hls::host::BitTrueBanks<P> banks(f.memory);
    img = ref::QuantImage(f.setup.regs.width, f.setup.regs.height, P::out_bits);
    hls::NullTracer tracer;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        std::uint64_t n = 0;
        const auto px = hls::cast_ray<P>(*frame, banks, x, y, n, tracer);
        for (std::size_t c = 0; c < 4; ++c)
          img.at(x, y)[c] = static_cast<std::uint32_t>(px.ch[c].to_uint64());
      }
  };
  EXPECT_TRUE(hls::host::dispatch_profile(f.setup.profile, run));
  return img;
}

void expect_same_image(const ref::QuantImage& got, const ref::QuantImage& want,
                       const std::string& what) {
  ASSERT_EQ(got.width, want.width) << what;
  ASSERT_EQ(got.height, want.height) << what;
  ASSERT_EQ(got.bits, want.bits) << what;
  for (int y = 0; y < want.height; ++y)
    for (int x = 0; x < want.width; ++x)
      ASSERT_EQ(got.at(x, y), want.at(x, y)) << what << ": pixel (" << x << ", " << y << ")";
}

std::size_t lit(const ref::QuantImage& img) {
  std::size_t n = 0;
  for (const auto& p : img.pixels) n += p[3] > 0 ? 1 : 0;
  return n;
}

rtl::RtlConfig u250(int pipelines) {
  ref::RtlDesc d;
  d.board = "alveo_u250";
  d.pipelines = pipelines;
  return rtl::rtl_config(d);
}

TEST(Ddr4Card, TheU250BoardRunsTheDdr4Card) {
  const rtl::RtlConfig c = rtl::rtl_config_for_board(rtl::board::shipped_board("alveo_u250"));
  EXPECT_TRUE(c.card.enabled);
  EXPECT_EQ(c.card.core_period_ps, 3333);             // 300 MHz
  EXPECT_EQ(c.pipeline.dimm.clock.period_ps(), 833);  // DDR4-2400: 1200 MHz
  EXPECT_EQ(c.pipeline.dimm.burst_length, 8);
  EXPECT_EQ(c.pipeline.dimm.geometry.bank_groups, 4u);
  EXPECT_FALSE(rtl::vizard2_baseline().card.enabled);  // the SDR card is unchanged
}

struct Mode {
  const char* name;
  std::vector<std::string> overrides;
};

// Shaded, MIP and a low ERT threshold (rays end early, their speculative
// samples drain), on 1, 2 and 4 pipelines: the hls engine's image and sample
// count, every pixel.
TEST(Ddr4Card, BitIdenticalToTheHlsEngine) {
  const std::vector<Mode> modes = {
      {"shaded", {"render.mode=shaded"}},
      {"mip", {"render.mode=mip", "camera.projection=parallel"}},
      {"ert", {"render.mode=unshaded", "render.ert_threshold=0.3", "render.oversampling=3"}},
  };
  for (const Mode& m : modes) {
    ref::Overrides o = {"precision.profile=vizard2", kU250};
    o.insert(o.end(), m.overrides.begin(), m.overrides.end());
    const RtlFrame f = make_rtl_frame("shepp-logan", 24, 20, o);
    ref::FrameStats fs;
    const ref::QuantImage bt = bittrue::bt_render_image(f.setup, f.memory, 1, &fs);
    const ref::QuantImage hls = hls_image(f);
    expect_same_image(bt, hls, std::string(m.name) + " bit-true vs hls");
    EXPECT_GT(lit(hls), hls.pixels.size() / 20) << m.name;
    for (const int n : {1, 2, 4}) {
      const std::string what = std::string(m.name) + ", " + std::to_string(n) + " pipelines";
      const rtl::RtlResult r = rtl::rtl_render(f.setup, f.memory, u250(n));
      expect_same_image(r.image, hls, what);
      EXPECT_EQ(r.stats.samples, fs.samples) << what;
      EXPECT_EQ(r.stats.rays, 400u) << what;
      EXPECT_EQ(r.stats.card.pipelines, n) << what;
      // Each pipeline issues at most one sample (or one leap) per core clock.
      EXPECT_GE(r.stats.cycles * static_cast<std::uint64_t>(n), r.stats.samples_issued) << what;
      EXPECT_EQ(r.stats.samples_issued, r.stats.samples + r.stats.samples_discarded) << what;
      if (std::string(m.name) == "ert") {
        EXPECT_GT(r.stats.rays_ert, 0u) << what;
      }
    }
  }
}

// A profile with 64-bit voxel words: 8 voxels a burst, 2x2x2 bricks.
TEST(Ddr4Card, WideVoxelsUseSmallerBricks) {
  const RtlFrame f = make_rtl_frame("tube", 20, 16, {"precision.profile=balanced", kU250});
  const rtl::RtlResult r = rtl::rtl_render(f.setup, f.memory, u250(2));
  expect_same_image(r.image, hls_image(f), "balanced, 2 pipelines");
}

// A 16^3 volume is 256 bursts, 64 a channel: the cache holds it all, so after
// each burst's one miss every look-up hits and the pipeline is the bound. One
// pipeline issues at most one sample per core clock: at most 300 M samples/s.
TEST(Ddr4Card, OnePipelineIsAtMostOneSamplePerCoreClock) {
  const RtlFrame f = make_rtl_frame("shepp-logan", 16, 24, {"precision.profile=vizard2", kU250});
  const rtl::RtlResult r = rtl::rtl_render(f.setup, f.memory, u250(1));
  const auto& k = r.stats.card;
  EXPECT_LE(k.cache_misses, 256u);
  EXPECT_GT(k.cache_hit_rate(), 0.9);
  EXPECT_GE(r.stats.cycles, r.stats.samples_issued + r.stats.leaps);
  EXPECT_LE(r.stats.samples_per_second(), 1e12 / 3333.0);
  EXPECT_GT(k.pipeline_utilisation(r.stats.cycles), k.channel_utilisation());
  EXPECT_LE(k.pipeline_utilisation(r.stats.cycles), 1.0);
  EXPECT_NE(std::string(k.bound(r.stats.cycles)), "channels");
  std::uint64_t bursts = 0;
  for (const auto b : k.bursts) bursts += b;
  EXPECT_EQ(bursts, k.cache_misses);  // one request per miss
}

// With one line per channel nearly every look-up misses; each burst holds
// its channel's data bus for BL/2 = 4 memory clocks, so the frame lasts at
// least 4 x bursts memory clocks on every channel; every burst requested is
// one READ; the image is still the hls engine's (pending lines replaced
// before their data returned fill their waiting samples).
TEST(Ddr4Card, OneLineCacheIsBoundByTheDataBus) {
  const RtlFrame f = make_rtl_frame("shepp-logan", 20, 16, {"precision.profile=vizard2", kU250});
  rtl::RtlConfig c = u250(2);
  c.card.cache_lines = 1;
  const rtl::RtlResult r = rtl::rtl_render(f.setup, f.memory, c);
  expect_same_image(r.image, hls_image(f), "one-line cache");
  const auto& k = r.stats.card;
  EXPECT_EQ(k.burst_clocks, 4);
  for (std::size_t ch = 0; ch < 4; ++ch) {
    EXPECT_GT(k.bursts[ch], 0u) << ch;
    EXPECT_EQ(r.stats.dimms[ch].controller.reads, k.bursts[ch]) << ch;
    EXPECT_GE(k.memory_cycles, 4 * k.bursts[ch]) << ch;
  }
  EXPECT_LE(k.channel_utilisation(), 1.0);
  // Every sample needs at least one burst and a sample's bursts are distinct.
  EXPECT_GE(k.cache_misses + k.cache_hits + k.cache_pending_hits, r.stats.samples_issued);
  EXPECT_LT(k.cache_hit_rate(), 0.5);
}

TEST(Ddr4Card, MorePipelinesFinishSooner) {
  const RtlFrame f = make_rtl_frame("shepp-logan", 16, 24, {"precision.profile=vizard2", kU250});
  const rtl::RtlResult one = rtl::rtl_render(f.setup, f.memory, u250(1));
  const rtl::RtlResult four = rtl::rtl_render(f.setup, f.memory, u250(4));
  EXPECT_EQ(one.stats.samples, four.stats.samples);
  EXPECT_LT(four.stats.cycles, one.stats.cycles);
}

TEST(Ddr4Card, Deterministic) {
  const RtlFrame f = make_rtl_frame("tube", 20, 16, {"precision.profile=vizard2", kU250});
  const rtl::RtlResult a = rtl::rtl_render(f.setup, f.memory, u250(2));
  const rtl::RtlResult b = rtl::rtl_render(f.setup, f.memory, u250(2));
  expect_same_image(a.image, b.image, "second run");
  EXPECT_EQ(a.stats.cycles, b.stats.cycles);
  EXPECT_EQ(a.stats.card.memory_cycles, b.stats.card.memory_cycles);
  EXPECT_EQ(a.stats.card.bursts, b.stats.card.bursts);
  EXPECT_EQ(a.stats.card.cache_hits, b.stats.card.cache_hits);
  EXPECT_EQ(a.stats.row_hits(), b.stats.row_hits());
}

void expect_one_error(const ref::Overrides& o, const std::string& needle) {
  try {
    const RtlFrame f = make_rtl_frame("tube", 8, 4, o);
    (void)rtl::rtl_config(f.scene.rtl);
    ADD_FAILURE() << "no error for " << needle;
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(needle), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
  }
}

TEST(Ddr4Card, BadPipelinesIsOneError) {
  expect_one_error({kU250, "rtl.pipelines=0"}, "rtl.pipelines");
  expect_one_error({kU250, "rtl.pipelines=65"}, "rtl.pipelines");
  expect_one_error({kU250, "rtl.pipelines=\"four\""}, "rtl.pipelines");
  expect_one_error({"rtl.pipelines=2"}, "rtl.pipelines = 2: the SDR card");
  expect_one_error({kU250, "rtl.layout=\"morton\""}, "rtl.layout");
  expect_one_error({kU250, "rtl.sdram=\"pc100-cl2\""}, "rtl.sdram");
}

}  // namespace VOXCAST_UNITY_ID
}  // namespace voxcast::test
