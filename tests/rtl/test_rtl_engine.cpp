// The rtl engine against the bit-true reference (which equals the hls engine
// bit for bit, tests/cosim): every pixel, every preset, mode and projection;
// the composited sample count equals the reference's; deterministic cycles;
// every traversal, layout and issue policy gives the same image.
#include <gtest/gtest.h>

#include <string>
#include <thread>
#include <vector>

#include "refmodel/error.hpp"
#include "rtl_frames.hpp"
#include "rtl_model/engine.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

void expect_same_image(const ref::QuantImage& rtl, const ref::QuantImage& ref,
                       const std::string& what) {
  ASSERT_EQ(rtl.width, ref.width) << what;
  ASSERT_EQ(rtl.height, ref.height) << what;
  ASSERT_EQ(rtl.bits, ref.bits) << what;
  for (int y = 0; y < ref.height; ++y)
    for (int x = 0; x < ref.width; ++x)
      ASSERT_EQ(rtl.at(x, y), ref.at(x, y)) << what << ": pixel (" << x << ", " << y << ")";
}

std::size_t lit(const ref::QuantImage& img) {
  std::size_t n = 0;
  for (const auto& p : img.pixels) n += p[3] > 0 ? 1 : 0;
  return n;
}

struct Case {
  std::string phantom;
  std::string projection;
};

class RtlBitExact : public ::testing::TestWithParam<Case> {};

TEST_P(RtlBitExact, EveryPresetAndMode) {
  const Case c = GetParam();
  for (const char* profile : {"vizard2", "balanced", "precise"})
    for (const char* mode : {"shaded", "unshaded", "mip"}) {
      const std::string what = c.phantom + " " + c.projection + " " + profile + " " + mode;
      const RtlFrame f = make_rtl_frame(
          c.phantom, 20, 20,
          {std::string("precision.profile=") + profile, std::string("render.mode=") + mode,
           "camera.projection=" + c.projection});
      ref::FrameStats fs;
      const ref::QuantImage bt = bittrue::bt_render_image(f.setup, f.memory, 1, &fs);
      const rtl::RtlResult r = rtl::rtl_render(f.setup, f.memory);
      expect_same_image(r.image, bt, what);
      EXPECT_EQ(r.stats.samples, fs.samples) << what;
      EXPECT_EQ(r.stats.rays, 400u) << what;
      EXPECT_GT(lit(bt), bt.pixels.size() / 20) << what;
      // One READ per DIMM per sample on a command bus of one command a clock.
      EXPECT_GE(r.stats.cycles, r.stats.samples_issued) << what;
    }
}

INSTANTIATE_TEST_SUITE_P(Phantoms, RtlBitExact,
                         ::testing::Values(Case{"shepp-logan", "perspective"},
                                           Case{"shepp-logan", "parallel"},
                                           Case{"tube", "perspective"},
                                           Case{"shells", "parallel"}),
                         [](const auto& param_info) {
                           std::string n = param_info.param.phantom + "_" + param_info.param.projection;
                           for (char& ch : n)
                             if (ch == '-') ch = '_';
                           return n;
                         });

// Odd extents, a crop box and early ray termination at a low threshold.
TEST(RtlEngine, OddDimsCropAndEarlyTermination) {
  const RtlFrame f = make_rtl_frame("box", 17, 24,
                                    {"precision.profile=vizard2", "volume.crop.lo=[1, 2, 0]",
                                     "volume.crop.hi=[15, 16, 13]", "render.ert_threshold=0.3",
                                     "render.oversampling=3"});
  ref::FrameStats fs;
  const ref::QuantImage bt = bittrue::bt_render_image(f.setup, f.memory, 1, &fs);
  const rtl::RtlResult r = rtl::rtl_render(f.setup, f.memory);
  expect_same_image(r.image, bt, "box 17 crop ERT");
  EXPECT_EQ(r.stats.samples, fs.samples);
  EXPECT_GT(r.stats.rays_ert, 0u);
  EXPECT_EQ(r.stats.samples_issued, r.stats.samples + r.stats.samples_discarded);
}

