// VIRIM's cycle model (rtl_model/virim/, docs/virim-rtl.md): the pixels are
// the hls kernels' on every run; the parity memory's counts and the
// rotator's throughput follow closed forms on axis-aligned views; the
// results do not depend on the host threads; impossible configurations are
// errors. The 256x256x128 calibration against the paper is opt-in:
//   VOXCAST_CALIBRATION=1 ./build/dev/tests/voxcast_tests_heidelberg --gtest_filter='VirimRtlCalibration*'
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>

#include "cosim/engines/engines.hpp"
#include "cosim/engines/heidelberg.hpp"
#include "refmodel/bittrue/heidelberg.hpp"
#include "refmodel/error.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/virim/engine.hpp"
#include "tests/heidelberg/fixtures.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

using rtl::virim::VirimRtlConfig;
using rtl::virim::VirimRtlResult;
using rtl::virim::VirimRtlStats;

struct Case {
  ref::Volume volume;
  ref::Scene scene;
  bittrue::VirimSetup setup;
  bittrue::VirimMemory memory;
  Case(ref::Volume v, ref::Scene s)
      : volume(std::move(v)), scene(std::move(s)),
        setup(bittrue::make_virim_setup(bittrue::heidelberg_profile(scene), scene, volume, 0.0)),
        memory(bittrue::make_virim_memory(volume)) {}
};

// The cycle model's frame, held to the hls kernels' pixels.
VirimRtlResult run(const Case& c, const VirimRtlConfig& cfg, int threads = 1) {
  VirimRtlResult r = rtl::virim::virim_rtl_render(c.setup, c.memory, cfg, threads);
  const ref::QuantImage hls = cosim::hls_render_heidelberg(c.setup, c.memory, 1);
  EXPECT_EQ(r.image.pixels, hls.pixels) << "rtl differs from hls";
  EXPECT_EQ(r.stats.unit_reads, 8 * r.stats.voxels);
  EXPECT_EQ(r.stats.unit_reads, r.stats.ram_reads + r.stats.suppressed + r.stats.out_of_range);
  EXPECT_EQ(r.stats.bus_words, r.stats.voxels);  // one 48-bit word per rotated voxel
  return r;
}

// A DSP side that never holds the rotator back: the rotator's own timing shows.
VirimRtlConfig fast_dsps(VirimRtlConfig c = {}) {
  c.bus_mhz = 1000.0;
  c.dsp_mhz = 1000.0;
  c.dsp_cycles_per_voxel = 1;
  return c;
}

Case oblique() { return Case(oblique_volume(), oblique_heidelberg_scene()); }

// The view cube equals the volume, unrotated, unzoomed: output voxel (i, j, k)
// reads the neighbourhood with lower corner (i, j, k) exactly.
Case aligned(int nx, int ny, int nz, double zoom = 1.0) {
  const int W = static_cast<int>(nx * zoom), D = static_cast<int>(ny * zoom),
            H = static_cast<int>(nz * zoom);
  ref::Scene s = heidelberg_scene(W, D, H);
  s.heidelberg.zoom = zoom;
  return Case(random_volume(nx, ny, nz, 3), s);
}

TEST(VirimRtl, EqualsHlsOnAnObliquePerspectiveViewForEveryConfiguration) {
  const Case c = oblique();
  VirimRtlConfig base;
  for (int modules : {1, 2, 3}) {
    VirimRtlConfig cfg = base;
    cfg.modules = modules;
    run(c, cfg);
  }
  VirimRtlConfig tight = base;  // every buffer at its minimum: the bus and DSPs stall
  tight.modules = 1;
  tight.dsps_per_module = 3;
  tight.dsp_fifo_words = 1;
  tight.bus_fifo_words = 2 * c.setup.W;
  const VirimRtlResult r = run(c, tight);
  EXPECT_GT(r.stats.stalls.bus_dsp_fifo_full, 0u);
  EXPECT_GT(r.stats.stalls.rotator_bus_full, 0u);
  VirimRtlConfig plain = base;
  plain.ping_pong = false;
  plain.suppress_repeats = false;
  plain.bank_cycle_clocks = 3;
  run(c, plain);
}

TEST(VirimRtl, EqualsHlsOnThePhantomScene) {
  ref::Scene s = ref::load_scene_file(std::string(VOXCAST_SOURCE_DIR) + "/scenes/heidelberg.toml",
                                      {"volume.source=phantom:shepp-logan?size=40&aa=1",
                                       "render.width=40", "render.height=36",
                                       "heidelberg.depth=40", "heidelberg.perspective=100",
                                       "heidelberg.modules=2"});
  const cosim::SceneVolume sv = cosim::load_scene_volume(s);
  const Case c(sv.volume, s);
  const VirimRtlResult r = run(c, rtl::virim::virim_rtl_config(s.heidelberg));
  EXPECT_GT(r.stats.suppressed, 0u);
  EXPECT_GT(r.stats.out_of_range, 0u);  // the rotated cube's corners leave the data
}

