// Running the `voxcast` command (or another program: run_command) from the
// tests, as users and scripts do: its exit status and everything it printed
// (stdout and stderr). VOXCAST_EXE is the binary under test (tests/CMakeLists.txt).
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace voxcast::test {

struct Command {
  int status = -1;
  std::string output;  // stdout and stderr
};

// Any command line, through the shell.
inline Command run_command(const std::string& command) {
  Command r;
  const std::string cmd = command + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  while (fgets(buf.data(), static_cast<int>(buf.size()), pipe)) r.output += buf.data();
  const int raw = pclose(pipe);
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return r;
}

// `prefix` goes before the program, e.g. "env PATH=/nonexistent".
inline Command run_voxcast(const std::string& args, const std::string& prefix = "") {
  return run_command(prefix + " " + std::string(VOXCAST_EXE) + " " + args);
}

}  // namespace voxcast::test
