// The geometry processor's error bounds (docs/pipeline.md §0-1): how far the
// fixed-point rays of a frame can lie from the float reference's, derived from
// the widths alone. The extremes suite asserts them pixel by pixel
// (tests/extremes/); the precision guard (cosim/engines/warnings.cpp) predicts a
// scene's worst case from them before anything renders.
#pragma once

#include <vector>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/math/geometry.hpp"
#include "refmodel/precision/profile.hpp"
#include "refmodel/render/camera.hpp"

namespace voxcast::bittrue {

// Per component, |u - u_f| of pixel (x, y)'s unit direction (world space).
// Perspective (§1.1-1.2): d = A + x B + y C with A, B, C each rounded to df
// fraction bits, so per component |d - d_exact| <= dd = (1 + x + y) 2^-(df+1);
// normalising a direction of length |d| (<= 1; 1 at the corners) moves each
// component by at most (1 + sqrt 3) dd / |d| (the component's own error plus
// the length's, first order). The rsqrt unit adds <= 3 2^-df: m = Q_RND(n2 4^e,
// df) costs 2^-df relative, the two rounded products of the last Newton step
// (y/2)·2^-df <= 2^-df, the final Q_RND(d'y) 2^-(df+1); we allow 4 2^-df, the
// extra LSB covering the seed's residual after two Newton steps (quadratic:
// below 2^-df for every preset's seed bits) and second-order terms. Parallel:
// U = Q_RND(forward, df): 2^-(df+1).
double direction_error_bound(const PrecisionProfile& p, const ref::CameraFrame& cam, int x, int y);

// Per component, |o - o_f| of pixel (x, y)'s origin on the origin plane (§0),
// index space, either camera: O + x P + y R with O, P, R each rounded to pf
// bits, (1 + x + y) 2^-(pf+1).
double origin_error_bound(const PrecisionProfile& p, int x, int y);

// Per component, |s - s_f| of pixel (x, y)'s step vector (§1.3, index space):
// s = Q_RND(u·K, pf) with K within 2^-(df+1) of step/ws, so
// du·step/ws_a + (1 + du)·2^-(df+1) + 2^-(pf+1), du = direction_error_bound,
// at the axis of the smallest world scale (the largest).
double step_error_bound(const PrecisionProfile& p, const ref::CameraFrame& cam,
                        const ref::Vec3& world_scale, double step, int x, int y);

// The largest k_in (samples from the origin plane at depth `depth`) of any ray
// that enters `world_box`: every entry point lies at depth <= depth_far (the
// farthest box corner along the view direction) and a ray climbs at least
// step/M in depth per sample (M = |forward + u0·right + v0·up|, the corner
// pixels' length), so k_in <= M·(depth_far - depth)/step, + 1 for the clip's
// truncations.
double lever_bound(const ref::CameraFrame& cam, const ref::Box& world_box, double depth,
                   double step);

// How far pixel (x, y)'s first sample p0 = o + Q_RND(k_in·s, pf) (§1.6) lies
// from the float ray's line, Euclidean, index space: the line's point
// o_f + k_in·s_f is within origin + k_in·step + 2^-(pf+1) per component.
double first_sample_error_bound(const PrecisionProfile& p, const ref::CameraFrame& cam,
                                const ref::Vec3& world_scale, double step, int x, int y,
                                double k_in);

// The frame's worst case of first_sample_error_bound over every pixel, each at
// its float ray's entry k from the plane (+ 1 sample); rays that miss the box
// take no sample. No term holds the eye's
// distance (docs/pipeline.md §0, "The origin plane"). O(width·height).
double frame_first_sample_error_bound(const PrecisionProfile& p, const ref::CameraFrame& cam,
                                      const ref::Vec3& world_scale, const ref::Box& world_box,
                                      double depth, double step);

// Not a bound but the frame's own figure, from its registers alone: the
// largest distance, per axis and index space, of any sample p_j = p0 + j·s
// (§1.6, §2; j = 0 .. n-1) of any ray from the float ray's point at the same
// parameter on the origin plane's ray (ref::origin_plane_ray). Stepping is exact,
// so a ray's error is affine in j and its largest is at j = 0 or j = n - 1.
// Every pixel when the image is at most `max_side` pixels on each side; beyond,
// every stride-th row and column (stride = ceil(side / max_side)) and the last.
struct SamplePositionError {
  double voxels = 0.0;  // the largest per-axis error
  int x = -1, y = -1;   // the pixel that has it
};
SamplePositionError frame_sample_position_error(const PrecisionProfile& p,
                                                const FrameRegisters& regs,
                                                const std::vector<Raw>& rsqrt_seed,
                                                const ref::CameraFrame& cam,
                                                const ref::Vec3& world_scale, double step,
                                                int max_side = 1024);

}  // namespace voxcast::bittrue
