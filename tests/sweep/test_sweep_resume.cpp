// Nothing finished is lost (issue 24): a sweep journals each point as it
// finishes; SIGTERM (Slurm's preemption, a time limit) and SIGKILL stop it
// with every finished point kept; `--resume` computes only the missing points
// and ends byte-identical to an uninterrupted run. The truth is kept on disk,
// so a resumed run or a second shard sharing the folder renders it no more.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "tests/common/voxcast_cli.hpp"

namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;
using voxcast::test::Command;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// 8 points on the MIP scene, each a few tenths of a second.
std::string sweep_args(const fs::path& out) {
  return "sweep " + std::string(VOXCAST_SOURCE_DIR) +
         "/scenes/mip.toml --set render.width=32 --set render.height=32 --truth-oversampling 2 "
         "--vary precision.profile=vizard2,balanced --vary render.oversampling=1,2 "
         "--vary render.ert_threshold=0.95,0.99 --no-plots --out " + out.string();
}

std::size_t journaled(const fs::path& out) {
  std::size_t n = 0;
  const std::regex entry("\\d{6}\\.json");
  if (fs::exists(out / "points"))
    for (const auto& e : fs::directory_iterator(out / "points"))
      n += std::regex_match(e.path().filename().string(), entry) ? 1 : 0;
  return n;
}

// Starts the sweep in the background, sends `signal` once two points are on
// disk, and returns what the shell saw: "status=N".
Command interrupted(const fs::path& out, const std::string& signal) {
  const std::string points = (out / "points").string();
  return voxcast::test::run_command(
      std::string(VOXCAST_EXE) + " " + sweep_args(out) + " 2>&1 & pid=$!; "
      "for i in $(seq 1 3000); do "
      "  n=$(ls " + points + " 2>/dev/null | grep -c '^[0-9]\\{6\\}\\.json$'); "
      "  [ \"$n\" -ge 2 ] && break; sleep 0.01; done; "
      "kill -" + signal + " $pid; wait $pid; echo status=$?");
}

std::size_t resumed_count(const std::string& output) {
  std::smatch m;
  return std::regex_search(output, m, std::regex(", (\\d+) resumed\\)")) ? std::stoul(m[1]) : 0;
}

class SweepResume : public ::testing::Test {
 protected:
  // ctest runs each test in its own process, two at a time: each process
  // makes its own uninterrupted run to compare with.
  static void SetUpTestSuite() {
    whole_ = fs::temp_directory_path() / ("voxcast_resume_whole_" + std::to_string(getpid()));
    fs::remove_all(whole_);
    const Command r = voxcast::test::run_voxcast(sweep_args(whole_));
    ASSERT_EQ(r.status, 0) << r.output;
    ASSERT_EQ(journaled(whole_), 8u);
  }
  static void TearDownTestSuite() { fs::remove_all(whole_); }
  static fs::path whole_;

  void resume_and_compare(const fs::path& out, const std::string& signal, int status) {
    const Command stop = interrupted(out, signal);
    EXPECT_NE(stop.output.find("status=" + std::to_string(status)), std::string::npos)
        << stop.output;
    const std::size_t kept = journaled(out);
    ASSERT_GE(kept, 2u);
    ASSERT_LT(kept, 8u) << "the sweep finished before the signal: make its points slower";
    if (signal == "TERM") {
      EXPECT_NE(stop.output.find("voxcast: sweep: stopped by SIGTERM: " + std::to_string(kept) +
                                 " of 8 points kept"),
                std::string::npos)
          << stop.output;
    }

    const Command again = voxcast::test::run_voxcast(sweep_args(out) + " --resume");
    ASSERT_EQ(again.status, 0) << again.output;
    EXPECT_EQ(resumed_count(again.output), kept) << again.output;  // no finished point redone
    EXPECT_NE(again.output.find("(0 truth images rendered"), std::string::npos)
        << "the truth is read from disk:\n" << again.output;
    for (const char* f : {"results.csv", "results.json"})
      EXPECT_EQ(slurp(out / f), slurp(whole_ / f)) << f;
  }
};
fs::path SweepResume::whole_;

TEST_F(SweepResume, AfterSigtermEndsByteIdentical) {
  const fs::path out = fs::temp_directory_path() / "voxcast_resume_term";
  fs::remove_all(out);
  resume_and_compare(out, "TERM", 143);
}

TEST_F(SweepResume, AfterSigkillEndsByteIdentical) {
  const fs::path out = fs::temp_directory_path() / "voxcast_resume_kill";
  fs::remove_all(out);
  resume_and_compare(out, "KILL", 137);
}

TEST_F(SweepResume, AnotherSweepIsRefusedNamingWhatDiffers) {
  const fs::path out = fs::temp_directory_path() / "voxcast_resume_other";
  fs::remove_all(out);
  fs::copy(whole_, out, fs::copy_options::recursive);
  const Command r = voxcast::test::run_voxcast(
      std::regex_replace(sweep_args(out), std::regex("0.95,0.99"), "0.9,0.99") + " --resume");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("holds another sweep: its axes differ"), std::string::npos) << r.output;
  const Command none = voxcast::test::run_voxcast(
      sweep_args(fs::temp_directory_path() / "voxcast_resume_none") + " --resume");
  EXPECT_EQ(none.status, 1) << none.output;
  EXPECT_NE(none.output.find("holds no sweep to resume"), std::string::npos) << none.output;
}

// Two shards sharing a truth folder: the truth is rendered by the first only.
TEST_F(SweepResume, ShardsShareOneTruth) {
  const fs::path d = fs::temp_directory_path() / "voxcast_resume_shards";
  fs::remove_all(d);
  const std::string cache = " --truth-cache " + (d / "truth").string();
  const Command a = voxcast::test::run_voxcast(sweep_args(d / "s0") + " --shard 0/2" + cache);
  ASSERT_EQ(a.status, 0) << a.output;
  EXPECT_NE(a.output.find("(1 truth image rendered"), std::string::npos) << a.output;
  const Command b = voxcast::test::run_voxcast(sweep_args(d / "s1") + " --shard 1/2" + cache);
  ASSERT_EQ(b.status, 0) << b.output;
  EXPECT_NE(b.output.find("(0 truth images rendered"), std::string::npos) << b.output;
  const Command m = voxcast::test::run_voxcast("sweep-merge " + (d / "s0").string() + " " +
                                               (d / "s1").string() + " --no-plots --out " +
                                               (d / "merged").string());
  ASSERT_EQ(m.status, 0) << m.output;
  EXPECT_EQ(slurp(d / "merged" / "results.csv"), slurp(whole_ / "results.csv"));
}

}  // namespace VOXCAST_UNITY_ID