// Unit u = (px, py, pz) reads, for lower corner (i, j, k), the coordinate of
// parity px among {i, i+1} (and so on): along a row px = 0 reads x = 0, 2, 2,
// 4, 4, ..., W (out of range for even W) and px = 1 reads 1, 1, 3, 3, ...
// A row whose y or z read falls outside (j = Ny-1 for py = 0 with Ny even)
// reads 0 throughout.
TEST(VirimRtl, SuppressionAndOutOfRangeCountsFollowTheParityClosedForm) {
  const int W = 16, D = 12, H = 10;
  const Case c = aligned(W, D, H);
  VirimRtlConfig cfg;
  cfg.modules = 2;
  const VirimRtlResult r = run(c, cfg);
  std::uint64_t ram = 0, suppressed = 0, oor = 0;
  for (int u = 0; u < 8; ++u) {
    const int px = u & 1, py = (u >> 1) & 1, pz = (u >> 2) & 1;
    const std::uint64_t rows = static_cast<std::uint64_t>(D) * H;
    const std::uint64_t valid = static_cast<std::uint64_t>(D - (py == 0)) * (H - (pz == 0));
    ram += valid * W / 2;
    suppressed += valid * (W / 2 - (px == 0));
    oor += (rows - valid) * W + valid * (px == 0);
  }
  EXPECT_EQ(r.stats.ram_reads, ram);
  EXPECT_EQ(r.stats.suppressed, suppressed);
  EXPECT_EQ(r.stats.out_of_range, oor);
  // hls counts the same reads (its lines start from a reset unit; no row
  // here can reuse the previous row's last address).
  hls::virim::MemoryStats ms;
  cosim::hls_render_heidelberg(c.setup, c.memory, 1, &ms);
  EXPECT_EQ(ms.suppressed, r.stats.suppressed);
  EXPECT_EQ(ms.out_of_bounds, r.stats.out_of_range);
  EXPECT_EQ(ms.bank_reads[0] + ms.bank_reads[1], r.stats.ram_reads);
  // Without suppression every in-range read reaches a bank.
  cfg.suppress_repeats = false;
  const VirimRtlResult all = run(c, cfg);
  EXPECT_EQ(all.stats.suppressed, 0u);
  EXPECT_EQ(all.stats.ram_reads, ram + suppressed);
}

TEST(VirimRtl, OutOfRangeReadsCostNoMemoryCycle) {
  Case c = aligned(16, 12, 10);
  c.scene.heidelberg.translation = {500.0, 0.0, 0.0};  // the cube far right of the view
  c.setup = bittrue::make_virim_setup(bittrue::heidelberg_profile(c.scene), c.scene, c.volume, 0.0);
  VirimRtlConfig cfg = fast_dsps();
  cfg.ping_pong = false;
  cfg.suppress_repeats = false;
  cfg.bank_cycle_clocks = 7;
  cfg.modules = 1;
  const VirimRtlResult r = run(c, cfg);
  EXPECT_EQ(r.stats.out_of_range, r.stats.unit_reads);
  EXPECT_EQ(r.stats.ram_reads, 0u);
  EXPECT_EQ(r.stats.access_cycles, 0u);
  EXPECT_EQ(r.stats.stalls.rotator_bank_busy, 0u);
  EXPECT_EQ(r.stats.rotating_cycles, r.stats.voxels);  // one voxel per rotator clock
  // Without the feature every read costs the bank cycle: voxels B clocks apart.
  cfg.zero_out_of_range = false;
  const VirimRtlResult paid = run(c, cfg);
  EXPECT_EQ(paid.stats.stalls.rotator_bank_busy, 6u * (r.stats.voxels - 1));
  EXPECT_DOUBLE_EQ(paid.stats.mean_access_ns(),
                   (8.0 * 7 * static_cast<double>(r.stats.voxels) + 8.0 * 6 * static_cast<double>(r.stats.voxels - 1)) /
                       (8.0 * static_cast<double>(r.stats.voxels)) * 25.0);
}

