// The [heidelberg] scene keys and the commands on a Heidelberg scene: errors
// name the key, the scene writes back equal, render writes a stereo pair with
// every engine (rtl: VIRIM's cycle model, held to the hls pixels).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cosim/explore/bench.hpp"
#include "cosim/engines/render.hpp"
#include "cosim/engines/cosim.hpp"
#include "refmodel/error.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

const std::string kBase = R"(
[volume]
source = "phantom:shells?size=32"
[classification]
points = [ { value = 0, alpha = 0.0 }, { value = 255, alpha = 0.5 } ]
[render]
algorithm = "heidelberg"
width = 32
height = 24
)";

std::string error_of(const std::string& text, const ref::Overrides& sets = {}) {
  try {
    ref::parse_scene(text, "t.toml", ".", sets);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(HeidelbergScene, ParsesWithoutACameraAndWritesBackEqual) {
  const ref::Scene a = ref::parse_scene(kBase + "[heidelberg]\nangle_deg = 30\naxis = [1, 2, 3]\n"
                                                "interpolation = \"trilinear\"\nstereo_deg = 4\n",
                                        "t.toml", ".");
  EXPECT_EQ(a.algorithm, ref::Algorithm::Heidelberg);
  EXPECT_EQ(a.heidelberg.interpolation, ref::HeidelbergInterpolation::Trilinear);
  const ref::Scene b = ref::parse_scene(ref::scene_to_toml(a), "written", ".");
  EXPECT_EQ(ref::scene_to_toml(b), ref::scene_to_toml(a));
  EXPECT_EQ(b.heidelberg.angle_deg, 30.0);
  EXPECT_EQ(b.heidelberg.axis, glm::dvec3(1, 2, 3));
  EXPECT_EQ(b.heidelberg.stereo_deg, 4.0);
  const ref::Scene c = ref::parse_scene(kBase + "[heidelberg]\nmodules = 2\nrotator_mhz = 50\n"
                                                "dsp_mhz = 33\nbus_mhz = 25\n",
                                        "t.toml", ".");
  const ref::Scene d = ref::parse_scene(ref::scene_to_toml(c), "written", ".");
  EXPECT_EQ(d.heidelberg.modules, 2);
  EXPECT_EQ(d.heidelberg.rotator_mhz, 50.0);
  EXPECT_EQ(d.heidelberg.dsp_mhz, 33.0);
  EXPECT_EQ(d.heidelberg.bus_mhz, 25.0);
}

TEST(HeidelbergScene, BadKeysAreNamed) {
  EXPECT_NE(error_of(kBase + "[heidelberg]\nzoom = 0\n").find("t.toml:11: heidelberg.zoom = 0 is outside"),
            std::string::npos)
      << error_of(kBase + "[heidelberg]\nzoom = 0\n");
  EXPECT_NE(error_of(kBase + "[heidelberg]\nangel_deg = 3\n").find("did you mean heidelberg.angle_deg"),
            std::string::npos);
  EXPECT_NE(error_of(kBase + "[heidelberg]\naxis = [0, 0, 0]\n").find("heidelberg.axis is the zero vector"),
            std::string::npos);
  EXPECT_NE(error_of(kBase + "[heidelberg]\ndepth = 64\nperspective = 30\n").find("heidelberg.perspective"),
            std::string::npos);
  EXPECT_NE(error_of(kBase, {"render.algorithm=raycast"}).find("camera table is required"), std::string::npos);
  EXPECT_NE(error_of(kBase + "[heidelberg]\nzoom = 2\n", {"render.algorithm=raycast"})
                .find("heidelberg applies only with render.algorithm = \"heidelberg\""),
            std::string::npos);
  EXPECT_NE(error_of(kBase + "[heidelberg]\nmodules = 0\n").find("heidelberg.modules = 0 is outside [1, 64]"),
            std::string::npos);
  EXPECT_NE(error_of(kBase + "[heidelberg]\ndsp_mhz = 0.5\n").find("heidelberg.dsp_mhz"),
            std::string::npos);
  EXPECT_NE(error_of(kBase + "[heidelberg]\nrotator_hz = 4\n").find("heidelberg.rotator_hz"),
            std::string::npos);
  EXPECT_NE(error_of(kBase, {"render.algorithm=levoy"}).find("is not one of \"raycast\", \"heidelberg\""),
            std::string::npos);
}

TEST(HeidelbergCommands, RenderWritesAStereoPairWithEveryEngine) {
  const ref::Scene s = ref::parse_scene(kBase + "[heidelberg]\nstereo_deg = 4\n", "t.toml", ".");
  const std::string dir = (std::filesystem::temp_directory_path() / "voxcast_heidelberg_cmd").string();
  cosim::RenderOptions o;
  o.outputs = {dir + "/img.png"};
  for (auto e : {cosim::Engine::Ref, cosim::Engine::BitTrue, cosim::Engine::Hls, cosim::Engine::Rtl}) {
    o.engine = e;
    const cosim::RenderSummary r = cosim::run_render(s, o);
    ASSERT_EQ(r.written.size(), 2u);
    EXPECT_TRUE(std::filesystem::exists(dir + "/img_left.png"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/img_right.png"));
  }
  o.vcd_path = dir + "/t.vcd";  // a trace the VIRIM model does not write is an error, not ignored
  EXPECT_THROW(cosim::run_render(s, o), Error);
  std::filesystem::remove_all(dir);
}

// cosim holds the cycle model to the hls pixels and reports its figures;
// bench counts VIRIM's work in voxels (W x D x H) for every engine.
TEST(HeidelbergCommands, CosimAndBenchRunTheCycleModel) {
  const ref::Scene s = ref::parse_scene(kBase + "[heidelberg]\nangle_deg = 20\nmodules = 2\n",
                                        "t.toml", ".");
  const std::string dir = (std::filesystem::temp_directory_path() / "voxcast_heidelberg_cosim").string();
  const cosim::CosimResult r = cosim::run_cosim(s, dir);
  EXPECT_TRUE(r.bit_exact);
  EXPECT_TRUE(r.rtl_exact);
  EXPECT_GT(r.rtl_cycles, 0u);
  std::ifstream in(dir + "/report.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j["rtl_bit_exact"], true);
  EXPECT_EQ(j["cycles"], r.rtl_cycles);
  for (const char* key : {"fps", "ns_per_voxel", "stalls"}) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["rtl"]["voxels"], 32 * 32 * 24);
  EXPECT_EQ(j["rtl"]["config"]["modules"], 2);
  std::filesystem::remove_all(dir);
  for (const cosim::BenchResult& b : cosim::run_bench(s, {"hls", "rtl"}, 1))
    EXPECT_EQ(b.samples, 32u * 32u * 24u) << b.engine;
}

}  // namespace
}  // namespace voxcast::test
