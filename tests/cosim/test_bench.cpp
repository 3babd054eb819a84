// voxcast bench (issue 21): the cycle model's own measure, simulated samples
// and card cycles per CPU second, counts the frame it simulated, and
// bench --json gives scripts the same numbers as the table.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "tests/common/voxcast_cli.hpp"

namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;

nlohmann::json read_json(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

const std::string kSmall = std::string(VOXCAST_SOURCE_DIR) +
                           "/scenes/default.toml --set render.width=24 --set render.height=24";

TEST(Bench, TheCycleModelsRatesAreOfTheFrameItSimulated) {
  const fs::path d = fs::temp_directory_path() / "voxcast_bench";
  fs::remove_all(d);
  const auto bench = voxcast::test::run_voxcast("bench " + kSmall +
                                                " --engines ref,rtl --repeat 1 --json " +
                                                (d / "b.json").string());
  ASSERT_EQ(bench.status, 0) << bench.output;
  EXPECT_NE(bench.output.find("rtl simulates "), std::string::npos) << bench.output;
  EXPECT_NE(bench.output.find(" M card cycles per CPU second"), std::string::npos) << bench.output;

  // The same frame rendered by `render --engine rtl`: the same cycles.
  const auto render = voxcast::test::run_voxcast("render " + kSmall + " --engine rtl -o " +
                                                 (d / "r.png").string() + " --report " +
                                                 (d / "r.json").string());
  ASSERT_EQ(render.status, 0) << render.output;
  const double cycles = read_json(d / "r.json")["rtl"]["cycles"].get<double>();

  const nlohmann::json b = read_json(d / "b.json");
  ASSERT_EQ(b["engines"].size(), 2u);
  const nlohmann::json& ref = b["engines"][0];
  const nlohmann::json& rtl = b["engines"][1];
  EXPECT_EQ(ref["engine"], "ref");
  EXPECT_EQ(ref["cycles"], 0) << "the float engine simulates no card";
  EXPECT_EQ(rtl["engine"], "rtl");
  EXPECT_EQ(rtl["cycles"].get<double>(), cycles);
  EXPECT_EQ(b["width"], 24);
  // The rates are the counts over the measured CPU time.
  const double cpu = rtl["median_cpu_seconds"].get<double>();
  ASSERT_GT(cpu, 0.0);
  EXPECT_DOUBLE_EQ(rtl["cycles_per_cpu_second"].get<double>(), cycles / cpu);
  EXPECT_DOUBLE_EQ(rtl["samples_per_cpu_second"].get<double>(),
                   rtl["samples"].get<double>() / cpu);
}

TEST(Bench, ARepeatBelowOneIsACommandLineError) {
  const auto r = voxcast::test::run_voxcast("bench " + kSmall + " --repeat 0");
  EXPECT_EQ(r.status, 64) << r.output;
  EXPECT_NE(r.output.find("--repeat"), std::string::npos) << r.output;
}

}  // namespace VOXCAST_UNITY_ID
