// Long runs say how far they are (issue 20): a progress line on stderr when it
// is a terminal (cosim/reports/progress.hpp), none when it is not, and the same files
// either way. The terminal is a pseudo-terminal from util-linux's `script`
// (Debian's bsdutils, essential).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/common/voxcast_cli.hpp"

namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;
using voxcast::test::Command;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `voxcast regress` of one small scene, blessing into `golden`.
std::string regress_args(const fs::path& scenes, const fs::path& golden) {
  return "regress --scenes " + scenes.string() + " --golden " + golden.string() +
         " --bless --profiles balanced --set render.width=16 --set render.height=16";
}

TEST(Progress, OnATerminalOnlyAndTheSameFilesEitherWay) {
  if (voxcast::test::run_command("command -v script").status != 0)
    GTEST_SKIP() << "util-linux script is not installed";
  const fs::path d = fs::temp_directory_path() / "voxcast_progress";
  fs::remove_all(d);
  fs::create_directories(d / "scenes");
  fs::copy_file(std::string(VOXCAST_SOURCE_DIR) + "/scenes/mip.toml", d / "scenes" / "mip.toml");

  const Command tty = voxcast::test::run_command(
      "script -qec '" + std::string(VOXCAST_EXE) + " " +
      regress_args(d / "scenes", d / "tty") + "' /dev/null");
  ASSERT_EQ(tty.status, 0) << tty.output;
  EXPECT_NE(tty.output.find("regress [##############################] 1/1 100%"),
            std::string::npos)
      << tty.output;
  EXPECT_NE(tty.output.find("elapsed 0:"), std::string::npos) << tty.output;

  const Command pipe = voxcast::test::run_voxcast(regress_args(d / "scenes", d / "pipe"));
  ASSERT_EQ(pipe.status, 0) << pipe.output;
  EXPECT_EQ(pipe.output.find("regress ["), std::string::npos) << pipe.output;

  const std::string a = slurp(d / "tty" / "mip.balanced.json"),
                    b = slurp(d / "pipe" / "mip.balanced.json");
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, b);
}

// The truth, the longest single render of a cosim (16x the scene's samples),
// counts its rows: 16 of a 16-pixel-high image.
TEST(Progress, TheTruthCountsItsRows) {
  if (voxcast::test::run_command("command -v script").status != 0)
    GTEST_SKIP() << "util-linux script is not installed";
  const fs::path d = fs::temp_directory_path() / "voxcast_progress_truth";
  fs::remove_all(d);
  const std::string args = "cosim " + std::string(VOXCAST_SOURCE_DIR) +
                           "/scenes/mip.toml --set render.width=16 --set render.height=16 --out ";
  const Command tty = voxcast::test::run_command("script -qec '" + std::string(VOXCAST_EXE) +
                                                 " " + args + (d / "tty").string() + "' /dev/null");
  ASSERT_EQ(tty.status, 0) << tty.output;
  EXPECT_NE(tty.output.find("truth [##############################] 16/16 100%"),
            std::string::npos)
      << tty.output;

  const Command pipe = voxcast::test::run_voxcast(args + (d / "pipe").string());
  ASSERT_EQ(pipe.status, 0) << pipe.output;
  EXPECT_EQ(pipe.output.find("truth ["), std::string::npos) << pipe.output;
}

}  // namespace VOXCAST_UNITY_ID
