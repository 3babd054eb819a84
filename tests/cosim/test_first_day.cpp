// What a new user met on the first day (issue 20), each reproduced and fixed:
// the exit status and the one line asserted, and every argument checked before
// any work (the cases here fail in well under a second: no volume loads).
// Exit statuses: README, "Exit status" (cosim/main.cpp, kUsageError = 64).
#include <gtest/gtest.h>


#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cosim/reports/image_io.hpp"
#include "tests/common/voxcast_cli.hpp"

namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;
using voxcast::test::Command;

Command run(const std::string& args) { return voxcast::test::run_voxcast(args); }

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("voxcast_first_day_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string scene(const char* name) { return std::string(VOXCAST_SOURCE_DIR) + "/scenes/" + name; }

const std::string kSmall = " --set render.width=16 --set render.height=16";

// One line on stderr (the command prints nothing else here), starting "voxcast: ".
void expect_one_line(const Command& r, const std::string& starts, const std::string& what) {
  EXPECT_EQ(r.output.rfind("voxcast: " + starts, 0), 0u) << what << ":\n" << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << what << ":\n" << r.output;
}

TEST(FirstDay, AnOutputFolderThatCannotBeCreatedIsOneLine) {
  const fs::path d = fresh_dir("folder");
  const std::string f = (d / "f").string();
  std::ofstream(f) << "a file in the way\n";
  const std::string in_f = (fs::path(f) / "sub").string();
  const std::string folder = "cannot create the output folder ";
  struct Case {
    std::string args, folder_named;
  };
  for (const Case& c : {
           Case{"render " + scene("mip.toml") + " -o " + in_f + "/x.png" + kSmall, in_f},
           Case{"render " + scene("mip.toml") + " -o " + (d / "ok.png").string() + " --report " +
                    in_f + "/r.json" + kSmall,
                in_f},
           Case{"cosim " + scene("endoscopy.toml") + " --out " + f + kSmall, f},
           Case{"sweep " + scene("mip.toml") + " --vary render.oversampling=1,2 --out " + f, f},
           Case{"flythrough " + scene("endoscopy.toml") + " --out " + f + " --frames 2" + kSmall,
                f},
           Case{"paper vizard2 --out " + f, f},
       }) {
    const Command r = run(c.args);
    EXPECT_EQ(r.status, 1) << c.args << "\n" << r.output;
    expect_one_line(r, folder + c.folder_named + ": ", c.args);
    EXPECT_EQ(r.output.find("internal error"), std::string::npos) << r.output;
  }
}

TEST(FirstDay, ANonUtf8OutputNameKeepsTheJsonReportValid) {
  const fs::path d = fresh_dir("utf8");
  const std::string name = (d / "o\xff.png").string();
  const std::string report = (d / "r.json").string();
  const Command r = run("render " + scene("mip.toml") + " -o '" + name + "' --report " + report +
                        kSmall);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_TRUE(fs::exists(name));
  std::ifstream in(report);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_FALSE(text.empty()) << "no 0-byte report";
  const nlohmann::json j = nlohmann::json::parse(text);
  // The byte that is not UTF-8 is written as U+FFFD.
  EXPECT_NE(j.at("written").dump().find("o\xef\xbf\xbd.png"), std::string::npos) << j.dump();
}

TEST(FirstDay, AnUnknownSubcommandIsNamedWithTheNearest) {
  const Command r = run("renderr " + scene("mip.toml"));
  EXPECT_EQ(r.status, 64);
  EXPECT_EQ(r.output,
            "voxcast: unknown subcommand 'renderr'; did you mean 'render'? (voxcast --help lists "
            "the subcommands)\n");
  const Command far = run("zzzzzzzz");
  EXPECT_EQ(far.status, 64);
  EXPECT_EQ(far.output, "voxcast: unknown subcommand 'zzzzzzzz' (voxcast --help lists the "
                        "subcommands)\n");
}

TEST(FirstDay, CommandLineErrorsAreOneLineWithTheirExitStatus) {
  for (const std::string& args : {std::string("render"), std::string(""),
                                  "render " + scene("mip.toml") + " -o x.png --bogus"}) {
    const Command r = run(args);
    EXPECT_EQ(r.status, 64) << args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("voxcast: ", 0), 0u) << args << "\n" << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("--help)"), std::string::npos) << r.output;
  }
  EXPECT_EQ(run("--help").status, 0);
  EXPECT_EQ(run("render --help").status, 0);
}

