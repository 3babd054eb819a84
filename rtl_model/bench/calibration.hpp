// The calibration frames of docs/performance.md: the scenes, and one call
// that loads a scene's volume, builds the host set-up and runs the rtl engine
// on it, timing the simulation on the host. `voxcast bench` can list and run
// these; tests/rtl/test_rtl_calibration.cpp runs them (VOXCAST_CALIBRATION=1).
#pragma once

#include <string>
#include <vector>

#include "refmodel/scene/scene.hpp"
#include "rtl_model/engine.hpp"

namespace voxcast::rtl::bench {

struct CalibrationPoint {
  std::string name;         // "baseline-256-perspective", ...
  std::string description;  // what the paper says about it
  ref::Scene scene;
};

// The frames of the first calibration (VIZARD II at 100 MHz):
//   baseline-256-perspective  phantom:shepp-logan?size=256, 256x256, shaded,
//                             1 sample per voxel, ERT off, perspective from
//                             the front and above (the default scene's view)
//   baseline-256-x/-y/-z      the same, parallel, looking along +x, +y, +z
//   endoscopy-ert-1x/-4x      scenes/endoscopy.toml (opaque tube walls, ERT
//                             0.98) at 1 and 4 samples per voxel
// All with precision.profile = vizard2.
std::vector<CalibrationPoint> calibration_points();
// One of the above by name; throws voxcast::Error naming the known ones.
CalibrationPoint calibration_point(const std::string& name);
// The four baseline frames at another size: baseline-N-perspective, -x, -y,
// -z on an N^3 phantom in N x N pixels, the same view scaled (N = 256 gives
// the frames above; tests/rtl/test_rtl_calibration.cpp runs N = 64 in the
// normal suite, docs/performance.md §3.1). Throws voxcast::Error for N < 2.
std::vector<CalibrationPoint> baseline_points(int size);

// The organisation that meets the 10.5 ns goal (docs/performance.md §7): row-hit
// issue (bypass limit 4096) over 32 ray slots in tiles of 4 x 4, the
// bricked-swizzled layout, look-ahead activation, READ with auto precharge.
RtlConfig row_hit_goal_config();

struct CalibrationResult {
  std::string name;
  RtlStats stats;
  double setup_seconds = 0.0;     // host: volume, gradients, FrameSetup, VoxelMemory
  double simulate_seconds = 0.0;  // host: rtl_render
  // Host CPU time of rtl_render (one thread): the figure to compare on a
  // shared machine, where the wall time depends on the other jobs.
  double simulate_cpu_seconds = 0.0;
  // Simulated composited samples per host second.
  double samples_per_host_second() const;
};

CalibrationResult run_calibration(const CalibrationPoint& point,
                                  const RtlConfig& config = vizard2_baseline());

}  // namespace voxcast::rtl::bench
