// Space leaping (docs/leaping.md): skipping the samples of empty min-max blocks
// changes no pixel in any engine, and removes exactly the skipped samples from
// every engine's count and from the cycle model's memory requests.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "cosim/engines/engines.hpp"
#include "cosim/hardware/report.hpp"
#include "hls/host_frame.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/error.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/render/space_leaping.hpp"
#include "refmodel/scene/elaboration.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/engine.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

// ---- Every engine, leaping off and on ------------------------------------------------------

struct Engines {
  ref::Image ref;
  ref::FrameStats ref_stats;
  ref::QuantImage bt, hls;
  ref::FrameStats bt_stats, hls_stats;
  rtl::RtlResult rtl;
};

Engines run_all(const ref::Scene& s, const cosim::SceneVolume& sv, int threads = 2) {
  const ref::RenderInputs in = ref::make_render_inputs(s, sv.volume, sv.gradients, s.camera.pose);
  const bittrue::FrameSetup fs = bittrue::make_frame_setup(s.precision, s, in);
  const bittrue::VoxelMemory mem = bittrue::make_voxel_memory(s.precision, sv.volume, sv.gradients);
  Engines r;
  r.ref = ref::render_image(in, threads, &r.ref_stats);
  r.bt = bittrue::bt_render_image(fs, mem, threads, &r.bt_stats);
  r.hls = cosim::hls_render_image(fs, mem, threads, &r.hls_stats);
  r.rtl = rtl::rtl_render(fs, mem, rtl::vizard2_baseline());
  return r;
}

ref::Scene shipped(const std::string& name, ref::Overrides o) {
  o.insert(o.begin(), {"render.width=24", "render.height=24"});
  return ref::load_scene_file(std::string(VOXCAST_SOURCE_DIR) + "/scenes/" + name, o);
}

// Off and on: bit-identical images; each engine's samples read with leaping
// plus those it skipped equal its samples without.
void expect_exact(const std::string& scene, ref::Overrides extra, bool expect_skips) {
  SCOPED_TRACE(scene);
  ref::Overrides off = extra, on = extra;
  off.push_back("render.space_leaping=false");
  on.push_back("render.space_leaping=true");
  const ref::Scene s_off = shipped(scene, off), s_on = shipped(scene, on);
  const cosim::SceneVolume sv = cosim::load_scene_volume(s_off);
  const Engines a = run_all(s_off, sv), b = run_all(s_on, sv);
  // The double reference: skipped samples are transparent, so identical.
  ASSERT_EQ(a.ref.pixels.size(), b.ref.pixels.size());
  for (std::size_t i = 0; i < a.ref.pixels.size(); ++i)
    ASSERT_EQ(a.ref.pixels[i], b.ref.pixels[i]) << "double pixel " << i;
  EXPECT_EQ(a.ref_stats.samples, b.ref_stats.samples + b.ref_stats.samples_skipped);
  // Fixed point: every engine the same bits as without leaping, and as each other.
  EXPECT_EQ(a.bt.pixels, b.bt.pixels);
  EXPECT_EQ(a.hls.pixels, b.hls.pixels);
  EXPECT_EQ(a.rtl.image.pixels, b.rtl.image.pixels);
  EXPECT_EQ(b.hls.pixels, b.bt.pixels);
  EXPECT_EQ(b.rtl.image.pixels, b.hls.pixels);
  EXPECT_EQ(a.bt_stats.samples_skipped, 0u);
  EXPECT_EQ(a.bt_stats.samples, b.bt_stats.samples + b.bt_stats.samples_skipped);
  // The hls leaping stepper (binary search over the block) skips exactly the
  // samples the bit-true engine tests one by one.
  EXPECT_EQ(b.hls_stats.samples_skipped, b.bt_stats.samples_skipped);
  EXPECT_EQ(b.hls_stats.samples, b.bt_stats.samples);
  // The cycle model composites the hls engine's samples.
  EXPECT_EQ(b.rtl.stats.samples, b.hls_stats.samples);
  EXPECT_EQ(a.rtl.stats.samples_skipped, 0u);
  // Every count (docs/pipeline.md §9) the same in the three fixed-point engines,
  // the cycle model's leaps beyond an early termination left out.
  for (const Engines* e : {&a, &b}) {
    EXPECT_EQ(e->hls_stats, e->bt_stats);
    EXPECT_EQ(rtl::frame_stats(e->rtl.stats), e->hls_stats);
  }
  if (expect_skips) {
    EXPECT_GT(b.bt_stats.samples_skipped, 0u);
    EXPECT_GT(b.ref_stats.samples_skipped, 0u);
    EXPECT_LT(b.rtl.stats.cycles, a.rtl.stats.cycles);  // fewer memory reads: a faster frame
  }
}

TEST(SpaceLeaping, DefaultSceneBitExactInEveryEngine) { expect_exact("default.toml", {}, true); }

TEST(SpaceLeaping, EndoscopySceneBitExactInEveryEngine) {
  expect_exact("endoscopy.toml", {}, true);
}

