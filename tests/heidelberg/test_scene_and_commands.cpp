// The [heidelberg] scene keys and the commands on a Heidelberg scene: errors
// name the key, the scene writes back equal, render writes a stereo pair and
// refuses the rtl engine (not modelled for VIRIM).
#include <gtest/gtest.h>

#include <filesystem>

#include "cosim/commands.hpp"
#include "refmodel/error.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace voxcast::test {
namespace {

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
  EXPECT_NE(error_of(kBase, {"render.algorithm=levoy"}).find("is not one of \"raycast\", \"heidelberg\""),
            std::string::npos);
}

TEST(HeidelbergCommands, RenderWritesAStereoPairAndRefusesTheRtlEngine) {
  const ref::Scene s = ref::parse_scene(kBase + "[heidelberg]\nstereo_deg = 4\n", "t.toml", ".");
  const std::string dir = (std::filesystem::temp_directory_path() / "voxcast_heidelberg_cmd").string();
  cosim::RenderOptions o;
  o.outputs = {dir + "/img.png"};
  for (auto e : {cosim::Engine::Ref, cosim::Engine::BitTrue, cosim::Engine::Hls}) {
    o.engine = e;
    const cosim::RenderSummary r = cosim::run_render(s, o);
    ASSERT_EQ(r.written.size(), 2u);
    EXPECT_TRUE(std::filesystem::exists(dir + "/img_left.png"));
    EXPECT_TRUE(std::filesystem::exists(dir + "/img_right.png"));
  }
  o.engine = cosim::Engine::Rtl;
  EXPECT_THROW(cosim::run_render(s, o), Error);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace voxcast::test
