// `voxcast tune SCENE --target-psnr DB`: the cheapest precision profile, by the
// resource model (cosim/hardware/report.hpp), whose image meets a PSNR target against
// the truth (cosim/engines/truth.hpp: the float reference at 16x oversampling, like
// every accuracy figure of the tool; issue 6, part 5). Images come from the bit-true engine,
// which takes any profile at run time and is bit-exact with the hls kernels.
//
// Search (docs/resources.md): every point of the search space (a few profile
// fields, each over a range; the scene's profile elsewhere) is priced by the
// resource model, which is cheap; points are rendered in ascending cost and the
// first that meets the target is the answer — so no cheaper point of the space
// meets it, whatever the accuracy does. Pruning (prune = true, a heuristic)
// takes accuracy to be monotone in each width: a binary search per axis, the
// other axes at their widest, finds the narrowest value that can meet the
// target, and the points below it on any axis are skipped unrendered. Accuracy
// is not always monotone (tests/report/test_tune.cpp meets a case), so a
// pruned answer meets the target but may not be the cheapest.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "cosim/hardware/report.hpp"
#include "cosim/engines/truth.hpp"
#include "refmodel/precision/profile.hpp"
#include "refmodel/scene/scene.hpp"

namespace voxcast::cosim {

struct TuneAxis {
  std::string field;  // a PrecisionProfile field name (profile_fields())
  int lo = 0, hi = 0; // inclusive
};

// The default search space for a scene: the fields of the units its design
// contains (elaboration) that trade accuracy for resources, each over a range
// around the presets (docs/resources.md lists them).
std::vector<TuneAxis> default_tune_axes(const ref::Elaboration& e);
// "weight_bits=3..8" -> axis; throws voxcast::Error naming the text.
TuneAxis parse_tune_axis(const std::string& text);

struct TuneOptions {
  double target_psnr_db = 40.0;
  std::string part = "xc7a200t";
  std::vector<TuneAxis> axes;  // empty: default_tune_axes
  bool prune = false;  // exact by default: accuracy is not always monotone (docs/resources.md)
  TruthSettings truth;  // what the PSNR is measured against (--truth-oversampling)
};

struct TunePoint {
  PrecisionProfile profile;
  double cost = 0.0;
  double psnr_db = 0.0;
  bool rendered = false;
  bool valid = true;  // the profile can hold the scene (check_profile_fits)
};

struct TuneResult {
  bool found = false;
  TunePoint best;
  std::vector<TuneAxis> axes;
  std::size_t space = 0;     // points in the search space
  std::size_t rendered = 0;  // renders (walk and pruning probes)
  std::size_t pruned = 0;    // points skipped by monotonicity (below an axis floor)
  std::vector<TunePoint> points;  // every point, ascending cost (rendered ones carry psnr)
};

TuneResult run_tune(const ref::Scene& scene, const TuneOptions& options);

// The best profile as a [precision] table for the scene file (profile = the
// scene's preset, then every field that differs from it).
std::string precision_table(const ref::Scene& scene, const PrecisionProfile& p);
void print_tune(std::ostream& os, const ref::Scene& scene, const TuneOptions& o,
                const TuneResult& r);

}  // namespace voxcast::cosim