TEST(SpaceLeaping, MipSceneIsUntouched) {
  // Every MIP sample can be the maximum: the design has no leaping there.
  expect_exact("mip.toml", {}, false);
}

TEST(SpaceLeaping, OtherBlockSizesAndProfiles) {
  expect_exact("default.toml", {"render.leap_block=4", "precision.profile=vizard2"}, true);
  expect_exact("default.toml", {"render.leap_block=32", "render.mode=unshaded"}, true);
  // Runs longer than one leap's 2^leap_bits = 1024 samples (a 64-cell block
  // at 16x: up to 64·sqrt(3)·16 = 1774) take several leaps, still exact. A
  // transparent transfer function empties every block: every sample is skipped.
  expect_exact("default.toml",
               {"render.width=8", "render.height=8", "render.leap_block=64",
                "render.oversampling=16",
                "classification.points=[{value=0, alpha=0.0}, {value=255, alpha=0.0}]"},
               true);
}

TEST(SpaceLeaping, RtlIssuesExactlyTheSkippedSamplesFewer) {
  // Without ERT no sample is issued speculatively, so the memory requests drop
  // by exactly the samples leapt over.
  const ref::Overrides base{"render.ert_threshold=1.0"};
  ref::Overrides on = base;
  on.push_back("render.space_leaping=true");
  const ref::Scene s_off = shipped("default.toml", base), s_on = shipped("default.toml", on);
  const cosim::SceneVolume sv = cosim::load_scene_volume(s_off);
  const Engines a = run_all(s_off, sv), b = run_all(s_on, sv);
  EXPECT_EQ(a.rtl.image.pixels, b.rtl.image.pixels);
  ASSERT_GT(b.rtl.stats.samples_skipped, 0u);
  EXPECT_EQ(a.rtl.stats.samples_issued, b.rtl.stats.samples_issued + b.rtl.stats.samples_skipped);
  EXPECT_EQ(b.rtl.stats.samples_skipped, b.hls_stats.samples_skipped);
  EXPECT_EQ(b.rtl.stats.samples_issued, b.hls_stats.samples);
  EXPECT_GT(b.rtl.stats.leaps, 0u);
  EXPECT_LE(b.rtl.stats.leaps, b.rtl.stats.samples_skipped);
}

// ---- The block structure and the emptiness test in closed form ------------------------------

// Voxel (x, y, z) of an n^3 volume holds x + 8y + 64z (n <= 8).
ref::Volume ramp_volume(int n) {
  ref::Volume v;
  v.dims = {n, n, n};
  v.bits = 12;
  v.data.resize(static_cast<std::size_t>(n * n * n));
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        v.data[v.index(x, y, z)] = static_cast<std::uint16_t>(x + 8 * y + 64 * z);
  return v;
}

TEST(MinMaxBlocks, EachBlockSpansItsCellsAndTheApron) {
  // 7 voxels per axis: cells 0..5, blocks of 4 cells: {0..3} reading voxels
  // 0..4 and {4, 5} reading voxels 4..6. The value is increasing in every
  // axis, so min is at the block's first voxel and max at its last.
  const ref::MinMaxBlocks b = ref::make_min_max_blocks(ramp_volume(7), 2);
  EXPECT_EQ(b.blocks, (std::array<int, 3>{2, 2, 2}));
  const int first[2] = {0, 4}, last[2] = {4, 6};
  for (int bz = 0; bz < 2; ++bz)
    for (int by = 0; by < 2; ++by)
      for (int bx = 0; bx < 2; ++bx) {
        const std::size_t i = b.index(bx, by, bz);
        EXPECT_EQ(b.vmin[i], first[bx] + 8 * first[by] + 64 * first[bz]);
        EXPECT_EQ(b.vmax[i], last[bx] + 8 * last[by] + 64 * last[bz]);
      }
  EXPECT_THROW(ref::make_min_max_blocks(ramp_volume(7), 7), Error);
}

