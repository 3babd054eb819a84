// The scene's [rtl] table (docs/scenes.md) and the cycle model's
// configuration built from it (rtl_model/scene_config.hpp).
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "refmodel/error.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/layout/address_mapping.hpp"
#include "rtl_model/scene_config.hpp"
#include "rtl_model/sched/registry.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast;

std::string error_of(const ref::Overrides& o) {
  try {
    ref::default_scene(o);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

std::string printed(const rtl::RtlConfig& c) {
  std::ostringstream os;
  os << c;
  return os.str();
}

// The scene parser's names are the model's registries, one to one.
TEST(RtlScene, KnownNamesAreTheRegistries) {
  EXPECT_EQ(ref::rtl_choices("scheduler"), rtl::sched::scheduler_names());
  EXPECT_EQ(ref::rtl_choices("refresh"), rtl::sched::refresh_policy_names());
  EXPECT_EQ(ref::rtl_choices("layout"), rtl::layout::mapping_names());
  EXPECT_EQ(ref::rtl_choices("issue"), rtl::pipeline::issue_policy_names());
  for (const std::string& t : ref::rtl_choices("traversal"))
    EXPECT_EQ(rtl::pipeline::to_string(rtl::pipeline::parse_traversal(t)), t);
  ref::RtlDesc d;
  for (const std::string& s : ref::rtl_choices("sdram")) {
    d.sdram = s;
    EXPECT_NO_THROW(rtl::rtl_config(d)) << s;
  }
}

TEST(RtlScene, DefaultsAreTheVizard2Baseline) {
  EXPECT_EQ(printed(rtl::rtl_config(ref::default_scene().rtl)), printed(rtl::vizard2_baseline()));
}

TEST(RtlScene, EveryKeyReachesTheConfiguration) {
  const ref::Scene s = ref::default_scene(
      {"rtl.scheduler=fr-fcfs", "rtl.reorder_window=4", "rtl.starvation_limit=9",
       "rtl.refresh_postpone=2", "rtl.sdram=pc100-cl3", "rtl.layout=bricked",
       "rtl.brick=[4, 2, 8]", "rtl.traversal=tiles", "rtl.tile=16", "rtl.ray_slots=32",
"rtl.issue_burst=3", "rtl.issue_bypass_limit=5", "rtl.sample_buffer=128", "rtl.queue_depth=12",
       "rtl.return_depth=6", "rtl.refresh=eager", "rtl.auto_precharge=true"});
  const rtl::RtlConfig c = rtl::rtl_config(s.rtl);
  EXPECT_EQ(c.scheduler, "fr-fcfs");
  EXPECT_EQ(c.pipeline.scheduler_params.reorder_window, 4);
  EXPECT_EQ(c.pipeline.scheduler_params.starvation_limit, 9);
  EXPECT_EQ(c.pipeline.dimm.refresh_postpone_limit, 2);
  EXPECT_EQ(c.pipeline.dimm.timing.name, rtl::sdram::presets::pc100_cl3().name);
  EXPECT_EQ(c.mapping.name, "bricked");
  EXPECT_EQ(c.mapping.brick, (std::array<std::uint32_t, 3>{4, 2, 8}));
  EXPECT_EQ(c.pipeline.traversal, rtl::pipeline::Traversal::kTiles);
  EXPECT_EQ(c.pipeline.tile, 16);
  EXPECT_EQ(c.pipeline.ray_slots, 32);
  EXPECT_EQ(c.pipeline.issue_burst, 3);
  EXPECT_EQ(c.pipeline.issue, rtl::pipeline::IssuePolicy::kOldest);
  EXPECT_EQ(c.pipeline.issue_bypass_limit, 5);
  EXPECT_EQ(c.pipeline.sample_buffer, 128);
  EXPECT_EQ(c.pipeline.controller.queue_depth, 12u);
  EXPECT_EQ(c.pipeline.controller.return_depth, 6u);
  EXPECT_TRUE(c.pipeline.controller.auto_precharge);
  EXPECT_EQ(c.refresh, "eager");
  // And back through the TOML writer.
  const ref::Scene t = ref::parse_scene(ref::scene_to_toml(s), "round trip", ".");
  EXPECT_EQ(printed(rtl::rtl_config(t.rtl)), printed(c));
}

TEST(RtlScene, BadValuesAreOneLineErrorsNamingKeyAndKnownValues) {
  const std::string e = error_of({"rtl.scheduler=fifo"});
  EXPECT_NE(e.find("rtl.scheduler"), std::string::npos) << e;
  EXPECT_NE(e.find("\"in-order\", \"fr-fcfs\", \"lookahead\""), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  EXPECT_NE(error_of({"rtl.layout=hilbert"})
                .find("\"linear\", \"bricked\", \"bricked-swizzled\", \"morton\""),
            std::string::npos);
  EXPECT_NE(error_of({"rtl.traversal=spiral"}).find("rtl.traversal"), std::string::npos);
  EXPECT_NE(error_of({"rtl.sdram=ddr4"}).find("\"pc100-cl2\", \"pc100-cl3\""), std::string::npos);
  EXPECT_NE(error_of({"rtl.refresh=lazy"}).find("rtl.refresh"), std::string::npos);
  EXPECT_NE(error_of({"rtl.issue=youngest"}).find("\"oldest\", \"row-hit\""), std::string::npos);
  EXPECT_NE(error_of({"rtl.issue=row-hit", "rtl.issue_burst=2"})
                .find("rtl.issue_burst = 2 applies to rtl.issue = \"oldest\" only"),
            std::string::npos);
  EXPECT_EQ(rtl::rtl_config(ref::default_scene({"rtl.issue=row-hit"}).rtl).pipeline.issue,
            rtl::pipeline::IssuePolicy::kRowHit);
  EXPECT_NE(error_of({"rtl.brick=[3, 8, 8]"}).find("powers of two"), std::string::npos);
  EXPECT_NE(error_of({"rtl.ray_slots=0"}).find("rtl.ray_slots = 0 is outside"), std::string::npos);
  EXPECT_NE(error_of({"rtl.reorder_window=16"}).find("exceeds rtl.queue_depth"), std::string::npos);
  EXPECT_NE(error_of({"rtl.schedular=fr-fcfs"}).find("did you mean rtl.scheduler"),
            std::string::npos);
  // Descriptions built in code are checked by the model too.
  ref::RtlDesc d;
  d.scheduler = "fifo";
  try {
    rtl::rtl_config(d);
    ADD_FAILURE() << "no error";
  } catch (const Error& x) {
    EXPECT_NE(std::string(x.what()).find("rtl.scheduler = \"fifo\" is not known (known: in-order"),
              std::string::npos)
        << x.what();
  }
}

}  // namespace
