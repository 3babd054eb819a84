// `voxcast cosim`: one scene through the float reference, the bit-true
// reference and the hls kernels; proves hls == bit-true on every bit and
// measures the design's error against the float truth.
#pragma once

#include <ostream>
#include <string>

#include "cosim/reports/junit.hpp"
#include "cosim/reports/metrics.hpp"
#include "cosim/engines/truth.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/scene/scene.hpp"
#include "cosim/engines/warnings.hpp"

namespace voxcast::cosim {

struct Mismatch {
  int x = -1, y = -1;             // first differing pixel (row-major order)
  std::uint64_t sample = 0;       // index along its ray
  bittrue::Unit unit = bittrue::Unit::Output;
  std::string reproducer;         // path of the saved reproducer scene
  std::string engine = "hls";     // the engine that differs from the reference
  // hls against bit-true: both rays' unit outputs, sample by sample (the
  // report page's per-unit trace); empty when the cycle model differs.
  bittrue::RayTrace hls_trace = {}, bt_trace = {};
};

// An engine cosim could not run, and why (a profile the hls kernels are not
// compiled for; a volume larger than the card's memory for the cycle model).
struct EngineNotRun {
  std::string engine;  // "hls", "rtl"
  std::string reason;  // one line
};

struct CosimResult {
  bool hls_ran = false;       // the hls engine is compiled for the profile
  bool rtl_ran = false;       // the cycle model ran (it needs hls_ran and the volume in its DIMMs)
  std::vector<EngineNotRun> not_run = {};  // what did not run, and why
  bool bit_exact = false;     // hls == bit-true == rtl on every pixel (true when !hls_ran)
  bool rtl_exact = true;      // rtl == hls
  std::uint64_t rtl_cycles = 0;
  double rtl_fps = 0.0, rtl_ns_per_sample = 0.0;
  double rtl_clock_mhz = 0.0;  // the card's core clock
  int rtl_pipelines = 0;       // the DDR4 card's (0: the SDR card)
  Accuracy accuracy;          // hls against the float reference at the same settings
  TruthSettings truth;        // how the truth was rendered
  Accuracy truth_accuracy;    // hls (bit-true if !hls_ran) against the truth
  ErrorHistogram truth_histogram = {};  // the same pixels' worst-channel errors, binned
  Mismatch mismatch;          // when !bit_exact
  std::uint64_t samples_float = 0, samples_hls = 0;
  std::vector<Hazard> hazards;  // the precision guard's (cosim/engines/warnings.hpp)
  double seconds_float = 0, seconds_bittrue = 0, seconds_hls = 0, seconds_rtl = 0, seconds_truth = 0;
  std::vector<std::string> written;
};

// Writes DIR/report.json, DIR/layers.exr (float, hls and difference layers)
// and DIR/{float,hls,bittrue,diff,truth}.png. report.json's "truth" section
// holds the design's accuracy against the truth (cosim/engines/truth.hpp).
// strict: refuse a scene with precision hazards (cosim/engines/warnings.hpp).
CosimResult run_cosim(const ref::Scene& scene, const std::string& out_dir,
                      const TruthSettings& truth = {}, bool strict = false);

void print_cosim_summary(std::ostream& os, const ref::Scene& scene, const CosimResult& r);

// The first pixel, in row-major order, where two images differ: true and its
// (x, y), or false.
bool first_difference(const ref::QuantImage& a, const ref::QuantImage& b, int& x, int& y);

// The images of a cosim in OUT (the ray caster's and VIRIM's): layers.exr
// (float, hls and their difference), float.png, hls.png (if it ran),
// bittrue.png, diff.png (|hls - float| as a heat map, 4 LSB full scale) and,
// given one, truth.png; appends the paths to `written`.
void write_cosim_images(const std::string& out_dir, const ref::Scene& scene,
                        const ref::Image& float_image, const ref::QuantImage& bittrue_image,
                        const ref::QuantImage& hls_image, bool hls_ran,
                        const ref::Image* truth_image, std::vector<std::string>& written);

// The cosim as JUnit cases (cosim --junit): classname "cosim.SCENE", one case
// per engine pair: "hls == bit-true" and "rtl == hls", failing with the first
// differing pixel, the sample and the unit, or skipped naming why the engine
// did not run.
JUnitSuite cosim_junit(const ref::Scene& scene, const CosimResult& r);

}  // namespace voxcast::cosim
