// The fixed-point engines against each other: hls == bit-true on every bit of
// every pixel, for every preset and render mode, on the phantoms, on Colin27
// at 256x256 and on the regression scenes; and a planted fault is pinned to
// the unit it was planted in.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "cosim/engines/cosim.hpp"
#include "cosim/engines/engines.hpp"
#include "cosim/reports/rtl_json.hpp"
#include "refmodel/scene/rtl_keys.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

using cosim::SceneVolume;

struct Frame {
  bittrue::FrameSetup setup;
  bittrue::VoxelMemory memory;
};

Frame prepare(const ref::Scene& scene, const SceneVolume& sv) {
  cosim::check_fixed_point(scene, sv, true);
  const ref::RenderInputs in =
      ref::make_render_inputs(scene, sv.volume, sv.gradients, scene.camera.pose);
  return {bittrue::make_frame_setup(scene.precision, scene, in),
          bittrue::make_voxel_memory(scene.precision, sv.volume, sv.gradients)};
}

// Compares the two engines; on a mismatch names the first pixel and unit.
void expect_bit_exact(const ref::Scene& scene, const SceneVolume& sv, const std::string& what) {
  const Frame f = prepare(scene, sv);
  ref::FrameStats hls_stats, bt_stats;
  const ref::QuantImage hls = cosim::hls_render_image(f.setup, f.memory, 2, &hls_stats);
  const ref::QuantImage bt = bittrue::bt_render_image(f.setup, f.memory, 2, &bt_stats);
  EXPECT_EQ(hls_stats, bt_stats) << what;  // docs/pipeline.md §9
  ASSERT_EQ(hls.pixels.size(), bt.pixels.size());
  for (int y = 0; y < hls.height; ++y)
    for (int x = 0; x < hls.width; ++x)
      if (hls.at(x, y) != bt.at(x, y)) {
        bittrue::RayTrace t;
        bittrue::bt_cast_ray(f.setup, f.memory, x, y, &t);
        const auto d = bittrue::first_divergence(cosim::hls_trace_ray(f.setup, f.memory, x, y), t);
        FAIL() << what << ": pixel (" << x << ", " << y << ") differs, sample " << d.sample
               << ", first in the " << bittrue::to_string(d.unit);
      }
  // Something was drawn: the comparison is not between two empty images.
  std::size_t lit = 0;
  for (const auto& px : hls.pixels) lit += px[3] > 0 ? 1 : 0;
  EXPECT_GT(lit, hls.pixels.size() / 20) << what;
}

const char* const kModes[] = {"shaded", "unshaded", "mip"};

ref::Scene phantom_scene(const std::string& phantom, int size) {
  const double c = (size - 1) / 2.0;
  std::string text = "[volume]\nsource = \"phantom:" + phantom + "?size=" + std::to_string(size) +
                     "&aa=2\"\n[classification]\npoints = [ {value = 0, alpha = 0.0}, "
                     "{value = 30, color = [0.9, 0.6, 0.4], alpha = 0.05}, "
                     "{value = 200, color = [0.5, 0.8, 1.0], alpha = 0.7} ]\n"
                     "[camera]\neye = [" + std::to_string(c + 0.3 * size) + ", " +
                     std::to_string(-1.2 * size) + ", " + std::to_string(c + 0.4 * size) +
                     "]\ncenter = [" + std::to_string(c) + ", " + std::to_string(c) + ", " +
                     std::to_string(c) + "]\nfov_deg = 45\n[render]\nwidth = 64\nheight = 64\n"
                     "oversampling = 1.5\n"
                     "[[lights]]\ntype = \"directional\"\ndirection = [1, -1, 1]\nintensity = 0.6\n"
                     "[[lights]]\ntype = \"headlight\"\nintensity = 0.6\n";
  return ref::parse_scene(text, "phantom " + phantom, ".");
}

class PhantomEngines : public ::testing::TestWithParam<std::string> {};

