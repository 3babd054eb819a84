// The truth's settings and its cache key: what the truth depends on and what
// it does not.
#include <gtest/gtest.h>

#include "cosim/engines/truth.hpp"
#include "refmodel/error.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace VOXCAST_UNITY_ID {

using voxcast::cosim::truth_key;
using voxcast::cosim::TruthSettings;

voxcast::ref::Scene scene(const voxcast::ref::Overrides& sets = {}) {
  return voxcast::ref::load_scene_file(
      std::string(VOXCAST_SOURCE_DIR) + "/tests/sweep/tube_tiny.toml", sets);
}

TEST(Truth, KeyIgnoresWhatTheTruthDoesNotDependOn) {
  const std::string base = truth_key(scene(), {});
  for (const char* set : {"precision.profile=vizard2", "precision.weight_bits=3",
                          "render.oversampling=8", "render.ert_threshold=0.5", "render.threads=1"})
    EXPECT_EQ(truth_key(scene({set}), {}), base) << set;
}

TEST(Truth, KeyFollowsEverythingElse) {
  const std::string base = truth_key(scene(), {});
  for (const char* set :
       {"classification.interpolation=binary", "render.width=25", "camera.fov_deg=60",
        "lights[0].intensity=0.5", "volume.source=phantom:tube?size=33", "render.mode=unshaded"})
    EXPECT_NE(truth_key(scene({set}), {}), base) << set;
  EXPECT_NE(truth_key(scene(), TruthSettings{8.0}), base);
}

TEST(Truth, SceneChangesOnlyOversamplingAndErt) {
  const voxcast::ref::Scene s = scene();
  const voxcast::ref::Scene t = voxcast::cosim::truth_scene(s, TruthSettings{12.0});
  EXPECT_EQ(t.render.oversampling, 12.0);
  EXPECT_EQ(t.render.ert_threshold, 1.0 - 0x1p-20);
  EXPECT_EQ(voxcast::ref::scene_to_toml(voxcast::cosim::truth_scene(t, TruthSettings{2.0})),
            voxcast::ref::scene_to_toml(voxcast::cosim::truth_scene(s, TruthSettings{2.0})));
}

TEST(Truth, SettingsOutsideTheirRangeAreErrors) {
  EXPECT_THROW(voxcast::cosim::check_truth_settings(TruthSettings{0.5}, scene()), voxcast::Error);
  EXPECT_THROW(voxcast::cosim::check_truth_settings(TruthSettings{65.0}, scene()), voxcast::Error);
  EXPECT_THROW(voxcast::cosim::check_truth_settings(TruthSettings{1.0}, scene()),
               voxcast::Error);  // below the scene's 2x
  EXPECT_NO_THROW(voxcast::cosim::check_truth_settings(TruthSettings{2.0}, scene()));
}

}  // namespace
