// `voxcast bench`: throughput of the engines on one scene, measured the same
// way for each (the same frame, the same threads, median of repeated runs
// after a warm-up). A measurement, not a test: CI never times anything.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "refmodel/scene/scene.hpp"

namespace voxcast::cosim {

struct BenchResult {
  std::string engine;
  std::uint64_t samples = 0;    // per frame
  std::uint64_t cycles = 0;     // per frame: the card's simulated cycles (rtl engine), else 0
  double median_seconds = 0.0;  // per frame, wall time
  double min_seconds = 0.0;
  double median_cpu_seconds = 0.0;  // per frame, CPU time of the process (every thread's)
  double samples_per_second() const {
    return median_seconds > 0 ? static_cast<double>(samples) / median_seconds : 0.0;
  }
  // What a simulation costs in CPU, not in wall time: the rtl engine's
  // simulated samples and card cycles per CPU second (docs/performance.md).
  double samples_per_cpu_second() const {
    return median_cpu_seconds > 0 ? static_cast<double>(samples) / median_cpu_seconds : 0.0;
  }
  double cycles_per_cpu_second() const {
    return median_cpu_seconds > 0 ? static_cast<double>(cycles) / median_cpu_seconds : 0.0;
  }
};

std::vector<BenchResult> run_bench(const ref::Scene& scene, const std::vector<std::string>& engines,
                                   int repeats);

void print_bench(std::ostream& os, const ref::Scene& scene, const std::vector<BenchResult>& r);

// The same numbers for scripts (bench --json FILE): the scene, its size and
// threads, and per engine every field of BenchResult and its rates.
nlohmann::json bench_json(const ref::Scene& scene, const std::vector<BenchResult>& r);

}  // namespace voxcast::cosim