TEST_P(PhantomEngines, BitExactForEveryPresetAndMode) {
  const ref::Scene base = phantom_scene(GetParam(), 48);
  const SceneVolume sv = cosim::load_scene_volume(base);
  for (const std::string& profile : preset_names())
    for (const char* mode : kModes) {
      ref::Scene s = ref::parse_scene(ref::scene_to_toml(base), base.origin, ".",
                                      {"precision.profile=" + profile,
                                       std::string("render.mode=") + mode});
      expect_bit_exact(s, sv, GetParam() + " " + profile + " " + mode);
    }
}

INSTANTIATE_TEST_SUITE_P(Phantoms, PhantomEngines,
                         ::testing::Values("shepp-logan", "shells", "tube", "box"));

TEST(Colin27Engines, BitExactAt256ForEveryPresetAndMode) {
  const std::string path = std::string(VOXCAST_SOURCE_DIR) + "/scenes/colin27.toml";
  if (!std::filesystem::exists("/usr/share/mricron/templates/ch2.nii.gz"))
    GTEST_SKIP() << "mricron-data is not installed";
  const ref::Scene base = ref::load_scene_file(path);
  ASSERT_EQ(base.render.width, 256);
  ASSERT_EQ(base.render.height, 256);
  const SceneVolume sv = cosim::load_scene_volume(base);
  for (const std::string& profile : preset_names())
    for (const char* mode : kModes) {
      const ref::Scene s = ref::load_scene_file(
          path, {"precision.profile=" + profile, std::string("render.mode=") + mode});
      expect_bit_exact(s, sv, "colin27 " + profile + " " + mode);
    }
}

TEST(RegressionScenes, StayBitExact) {
  const std::filesystem::path dir = std::filesystem::path(VOXCAST_SOURCE_DIR) / "tests/regress";
  int scenes = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".toml") continue;
    for (const std::string& profile : preset_names()) {
      const ref::Scene s = ref::load_scene_file(e.path().string(), {"precision.profile=" + profile});
      expect_bit_exact(s, cosim::load_scene_volume(s), e.path().filename().string() + " " + profile);
    }
    ++scenes;
  }
  EXPECT_GE(scenes, 2);
}

// --- Planted faults are found where they were planted ----------------------------

struct Planted {
  Frame good, bad;
  int x = 0, y = 0;
  std::uint64_t sample = 0;
};

// Finds the first lit pixel's first composited sample and corrupts, in the
// hls engine's copy of the set-up only, the table entry that sample reads.
Planted plant(bool reflectance) {
  const ref::Scene s = phantom_scene("shells", 32);
  const SceneVolume sv = cosim::load_scene_volume(s);
  Planted p{prepare(s, sv), prepare(s, sv)};
  for (p.y = 0; p.y < s.render.height; ++p.y)
    for (p.x = 0; p.x < s.render.width; ++p.x) {
      bittrue::RayTrace t;
      bittrue::bt_cast_ray(p.good.setup, p.good.memory, p.x, p.y, &t);
      for (p.sample = 0; p.sample < t.trace.size(); ++p.sample) {
        const bittrue::SampleTrace& st = t.trace[p.sample];
        if (st.alpha <= 0.0) continue;
        if (!reflectance) {
          p.bad.setup.class_table[static_cast<std::size_t>(st.class_address)].r ^= 1u;
          return p;
        }
        if (st.diffuse > 0.0) {
          // The entries the sample read (its cell, or with rm_bilinear the cell's four
          // corners, docs/pipeline.md §5.5), all set to the diffuse value read with its LSB
          // flipped: the unit's D then changes by one LSB in either mode.
          const PrecisionProfile& pr = p.good.setup.profile;
          const bittrue::BtCell c = bittrue::bt_rm_cell(pr, p.good.setup.regs.IS, st.gradient);
          const std::uint32_t bad =
              static_cast<std::uint32_t>(std::ldexp(st.diffuse, pr.rm_frac_bits)) ^ 1u;
          const auto i = static_cast<std::size_t>(c.index);
          const auto row = static_cast<std::size_t>(pr.rm_res) + 1;
          if (pr.rm_bilinear)
            for (const std::size_t k : {i, i + 1, i + row, i + row + 1})
              p.bad.setup.rm_diffuse[k] = bad;
          else
            p.bad.setup.rm_diffuse[i] = bad;
          return p;
        }
      }
    }
  ADD_FAILURE() << "no pixel to plant a fault in";
  return p;
}

