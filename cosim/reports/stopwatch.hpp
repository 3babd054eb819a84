// Wall-clock timing of the harness's stages (load, render, each engine).
#pragma once

#include <chrono>

namespace voxcast::cosim {

using StopwatchClock = std::chrono::steady_clock;

// Seconds elapsed since t0 on the monotonic clock.
inline double seconds_since(StopwatchClock::time_point t0) {
  return std::chrono::duration<double>(StopwatchClock::now() - t0).count();
}

}  // namespace voxcast::cosim