// Zoom 1/2: output voxel i reads x0 = 2i, so each unit reads a new address
// every clock, alternately from its two banks ((x >> 1) & 1 = i & 1).
TEST(VirimRtl, PingPongHidesTheBankCycle) {
  const Case c = aligned(32, 24, 20, 0.5);
  for (bool suppress : {true, false}) {
    VirimRtlConfig cfg = fast_dsps();
    cfg.suppress_repeats = suppress;
    cfg.modules = 2;
    const VirimRtlResult on = run(c, cfg);
    EXPECT_EQ(on.stats.suppressed, 0u);
    EXPECT_EQ(on.stats.out_of_range, 0u);
    EXPECT_EQ(on.stats.ram_reads, on.stats.unit_reads);
    EXPECT_EQ(on.stats.stalls.rotator_bank_busy, 0u);
    EXPECT_EQ(on.stats.stalls.rotator_bus_full, 0u);
    EXPECT_EQ(on.stats.rotating_cycles, on.stats.voxels);  // one voxel per clock
    EXPECT_EQ(on.stats.bank_reads[0], on.stats.bank_reads[1]);
    // Mean access time: every read waits for nothing and takes the bank cycle.
    EXPECT_DOUBLE_EQ(on.stats.mean_access_ns(), 2 * 25.0);
    // Without ping-pong a unit starts a read every bank cycle B: each module's
    // N voxels are issued B clocks apart.
    for (int B : {2, 3}) {
      cfg.ping_pong = false;
      cfg.bank_cycle_clocks = B;
      const VirimRtlResult off = run(c, cfg);
      const std::uint64_t per_module = off.stats.voxels / 2;
      EXPECT_EQ(off.stats.stalls.rotator_bank_busy, 2 * (B - 1) * (per_module - 1));
      EXPECT_EQ(off.stats.rotating_cycles, 2 * (B * (per_module - 1) + 1));
      EXPECT_NEAR(off.stats.rotation_rate(), 2 * 40e6 / B, 2 * 40e6 / B * 1e-3);
    }
  }
}

// Zoom 1 without ping-pong: suppression leaves each unit one read per two
// voxels, except the px = 0 units' reads at i = 0 and 1 (x = 0, then 2): one
// bank stall per row with B = 2; ping-pong puts x = 0 and 2 in different banks.
TEST(VirimRtl, SuppressionAloneStallsOncePerRow) {
  const int W = 16, D = 12, H = 10;
  const Case c = aligned(W, D, H);
  VirimRtlConfig cfg = fast_dsps();
  cfg.modules = 1;
  cfg.ping_pong = false;
  EXPECT_EQ(run(c, cfg).stats.stalls.rotator_bank_busy, static_cast<std::uint64_t>(D * H));
  cfg.ping_pong = true;
  EXPECT_EQ(run(c, cfg).stats.stalls.rotator_bank_busy, 0u);
}

// With a fast rotator and FIFOs that hold every word, the frame is the DSPs'
// work: each of 16 DSPs computes H/16 lines of W x D voxels at 30 cycles each.
TEST(VirimRtl, DspBoundFrameTimeIsTheSliceProcessorsWork) {
  const int W = 16, D = 12, H = 32;
  const Case c = aligned(W, D, H);
  VirimRtlConfig cfg;
  cfg.modules = 1;
  cfg.rotator_mhz = 1000.0;
  cfg.bus_mhz = 1000.0;
  cfg.dsp_fifo_words = 2 * W * D;
  const VirimRtlResult r = run(c, cfg);
  const double work_ns = 2.0 * W * D * 30 / 40e6 * 1e9;  // 2 lines per DSP
  // The last DSP's first word is released when its line's second row is
  // rotated: after row 0 of all 16 lines and row 1 of all 16, voxel 32 W - 1
  // issued at 1 ns per clock, plus bank cycle, interpolation and gradient
  // latency (2 + 3 + 2 ns) and one bus clock; the DSP starts at its next
  // 25 ns edge and then works without a gap.
  const double first_ns = 32.0 * W - 1 + 2 + 3 + 2 + 1;
  EXPECT_DOUBLE_EQ(r.stats.frame_ns, std::ceil(first_ns / 25.0) * 25.0 + work_ns);
  EXPECT_GT(r.stats.dsp_utilisation(), 0.99);
  EXPECT_EQ(r.stats.stalls.dsp_starved, 0u);
}

TEST(VirimRtl, SameCyclesAndPixelsForOneAndTwoHostThreads) {
  const Case c = oblique();
  VirimRtlConfig cfg;
  cfg.modules = 3;
  const VirimRtlResult a = run(c, cfg, 1), b = run(c, cfg, 2);
  EXPECT_EQ(a.image.pixels, b.image.pixels);
  EXPECT_EQ(a.stats.cycles, b.stats.cycles);
  EXPECT_EQ(a.stats.frame_ns, b.stats.frame_ns);
  EXPECT_EQ(a.stats.access_cycles, b.stats.access_cycles);
  EXPECT_EQ(a.stats.stalls.bus_dsp_fifo_full, b.stats.stalls.bus_dsp_fifo_full);
  EXPECT_EQ(a.stats.stalls.dsp_starved, b.stats.stalls.dsp_starved);
}

