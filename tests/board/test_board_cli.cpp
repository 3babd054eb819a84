// The two commands through the voxcast binary: exit codes, files, one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;

struct CliRun {
  int code;
  std::string err;
};

CliRun voxcast(const std::string& args, const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  const std::string cmd =
      std::string(VOXCAST_EXE) + " " + args + " > /dev/null 2> '" + err.string() + "'";
  const int rc = std::system(cmd.c_str());
  std::ifstream f(err);
  std::ostringstream ss;
  ss << f.rdbuf();
  return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, ss.str()};
}

std::string read(const fs::path& p) {
  std::ifstream f(p);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

class BoardCli : public ::testing::Test {
 protected:
  fs::path dir = fs::temp_directory_path() /
                 ("voxcast_board_cli_" +
                  std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
  void SetUp() override {
    fs::remove_all(dir);
    fs::create_directories(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
};

TEST_F(BoardCli, ConstraintsWritesTheGoldenText) {
  const std::string golden = std::string(VOXCAST_SOURCE_DIR) + "/tests/golden/constraints";
  for (const std::string fmt : {"xdc", "sdc"}) {
    const fs::path out = dir / ("card." + fmt);
    const CliRun r =
        voxcast("constraints vizard2_pci --format " + fmt + " --out " + out.string(), dir);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(read(out), read(golden + "/vizard2_pci." + fmt));
  }
  EXPECT_EQ(voxcast("constraints --golden " + golden, dir).code, 0);
}

TEST_F(BoardCli, ErrorsAreOneLine) {
  const CliRun bad_format = voxcast("constraints vizard2_pci --format ucf --out x", dir);
  EXPECT_EQ(bad_format.code, 1);
  EXPECT_EQ(bad_format.err, "voxcast: unknown constraint format 'ucf' (known: xdc, sdc)\n");
  std::ofstream(dir / "bad.toml") << "name = \"x\"\n";
  const CliRun missing = voxcast("constraints " + (dir / "bad.toml").string() + " --out x", dir);
  EXPECT_EQ(missing.code, 1);
  EXPECT_NE(missing.err.find("bad.toml:1: description is missing"), std::string::npos)
      << missing.err;
  EXPECT_EQ(std::count(missing.err.begin(), missing.err.end(), '\n'), 1) << missing.err;
  // A golden that differs: exit 4, the file and line named.
  fs::create_directories(dir / "golden");
  ASSERT_EQ(voxcast("constraints --golden " + (dir / "golden").string() + " --bless", dir).code, 0);
  std::ofstream(dir / "golden" / "vizard2_pci.xdc", std::ios::app) << "# changed\n";
  const CliRun differ = voxcast("constraints --golden " + (dir / "golden").string(), dir);
  EXPECT_EQ(differ.code, 4);
  const CliRun synth = voxcast(
      "synth-script " + std::string(VOXCAST_SOURCE_DIR) +
          "/scenes/default.toml --board vizard2_pci --tool catapult --out " + (dir / "s").string(),
      dir);
  EXPECT_EQ(synth.code, 1);
  EXPECT_EQ(synth.err, "voxcast: synth-script: unknown tool 'catapult' (known: vitis)\n");
}

}  // namespace
