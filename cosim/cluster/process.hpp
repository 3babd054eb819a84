// Running a cluster's own commands (sbatch, scontrol, bash) and keeping what
// they print: the scheduler's job ids come back on standard output, its
// reasons for refusing on standard error.
#pragma once

#include <string>
#include <vector>

namespace voxcast::cosim::cluster {

struct Captured {
  int status = -1;       // the exit status; 128 + N when killed by signal N; 127: not run
  std::string out, err;  // everything the program printed on each stream
  bool ok() const { return status == 0; }
  // The first line of `err` (else of `out`), for a one-line error message.
  std::string first_line() const;
};

// Runs argv[0] (found on PATH) with the rest as its arguments, with no
// standard input, and waits for it.
Captured run_captured(const std::vector<std::string>& argv);

}  // namespace voxcast::cosim::cluster
