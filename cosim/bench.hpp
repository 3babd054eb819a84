// `voxcast bench`: throughput of the engines on one scene, measured the same
// way for each (the same frame, the same threads, median of repeated runs
// after a warm-up). A measurement, not a test: CI never times anything.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "refmodel/scene/scene.hpp"

namespace voxcast::cosim {

struct BenchResult {
  std::string engine;
  std::uint64_t samples = 0;    // per frame
  double median_seconds = 0.0;  // per frame
  double min_seconds = 0.0;
  double samples_per_second() const {
    return median_seconds > 0 ? static_cast<double>(samples) / median_seconds : 0.0;
  }
};

std::vector<BenchResult> run_bench(const ref::Scene& scene, const std::vector<std::string>& engines,
                                   int repeats);

void print_bench(std::ostream& os, const ref::Scene& scene, const std::vector<BenchResult>& r);

}  // namespace voxcast::cosim