TEST(Divergence, APlantedClassificationFaultIsNamed) {
  const Planted p = plant(false);
  bittrue::RayTrace t;
  bittrue::bt_cast_ray(p.good.setup, p.good.memory, p.x, p.y, &t);
  const auto d = bittrue::first_divergence(cosim::hls_trace_ray(p.bad.setup, p.bad.memory, p.x, p.y), t);
  EXPECT_TRUE(d.diverged);
  EXPECT_EQ(d.unit, bittrue::Unit::Shader);  // colour feeds the shader; the entry's address and alpha agree
  EXPECT_EQ(d.sample, p.sample);
}

TEST(Divergence, APlantedReflectanceFaultIsNamed) {
  const Planted p = plant(true);
  bittrue::RayTrace t;
  bittrue::bt_cast_ray(p.good.setup, p.good.memory, p.x, p.y, &t);
  const auto d = bittrue::first_divergence(cosim::hls_trace_ray(p.bad.setup, p.bad.memory, p.x, p.y), t);
  EXPECT_TRUE(d.diverged);
  EXPECT_EQ(d.unit, bittrue::Unit::ReflectanceMap);
  EXPECT_EQ(d.sample, p.sample);
}

TEST(Divergence, IdenticalTracesDoNotDiverge) {
  const ref::Scene s = phantom_scene("box", 16);
  const Frame f = prepare(s, cosim::load_scene_volume(s));
  bittrue::RayTrace t;
  bittrue::bt_cast_ray(f.setup, f.memory, 32, 32, &t);
  EXPECT_FALSE(bittrue::first_divergence(cosim::hls_trace_ray(f.setup, f.memory, 32, 32), t).diverged);
  EXPECT_GT(t.trace.size(), 0u);
}

}  // namespace
}  // namespace voxcast::test

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

// The reports' "rtl" object and the written scene's [rtl] table come from the
// one key list (refmodel/scene/rtl_keys.hpp): every key the reader accepts,
// with the value the scene set, and the written scene reads back the same.
TEST(RtlKeys, ReportAndWrittenSceneCarryEveryKeyWithItsValue) {
  const ref::Scene s = ref::default_scene(
      {"rtl.scheduler=fr-fcfs", "rtl.reorder_window=4", "rtl.starvation_limit=9",
       "rtl.layout=bricked", "rtl.brick=[4, 2, 8]", "rtl.ray_slots=32", "rtl.queue_depth=12",
       "rtl.return_depth=6", "rtl.issue=row-hit", "rtl.issue_bypass_limit=11",
       "rtl.auto_precharge=true", "rtl.pipelines=3"});
  const nlohmann::json j = cosim::rtl_desc_json(s.rtl);
  const std::vector<std::string> names = ref::rtl_key_names();
  EXPECT_EQ(names.size(), 20u);
  EXPECT_EQ(j.size(), names.size());
  for (const std::string& k : names) EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_EQ(j.at("scheduler"), "fr-fcfs");
  EXPECT_EQ(j.at("reorder_window"), 4);
  EXPECT_EQ(j.at("starvation_limit"), 9);
  EXPECT_EQ(j.at("brick"), nlohmann::json::array({4, 2, 8}));
  EXPECT_EQ(j.at("ray_slots"), 32);
  EXPECT_EQ(j.at("return_depth"), 6);
  EXPECT_EQ(j.at("issue"), "row-hit");
  EXPECT_EQ(j.at("issue_bypass_limit"), 11);
  EXPECT_EQ(j.at("auto_precharge"), true);
  EXPECT_EQ(j.at("pipelines"), 3);
  const ref::Scene t = ref::parse_scene(ref::scene_to_toml(s), "round trip", ".");
  EXPECT_EQ(cosim::rtl_desc_json(t.rtl), j);
}

}  // namespace
}  // namespace voxcast::test
