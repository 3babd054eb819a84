// Replays fuzz inputs through the fuzz targets' bodies (fuzz/targets/), with
// whatever compiler builds the suite (docs/extremes.md, "Fuzzing"):
//  - every seed of fuzz/corpus/<target>/: a file named broken_* must be
//    rejected with voxcast::Error, every other seed must be accepted (so the
//    seeds keep reaching the code they were written for);
//  - every saved finding tests/fuzz_regress/data/<target>/<input> with its
//    <input>.expect: "ok" (accepted) or "error: TEXT" (rejected with a message
//    containing TEXT). Before the fix each of these crashed, hung, or escaped
//    with something other than voxcast::Error.
// A fuzz::Finding (differential mismatch) or any other exception fails the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <vector>

#include "fuzz/targets/targets.hpp"
#include "refmodel/error.hpp"

namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;
using Body = void (*)(const std::uint8_t*, std::size_t);

struct Case {
  std::string target;
  fs::path input;
  bool expect_error = false;
  std::string expect_text;  // a substring of the error message ("" = any)
};

// gtest prints a parameter that fails: its file, not its bytes.
void PrintTo(const Case& c, std::ostream* os) { *os << c.target << " " << c.input.string(); }

Body body_of(const std::string& target) {
  if (target == "scene_toml") return &voxcast::fuzz::scene_toml;
  if (target == "nifti") return &voxcast::fuzz::nifti;
  if (target == "raw") return &voxcast::fuzz::raw;
  if (target == "dicom") return &voxcast::fuzz::dicom;
  return nullptr;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::vector<fs::path> files_in(const fs::path& dir) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && e.path().extension() != ".expect") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// Not the fixed-point target (tests/CMakeLists.txt): it has no saved findings,
// and the fuzz step runs its seeds under ASan and UBSan before it fuzzes.
const char* const kTargets[] = {"scene_toml", "nifti", "raw", "dicom"};

std::vector<Case> corpus_cases() {
  std::vector<Case> cases;
  for (const char* t : kTargets)
    for (const fs::path& p : files_in(fs::path(VOXCAST_SOURCE_DIR) / "fuzz/corpus" / t))
      cases.push_back({t, p, p.filename().string().rfind("broken_", 0) == 0, ""});
  return cases;
}

std::vector<Case> finding_cases() {
  std::vector<Case> cases;
  for (const char* t : kTargets)
    for (const fs::path& p : files_in(fs::path(VOXCAST_SOURCE_DIR) / "tests/fuzz_regress/data" / t)) {
      std::string expect = read_all(fs::path(p.string() + ".expect"));
      while (!expect.empty() && (expect.back() == '\n' || expect.back() == '\r')) expect.pop_back();
      Case c{t, p, false, ""};
      if (expect.rfind("error: ", 0) == 0) {
        c.expect_error = true;
        c.expect_text = expect.substr(7);
      } else if (expect != "ok") {
        c.expect_text = "<" + p.string() + ".expect must hold 'ok' or 'error: TEXT'>";
        c.expect_error = true;
      }
      cases.push_back(c);
    }
  return cases;
}

void replay(const Case& c) {
  const Body body = body_of(c.target);
  ASSERT_NE(body, nullptr) << c.target;
  const std::string bytes = read_all(c.input);
  std::string error;
  bool rejected = false;
  try {
    body(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
  } catch (const voxcast::Error& e) {
    rejected = true;
    error = e.what();
  }
  // Anything else (voxcast::fuzz::Finding included) propagates and fails the test.
  if (c.expect_error) {
    EXPECT_TRUE(rejected) << c.input << " was accepted; expected a voxcast::Error";
    EXPECT_NE(error.find(c.expect_text), std::string::npos)
        << c.input << ": error \"" << error << "\" does not contain \"" << c.expect_text << "\"";
    EXPECT_EQ(error.find('\n'), std::string::npos) << "a multi-line error: " << error;
  } else {
    EXPECT_FALSE(rejected) << c.input << " was rejected: " << error;
  }
}

std::string case_name(const testing::TestParamInfo<Case>& info) {
  std::string name = info.param.target + "_" + info.param.input.filename().string();
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
}

class FuzzCorpus : public testing::TestWithParam<Case> {};
TEST_P(FuzzCorpus, SeedHasItsDocumentedOutcome) { replay(GetParam()); }
INSTANTIATE_TEST_SUITE_P(Seeds, FuzzCorpus, testing::ValuesIn(corpus_cases()), case_name);

class FuzzFinding : public testing::TestWithParam<Case> {};
TEST_P(FuzzFinding, FixedInputHasItsExpectedOutcome) { replay(GetParam()); }
INSTANTIATE_TEST_SUITE_P(Findings, FuzzFinding, testing::ValuesIn(finding_cases()), case_name);
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(FuzzFinding);

TEST(FuzzCorpus, EveryTargetHasSeeds) {
  for (const char* t : kTargets)
    EXPECT_FALSE(files_in(fs::path(VOXCAST_SOURCE_DIR) / "fuzz/corpus" / t).empty()) << t;
}

}  // namespace