// Every ray hits an opaque slab and terminates early, the last one too: the
// frame ends only when its speculative samples have drained.
TEST(RtlEngine, EarlyTerminationOfTheLastRayDrains) {
  for (const char* projection : {"parallel", "perspective"}) {
    const RtlFrame f = make_rtl_frame(
        "box", 24, 16,
        {"precision.profile=vizard2", "render.ert_threshold=0.2", "render.mode=unshaded",
         std::string("camera.projection=") + projection, "camera.height=6", "camera.fov_deg=8",
         "classification.points[1].alpha=0.9", "classification.points[0].alpha=0.9"});
    ref::FrameStats fs;
    const ref::QuantImage bt = bittrue::bt_render_image(f.setup, f.memory, 1, &fs);
    const rtl::RtlResult r = rtl::rtl_render(f.setup, f.memory);
    expect_same_image(r.image, bt, projection);
    EXPECT_EQ(r.stats.rays_ert, r.stats.rays) << projection;
    EXPECT_GT(r.stats.samples_discarded, 0u) << projection;
    EXPECT_EQ(r.stats.samples, fs.samples) << projection;
  }
}

// Traversal, layout, issue policy, ray slots: the same image and samples,
// their own timing.
TEST(RtlEngine, EveryOrganisationGivesTheSameImage) {
  const RtlFrame f = make_rtl_frame("shepp-logan", 24, 24, {"precision.profile=vizard2"});
  const ref::QuantImage bt = bittrue::bt_render_image(f.setup, f.memory, 1);
  const rtl::RtlResult base = rtl::rtl_render(f.setup, f.memory, rtl::vizard2_baseline());
  expect_same_image(base.image, bt, "baseline");
  struct Variant {
    const char* what;
    void (*apply)(rtl::RtlConfig&);
  };
  const Variant variants[] = {
      {"tiles 8", [](rtl::RtlConfig& c) { c.pipeline.traversal = rtl::pipeline::Traversal::kTiles; }},
      {"tiles 3",
       [](rtl::RtlConfig& c) {
         c.pipeline.traversal = rtl::pipeline::Traversal::kTiles;
         c.pipeline.tile = 3;
       }},
      {"bricked", [](rtl::RtlConfig& c) { c.mapping.name = "bricked"; }},
      {"bricked 4x2x8",
       [](rtl::RtlConfig& c) {
         c.mapping.name = "bricked";
         c.mapping.brick = {4, 2, 8};
       }},
      {"morton", [](rtl::RtlConfig& c) { c.mapping.name = "morton"; }},
      {"bricked-swizzled, lookahead",
       [](rtl::RtlConfig& c) {
         c.mapping.name = "bricked-swizzled";
         c.scheduler = "lookahead";
       }},
      {"round robin", [](rtl::RtlConfig& c) { c.pipeline.issue_burst = 1; }},
      // Row-hit issue interleaves the rays' samples in any order.
      {"row-hit", [](rtl::RtlConfig& c) { c.pipeline.issue = rtl::pipeline::IssuePolicy::kRowHit; }},
      {"row-hit, bricked-swizzled, lookahead, tiles, 64 slots, limit 3",
       [](rtl::RtlConfig& c) {
         c.pipeline.issue = rtl::pipeline::IssuePolicy::kRowHit;
         c.pipeline.issue_bypass_limit = 3;
         c.pipeline.ray_slots = 64;
         c.pipeline.traversal = rtl::pipeline::Traversal::kTiles;
         c.mapping.name = "bricked-swizzled";
         c.scheduler = "lookahead";
       }},
      {"auto precharge, in-order (reference controller)",
       [](rtl::RtlConfig& c) { c.pipeline.controller.auto_precharge = true; }},
      {"auto precharge, lookahead, bricked-swizzled, row-hit",
       [](rtl::RtlConfig& c) {
         c.pipeline.controller.auto_precharge = true;
         c.scheduler = "lookahead";
         c.mapping.name = "bricked-swizzled";
         c.pipeline.issue = rtl::pipeline::IssuePolicy::kRowHit;
       }},
      {"row-hit, 1 ray slot, tiny buffers",
       [](rtl::RtlConfig& c) {
         c.pipeline.issue = rtl::pipeline::IssuePolicy::kRowHit;
         c.pipeline.ray_slots = 1;
         c.pipeline.sample_buffer = 1;
         c.pipeline.controller.queue_depth = 1;
       }},
      {"1 ray slot", [](rtl::RtlConfig& c) { c.pipeline.ray_slots = 1; }},
      {"tiny buffers",
       [](rtl::RtlConfig& c) {
         c.pipeline.sample_buffer = 1;
         c.pipeline.fifo_depth = 1;
         c.pipeline.output_depth = 1;
         c.pipeline.controller.queue_depth = 1;
         c.pipeline.controller.return_depth = 1;
       }},
      {"slow setup", [](rtl::RtlConfig& c) { c.pipeline.latency.ray_setup_interval = 7; }},
      {"PC100 CL3", [](rtl::RtlConfig& c) { c.pipeline.dimm.timing = rtl::sdram::presets::pc100_cl3(); }},
      // The schedulers reorder commands and completions, never pixels.
      {"fr-fcfs", [](rtl::RtlConfig& c) { c.scheduler = "fr-fcfs"; }},
      {"fr-fcfs window 2, limit 1",
       [](rtl::RtlConfig& c) {
         c.scheduler = "fr-fcfs";
         c.pipeline.scheduler_params = {.reorder_window = 2, .starvation_limit = 1};
       }},
      {"lookahead", [](rtl::RtlConfig& c) { c.scheduler = "lookahead"; }},
      {"lookahead, bricked, tiles",
       [](rtl::RtlConfig& c) {
         c.scheduler = "lookahead";
         c.mapping.name = "bricked";
         c.pipeline.traversal = rtl::pipeline::Traversal::kTiles;
       }},
      {"fr-fcfs, morton, tiny buffers",
       [](rtl::RtlConfig& c) {
         c.scheduler = "fr-fcfs";
         c.mapping.name = "morton";
         c.pipeline.sample_buffer = 2;
         c.pipeline.controller.queue_depth = 3;
         c.pipeline.controller.return_depth = 1;
         c.pipeline.scheduler_params.reorder_window = 3;
       }},
  };
  for (const Variant& v : variants) {
    rtl::RtlConfig c = rtl::vizard2_baseline();
    v.apply(c);
    const rtl::RtlResult r = rtl::rtl_render(f.setup, f.memory, c);
    expect_same_image(r.image, bt, v.what);
    EXPECT_EQ(r.stats.samples, base.stats.samples) << v.what;
  }
}

