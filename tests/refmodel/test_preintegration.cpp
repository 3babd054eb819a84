// The float twin of the pre-integration table (issue 25, Engel, Kraus and
// Ertl 2001): the transfer function integrated along a linear segment,
// against closed forms and against the compositing of a very fine sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "refmodel/render/raycaster.hpp"
#include "refmodel/volume/preintegration.hpp"
#include "refmodel/volume/transfer_function.hpp"

namespace VOXCAST_UNITY_ID {

using voxcast::ref::Material;
using voxcast::ref::preintegrate;
using voxcast::ref::SegmentClass;
using voxcast::ref::TfInterpolation;
using voxcast::ref::TfPoint;
using voxcast::ref::TransferFunction;
using glm::dvec3;

TransferFunction tf(std::vector<TfPoint> points, TfInterpolation i) {
  return TransferFunction(std::move(points), i, Material{});
}

void expect_near(const dvec3& a, const dvec3& b, double tol) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tol) << "channel " << k;
}

// Front to back over n equal sub-steps, each classified at its midpoint: the
// integral's midpoint rule (error O(1/n^2)).
SegmentClass fine_sampling(const TransferFunction& f, double front, double back, double length,
                           int n) {
  voxcast::ref::Accumulator acc;
  const double h = length / n;
  for (int i = 0; i < n; ++i) {
    const double s = front + (back - front) * (i + 0.5) / n;
    const voxcast::ref::Classified c = f.classify(s);
    voxcast::ref::composite(acc, c.color, voxcast::ref::opacity_correct(c.alpha, h));
  }
  SegmentClass out;
  out.premultiplied = acc.color;
  out.alpha = acc.alpha;
  return out;
}

const std::vector<TfPoint> kRamp = {{0.0, {0.1, 0.2, 0.3}, 0.0},
                                    {40.0, {0.9, 0.5, 0.1}, 0.35},
                                    {70.0, {0.2, 0.8, 0.6}, 0.1},
                                    {100.0, {1.0, 1.0, 1.0}, 0.8}};

// Both samples of one value: the post-classified sample, opacity-corrected
// for the step (what the ray caster composites without pre-integration).
TEST(Preintegration, ConstantSegmentIsThePostClassifiedSample) {
  const TransferFunction f = tf(kRamp, TfInterpolation::Ramp);
  for (double v : {0.0, 20.0, 55.0, 100.0, 130.0})
    for (double len : {0.25, 1.0, 2.0}) {
      const SegmentClass s = preintegrate(f, v, v, len);
      const voxcast::ref::Classified c = f.classify(v);
      EXPECT_NEAR(s.alpha, voxcast::ref::opacity_correct(c.alpha, len), 1e-15) << v << " " << len;
      if (c.alpha > 0.0) expect_near(s.color(), c.color, 1e-14);
    }
}

// A binary step at 100 between samples of 40 and 140: only the last 40 % of
// the segment is in the material, whichever way the ray crosses it.
TEST(Preintegration, BinaryStepBetweenTwoSamplesGivesTheAnalyticOpacity) {
  const TransferFunction f =
      tf({{0.0, {1.0, 0.0, 0.0}, 0.0}, {100.0, {0.2, 0.4, 0.9}, 0.6}}, TfInterpolation::Binary);
  const double want = 1.0 - std::pow(1.0 - 0.6, 0.4);
  for (const auto& [front, back] : {std::pair{40.0, 140.0}, std::pair{140.0, 40.0}}) {
    const SegmentClass s = preintegrate(f, front, back, 1.0);
    EXPECT_NEAR(s.alpha, want, 1e-15) << front << " -> " << back;
    expect_near(s.color(), {0.2, 0.4, 0.9}, 1e-14);
  }
  // Post-classification at the two samples sees 0.6 at one end only: the
  // step's opacity depends on where the samples fall; pre-integration's not.
  EXPECT_NEAR(preintegrate(f, 90.0, 190.0, 1.0).alpha, 1.0 - std::pow(0.4, 0.9), 1e-15);
}

// Two layers: the front one attenuates the back one, not the other way round.
TEST(Preintegration, TwoLayersCompositeFrontToBack) {
  const dvec3 c1{1.0, 0.0, 0.0}, c2{0.0, 0.0, 1.0};
  const TransferFunction f = tf({{0.0, c1, 0.3}, {50.0, c2, 0.5}}, TfInterpolation::Binary);
  const SegmentClass forward = preintegrate(f, 0.0, 100.0, 2.0);  // 1 unit in each
  EXPECT_NEAR(forward.alpha, 1.0 - 0.7 * 0.5, 1e-15);
  expect_near(forward.premultiplied, 0.3 * c1 + 0.7 * 0.5 * c2, 1e-14);
  const SegmentClass backward = preintegrate(f, 100.0, 0.0, 2.0);
  EXPECT_NEAR(backward.alpha, 1.0 - 0.7 * 0.5, 1e-15);
  expect_near(backward.premultiplied, 0.5 * c2 + 0.5 * 0.3 * c1, 1e-14);
}

// alpha rising linearly from 0 to 1 over the segment: D = int_0^1 -ln(1 - x) dx = 1.
TEST(Preintegration, RampToFullOpacityHasOpticalDepthOne) {
  const TransferFunction f =
      tf({{0.0, {1.0, 1.0, 1.0}, 0.0}, {100.0, {1.0, 1.0, 1.0}, 1.0}}, TfInterpolation::Ramp);
  EXPECT_NEAR(preintegrate(f, 0.0, 100.0, 1.0).alpha, 1.0 - std::exp(-1.0), 1e-15);
  EXPECT_NEAR(preintegrate(f, 100.0, 0.0, 1.0).alpha, 1.0 - std::exp(-1.0), 1e-15);
}

// An opaque layer inside the segment: the pixel is its colour, nothing behind it.
TEST(Preintegration, AnOpaqueLayerHidesWhatLiesBehindIt) {
  const TransferFunction f = tf({{0.0, {0.0, 0.0, 0.0}, 0.0},
                                 {60.0, {0.0, 1.0, 0.0}, 1.0},
                                 {80.0, {1.0, 0.0, 0.0}, 0.5}},
                                TfInterpolation::Binary);
  const SegmentClass s = preintegrate(f, 0.0, 100.0, 1.0);
  EXPECT_EQ(s.alpha, 1.0);
  expect_near(s.color(), {0.0, 1.0, 0.0}, 0.0);
  EXPECT_EQ(preintegrate(f, 0.0, 100.0, 0.0).alpha, 0.0);  // no length: transparent
}

// Ramps in alpha and colour across several control points, both directions,
// long and short steps: the exact integral equals the limit of fine sampling
// (2^16 sub-steps: the midpoint rule's error is below 1e-8 here).
TEST(Preintegration, AgreesWithTheLimitOfFineSampling) {
  const TransferFunction f = tf(kRamp, TfInterpolation::Ramp);
  for (const auto& [front, back] : {std::pair{5.0, 95.0}, std::pair{95.0, 5.0},
                                    std::pair{30.0, 75.0}, std::pair{-20.0, 120.0}})
    for (double len : {0.5, 1.0, 4.0}) {
      const SegmentClass exact = preintegrate(f, front, back, len);
      const SegmentClass fine = fine_sampling(f, front, back, len, 1 << 16);
      EXPECT_NEAR(exact.alpha, fine.alpha, 1e-8) << front << " -> " << back << ", " << len;
      expect_near(exact.premultiplied, fine.premultiplied, 1e-8);
    }
}

}  // namespace VOXCAST_UNITY_ID
