// `voxcast paper engel2001 SCENE`: pre-integrated classification (Engel, Kraus
// and Ertl, Graphics Hardware 2001) against oversampling, as an error budget on
// the float reference. Post-classification at 1x, 2x and 4x and pre-integration
// at 1x and 2x against the truth (16x, post-classified), and then
// pre-integration at 1x with each of its two approximations removed in turn:
//   * the lighting: one gradient per segment (the front sample's). Lit with the
//     true gradient along the ray instead, the row is the best any lighting of
//     a pre-integrated segment can do, a bound for every hardware variant
//     (gradient lerp, Lum et al. 2004's illumination lerp: rows of their own);
//   * the value: linear between the two samples (the table's premise). With the
//     trilinear value along the ray instead, the row is what the table's 2-D
//     address costs.
// The goal (pre-integration at 1x at least as accurate as
// post-classification at 4x) and whether any lighting could reach it are
// checked with the numbers (docs/accuracy.md, "Pre-integrated classification").
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "cosim/engines/truth.hpp"
#include "cosim/reports/metrics.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace voxcast::cosim::paper {

struct Engel2001Options {
  std::string scene_file;
  std::string out_dir;
  ref::Overrides sets;  // --set KEY=VALUE on the scene
  TruthSettings truth;  // 16x by default
};

struct Engel2001Row {
  std::string name;  // file stem and table label, e.g. "post_4x", "preint_1x_exact_lighting"
  std::string what;  // one line: what this row changes
  double oversampling = 1.0;
  bool preintegrated = false;
  ref::RenderSettings::SegmentStudy study = ref::RenderSettings::SegmentStudy::None;
  Accuracy accuracy;  // the float reference, rounded to the output bits, vs the truth
  double seconds = 0.0;
};

struct Engel2001Result {
  std::string scene;
  std::string mode;                 // render.mode of the rows
  std::vector<Engel2001Row> rows;   // in the order of engel2001_rows()
  bool goal_met = false;            // pre-integration 1x >= post-classification 4x (PSNR)
  bool lighting_can_reach = false;  // the exact-lighting bound >= post-classification 4x
  std::string finding;              // the numbers behind both
  std::vector<std::string> written;
};

// The rows the experiment renders (accuracy not yet measured).
std::vector<Engel2001Row> engel2001_rows();

Engel2001Result run_engel2001(const Engel2001Options& o);
void print_engel2001_summary(std::ostream& os, const Engel2001Result& r);

}  // namespace voxcast::cosim::paper
