// A progress line for long runs (sweep, tune, flythrough, regress, bench,
// paper): "LABEL [#########.....] 12/40  30%  elapsed 0:12  left 0:28" on
// stderr, redrawn in place, when stderr is a terminal; silent otherwise, so
// what a run writes (its files and stdout) is the same with and without a
// terminal. `force` (sweep --progress) prints a line per step to a log instead.
#pragma once

#include <cstddef>
#include <mutex>
#include <string>

#include "cosim/reports/stopwatch.hpp"

namespace voxcast::cosim {

class Progress {
 public:
  // `total`: the steps expected; `at_most`: the run may end sooner (tune).
  Progress(std::string label, std::size_t total, bool force = false, bool at_most = false);
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  ~Progress();  // ends a line left open on a terminal

  void step(std::size_t n = 1);  // thread-safe

  static bool stderr_is_terminal();

 private:
  void draw();

  std::string label_;
  std::size_t total_, done_ = 0;
  bool enabled_, tty_, at_most_, open_ = false;
  StopwatchClock::time_point t0_;
  std::mutex mutex_;
};

}  // namespace voxcast::cosim