std::string error_of(const Case& c, const VirimRtlConfig& cfg) {
  try {
    rtl::virim::virim_rtl_render(c.setup, c.memory, cfg, 1);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// render --engine rtl refuses an image that differs from the hls kernels'.
TEST(VirimRtl, AMismatchWithHlsIsAnErrorNamingThePixel) {
  ref::QuantImage a(5, 4, 8), b(5, 4, 8);
  EXPECT_NO_THROW(cosim::check_rtl_matches_hls(a, b));
  b.at(3, 2) = {1, 1, 1, 255};
  b.at(1, 3) = {1, 1, 1, 255};
  try {
    cosim::check_rtl_matches_hls(a, b);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("at pixel (3, 2)"), std::string::npos) << e.what();
  }
}

TEST(VirimRtl, ImpossibleConfigurationsAreErrors) {
  const Case c = aligned(16, 12, 10);
  VirimRtlConfig cfg;
  cfg.bus_fifo_words = 2 * 16 - 1;  // a line's last row releases two rows
  EXPECT_NE(error_of(c, cfg).find("would deadlock"), std::string::npos) << error_of(c, cfg);
  cfg = {};
  cfg.modules = 0;
  EXPECT_NE(error_of(c, cfg).find("modules = 0 is outside"), std::string::npos);
  cfg = {};
  cfg.dsp_mhz = 0.0;
  EXPECT_NE(error_of(c, cfg).find("dsp_mhz"), std::string::npos);
  Case five = c;
  five.scene.heidelberg.weight_bits = 5;
  five.setup = bittrue::make_virim_setup(bittrue::heidelberg_profile(five.scene), five.scene,
                                         five.volume, 0.0);
  EXPECT_NE(error_of(five, {}).find("not compiled in"), std::string::npos);
}

// The paper's figures (docs/virim-rtl.md §4): 4 modules, 256x256x128, the
// shipped scene's oblique perspective view.
TEST(VirimRtlCalibration, PaperFigures) {
  if (!std::getenv("VOXCAST_CALIBRATION")) GTEST_SKIP() << "set VOXCAST_CALIBRATION=1";
  ref::Scene s = ref::load_scene_file(std::string(VOXCAST_SOURCE_DIR) + "/scenes/heidelberg.toml",
                                      {"render.width=256", "render.height=128",
                                       "heidelberg.depth=256", "heidelberg.perspective=600"});
  const Case c(make_volume(256, 256, 128, 8,
                           [](int x, int y, int z) {
                             const int dx = x - 128, dy = y - 128, dz = 2 * (z - 64);
                             return static_cast<std::uint16_t>(dx * dx + dy * dy + dz * dz < 100 * 100 ? 102 : 0);
                           }),
               s);
  const int threads = 2;
  for (double angle : {0.0, 35.0}) {
    Case v = c;
    v.scene.heidelberg.angle_deg = angle;
    v.setup = bittrue::make_virim_setup(bittrue::heidelberg_profile(v.scene), v.scene, v.volume, 0.0);
    VirimRtlStats on, off;
    const char* names[] = {"all on", "no suppression", "no ping-pong", "out of range costs", "all off"};
    for (int mode = 0; mode < 5; ++mode) {
      VirimRtlConfig cfg;
      cfg.suppress_repeats = mode != 1 && mode != 4;
      cfg.ping_pong = mode != 2 && mode != 4;
      cfg.zero_out_of_range = mode != 3 && mode != 4;
      const VirimRtlResult r = rtl::virim::virim_rtl_render(v.setup, v.memory, cfg, threads);
      (mode == 0 ? on : off) = r.stats;
      const VirimRtlStats& t = r.stats;
      std::cout << "| " << angle << " | " << names[mode] << " | " << t.mean_access_ns() << " | x"
                << t.mean_access_ns() / on.mean_access_ns() << " | " << t.rotation_rate() * 1e-6
                << " | " << t.fps() << " | " << t.dsp_utilisation() * 100 << " | "
                << t.ram_reads << " / " << t.suppressed << " / " << t.out_of_range << " | "
                << t.stalls.rotator_bank_busy << " / " << t.stalls.rotator_bus_full << " / "
                << t.stalls.bus_dsp_fifo_full << " / " << t.stalls.dsp_starved << " |\n";
    }
    // "Using these additional features, the mean access time can be reduced
    // by more than a factor of two."
    EXPECT_GT(off.mean_access_ns() / on.mean_access_ns(), 2.0);
    EXPECT_GE(on.fps(), 10.0);  // "256x256x128 voxels ... at a frame rate of 10 Hz"
    EXPECT_DOUBLE_EQ(on.peak_rotation_rate(), 160e6);  // "160 million voxels/s"
    // One 256-pixel line: 256 x 256 voxels x 30 cycles at 40 MHz <= 50 ms.
    EXPECT_LE(256.0 * 256 * 30 / 40e6, 0.050);
  }
}

}  // namespace
}  // namespace voxcast::test
