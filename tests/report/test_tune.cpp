// voxcast tune (issue 6, part 5): on a tiny search space and a tiny image,
// every point is rendered with the bit-true engine and the answer is checked
// exhaustively — it meets the target and no cheaper point of the space does —
// with and without the monotonicity pruning. PSNRs are against the truth (the
// float reference at 16x, cosim/engines/truth.hpp), recomputed here independently.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <vector>

#include "cosim/engines/engines.hpp"
#include "cosim/reports/metrics.hpp"
#include "cosim/engines/truth.hpp"
#include "cosim/explore/tune.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/error.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

const std::string kTinyScene =
      "[volume]\nsource = \"phantom:shepp-logan?size=24&aa=2\"\n"
      "[classification]\npoints = [ {value = 0, alpha = 0.0}, "
      "{value = 30, color = [0.9, 0.6, 0.4], alpha = 0.05}, "
      "{value = 200, color = [0.5, 0.8, 1.0], alpha = 0.7} ]\n"
      "[camera]\neye = [30, -30, 30]\ncenter = [11.5, 11.5, 11.5]\nfov_deg = 40\n"
      "[render]\nwidth = 16\nheight = 16\nthreads = 1\n"
      "[precision]\nprofile = \"vizard2\"\n";

ref::Scene tiny_scene() { return ref::parse_scene(kTinyScene, "tiny scene", "."); }

// The PSNR of a profile's bit-true image against the truth, computed here
// without run_tune: what every tune point must carry.
double psnr_against_truth(const ref::Scene& scene, const PrecisionProfile& p,
                          const cosim::TruthSettings& t) {
  const cosim::SceneVolume sv = cosim::load_scene_volume(scene);
  const ref::Image truth = cosim::render_truth(scene, sv, t);
  const ref::CameraPose pose = ref::frame_poses(scene.camera, 1).front();
  const ref::RenderInputs in = ref::make_render_inputs(scene, sv.volume, sv.gradients, pose);
  const ref::QuantImage img =
      bittrue::bt_render_image(bittrue::make_frame_setup(p, scene, in),
                               bittrue::make_voxel_memory(p, sv.volume, sv.gradients), 1);
  return cosim::measure_accuracy(img, truth).psnr_db;
}

const std::vector<cosim::TuneAxis> kAxes = {
    {"weight_bits", 2, 4}, {"sample_frac_bits", 0, 2}, {"acc_bits", 6, 9}};

TEST(Tune, TheAnswerMeetsTheTargetAndNoCheaperPointDoes) {
  const ref::Scene scene = tiny_scene();
  // Every point's PSNR, rendered here independently of run_tune.
  cosim::TuneOptions all{1e9, "xc7a200t", kAxes, false, {}};  // unreachable target: renders all
  const cosim::TuneResult every = cosim::run_tune(scene, all);
  ASSERT_FALSE(every.found);
  ASSERT_EQ(every.space, 3u * 3u * 4u);
  ASSERT_EQ(every.rendered, every.space);
  // Measured against the 16x truth, not the float reference at the scene's own
  // oversampling: the cheapest and the dearest point, recomputed.
  for (const cosim::TunePoint* p : {&every.points.front(), &every.points.back()})
    EXPECT_EQ(p->psnr_db, psnr_against_truth(scene, p->profile, cosim::TruthSettings{}));
  std::vector<double> psnr;
  for (const auto& p : every.points) psnr.push_back(p.psnr_db);
  std::sort(psnr.begin(), psnr.end());
  // The widest point (every axis at its top): pruning renders it first.
  double widest_psnr = 0.0;
  for (const auto& p : every.points)
    if (p.profile.weight_bits == 4 && p.profile.sample_frac_bits == 2 && p.profile.acc_bits == 9)
      widest_psnr = p.psnr_db;
  // Targets across the range of what the space reaches.
  std::size_t pruned = 0;
  int cheapest_missed = 0, nothing_found = 0;
  for (const double target : {psnr[psnr.size() / 4], psnr[psnr.size() / 2],
                              psnr[3 * psnr.size() / 4], psnr.back()}) {
    // Exact (the default): the answer meets the target, no cheaper point does.
    const cosim::TuneResult r = cosim::run_tune(scene, {target, "xc7a200t", kAxes, false, {}});
    ASSERT_TRUE(r.found) << target;
    EXPECT_GE(r.best.psnr_db, target);
    for (const auto& p : every.points)
      if (p.cost < r.best.cost) {
        EXPECT_LT(p.psnr_db, target) << "a cheaper point meets " << target << " dB";
      }
    // Pruned: finds a point exactly when the widest point meets the target
    // (it is above every axis floor, and a miss there ends the search); what
    // it finds meets the target and is never cheaper than the exact answer.
    const cosim::TuneResult q = cosim::run_tune(scene, {target, "xc7a200t", kAxes, true, {}});
    ASSERT_EQ(q.found, widest_psnr >= target) << target;
    pruned += q.pruned;
    if (!q.found) {
      ++nothing_found;
      continue;
    }
    EXPECT_GE(q.best.psnr_db, target);
    EXPECT_GE(q.best.cost, r.best.cost);
    cheapest_missed += q.best.cost > r.best.cost ? 1 : 0;
  }
  EXPECT_GT(pruned, 0u);
  // Accuracy is not monotone in every width on this space (why pruning is off
  // by default): recorded in docs/resources.md.
  std::cout << "pruning missed the cheapest point for " << cheapest_missed << " of 4 targets and "
            << "found nothing for " << nothing_found << " (widest point " << widest_psnr
            << " dB, best " << psnr.back() << " dB)\n";
}

