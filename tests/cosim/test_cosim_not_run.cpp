// cosim on a volume larger than the card's memory (issue 22): the float,
// bit-true and hls engines still run and prove their agreement; the summary
// and report.json name the cycle model as not run and why, and the exit
// status (8) says "not every engine ran", distinct from "the engines differ"
// (3). --junit carries the same verdicts: hls == bit-true passed, rtl == hls
// skipped with the reason.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>
#include <pugixml.hpp>

#include "tests/common/voxcast_cli.hpp"

namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The shipped VIZARD II board with DIMMs of 4 banks x 2 rows x 512 columns:
// 4096 words each, where default.toml's 64^3 volume needs 65536 per DIMM.
fs::path tiny_board(const fs::path& dir) {
  std::string board = slurp(std::string(VOXCAST_SOURCE_DIR) + "/constraints/boards/vizard2_pci.toml");
  board = std::regex_replace(board, std::regex("\nrows = 4096"), "\nrows = 2");
  EXPECT_NE(board.find("\nrows = 2"), std::string::npos);
  fs::create_directories(dir);
  const fs::path p = dir / "tiny_dimms.toml";
  std::ofstream(p) << board;
  return p;
}

TEST(CosimNotRun, AVolumeLargerThanTheCardStillProvesHlsEqualsBitTrue) {
  const fs::path d = fs::temp_directory_path() / "voxcast_cosim_not_run";
  fs::remove_all(d);
  const fs::path board = tiny_board(d);
  const auto r = voxcast::test::run_voxcast(
      "cosim " + std::string(VOXCAST_SOURCE_DIR) + "/scenes/default.toml --set render.width=16 "
      "--set render.height=16 --set rtl.board=" + board.string() + " --out " +
      (d / "out").string() + " --truth-oversampling 2 --junit " + (d / "cosim.xml").string());
  EXPECT_EQ(r.status, 8) << r.output;
  EXPECT_NE(r.output.find("bit-exact  yes: hls == bit-true on every pixel (rtl not run)"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("not run    rtl: the volume does not fit the card's memory"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("voxcast: cosim: not every engine ran: rtl ("), std::string::npos)
      << r.output;

  const nlohmann::json j = nlohmann::json::parse(slurp(d / "out" / "report.json"));
  EXPECT_EQ(j["bit_exact"], true);
  EXPECT_EQ(j["engines"], nlohmann::json({"float", "bittrue", "hls"}));
  ASSERT_EQ(j["not_run"].size(), 1u);
  EXPECT_EQ(j["not_run"][0]["engine"], "rtl");
  EXPECT_NE(j["not_run"][0]["reason"].get<std::string>().find("do not fit"), std::string::npos);
  EXPECT_FALSE(j.contains("cycles"));

  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_file((d / "cosim.xml").c_str()));
  const pugi::xml_node suite = doc.child("testsuites").child("testsuite");
  EXPECT_EQ(suite.attribute("tests").as_int(), 2);
  EXPECT_EQ(suite.attribute("failures").as_int(), 0);
  EXPECT_EQ(suite.attribute("skipped").as_int(), 1);
  const pugi::xml_node hls = suite.find_child_by_attribute("testcase", "name", "hls == bit-true");
  EXPECT_EQ(std::string(hls.attribute("classname").value()), "cosim.default");
  EXPECT_FALSE(hls.child("failure") || hls.child("skipped"));
  const pugi::xml_node rtl = suite.find_child_by_attribute("testcase", "name", "rtl == hls");
  EXPECT_NE(std::string(rtl.child("skipped").attribute("message").value()).find("rtl not run"),
            std::string::npos);
}

TEST(CosimNotRun, EveryEngineRanIsExitZeroWithBothPairsPassing) {
  const fs::path d = fs::temp_directory_path() / "voxcast_cosim_all_ran";
  fs::remove_all(d);
  const auto r = voxcast::test::run_voxcast(
      "cosim " + std::string(VOXCAST_SOURCE_DIR) + "/scenes/default.toml --set render.width=16 "
      "--set render.height=16 --out " + (d / "out").string() +
      " --truth-oversampling 2 --junit " + (d / "cosim.xml").string());
  EXPECT_EQ(r.status, 0) << r.output;
  pugi::xml_document doc;
  ASSERT_TRUE(doc.load_file((d / "cosim.xml").c_str()));
  const pugi::xml_node suite = doc.child("testsuites").child("testsuite");
  EXPECT_EQ(suite.attribute("tests").as_int(), 2);
  EXPECT_EQ(suite.attribute("failures").as_int(), 0);
  EXPECT_EQ(suite.attribute("skipped").as_int(), 0);
}

}  // namespace VOXCAST_UNITY_ID
