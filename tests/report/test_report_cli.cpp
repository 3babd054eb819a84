// `voxcast report` and `voxcast tune` as users run them: the files written,
// the JSON's totals, exit codes and one-line errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/common/voxcast_cli.hpp"

namespace VOXCAST_UNITY_ID {

using voxcast::test::Command;

Command run(const std::string& args) { return voxcast::test::run_voxcast(args); }

std::string scene(const char* name) { return std::string(VOXCAST_SOURCE_DIR) + "/scenes/" + name; }

TEST(ReportCli, WritesMarkdownAndJsonWhoseTotalsAreTheUnitsSums) {
  const auto dir = std::filesystem::temp_directory_path() / "voxcast_report_cli";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const Command r = run("report " + scene("mip.toml") + " --part xc2v3000 --set render.width=32 " +
                        "--json " + (dir / "r.json").string() + " --md " + (dir / "r.md").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::ifstream js(dir / "r.json");
  const nlohmann::json j = nlohmann::json::parse(js);
  EXPECT_EQ(j["part"]["name"], "xc2v3000");
  EXPECT_EQ(j["part"]["dsp"], 96);
  for (const char* k : {"lut", "ff", "dsp", "bram"}) {
    double sum = 0;
    for (const auto& u : j["units"]) sum += u["resources"][k].get<double>();
    EXPECT_NEAR(sum, j["total"][k].get<double>(), 1e-6) << k;
  }
  bool mip_omits_shader = false;
  for (const auto& o : j["omitted"]) mip_omits_shader |= o["unit"] == "shader";
  EXPECT_TRUE(mip_omits_shader);
  std::ifstream md(dir / "r.md");
  std::stringstream text;
  text << md.rdbuf();
  EXPECT_NE(text.str().find("## Left out (elaboration)"), std::string::npos);
  EXPECT_NE(text.str().find("MULT18X18"), std::string::npos);
}

TEST(ReportCli, BadInputIsOneLineError) {
  Command r = run("report " + scene("mip.toml") + " --part xc9999");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, "voxcast: unknown part \"xc9999\" (known: xcv1000e, xc2v3000, xc7a200t, "
                      "xc7k325t, xcu250)\n");
  r = run("tune " + scene("mip.toml") + " --target-psnr 40 --vary weight_bits=9..2");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output.find("voxcast: tune: --vary \"weight_bits=9..2\""), 0u) << r.output;
  r = run("tune " + scene("mip.toml") + " --target-psnr 40 --truth-oversampling 100");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(r.output, "voxcast: truth oversampling 100 is outside [1, 64]\n");
  r = run("report /nonexistent.toml");
  EXPECT_EQ(r.status, 1);
}

}  // namespace