TEST(RtlEngine, DeterministicCycles) {
  const RtlFrame f = make_rtl_frame("shells", 24, 24, {"precision.profile=balanced"});
  const rtl::RtlResult a = rtl::rtl_render(f.setup, f.memory);
  const rtl::RtlResult b = rtl::rtl_render(f.setup, f.memory);
  EXPECT_EQ(a.stats.cycles, b.stats.cycles);
  EXPECT_EQ(a.stats.samples_issued, b.stats.samples_issued);
  EXPECT_EQ(a.stats.row_hits(), b.stats.row_hits());
  EXPECT_EQ(a.stats.activates(), b.stats.activates());
  EXPECT_EQ(a.image.pixels, b.image.pixels);
}

// The host's thread count changes nothing: a scene asking for 1 or 4 worker
// threads, and frames simulated concurrently on 3 host threads (as a sweep
// would run them: no shared mutable state), give the same cycles, row
// outcomes and pixels.
TEST(RtlEngine, SameCyclesAndBitsForAnyHostThreadCount) {
  const RtlFrame one = make_rtl_frame("shells", 20, 20, {"precision.profile=vizard2", "render.threads=1"});
  const RtlFrame four = make_rtl_frame("shells", 20, 20, {"precision.profile=vizard2", "render.threads=4"});
  rtl::RtlConfig c = rtl::vizard2_baseline();
  c.scheduler = "lookahead";
  const rtl::RtlResult ref = rtl::rtl_render(one.setup, one.memory, c);
  const rtl::RtlResult b = rtl::rtl_render(four.setup, four.memory, c);
  EXPECT_EQ(b.stats.cycles, ref.stats.cycles);
  EXPECT_EQ(b.image.pixels, ref.image.pixels);
  std::vector<rtl::RtlResult> parallel(3);
  {
    std::vector<std::thread> threads;
    for (auto& r : parallel)
      threads.emplace_back([&r, &four, &c] { r = rtl::rtl_render(four.setup, four.memory, c); });
    for (auto& t : threads) t.join();
  }
  for (const rtl::RtlResult& r : parallel) {
    EXPECT_EQ(r.stats.cycles, ref.stats.cycles);
    EXPECT_EQ(r.stats.activates(), ref.stats.activates());
    EXPECT_EQ(r.stats.row_hits(), ref.stats.row_hits());
    EXPECT_EQ(r.image.pixels, ref.image.pixels);
  }
}

