// `voxcast regress`: the bit-accuracy regression a hardware engineer runs on
// every change. Each shipped scene under each precision preset goes through
// the hls kernels and the bit-true reference; the hls image must equal the
// bit-true one and hash to its golden file. A golden file is only written
// (`--bless`) after the case's accuracy against the float reference was
// measured and met the profile's floor, and it records those numbers.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "refmodel/render/quant_image.hpp"

namespace voxcast::cosim {

struct RegressOptions {
  std::string scenes_dir;                // every *.toml in it
  std::string golden_dir;                // <scene>.<profile>.json
  std::vector<std::string> profiles;     // presets to run
  bool bless = false;
  std::vector<std::string> overrides;    // --set, applied to every scene
  std::string junit_path = {};           // --junit: the cases as JUnit XML (empty: none)
  // --shard i/n: only the cases whose index in the scene x preset list is
  // i modulo n (a cluster's array task; cosim/cluster/cluster_runs.hpp).
  int shard_index = 0;
  int shard_count = 1;
  std::string results_path = {};         // --results: this run's cases as JSON, for --merge
  std::vector<std::string> only_scenes = {};  // --scene: these scenes (file stems) only; empty: all
};

// FNV-1a (64 bit) over the image's size, bit depth and pixels.
std::string image_hash(const ref::QuantImage& img);

// Minimum accuracy against the float reference for blessing a golden file.
struct AccuracyFloor {
  double psnr_db;
  double pct_within_1lsb;
};
AccuracyFloor accuracy_floor(const std::string& profile);

// Runs every case, prints one line per case and a summary to `os`; returns
// the number of failed cases (0: all bit-exact and matching their goldens).
// With options.junit_path, the same cases as JUnit XML (cosim/reports/junit.hpp):
// classname "regress.SCENE", name PROFILE, a failure naming the first pixel
// where hls and bit-true differ, or the changed or missing golden.
int run_regress(const RegressOptions& options, std::ostream& os);

// --merge: the results files of the shards (--results) joined: every case's
// line in the local run's order, the summary and options.junit_path; returns
// the number of failed cases, as run_regress. Results of different runs, a
// case in two files or a case in none are errors naming the file or the case.
int run_regress_merge(const std::vector<std::string>& results_files, const RegressOptions& options,
                      std::ostream& os);

}  // namespace voxcast::cosim