// --truth-oversampling chooses the truth; one below the scene's own
// oversampling is a one-line error before anything renders.
TEST(Tune, TruthOversamplingIsHonoured) {
  const ref::Scene scene = tiny_scene();
  const std::vector<cosim::TuneAxis> one = {{"weight_bits", 4, 4}};
  cosim::TuneOptions o{1e9, "xc7a200t", one, false, {}};
  o.truth.oversampling = 4.0;
  const cosim::TuneResult at4 = cosim::run_tune(scene, o);
  ASSERT_EQ(at4.points.size(), 1u);
  const double expected = psnr_against_truth(scene, at4.points[0].profile, o.truth);
  EXPECT_EQ(at4.points[0].psnr_db, expected);
  o.truth.oversampling = 16.0;
  const cosim::TuneResult at16 = cosim::run_tune(scene, o);
  EXPECT_NE(at16.points[0].psnr_db, expected);  // a different truth, a different figure
  ref::Scene dense = scene;
  dense.render.oversampling = 8.0;
  o.truth.oversampling = 4.0;
  EXPECT_THROW(cosim::run_tune(dense, o), Error);
}

TEST(Tune, PointsAreOrderedByTheResourceModelsCost) {
  const ref::Scene scene = tiny_scene();
  const cosim::TuneResult r = cosim::run_tune(scene, {1e9, "xc7a200t", kAxes, true, {}});
  for (std::size_t i = 1; i < r.points.size(); ++i)
    EXPECT_LE(r.points[i - 1].cost, r.points[i].cost);
  // Wider weights, fraction bits or accumulators never cost less.
  EXPECT_LT(r.points.front().cost, r.points.back().cost);
  EXPECT_EQ(r.points.front().profile.weight_bits, 2);
  EXPECT_EQ(r.points.back().profile.acc_bits, 9);
}

TEST(Tune, PrecisionTableReadsBackIntoTheScene) {
  const ref::Scene scene = tiny_scene();
  PrecisionProfile p = scene.precision;
  p.weight_bits = 3;
  p.acc_bits = 7;
  const std::string table = cosim::precision_table(scene, p);
  const ref::Scene back = ref::parse_scene(
      kTinyScene.substr(0, kTinyScene.find("[precision]")) + table, "round trip", ".");
  EXPECT_EQ(back.precision, p);
}

TEST(Tune, BadAxesAreOneLineErrors) {
  EXPECT_THROW(cosim::parse_tune_axis("weight_bits=3"), Error);
  EXPECT_THROW(cosim::parse_tune_axis("nonsense=1..2"), Error);
  EXPECT_THROW(cosim::parse_tune_axis("weight_bits=0..3"), Error);
  EXPECT_THROW(cosim::parse_tune_axis("weight_bits=5..3"), Error);
  const auto a = cosim::parse_tune_axis("precision.weight_bits=3..8");
  EXPECT_EQ(a.field, "weight_bits");
  EXPECT_EQ(a.lo, 3);
  EXPECT_EQ(a.hi, 8);
}

}  // namespace
}  // namespace voxcast::test