TEST(MinMaxBlocks, EmptinessIsTheOpacityOverTheBlocksValueRange) {
  // Block (0,0,0) of the ramp volume in 4-cell blocks holds values [0, 292].
  const ref::MinMaxBlocks mm = ref::make_min_max_blocks(ramp_volume(7), 2);
  const std::size_t b0 = mm.index(0, 0, 0);
  ASSERT_EQ(mm.vmax[b0], 292);
  bittrue::FrameSetup fs;
  fs.profile = kBalanced;  // 12-bit values, 12-bit table address: address = value
  std::vector<bittrue::ClassEntry> table(std::size_t{1} << kBalanced.tf_addr_bits);
  bittrue::LeapTables t;
  t.blocks = std::make_shared<const ref::MinMaxBlocks>(mm);
  const auto test = [&](std::size_t nonzero_entry) {
    for (auto& e : table) e.alpha = 0;
    if (nonzero_entry < table.size()) table[nonzero_entry].alpha = 1;
    t.nonzero_prefix = bittrue::nonzero_prefix(table);
    fs.leap = t;
    // The hls unit's test on the same block memory word and table.
    hls::LeapRegisters<ProfileTraits<kBalanced>> lr;
    auto memory = std::make_unique<hls::MinMaxMemory<ProfileTraits<kBalanced>>>();
    hls::host::load_leap<ProfileTraits<kBalanced>>(t, lr, *memory, "test");
    const bool hls_empty = hls::block_empty<ProfileTraits<kBalanced>>(lr, memory->block[b0]);
    EXPECT_EQ(hls_empty, bittrue::bt_block_empty(fs, b0)) << nonzero_entry;
    return hls_empty;
  };
  EXPECT_TRUE(test(table.size()));  // a transparent table: every block is empty
  EXPECT_FALSE(test(292));          // the one opaque entry at the block's max
  EXPECT_FALSE(test(0));            // ... at its min
  EXPECT_FALSE(test(150));          // ... inside
  EXPECT_TRUE(test(293));           // ... one past the max: still empty
  // The double reference asks the transfer function itself: a ramp that
  // leaves 0 only above 292 is transparent on [0, 292].
  const ref::TransferFunction tf({{0.0, {1, 1, 1}, 0.0}, {292.0, {1, 1, 1}, 0.0},
                                  {300.0, {1, 1, 1}, 0.8}},
                                 ref::TfInterpolation::Ramp, {});
  EXPECT_EQ(tf.max_alpha(0.0, 292.0), 0.0);
  EXPECT_DOUBLE_EQ(tf.max_alpha(0.0, 296.0), 0.4);  // halfway up the ramp
  const ref::TransferFunction step({{0.0, {1, 1, 1}, 0.0}, {150.0, {1, 1, 1}, 0.3}},
                                   ref::TfInterpolation::Binary, {});
  EXPECT_EQ(step.max_alpha(0.0, 149.9), 0.0);
  EXPECT_EQ(step.max_alpha(0.0, 150.0), 0.3);
}

// ---- Scene keys, elaboration, resources ---------------------------------------------------

TEST(SpaceLeaping, SceneKeysRoundTripAndAreChecked) {
  const ref::Scene s = ref::default_scene(
      {"render.space_leaping=true", "render.leap_block=16", "render.jitter=true"});
  const ref::Scene back = ref::parse_scene(ref::scene_to_toml(s), "round trip", ".");
  EXPECT_TRUE(back.render.space_leaping);
  EXPECT_EQ(back.render.leap_block, 16);
  EXPECT_TRUE(back.render.jitter);
  const ref::Scene d = ref::default_scene();
  EXPECT_FALSE(d.render.space_leaping);
  EXPECT_FALSE(d.render.jitter);
  const auto error_of = [](const std::string& set) {
    try {
      ref::default_scene({set});
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(error_of("render.leap_block=12").find("render.leap_block = 12 must be a power of two"),
            std::string::npos);
  EXPECT_NE(error_of("render.leap_block=128").find("outside [4, 64]"), std::string::npos);
  EXPECT_NE(error_of("render.space_leaping=1").find("must be true or false"), std::string::npos);
}

TEST(SpaceLeaping, ReportCountsTheBlockMemoryOnlyWhenEnabled) {
  const cosim::Part& part = cosim::find_part("xcv1000e");
  const auto units = [&](const ref::Overrides& o) {
    return cosim::estimate_resources(ref::default_scene(o), part);
  };
  const auto off = units({}), on = units({"render.space_leaping=true"});
  const auto find = [](const cosim::ResourceReport& r) -> const cosim::UnitResources* {
    for (const auto& u : r.units)
      if (u.unit.name == "space_leaping") return &u;
    return nullptr;
  };
  EXPECT_EQ(find(off), nullptr);
  bool listed = false;
  for (const auto& o : off.elaboration.omitted) listed |= o.unit == "space_leaping";
  EXPECT_TRUE(listed);
  const cosim::UnitResources* u = find(on);
  ASSERT_NE(u, nullptr);
  // The 128^3 shepp-logan volume in 8^3 blocks: (126 >> 3) + 1 = 16 blocks per axis.
  EXPECT_EQ(on.elaboration.leap_blocks, 16 * 16 * 16);
  bool memory = false;
  for (const auto& op : u->unit.ops)
    if (op.kind == cosim::OpKind::Ram && op.what.rfind("min-max", 0) == 0) {
      memory = true;
      EXPECT_EQ(op.a, 4096);
      EXPECT_EQ(op.b, 2 * on.elaboration.value_store_bits);
    }
  EXPECT_TRUE(memory);
  EXPECT_GT(on.total.brams, off.total.brams);
  EXPECT_GT(on.total.luts, off.total.luts);
  EXPECT_EQ(on.latency_sample, off.latency_sample + rtl::pipeline::UnitLatencies{}.leap_lookup);
}

}  // namespace
}  // namespace voxcast::test