TEST(FirstDay, TuneRefusesATargetThatIsNoNumberOfDecibels) {
  for (const char* target : {"nan", "inf", "-5", "0", "12dB"}) {
    const Command r = run("tune " + scene("mip.toml") + " --target-psnr " + target);
    EXPECT_EQ(r.status, 64) << target << "\n" << r.output;
    expect_one_line(r, "", target);
    EXPECT_NE(r.output.find("--target-psnr"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("must be a finite number above 0"), std::string::npos) << r.output;
  }
}

TEST(FirstDay, FlythroughChecksTheGifRateBeforeRendering) {
  const fs::path d = fresh_dir("gif");
  const Command r = run("flythrough " + scene("endoscopy.toml") + " --out " + (d / "o").string() +
                        " --gif-fps 0");
  EXPECT_EQ(r.status, 64) << r.output;
  expect_one_line(r, "--gif-fps", "--gif-fps 0");
  EXPECT_FALSE(fs::exists(d / "o")) << "nothing rendered, nothing written";
}

TEST(FirstDay, RenderFramesWithoutACameraPathIsRefusedAsFlythroughDoes) {
  const fs::path d = fresh_dir("frames");
  const Command r = run("render " + scene("mip.toml") + " -o " + (d / "f.png").string() +
                        " --set render.frames=3" + kSmall);
  EXPECT_EQ(r.status, 1) << r.output;
  expect_one_line(r, scene("mip.toml") + ": render.frames = 3 renders a camera path", "frames");
  EXPECT_NE(r.output.find("camera.path has 0 keyframe(s)"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_empty(d)) << "no frame written";
}

TEST(FirstDay, SweepNamesTheVaryOptionForAnUnknownKey) {
  const fs::path d = fresh_dir("vary");
  const Command r =
      run("sweep " + scene("mip.toml") + " --vary bogus.key=1,2 --out " + (d / "o").string());
  EXPECT_EQ(r.status, 1) << r.output;
  expect_one_line(r, "--vary bogus.key=1: unknown key bogus", "--vary");
}

TEST(FirstDay, ExrOutputsAreTheSameBytesForTheSameInputs) {
  const fs::path d = fresh_dir("exr");
  const std::string a = (d / "a.exr").string(), b = (d / "b.exr").string();
  ASSERT_EQ(run("render " + scene("mip.toml") + " -o " + a + kSmall).status, 0);
  ASSERT_EQ(run("render " + scene("mip.toml") + " -o " + b + kSmall).status, 0);
  // No time stamp (OpenImageIO's DateTime, OpenEXR's capDate) that would make
  // two runs a second apart differ.
  const auto attributes = voxcast::cosim::read_image_info(a).attributes;
  EXPECT_EQ(std::count(attributes.begin(), attributes.end(), "DateTime"), 0);
  EXPECT_EQ(std::count(attributes.begin(), attributes.end(), "compression"), 1)
      << "the attributes were read";
  std::ifstream fa(a, std::ios::binary), fb(b, std::ios::binary);
  const std::string ba((std::istreambuf_iterator<char>(fa)), std::istreambuf_iterator<char>());
  const std::string bb((std::istreambuf_iterator<char>(fb)), std::istreambuf_iterator<char>());
  EXPECT_EQ(ba, bb);
}

}  // namespace VOXCAST_UNITY_ID
