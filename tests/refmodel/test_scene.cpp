// Scene files: every error names the origin, the line and the key.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "refmodel/error.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

const char* const kMinimal = R"(
[volume]
source = "phantom:box?size=16"

[classification]
points = [ { value = 0, color = [1, 1, 1], alpha = 0.5 } ]

[camera]
eye = [7.5, -20, 7.5]
center = [7.5, 7.5, 7.5]
)";

// The message of the Error parse_scene throws, or "" if it does not throw.
std::string error_of(const std::string& text, const ref::Overrides& sets = {}) {
  try {
    ref::parse_scene(text, "test.toml", ".", sets);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Scene, MinimalSceneTakesTheDocumentedDefaults) {
  const ref::Scene s = ref::parse_scene(kMinimal, "test.toml", ".");
  EXPECT_EQ(s.render.width, 256);
  EXPECT_EQ(s.render.height, 256);
  EXPECT_EQ(s.render.oversampling, 1.0);
  EXPECT_EQ(s.render.ert_threshold, 0.98);
  EXPECT_EQ(s.render.mode, ref::RenderMode::Shaded);
  EXPECT_EQ(s.camera.projection, ref::Projection::Perspective);
  EXPECT_EQ(s.camera.fov_deg, 40.0);
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].type, ref::LightType::Headlight);
}

TEST(Scene, VolumeResampleIsABooleanDefaultingToTrue) {
  EXPECT_TRUE(ref::parse_scene(kMinimal, "test.toml", ".").volume.resample);
  const ref::Scene off = ref::parse_scene(kMinimal, "test.toml", ".", {"volume.resample=false"});
  EXPECT_FALSE(off.volume.resample);
  EXPECT_FALSE(ref::parse_scene(ref::scene_to_toml(off), "written", ".").volume.resample);
  EXPECT_EQ(error_of(kMinimal, {"volume.resample=1"}),
            "--set volume.resample=1: volume.resample must be true or false, not integer");
}

TEST(Scene, UnknownKeyNamesFileLineAndSuggestion) {
  const std::string e = error_of(std::string(kMinimal) + "\n[render]\noversmapling = 2\n");
  EXPECT_EQ(e, "test.toml:13: unknown key render.oversmapling (did you mean render.oversampling?)");
}

TEST(Scene, WrongTypeIsNamed) {
  const std::string e = error_of(std::string(kMinimal) + "\n[render]\nwidth = \"wide\"\n");
  EXPECT_EQ(e, "test.toml:13: render.width must be an integer, not string");
}

TEST(Scene, NanAndInfAreRejected) {
  EXPECT_EQ(error_of(std::string(kMinimal) + "\n[render]\noversampling = nan\n"),
            "test.toml:13: render.oversampling = nan is not a finite number");
  EXPECT_EQ(error_of(std::string(kMinimal) + "\n[render]\nert_threshold = inf\n"),
            "test.toml:13: render.ert_threshold = inf is not a finite number");
}

TEST(Scene, OutOfRangeIsNamedWithTheRange) {
  EXPECT_EQ(error_of(std::string(kMinimal) + "\n[render]\noversampling = 32\n"),
            "test.toml:13: render.oversampling = 32 is outside [0.25, 16]");
  EXPECT_EQ(error_of(std::string(kMinimal) + "\n[camera.x]\n"),
            "test.toml:12: unknown key camera.x (did you mean camera.up?)");
}

TEST(Scene, ImpossibleCamerasAreErrors) {
  EXPECT_NE(error_of(kMinimal, {"camera.center=[7.5,-20,7.5]"}).find("equals the eye"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"camera.up=[0,1,0]"}).find("parallel to the view direction"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"camera.fov_deg=180"}).find("camera.fov_deg = 180 is outside (0, 180)"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"camera.fov_deg=0"}).find("outside (0, 180)"), std::string::npos);
}

TEST(Scene, SetOverridesAnyKeyAndIsNamedInErrors) {
  const ref::Scene s = ref::parse_scene(
      kMinimal, "test.toml", ".",
      {"render.oversampling=4", "camera.fov_deg=70", "render.mode=mip", "volume.source=phantom:shells",
       "lights[0].intensity=0.5", "classification.points[0].alpha=0.25"});
  EXPECT_EQ(s.render.oversampling, 4.0);
  EXPECT_EQ(s.camera.fov_deg, 70.0);
  EXPECT_EQ(s.render.mode, ref::RenderMode::Mip);
  EXPECT_EQ(s.volume.source, "phantom:shells");
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].intensity, 0.5);
  EXPECT_EQ(s.tf_points[0].alpha, 0.25);
  EXPECT_EQ(error_of(kMinimal, {"render.width=0"}),
            "--set render.width=0: render.width = 0 is outside [1, 8192]");
  EXPECT_EQ(error_of(kMinimal, {"render.oversampling"}),
            "--set render.oversampling: expected key=value (e.g. render.oversampling=4)");
  EXPECT_EQ(error_of(kMinimal, {"render.bogus=1"}), "--set render.bogus=1: unknown key render.bogus");
}

