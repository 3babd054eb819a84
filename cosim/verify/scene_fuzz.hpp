// The scene-level differential fuzzer (issue 18, in the manner of Google XLS's
// fuzzer): random but valid scenes — phantom volumes, transfer functions with
// narrow features, random lights and materials, presets and single-width
// variations of them, oversampling and modes — each rendered small by the
// float reference, the bit-true engine and (for the compiled presets) the hls
// kernels. A finding is a scene whose engines disagree on a bit, or whose
// fixed-point error exceeds what the precision guard (cosim/engines/warnings.hpp)
// predicts for it:
//
//   error  = the 99th percentile of |fixed - float| over the image's channels,
//            in LSB of precision.out_bits, over the pixels whose fixed-point
//            ray takes as many samples as the float ray (the others are
//            geometry — a grazing ray that hits in one engine only, a clip
//            point on the other side of a sample — which the extremes suite
//            bounds ray by ray);
//   bound  = kHazardFraction of the output range (what the guard calls
//            ordinary) plus the largest predicted worst case of its hazards.
//
// Deterministic: the scenes follow from the seed alone (a splitmix64 stream,
// not the standard library's distributions, whose results differ between
// implementations). Each finding is written as a scene file, to be kept as a
// regression scene (tests/scene_fuzz/, docs/extremes.md).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "refmodel/scene/scene.hpp"

namespace voxcast::cosim {

struct SceneFuzzOptions {
  std::uint64_t seed = 1;
  int scenes = 20;
  int image_size = 16;  // pixels per side
  std::string out_dir;  // findings are written here as scene_SEED_INDEX.toml (empty: not written)
  int threads = 0;
};

// One scene's verdict.
struct SceneVerdict {
  bool feasible = true;       // false: the scene is refused (a width cannot hold it)
  std::string refusal;        // why, when not feasible
  bool hls_ran = false;       // the profile is a compiled preset
  bool bit_exact = true;      // hls == bit-true (true when !hls_ran)
  std::size_t hazards = 0;    // the guard's hazards
  double error_lsb = 0.0;     // the 99th-percentile channel error
  std::size_t geometry_pixels = 0;  // left out: the engines' rays take different sample counts
  double bound_lsb = 0.0;     // the guard's bound
  bool finding() const { return feasible && (!bit_exact || error_lsb > bound_lsb); }
};

struct SceneFuzzFinding {
  int index = 0;
  std::string scene_file;  // written under out_dir (empty if none)
  SceneVerdict verdict;
};

struct SceneFuzzResult {
  int scenes = 0, infeasible = 0, hazardous = 0, hls_ran = 0;
  double worst_ratio = 0.0;  // the largest error / bound among the feasible scenes
  std::vector<SceneFuzzFinding> findings;
};

// Scene `index` of the stream for `seed`, image_size pixels square.
ref::Scene random_scene(std::uint64_t seed, int index, int image_size);

// The verdict on one scene (the guard's hazards are computed from the scene).
SceneVerdict judge_scene(const ref::Scene& scene, int threads = 0);

SceneFuzzResult run_scene_fuzz(const SceneFuzzOptions& options);

void print_scene_fuzz(std::ostream& os, const SceneFuzzOptions& options, const SceneFuzzResult& r);

}  // namespace voxcast::cosim
