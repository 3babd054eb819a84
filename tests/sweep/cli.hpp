// Running the `voxcast` command from the sweep tests, as users and scripts do.
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace sweep_test {

struct Command {
  int status = -1;
  std::string output;  // stdout and stderr
};

// `prefix` goes before the program, e.g. "env PATH=/nonexistent".
inline Command run(const std::string& args, const std::string& prefix = "") {
  Command r;
  const std::string cmd = prefix + " " + std::string(VOXCAST_EXE) + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), static_cast<int>(buf.size()), pipe)) r.output += buf.data();
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
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

inline std::string tiny_scene() {
  return std::string(VOXCAST_SOURCE_DIR) + "/tests/sweep/tube_tiny.toml";
}

}  // namespace sweep_test
