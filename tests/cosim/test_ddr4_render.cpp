// `voxcast render --engine rtl --set rtl.board=alveo_u250` (issue 23): the
// DDR4 card renders the hls engine's image and reports its pipelines, rate,
// channels, cache and bound (docs/sdram.md §10).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/common/voxcast_cli.hpp"

namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

const std::string kScene = std::string(VOXCAST_SOURCE_DIR) +
                           "/scenes/default.toml --set render.width=24 --set render.height=24 "
                           "--set precision.profile=vizard2";

TEST(Ddr4Render, TheU250BoardRendersTheHlsImage) {
  const fs::path d = fs::temp_directory_path() / "voxcast_ddr4_render";
  fs::remove_all(d);
  const auto rtl = voxcast::test::run_voxcast(
      "render " + kScene + " --engine rtl --set rtl.board=alveo_u250 --set rtl.pipelines=2 -o " +
      (d / "rtl.png").string() + " --report " + (d / "rtl.json").string());
  ASSERT_EQ(rtl.status, 0) << rtl.output;
  EXPECT_NE(rtl.output.find("DDR4 card, 2 pipeline(s)"), std::string::npos) << rtl.output;
  const auto hls = voxcast::test::run_voxcast("render " + kScene + " --engine hls -o " +
                                              (d / "hls.png").string());
  ASSERT_EQ(hls.status, 0) << hls.output;
  EXPECT_EQ(bytes(d / "rtl.png"), bytes(d / "hls.png"));

  const nlohmann::json j = read_json(d / "rtl.json");
  const nlohmann::json& card = j["rtl"]["ddr4_card"];
  EXPECT_EQ(card["pipelines"], 2);
  EXPECT_EQ(j["rtl"]["config"]["pipelines"], 2);
  EXPECT_NEAR(card["clock_mhz"].get<double>(), 300.03, 0.01);
  // Samples per second = samples / (cycles / clock).
  const double samples = j["stats"]["samples"].get<double>();
  const double cycles = j["rtl"]["cycles"].get<double>();
  EXPECT_NEAR(card["samples_per_second"].get<double>(),
              samples / (cycles / (card["clock_mhz"].get<double>() * 1e6)),
              1e-6 * card["samples_per_second"].get<double>());
  EXPECT_GE(card["samples_issued"].get<double>(), samples);
  EXPECT_GT(card["cache_hit_rate"].get<double>(), 0.0);
  EXPECT_LE(card["bandwidth_share"].get<double>(), 1.0);
  EXPECT_LE(card["pipeline_busy"].get<double>(), 1.0);
}

TEST(Ddr4Render, ABadPipelineCountIsOneError) {
  const auto r = voxcast::test::run_voxcast("render " + kScene +
                                            " --engine rtl --set rtl.board=alveo_u250 "
                                            "--set rtl.pipelines=0 -o /tmp/voxcast_never.png");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.output.find("rtl.pipelines"), std::string::npos) << r.output;
}

}  // namespace VOXCAST_UNITY_ID
