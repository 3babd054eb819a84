// Running the `voxcast` command from the sweep tests, as users and scripts do.
#pragma once

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/common/voxcast_cli.hpp"

namespace sweep_test {

using voxcast::test::Command;

inline Command run(const std::string& args, const std::string& prefix = "") {
  return voxcast::test::run_voxcast(args, prefix);
}

inline std::filesystem::path temp_dir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("voxcast_sweep_" + name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

inline std::string text_of(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

inline nlohmann::json json_of(const std::filesystem::path& p) {
  return nlohmann::json::parse(text_of(p));
}

// One literal (no operator+: GCC 12 misreads it as out of bounds, -Warray-bounds).
inline std::string tiny_scene() { return VOXCAST_SOURCE_DIR "/tests/sweep/tube_tiny.toml"; }

}  // namespace sweep_test