// Fast-forward (skipping cycles in which nothing can move) and the
// event-driven memory ports (the in-order port; every policy's controller
// ticked at its next events) are simulation speed-ups only: against the
// reference controller ticked every cycle, the same cycles, commands, row
// outcomes, latencies, stalls, FIFO occupancies and image, for every
// scheduling policy, open page and auto precharge. The controllers' cycles
// are the frame's (the card clocks them in every cycle), whichever ticks
// the simulation ran.
TEST(RtlEngine, FastSimulationChangesNothing) {
  for (const char* policy : {"in-order", "fr-fcfs", "lookahead"})
    for (bool auto_precharge : {false, true})
      for (const char* mode : {"shaded", "mip"}) {
        const RtlFrame f =
            make_rtl_frame("shepp-logan", 24, 24,
                           {"precision.profile=vizard2", std::string("render.mode=") + mode,
                            "render.ert_threshold=0.5"});
        rtl::RtlConfig slow = rtl::vizard2_baseline();
        slow.scheduler = policy;
        slow.pipeline.scheduler_params.starvation_limit = 8;
        slow.pipeline.fast_forward = false;
        slow.pipeline.memory_model = rtl::pipeline::MemoryModel::kReference;
        slow.pipeline.controller.auto_precharge = auto_precharge;
        for (int slots : {16, 2}) {
          slow.pipeline.ray_slots = slots;
          rtl::RtlConfig fast = slow;
          fast.pipeline.fast_forward = true;
          fast.pipeline.memory_model = rtl::pipeline::MemoryModel::kAuto;
          const rtl::RtlResult a = rtl::rtl_render(f.setup, f.memory, slow);
          const rtl::RtlResult b = rtl::rtl_render(f.setup, f.memory, fast);
          SCOPED_TRACE(::testing::Message()
                       << policy << (auto_precharge ? ", auto precharge, " : ", ") << mode << ", "
                       << slots << " ray slots");
          EXPECT_EQ(a.image.pixels, b.image.pixels);
          EXPECT_EQ(a.stats.cycles, b.stats.cycles);
          EXPECT_EQ(a.stats.samples_issued, b.stats.samples_issued);
          EXPECT_EQ(a.stats.samples_discarded, b.stats.samples_discarded);
          for (std::size_t d = 0; d < 4; ++d) {
            const auto& x = a.stats.dimms[d];
            const auto& y = b.stats.dimms[d];
            EXPECT_EQ(x.controller.cycles, a.stats.cycles);
            EXPECT_EQ(y.controller.cycles, b.stats.cycles);
            EXPECT_EQ(x.controller.auto_precharges, y.controller.auto_precharges);
            EXPECT_EQ(x.controller.row_hits, y.controller.row_hits);
            EXPECT_EQ(x.controller.row_conflicts, y.controller.row_conflicts);
            EXPECT_EQ(x.controller.row_misses, y.controller.row_misses);
            EXPECT_EQ(x.controller.command_cycles, y.controller.command_cycles);
            EXPECT_EQ(x.controller.refresh_cycles, y.controller.refresh_cycles);
            EXPECT_EQ(x.controller.latency_sum, y.controller.latency_sum);
            EXPECT_EQ(x.controller.latency_max, y.controller.latency_max);
            EXPECT_EQ(x.controller.bytes, y.controller.bytes);
            EXPECT_EQ(x.dimm.refreshes, y.dimm.refreshes);
            EXPECT_EQ(x.dimm.commands, y.dimm.commands);
            EXPECT_EQ(x.dimm.precharge_alls, y.dimm.precharge_alls);
            EXPECT_EQ(x.dimm.data_bus_busy_cycles, y.dimm.data_bus_busy_cycles);
            for (std::size_t k = 0; k < x.dimm.banks.size(); ++k) {
              EXPECT_EQ(x.dimm.banks[k].activates, y.dimm.banks[k].activates);
              EXPECT_EQ(x.dimm.banks[k].precharges, y.dimm.banks[k].precharges);
              EXPECT_EQ(x.dimm.banks[k].open_cycles, y.dimm.banks[k].open_cycles);
              EXPECT_EQ(x.dimm.banks[k].reads, y.dimm.banks[k].reads);
            }
          }
          const auto& p = a.stats.stalls;
          const auto& q = b.stats.stalls;
          EXPECT_EQ(p.issue_no_ray, q.issue_no_ray);
          EXPECT_EQ(p.issue_buffer_full, q.issue_buffer_full);
          EXPECT_EQ(p.issue_memory_full, q.issue_memory_full);
          EXPECT_EQ(p.issue_idle, q.issue_idle);
          EXPECT_EQ(p.interp_wait_memory, q.interp_wait_memory);
          EXPECT_EQ(p.interp_blocked, q.interp_blocked);
          EXPECT_EQ(p.setup_no_slot, q.setup_no_slot);
          EXPECT_EQ(p.composite_blocked, q.composite_blocked);
          ASSERT_EQ(a.stats.fifos.size(), b.stats.fifos.size());
          for (std::size_t i = 0; i < a.stats.fifos.size(); ++i) {
            const auto& u = a.stats.fifos[i];
            const auto& v = b.stats.fifos[i];
            EXPECT_EQ(u.stats.occupancy_sum, v.stats.occupancy_sum) << u.name;
            EXPECT_EQ(u.stats.sampled_cycles, v.stats.sampled_cycles) << u.name;
            EXPECT_EQ(u.stats.sampled_cycles, static_cast<std::uint64_t>(a.stats.cycles)) << u.name;
            EXPECT_EQ(u.stats.full_cycles, v.stats.full_cycles) << u.name;
            EXPECT_EQ(u.stats.empty_cycles, v.stats.empty_cycles) << u.name;
            EXPECT_EQ(u.stats.max_occupancy, v.stats.max_occupancy) << u.name;
          }
        }
      }
}

TEST(RtlEngine, RejectsWhatItCannotRun) {
  const RtlFrame f = make_rtl_frame("box", 8, 8, {"precision.profile=vizard2"});
  bittrue::FrameSetup odd = f.setup;
  odd.profile.weight_bits = 5;
  EXPECT_FALSE(rtl::rtl_supports(odd.profile));
  try {
    rtl::rtl_render(odd, f.memory);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vizard2, balanced, precise"), std::string::npos) << e.what();
  }
  rtl::RtlConfig c;
  c.scheduler = "fr-fcfs-typo";
  EXPECT_THROW(rtl::rtl_render(f.setup, f.memory, c), Error);
  c = rtl::RtlConfig{};
  c.mapping.name = "hilbert";
  EXPECT_THROW(rtl::rtl_render(f.setup, f.memory, c), Error);
  c = rtl::RtlConfig{};
  c.pipeline.ray_slots = 0;
  EXPECT_THROW(rtl::rtl_render(f.setup, f.memory, c), Error);
}

}  // namespace
}  // namespace voxcast::test
