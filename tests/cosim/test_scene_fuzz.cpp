// The scene-level differential fuzzer (cosim/verify/scene_fuzz.hpp): a bounded,
// fixed-seed run finds nothing; the scenes an earlier run found (the guard
// then missed the reflectance map's saturation for dim colours) are now
// predicted; and the judge does flag a scene whose error the guard does not
// cover, so the run cannot pass vacuously.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "cosim/verify/scene_fuzz.hpp"
#include "cosim/engines/warnings.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

// The CI run: `voxcast fuzz-scenes --seed 1 --scenes 200 --size 16` (about
// 1.5 s); the long runs are documented in docs/extremes.md.
TEST(SceneFuzz, FixedSeedRunHasNoFinding) {
  cosim::SceneFuzzOptions o;
  o.seed = 1;
  o.scenes = 200;
  o.image_size = 16;
  o.threads = 2;
  const cosim::SceneFuzzResult r = cosim::run_scene_fuzz(o);
  EXPECT_EQ(r.scenes, 200);
  for (const auto& f : r.findings)
    ADD_FAILURE() << "scene " << f.index << ": error " << f.verdict.error_lsb << " LSB > bound "
                  << f.verdict.bound_lsb << (f.verdict.bit_exact ? "" : ", hls != bit-true");
  // The stream exercises what it is for: hazards, the hls kernels, varied profiles.
  EXPECT_GT(r.hazardous, 20);
  EXPECT_GT(r.hls_ran, 100);
  EXPECT_LT(r.worst_ratio, 1.0);
}

// Deterministic: the same seed and index give the same scene file.
TEST(SceneFuzz, ScenesFollowFromTheSeed) {
  EXPECT_EQ(ref::scene_to_toml(cosim::random_scene(7, 3, 16)),
            ref::scene_to_toml(cosim::random_scene(7, 3, 16)));
  EXPECT_NE(ref::scene_to_toml(cosim::random_scene(7, 3, 16)),
            ref::scene_to_toml(cosim::random_scene(7, 4, 16)));
  std::set<std::string> profiles;
  for (int i = 0; i < 40; ++i) profiles.insert(cosim::random_scene(1, i, 16).precision_name);
  EXPECT_GE(profiles.size(), 4u) << "presets and varied widths";
}

// The findings of `voxcast fuzz-scenes --seed 2 --scenes 2000 --size 24`
// before the guard priced the reflectance map's saturation per colour (ten)
// and material bands narrower than the sample value's error (one): each is
// now warned, and within the bound.
TEST(SceneFuzz, SavedFindingsArePredictedNow) {
  const std::filesystem::path dir = std::filesystem::path(VOXCAST_SOURCE_DIR) / "tests/scene_fuzz";
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".toml") continue;
    ++n;
    const ref::Scene scene = ref::load_scene_file(e.path().string());
    const cosim::SceneVerdict v = cosim::judge_scene(scene, 2);
    EXPECT_TRUE(v.feasible) << e.path() << ": " << v.refusal;
    EXPECT_GT(v.hazards, 0u) << e.path();
    EXPECT_FALSE(v.finding()) << e.path() << ": error " << v.error_lsb << " > " << v.bound_lsb;
  }
  EXPECT_EQ(n, 11);
}

// A finding is possible: the same saturated scenes judged against the
// ordinary bound alone (no hazard priced) exceed it.
TEST(SceneFuzz, JudgeFlagsErrorsBeyondTheOrdinaryBound) {
  const std::filesystem::path f = std::filesystem::path(VOXCAST_SOURCE_DIR) /
                                  "tests/scene_fuzz/rm_saturation_seed2_212.toml";
  const cosim::SceneVerdict v = cosim::judge_scene(ref::load_scene_file(f.string()), 2);
  EXPECT_GT(v.error_lsb, 255.0 * cosim::kHazardFraction);
  cosim::SceneVerdict unpriced = v;
  unpriced.bound_lsb = 255.0 * cosim::kHazardFraction;
  EXPECT_TRUE(unpriced.finding());
}

}  // namespace VOXCAST_UNITY_ID
}  // namespace voxcast::test