TEST(Scene, TransferFunctionPointsMustBeSorted) {
  const std::string text = R"(
[volume]
source = "phantom:box"
[classification]
points = [ { value = 10, alpha = 0.1 }, { value = 5, alpha = 0.2 } ]
[camera]
eye = [0, -20, 0]
center = [0, 0, 0]
)";
  EXPECT_EQ(error_of(text),
            "test.toml:5: classification.points[1].value = 5 is below the previous point's 10: "
            "points must be sorted by value");
}

TEST(Scene, RawKeysNeedDims) {
  EXPECT_EQ(error_of(kMinimal, {"volume.spacing=[1,1,2]"}),
            "--set volume.spacing=[1,1,2]: volume.spacing applies to raw files only: give "
            "volume.dims and volume.type too");
  const ref::Scene s = ref::parse_scene(kMinimal, "test.toml", ".",
                                        {"volume.dims=[4,5,6]", "volume.type=i16",
                                         "volume.spacing=[0.5,0.5,2]"});
  ASSERT_TRUE(s.volume.raw.has_value());
  EXPECT_EQ(s.volume.raw->dims, (std::array<int, 3>{4, 5, 6}));
  EXPECT_EQ(s.volume.raw->type, ref::RawType::I16);
  EXPECT_EQ(s.volume.raw->spacing.z, 2.0);
}

TEST(Scene, SyntaxErrorsNameTheLine) {
  EXPECT_EQ(error_of("[volume]\nsource = \n").rfind("test.toml:2: ", 0), 0u);
}

TEST(Scene, ShippedScenesParse) {
  for (const char* name : {"default.toml", "mip.toml", "endoscopy.toml", "colin27.toml"}) {
    const std::string path = std::string(VOXCAST_SOURCE_DIR) + "/scenes/" + name;
    EXPECT_NO_THROW(ref::load_scene_file(path)) << path;
  }
  EXPECT_NO_THROW(ref::default_scene());
}

TEST(Scene, DocsDocumentEveryKey) {
  std::ifstream in(std::string(VOXCAST_SOURCE_DIR) + "/docs/scenes.md");
  ASSERT_TRUE(in) << "docs/scenes.md is missing";
  std::stringstream text;
  text << in.rdbuf();
  for (const std::string& key : ref::known_scene_keys()) {
    if (key == "volume" || key == "classification" || key == "camera" || key == "render" ||
        key == "lights" || key == "precision" || key == "rtl")
      continue;  // tables, documented as sections
    EXPECT_NE(text.str().find("`" + key + "`"), std::string::npos)
        << "docs/scenes.md does not document `" << key << "`";
  }
}

}  // namespace
}  // namespace voxcast::test

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

TEST(Scene, WritesTomlThatReadsBackEqual) {
  for (const char* name : {"default.toml", "mip.toml", "endoscopy.toml", "colin27.toml"}) {
    const ref::Scene a = ref::load_scene_file(std::string(VOXCAST_SOURCE_DIR) + "/scenes/" + name,
                                              {"precision.weight_bits=5", "camera.stereo_deg=4"});
    const ref::Scene b = ref::parse_scene(ref::scene_to_toml(a), "written", ".");
    EXPECT_EQ(ref::scene_to_toml(b), ref::scene_to_toml(a)) << name;
    EXPECT_EQ(b.precision, a.precision) << name;
    EXPECT_EQ(b.precision_name, a.precision_name) << name;
    EXPECT_EQ(b.render.oversampling, a.render.oversampling) << name;
    EXPECT_EQ(b.camera.pose.eye, a.camera.pose.eye) << name;
    ASSERT_EQ(b.tf_points.size(), a.tf_points.size()) << name;
    EXPECT_EQ(b.tf_points.back().alpha, a.tf_points.back().alpha) << name;
  }
}

}  // namespace
}  // namespace voxcast::test

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

// docs/scenes.md's [precision] table lists each width's value in the three
// presets (columns: default = balanced, vizard2, precise); they must be the
// values the presets really have.
TEST(Scene, DocsListThePresetValues) {
  std::ifstream in(std::string(VOXCAST_SOURCE_DIR) + "/docs/scenes.md");
  ASSERT_TRUE(in);
  std::map<std::string, std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("| `precision.", 0) != 0) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, '|');) {
      const auto b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
      cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
    }
    rows[cells.at(1)] = cells;  // cells[0] is before the first '|'
  }
  const PrecisionProfile balanced = preset_profile("balanced"),
                         vizard2 = preset_profile("vizard2"), precise = preset_profile("precise");
  for (const ProfileField& f : profile_fields()) {
    const std::string key = std::string("`precision.") + f.name + "`";
    ASSERT_TRUE(rows.count(key)) << key << " has no row in docs/scenes.md";
    const auto& c = rows[key];
    ASSERT_GE(c.size(), 7u) << key;
    // The number leads the cell; a note may follow ("6 (unused)").
    const auto number = [](const std::string& cell) { return cell.substr(0, cell.find(' ')); };
    EXPECT_EQ(number(c[4]), std::to_string(balanced.*f.member)) << key << " (balanced column)";
    EXPECT_EQ(number(c[5]), std::to_string(vizard2.*f.member)) << key << " (vizard2 column)";
    EXPECT_EQ(number(c[6]), std::to_string(precise.*f.member)) << key << " (precise column)";
  }
}

}  // namespace
}  // namespace voxcast::test
