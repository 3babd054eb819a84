// Geometry processor (docs/pipeline.md §0-2), the three checks of STYLE.md:
//  (a) hls/geometry_processor.hpp == refmodel/bittrue/geometry.cpp on every bit
//      (hit, n, k_in, k_out, s, p0 and the stepped positions) for every pixel of
//      perspective and parallel cameras, all three presets;
//  (b) fixed point against the float reference (ref::primary_ray, ref::clip,
//      ref::sample_count, ray.at(t_enter + k·step) / world_scale) within error
//      bounds derived from the widths (see "Derived bounds" below);
//  plus the constexpr presets and the host's register-range checks.
// (c), the interleaving check, is in test_interpolation_processor.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <glm/geometric.hpp>
#include <limits>
#include <numbers>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "hls/geometry_processor.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/geometry.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/preset_profiles.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/render/camera.hpp"
#include "refmodel/render/raycaster.hpp"

namespace VOXCAST_UNITY_ID {

// make_frame_registers reads only the render inputs here; one named default
// scene (a temporary Scene{} trips GCC 12's -Wmaybe-uninitialized on its strings).
const voxcast::ref::Scene& no_scene() {
  static const voxcast::ref::Scene scene;
  return scene;
}


using namespace voxcast;
using bittrue::Raw;
using ref::Vec3;

// ---- Frames -----------------------------------------------------------------------------------
// A camera + volume box; the volume holds no data (the geometry processor only
// reads its dims, spacing and crop).
struct Case {
  std::string name;
  ref::Projection projection = ref::Projection::Perspective;
  Vec3 eye{0.0}, center{0.0}, up{0.0, 0.0, 1.0};
  double fov_deg = 40.0;      // perspective
  double view_height = 20.0;  // parallel
  int width = 31, height = 27;
  double oversampling = 1.0;
  std::array<int, 3> dims{17, 17, 17};
  Vec3 spacing{1.0};
  std::optional<ref::Crop> crop;
  int pixel_stride = 1;  // test every pixel_stride-th pixel in x and y (plus the last)
};

struct Frame {
  ref::Volume volume;
  ref::GradientField gradients;
  ref::RenderInputs in;
  std::vector<int> xs, ys;  // the pixels tested
};

std::vector<int> pixel_list(int n, int stride) {
  std::vector<int> v;
  for (int i = 0; i < n; i += stride) v.push_back(i);
  if (v.back() != n - 1) v.push_back(n - 1);
  return v;
}

std::unique_ptr<Frame> make_frame(const Case& c) {
  auto f = std::make_unique<Frame>();
  f->volume.dims = c.dims;
  f->volume.spacing = c.spacing;
  f->volume.bits = 8;
  ref::RenderVolume& rv = f->in.volume;
  rv.volume = &f->volume;
  rv.gradients = &f->gradients;
  rv.world_scale = ref::normalised_spacing(f->volume);
  Vec3 lo{0.0}, hi{c.dims[0] - 1.0, c.dims[1] - 1.0, c.dims[2] - 1.0};
  if (c.crop) {
    lo = Vec3(c.crop->lo[0], c.crop->lo[1], c.crop->lo[2]);
    hi = Vec3(c.crop->hi[0], c.crop->hi[1], c.crop->hi[2]);
  }
  rv.index_box = ref::Box{lo, hi};
  rv.world_box = ref::Box{lo * rv.world_scale, hi * rv.world_scale};
  ref::CameraDesc cam;
  cam.projection = c.projection;
  cam.fov_deg = c.fov_deg;
  cam.height = c.view_height;
  const ref::CameraPose pose{c.eye, c.center, c.up};
  f->in.camera = ref::make_camera_frame(cam, pose, c.width, c.height, rv.world_scale);
  f->in.settings.step = 1.0 / c.oversampling;
  f->xs = pixel_list(c.width, c.pixel_stride);
  f->ys = pixel_list(c.height, c.pixel_stride);
  return f;
}

std::vector<Case> cases() {
  std::vector<Case> v;
  {
    Case c;
    c.name = "perspective, eye outside";
    c.dims = {24, 20, 28};
    c.eye = {11.5, -40.0, 30.0};
    c.center = {11.5, 9.5, 13.5};
    c.width = 37;
    c.height = 31;
    c.oversampling = 2.0;
    v.push_back(c);
  }
  {
    Case c;
    c.name = "perspective, eye inside the volume";
    c.dims = {24, 20, 28};
    c.eye = {10.0, 8.0, 12.0};
    c.center = {20.0, 15.0, 3.0};
    c.fov_deg = 100.0;
    c.width = c.height = 33;
    v.push_back(c);
  }
  {
    // Odd image: the centre pixel's ray runs exactly along +y, the centre row
    // and column in the planes x = 8 and z = 8 (s components of 0).
    Case c;
    c.name = "perspective, rays along an axis";
    c.eye = {8.0, -30.0, 8.0};
    c.center = {8.0, 8.0, 8.0};
    c.fov_deg = 30.0;
    c.width = c.height = 31;
    v.push_back(c);
  }
  {
    Case c;
    c.name = "perspective, through corners and edges";
    c.eye = {-20.0, -20.0, -20.0};
    c.center = {8.0, 8.0, 8.0};
    c.fov_deg = 60.0;
    c.width = c.height = 25;
    c.oversampling = 0.5;
    v.push_back(c);
  }
  {
    Case c;
    c.name = "perspective, crop box, anisotropic spacing";
    c.dims = {20, 16, 24};
    c.spacing = {1.0, 1.5, 2.5};
    c.crop = ref::Crop{{3, 2, 4}, {15, 12, 20}};
    c.eye = {40.0, -30.0, 35.0};
    c.center = {9.0, 7.0, 12.0};
    c.fov_deg = 50.0;
    c.width = 35;
    c.height = 29;
    c.oversampling = 4.0;
    v.push_back(c);
  }
  {
    // Pixel centres at x, z = 0..4 exactly: rays on the faces, edges and corners
    // of the 5^3 box, parallel to y (s_x = s_z = 0).
    Case c;
    c.name = "parallel, rays on faces, edges and corners";
    c.projection = ref::Projection::Parallel;
    c.dims = {5, 5, 5};
    c.eye = {2.0, -10.0, 2.0};
    c.center = {2.0, 2.0, 2.0};
    c.view_height = 5.0;
    c.width = c.height = 5;
    v.push_back(c);
  }
  {
    Case c;
    c.name = "parallel, along -x";
    c.projection = ref::Projection::Parallel;
    c.eye = {30.0, 8.5, 7.0};
    c.center = {8.0, 8.5, 7.0};
    c.view_height = 20.0;
    c.width = c.height = 21;
    c.oversampling = 3.0;
    v.push_back(c);
  }
  {
    Case c;
    c.name = "parallel, oblique, crop box";
    c.projection = ref::Projection::Parallel;
    c.dims = {20, 18, 22};
    c.crop = ref::Crop{{2, 0, 5}, {17, 17, 21}};
    c.eye = {-15.0, -25.0, 40.0};
    c.center = {10.0, 10.0, 10.0};
    c.view_height = 40.0;
    c.width = 29;
    c.height = 23;
    c.oversampling = 2.0;
    v.push_back(c);
  }
  {
    // A large volume seen from far away on a large image: large k, long rays
    // and the largest direction errors (px + py up to 1398).
    Case c;
    c.name = "perspective, large image, far eye";
    c.dims = {500, 400, 300};
    c.eye = {-900.0, -1500.0, 800.0};
    c.center = {250.0, 200.0, 150.0};
    c.fov_deg = 35.0;
    c.width = 800;
    c.height = 600;
    c.pixel_stride = 41;
    v.push_back(c);
  }
  {
    Case c;
    c.name = "parallel, large image, far eye";
    c.projection = ref::Projection::Parallel;
    c.dims = {500, 400, 300};
    c.eye = {-1200.0, 900.0, 1100.0};
    c.center = {250.0, 200.0, 150.0};
    c.view_height = 700.0;
    c.width = 640;
    c.height = 480;
    c.oversampling = 0.25;
    c.pixel_stride = 37;
    v.push_back(c);
  }
  return v;
}

struct BitTrueFrame {
  bittrue::FrameRegisters regs;
  std::vector<Raw> seed;
};

BitTrueFrame setup(const PrecisionProfile& p, const Frame& f) {
  return {bittrue::make_frame_registers(p, no_scene(), f.in), bittrue::make_rsqrt_seed(p)};
}

// ---- (a) bit-exact -----------------------------------------------------------------------------
template <PrecisionProfile P>
void check_bit_exact(const Case& c) {
  SCOPED_TRACE(c.name);
  const auto frame = make_frame(c);
  const BitTrueFrame bt = setup(P, *frame);
  const auto regs = hls::host::load_geometry_registers<ProfileTraits<P>>(bt.regs);
  auto rom = std::make_unique<hls::RsqrtRom<ProfileTraits<P>>>();
  hls::host::load_rsqrt_rom<ProfileTraits<P>>(bt.seed, *rom);
  using G = hls::GeometryParams<ProfileTraits<P>>;
  int hits = 0;
  for (int py : frame->ys)
    for (int px : frame->xs) {
      SCOPED_TRACE(::testing::Message() << "pixel (" << px << ", " << py << ")");
      const bittrue::BtRay b = bittrue::bt_ray_setup(P, bt.regs, bt.seed, px, py);
      const hls::RaySetup<ProfileTraits<P>> h = regs.perspective
                                     ? hls::ray_setup_perspective<ProfileTraits<P>>(regs, rom->seed, px, py)
                                     : hls::ray_setup_parallel<ProfileTraits<P>>(regs, px, py);
      ASSERT_EQ(h.hit, b.hit);
      ASSERT_EQ(h.n.to_uint64(), b.n);
      ASSERT_EQ(h.k_in.to_double(), b.k_in);
      ASSERT_EQ(h.k_out.to_double(), b.k_out);
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(h.s[k].to_double(), b.s[static_cast<std::size_t>(k)]) << "axis " << k;
        ASSERT_EQ(h.p0[k].to_double(), b.p0[static_cast<std::size_t>(k)]) << "axis " << k;
      }
      if (regs.perspective) {
        // The rsqrt unit on its own.
        typename G::dir_t d[3];
        typename G::unit_t u[3];
        hls::pixel_direction<ProfileTraits<P>>(regs, px, py, d);
        hls::normalize_direction<ProfileTraits<P>>(d, rom->seed, u);
        const auto bu = bittrue::bt_unit_direction(P, bt.regs, bt.seed, px, py);
        for (int k = 0; k < 3; ++k) ASSERT_EQ(u[k].to_double(), bu[static_cast<std::size_t>(k)]);
      }
      if (!b.hit) continue;
      ++hits;
      // §2: every stepped position.
      typename G::pos_t p[3] = {h.p0[0], h.p0[1], h.p0[2]};
      std::array<double, 3> q = b.p0;
      for (std::uint64_t j = 1; j < b.n; ++j) {
        hls::step_position<ProfileTraits<P>>(p, h.s);
        q = bittrue::bt_step(q, b.s);
      }
      for (int k = 0; k < 3; ++k) ASSERT_EQ(p[k].to_double(), q[static_cast<std::size_t>(k)]);
    }
  EXPECT_GT(hits, 0);
}

template <PrecisionProfile P>
void check_all_cases_bit_exact() {
  for (const Case& c : cases()) check_bit_exact<P>(c);
}

TEST(GeometryProcessor, BitExactVizard2) { check_all_cases_bit_exact<kVizard2>(); }
TEST(GeometryProcessor, BitExactBalanced) { check_all_cases_bit_exact<kBalanced>(); }
TEST(GeometryProcessor, BitExactPrecise) { check_all_cases_bit_exact<kPrecise>(); }

// A profile off the presets: a narrow rsqrt seed (3 bits, the minimum) and
// t_frac_bits > pos_frac_bits (exact clip dividends).
inline constexpr PrecisionProfile kNarrowSeed = [] {
  PrecisionProfile p;
  p.rsqrt_seed_bits = 3;
  p.pos_frac_bits = 10;
  p.t_frac_bits = 14;
  p.dir_frac_bits = 16;
  return p;
}();
TEST(GeometryProcessor, BitExactOffPresetProfile) { check_all_cases_bit_exact<kNarrowSeed>(); }

// ---- (b) against the float reference -----------------------------------------------------------
// Derived bounds (df, pf, tf, sb = the profile's dir/pos/t frac bits and seed bits):
//
// 1. Unit direction (perspective). m = Q_RND(n2·4^e) is within 2^-(df+1) of
//    n2' = n2·4^e >= 1/4, so 1/sqrt(m) is within a relative 2^-df of 1/sqrt(n2').
//    Seed: for m in cell i >= 2^(sb-2), |SEED[i]·sqrt(m) - 1| <= eps0 =
//    max(1 - sqrt(i/(i+1/2)), sqrt((i+1)/(i+1/2)) - 1) at i = 2^(sb-2) (the
//    worst cell) plus the table rounding 2^-(df+1).
//    Newton step with y = (1+e)/sqrt(m): exactly y' sqrt(m) = 1 - 1.5e² - 0.5e³,
//    and the three roundings (t: 2^-(df+1); m·t: m·2^-(df+1) + 2^-(df+1) <= 2^-df;
//    y': (y/2)·2^-df + 2^-(df+1) with y <= 2.1) add at most rho = 1.6·2^-df, so
//    e' <= 1.5e² + 0.5|e|³ + rho. After two steps e2. Finally u = Q_RND(d'·y):
//    |u - d/|d|| <= e2 + 2^-df·(1 + e2) + sqrt(3)·2^-(df+1) =: eps_norm, which
//    bounds ||u| - 1| too.
// 2. Direction vs the float ray. A, B, C are each within 2^-(df+1) per component
//    of the exact scaled directions, so d is within eps_d = (1 + px + py)·2^-(df+1)
//    per component of d_f, |d_f| >= 1/M (its forward component), and
//    |d/|d| - d_f/|d_f|| <= 2|d - d_f|/|d_f| <= 2·sqrt(3)·eps_d·M. So
//    |u - dir_f| <= eps_u = eps_norm + 2·sqrt(3)·eps_d·M. Parallel: u = U =
//    Q_RND(forward, df): eps_u = sqrt(3)·2^-(df+1).
// 3. Step: s_f = dir_f·step/ws. K is within 2^-(df+1) of step/ws, so
//    |s_a - s_f,a| <= ds_a = eps_u·step/ws_a + (1 + eps_u)·2^-(df+1) + 2^-(pf+1).
// 4. Origin on the origin plane (§0): |o_a - o_f,a| <= do = (1 + px + py)·2^-(pf+1),
//    O, P and R each rounded to pf bits, o_f the float ray's point on the plane
//    (ref::origin_plane_ray).
// 5. Clip: per axis with s_a != 0, k_a = TRUNC0(Q_TRN(F - o_a, tf)/s_a, tf) is
//    within 2^-tf + [tf < pf]·2^-tf/|s_a| of (F - o_a)/s_a, which is within
//    do/|s_a| + |F - o_f,a|·ds_a/(|s_a||s_f,a|) of the float k_f,a = (F - o_f,a)/s_f,a.
//    Carried through min/max as intervals, k_in in [Lin, Uin], k_out in [Lout, Uout]
//    (the float values lie in the same intervals). Then |n - n_f| <= 1 whenever
//    the widths sum below 1 (n = floor(k_out - k_in) + 1 and the float's
//    n_f = floor(length/step) + 1 differ by less than 1 + the widths).
// 6. Positions: p_j = o + k_in·s + r + j·s (|r| <= 2^-(pf+1)) against the float
//    sample o_f + (k_in_f + j)·s_f: |p_j - P_f,j|_a <= do + (k_in + j)·ds_a +
//    2^-(pf+1) + (Uin - Lin)·|s_f,a| (j = 0: the entry point; j = n - 1: the
//    stepping drift included).
struct Bounds {
  double eps_norm = 0.0;
};

Bounds derive_bounds(const PrecisionProfile& p) {
  const double df = std::ldexp(1.0, -p.dir_frac_bits);
  const double i = std::ldexp(1.0, p.rsqrt_seed_bits - 2);
  double e =
      std::max(1.0 - std::sqrt(i / (i + 0.5)), std::sqrt((i + 1.0) / (i + 0.5)) - 1.0) + df / 2.0;
  const double rho = 1.6 * df;
  for (int it = 0; it < 2; ++it) e = 1.5 * e * e + 0.5 * e * e * e + rho;
  Bounds b;
  b.eps_norm = e + df * (1.0 + e) + std::sqrt(3.0) * df / 2.0;
  return b;
}

struct Measured {
  double worst_norm = 0.0, norm_bound = 0.0;       // ||u| - 1|
  double worst_p0 = 0.0, p0_bound_at_worst = 0.0;  // |p0 - float entry point|
  double worst_last = 0.0, last_bound_at_worst = 0.0;
  double worst_p0_ratio = 0.0, worst_last_ratio = 0.0;  // error / bound
  int rays = 0, hits = 0, count_checked = 0, count_off_by_one = 0, hit_disagree = 0, skipped = 0;
};

template <PrecisionProfile P>
void check_against_float(const Case& c, Measured& m) {
  SCOPED_TRACE(c.name);
  const auto frame = make_frame(c);
  const BitTrueFrame bt = setup(P, *frame);
  const auto regs = hls::host::load_geometry_registers<ProfileTraits<P>>(bt.regs);
  auto rom = std::make_unique<hls::RsqrtRom<ProfileTraits<P>>>();
  hls::host::load_rsqrt_rom<ProfileTraits<P>>(bt.seed, *rom);
  using G = hls::GeometryParams<ProfileTraits<P>>;
  const Bounds bounds = derive_bounds(P);
  const ref::CameraFrame& cam = frame->in.camera;
  const ref::RenderVolume& rv = frame->in.volume;
  const double step = frame->in.settings.step;
  const double half_pf = std::ldexp(1.0, -(P.pos_frac_bits + 1));
  const double half_df = std::ldexp(1.0, -(P.dir_frac_bits + 1));
  const double lsb_tf = std::ldexp(1.0, -P.t_frac_bits);
  const bool perspective = regs.perspective;
  const double u0 = (1.0 / cam.width - 1.0) * cam.half_width;
  const double v0 = (1.0 - 1.0 / cam.height) * cam.half_height;
  const double M = std::sqrt(1.0 + u0 * u0 + v0 * v0);
  constexpr double kSlack = 1e-9;  // double rounding of the float reference itself

  for (int py : frame->ys)
    for (int px : frame->xs) {
      SCOPED_TRACE(::testing::Message() << "pixel (" << px << ", " << py << ")");
      ++m.rays;
      const hls::RaySetup<ProfileTraits<P>> h = hls::ray_setup<ProfileTraits<P>>(regs, rom->seed, px, py);
      // The float twin of the origin plane: the same line from the plane's point.
      const ref::Ray ray = ref::origin_plane_ray(cam, px, py, bt.regs.origin_depth);
      const std::optional<ref::Segment> seg = ref::clip(ray, rv.world_box);

      // 1-2: the unit direction.
      double eps_u = std::sqrt(3.0) * half_df;
      if (perspective) {
        typename G::dir_t d[3];
        typename G::unit_t u[3];
        hls::pixel_direction<ProfileTraits<P>>(regs, px, py, d);
        hls::normalize_direction<ProfileTraits<P>>(d, rom->seed, u);
        const Vec3 uv(u[0].to_double(), u[1].to_double(), u[2].to_double());
        const double err = std::fabs(glm::length(uv) - 1.0);
        EXPECT_LE(err, bounds.eps_norm);
        m.worst_norm = std::max(m.worst_norm, err);
        m.norm_bound = bounds.eps_norm;
        const double eps_d = (1.0 + px + py) * half_df;
        eps_u = bounds.eps_norm + 2.0 * std::sqrt(3.0) * eps_d * M;
        EXPECT_LE(glm::length(uv - ray.direction), eps_u);
      }
      // 3-4: step and origin.
      const double d_o = (1.0 + px + py) * half_pf;
      const Vec3 o_f = ray.origin / rv.world_scale;
      const Vec3 s_f = ray.direction * step / rv.world_scale;
      std::array<double, 3> ds{}, s{}, o{};
      const auto bo = bittrue::bt_ray_origin(P, bt.regs, px, py);
      for (int a = 0; a < 3; ++a) {
        const auto ia = static_cast<std::size_t>(a);
        s[ia] = h.s[a].to_double();
        o[ia] = bo[ia];
        ds[ia] = eps_u * step / rv.world_scale[a] + (1.0 + eps_u) * half_df + half_pf;
        EXPECT_LE(std::fabs(s[ia] - s_f[a]), ds[ia]);
        EXPECT_LE(std::fabs(o[ia] - o_f[a]), d_o + kSlack);
      }

      // 5: clip intervals over the axes the fixed-point clip uses.
      double Lin = 0.0, Uin = 0.0, Lout = 0.0, Uout = 0.0;  // max(0, ·) applied below
      double kin_f = 0.0, kout_f = 0.0;                     // the float, same axes
      bool any = false, degenerate = false, zero_axis_ambiguous = false, zero_inside = true;
      for (int a = 0; a < 3; ++a) {
        const auto ia = static_cast<std::size_t>(a);
        const double lo = rv.index_box.lo[a], hi = rv.index_box.hi[a];
        if (s[ia] == 0.0) {
          zero_inside = zero_inside && lo <= o[ia] && o[ia] <= hi;
          if (std::fabs(o_f[a] - lo) <= d_o + kSlack || std::fabs(o_f[a] - hi) <= d_o + kSlack)
            zero_axis_ambiguous = true;
          continue;
        }
        double nearL, nearU, farL, farU, near_f, far_f;
        if (s_f[a] == 0.0) {
          // The float ray is parallel to this slab, the fixed one slightly
          // tilted (d quantized). With the float origin inside by a margin mu,
          // the fixed o is inside by mu' = mu - do - 2^-tf after Q_TRN, so its
          // k_near <= -mu'/|s| + 2^-tf and k_far >= mu'/|s| - 2^-tf; the float
          // has no constraint from this axis.
          const double mu = std::min(o_f[a] - lo, hi - o_f[a]) - d_o - lsb_tf - kSlack;
          if (mu <= 0.0) {
            degenerate = true;
            continue;
          }
          const double inf = std::numeric_limits<double>::infinity();
          nearL = -inf, nearU = -mu / std::fabs(s[ia]) + lsb_tf;
          farL = mu / std::fabs(s[ia]) - lsb_tf, farU = inf;
          near_f = -inf, far_f = inf;
        } else {
          double kf[2], e[2];
          const double F[2] = {lo, hi};
          for (int j = 0; j < 2; ++j) {
            kf[j] = (F[j] - o_f[a]) / s_f[a];
            e[j] = lsb_tf + (P.t_frac_bits < P.pos_frac_bits ? lsb_tf / std::fabs(s[ia]) : 0.0) +
                   d_o / std::fabs(s[ia]) +
                   std::fabs(F[j] - o_f[a]) * ds[ia] / (std::fabs(s[ia]) * std::fabs(s_f[a])) +
                   kSlack * (1.0 + std::fabs(kf[j]));
          }
          nearL = std::min(kf[0] - e[0], kf[1] - e[1]);
          nearU = std::min(kf[0] + e[0], kf[1] + e[1]);
          farL = std::max(kf[0] - e[0], kf[1] - e[1]);
          farU = std::max(kf[0] + e[0], kf[1] + e[1]);
          near_f = std::min(kf[0], kf[1]), far_f = std::max(kf[0], kf[1]);
        }
        if (!any) {
          Lin = nearL, Uin = nearU, Lout = farL, Uout = farU, kin_f = near_f, kout_f = far_f;
        } else {
          Lin = std::max(Lin, nearL), Uin = std::max(Uin, nearU);
          Lout = std::min(Lout, farL), Uout = std::min(Uout, farU);
          kin_f = std::max(kin_f, near_f), kout_f = std::min(kout_f, far_f);
        }
        any = true;
      }
      Lin = std::max(Lin, 0.0), Uin = std::max(Uin, 0.0), kin_f = std::max(kin_f, 0.0);
      // The float's own clip uses every axis with s_f != 0; the comparison holds
      // when the axes the fixed point drops (s = 0) do not bind the float.
      const bool float_hit_same_axes = any && zero_inside && kin_f <= kout_f;
      const bool float_hit = seg.has_value();
      if (degenerate || !any || float_hit != float_hit_same_axes ||
          (float_hit && (std::fabs(seg->t_enter / step - kin_f) > kSlack * (1 + kin_f) ||
                         std::fabs(seg->t_exit / step - kout_f) > kSlack * (1 + kout_f)))) {
        ++m.skipped;
        continue;
      }
      if (h.hit != float_hit) {
        // Only where the bounds cannot decide: intervals overlapping, or an
        // origin within do of a face of an axis with s = 0.
        ++m.hit_disagree;
        EXPECT_TRUE(Uin >= Lout || zero_axis_ambiguous)
            << "hit " << h.hit << " vs float " << float_hit << ", k_in in [" << Lin << ", " << Uin
            << "], k_out in [" << Lout << ", " << Uout << "]";
        continue;
      }
      if (!h.hit) continue;
      ++m.hits;
      const double k_in = h.k_in.to_double(), k_out = h.k_out.to_double();
      EXPECT_GE(k_in, Lin);
      EXPECT_LE(k_in, Uin);
      EXPECT_GE(k_out, Lout);
      EXPECT_LE(k_out, Uout);
      const double width = (Uin - Lin) + (Uout - Lout);
      const auto n = static_cast<std::int64_t>(h.n.to_uint64());
      const auto n_f = static_cast<std::int64_t>(ref::sample_count(*seg, step));
      if (width < 1.0) {
        ++m.count_checked;
        EXPECT_LE(std::llabs(n - n_f), 1) << "width " << width;
        if (n != n_f) ++m.count_off_by_one;
      } else {
        EXPECT_LE(static_cast<double>(std::llabs(n - n_f)), std::floor(width) + 1.0);
      }

      // 6: first and last sample against the float samples of the same index.
      typename G::pos_t p[3] = {h.p0[0], h.p0[1], h.p0[2]};
      for (int a = 0; a < 3; ++a) {
        const auto ia = static_cast<std::size_t>(a);
        const double P_f = o_f[a] + kin_f * s_f[a];
        const double err = std::fabs(h.p0[a].to_double() - P_f);
        const double bound = d_o + k_in * ds[ia] + half_pf + (Uin - Lin) * std::fabs(s_f[a]);
        EXPECT_LE(err, bound) << "axis " << a;
        if (err / bound > m.worst_p0_ratio) {
          m.worst_p0_ratio = err / bound;
          m.worst_p0 = err;
          m.p0_bound_at_worst = bound;
        }
      }
      for (std::int64_t j = 1; j < n; ++j) hls::step_position<ProfileTraits<P>>(p, h.s);
      const double j = static_cast<double>(n - 1);
      for (int a = 0; a < 3; ++a) {
        const auto ia = static_cast<std::size_t>(a);
        const double P_f = o_f[a] + (kin_f + j) * s_f[a];
        const double err = std::fabs(p[a].to_double() - P_f);
        const double bound = d_o + (k_in + j) * ds[ia] + half_pf + (Uin - Lin) * std::fabs(s_f[a]);
        EXPECT_LE(err, bound) << "axis " << a;
        if (err / bound > m.worst_last_ratio) {
          m.worst_last_ratio = err / bound;
          m.worst_last = err;
          m.last_bound_at_worst = bound;
        }
      }
    }
}

template <PrecisionProfile P>
void check_all_against_float(const char* name) {
  Measured m;
  for (const Case& c : cases()) check_against_float<P>(c, m);
  // Almost every ray is decidable and has a sample count within +-1.
  EXPECT_LE(m.skipped * 20, m.rays);
  EXPECT_LE(m.hit_disagree * 50, m.rays);
  EXPECT_GE(m.count_checked * 10, m.hits * 9);
  std::printf(
      "[ %s ] rays %d, hits %d (n within +-1 checked on %d, off by one %d), hit disagreements "
      "%d, skipped %d\n"
      "  ||u|-1| max %.3g (bound %.3g); p0 vs float entry: worst err/bound %.3f (%.3g of "
      "%.3g); last sample: worst err/bound %.3f (%.3g of %.3g)\n",
      name, m.rays, m.hits, m.count_checked, m.count_off_by_one, m.hit_disagree, m.skipped,
      m.worst_norm, m.norm_bound, m.worst_p0_ratio, m.worst_p0, m.p0_bound_at_worst,
      m.worst_last_ratio, m.worst_last, m.last_bound_at_worst);
}

TEST(GeometryProcessor, WithinDerivedBoundsOfFloatVizard2) {
  check_all_against_float<kVizard2>("vizard2");
}
TEST(GeometryProcessor, WithinDerivedBoundsOfFloatBalanced) {
  check_all_against_float<kBalanced>("balanced");
}
TEST(GeometryProcessor, WithinDerivedBoundsOfFloatPrecise) {
  check_all_against_float<kPrecise>("precise");
}

// The rsqrt unit over its whole input range: y·sqrt(m) within the Newton bound.
template <PrecisionProfile P>
void check_rsqrt_range() {
  using G = hls::GeometryParams<ProfileTraits<P>>;
  const std::vector<Raw> seed = bittrue::make_rsqrt_seed(P);
  auto rom = std::make_unique<hls::RsqrtRom<ProfileTraits<P>>>();
  hls::host::load_rsqrt_rom<ProfileTraits<P>>(seed, *rom);
  const Bounds b = derive_bounds(P);
  double worst = 0.0;
  const Raw lo = Raw{1} << (P.dir_frac_bits - 2), hi = Raw{1} << P.dir_frac_bits;
  const Raw stride = std::max<Raw>(1, (hi - lo) / 20011);
  for (Raw r = lo; r <= hi; r += stride) {
    const auto m = hls::host::from_raw_bits<typename G::m_t>(r);
    const double y = hls::rsqrt_newton<ProfileTraits<P>>(m, rom->seed).to_double();
    worst = std::max(worst, std::fabs(y * std::sqrt(m.to_double()) - 1.0));
  }
  EXPECT_LE(worst, b.eps_norm);
}
TEST(GeometryProcessor, RsqrtWithinNewtonBound) {
  check_rsqrt_range<kVizard2>();
  check_rsqrt_range<kBalanced>();
  check_rsqrt_range<kPrecise>();
  check_rsqrt_range<kNarrowSeed>();
}

// ---- Host set-up -------------------------------------------------------------------------------
TEST(GeometrySetup, RsqrtSeedTable) {
  const PrecisionProfile p = kVizard2;
  const std::vector<Raw> seed = bittrue::make_rsqrt_seed(p);
  ASSERT_EQ(seed.size(), 64u);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(seed[static_cast<std::size_t>(i)], 0);
  // SEED[16] = Q_RND(1/sqrt(16.5/64), 20) and SEED[63] = Q_RND(1/sqrt(63.5/64), 20).
  EXPECT_EQ(seed[16], std::llround(std::ldexp(1.0 / std::sqrt(16.5 / 64.0), 20)));
  EXPECT_EQ(seed[63], std::llround(std::ldexp(1.0 / std::sqrt(63.5 / 64.0), 20)));
}

TEST(GeometrySetup, QuantizeRndTiesTowardPlusInfinity) {
  EXPECT_EQ(bittrue::quantize_rnd(1.25, 1), 3);    // 2.5 -> 3
  EXPECT_EQ(bittrue::quantize_rnd(-1.25, 1), -2);  // -2.5 -> -2
  EXPECT_EQ(bittrue::quantize_rnd(-0.75, 0), -1);
  EXPECT_EQ(bittrue::quantize_rnd(0.49999999999999994, 0), 0);  // y + 0.5 would round to 1
  EXPECT_EQ(bittrue::quantize_rnd(std::ldexp(1.0, 51) + 0.5, 0), (Raw{1} << 51) + 1);
  EXPECT_THROW(bittrue::quantize_rnd(std::numeric_limits<double>::infinity(), 0), Error);
}

TEST(GeometrySetup, RegistersOfAnAxisAlignedParallelCamera) {
  Case c;
  c.projection = ref::Projection::Parallel;
  c.dims = {5, 5, 5};
  c.eye = {2.0, -10.0, 2.0};
  c.center = {2.0, 2.0, 2.0};
  c.view_height = 5.0;
  c.width = c.height = 5;
  c.oversampling = 2.0;
  const auto f = make_frame(c);
  const bittrue::FrameRegisters r = bittrue::make_frame_registers(kVizard2, no_scene(), f->in);
  const int pf = kVizard2.pos_frac_bits, df = kVizard2.dir_frac_bits;
  EXPECT_FALSE(r.perspective);
  // The origin plane lies at the box's near face y = 0 (depth 10 from the eye, §0).
  EXPECT_EQ(r.origin_depth, 10.0);
  EXPECT_EQ(r.O, (bittrue::Raw3{0, 0, 4 << pf}));
  EXPECT_EQ(r.P, (bittrue::Raw3{1 << pf, 0, 0}));
  EXPECT_EQ(r.R, (bittrue::Raw3{0, 0, -(1 << pf)}));
  EXPECT_EQ(r.U, (bittrue::Raw3{0, 1 << df, 0}));
  EXPECT_EQ(r.K, (bittrue::Raw3{1 << (df - 1), 1 << (df - 1), 1 << (df - 1)}));
  EXPECT_EQ(r.LO, (std::array<int, 3>{0, 0, 0}));
  EXPECT_EQ(r.HI, (std::array<int, 3>{4, 4, 4}));
  // The ray of pixel (0, 0) runs along the edge x = 0, z = 4: 9 samples from y = 0.
  const bittrue::BtRay b = bittrue::bt_ray_setup(kVizard2, r, {}, 0, 0);
  EXPECT_TRUE(b.hit);
  EXPECT_EQ(b.n, 9u);
  EXPECT_EQ(b.p0, (std::array<double, 3>{0.0, 0.0, 4.0}));
  EXPECT_EQ(b.s, (std::array<double, 3>{0.0, 0.5, 0.0}));
}

TEST(GeometrySetup, AFarEyeMovesTheOriginPlaneToTheVolume) {
  // vizard2 holds origins within +-2^12 voxels; the eye 5000 voxels out is not
  // loaded at all: the rays start on the plane through the box's nearest corner.
  Case c;
  c.eye = {8.0, -5000.0, 8.0};
  c.center = {8.0, 8.0, 8.0};
  const auto f = make_frame(c);
  const bittrue::FrameRegisters r = bittrue::make_frame_registers(kVizard2, no_scene(), f->in);
  EXPECT_EQ(r.origin_depth, 5000.0);  // box y in [0, 16]: the near face y = 0
  EXPECT_EQ(r.O[1], 0) << "pixel (0, 0)'s origin lies on the plane y = 0";
  EXPECT_NE(r.P[0], 0) << "the perspective origin moves with the pixel";
  EXPECT_EQ(r.P[1], 0) << "the plane is y = 0 for every pixel";
}

TEST(GeometrySetup, RejectsACameraWhoseOriginPlaneLeavesTheOriginRegister) {
  // A 179-degree field of view 5000 voxels out: the corner pixels' rays spread
  // ~114 voxels sideways per voxel of depth. vizard2's register (+-2^12) holds
  // neither the eye (a plane at depth < 905) nor the spread of a plane beyond
  // depth 36: no plane fits and the host refuses the frame. precise (+-2^13)
  // holds the eye: the plane falls back towards it, to depth 71 (8 + 71·114·31/27
  // stays below 2^13 - 1), not to the volume at 5000.
  Case c;
  c.eye = {8.0, -5000.0, 8.0};
  c.center = {8.0, 8.0, 8.0};
  c.fov_deg = 179.0;
  const auto f = make_frame(c);
  EXPECT_THROW(bittrue::make_frame_registers(kVizard2, no_scene(), f->in), Error);
  const bittrue::FrameRegisters r = bittrue::make_frame_registers(kPrecise, no_scene(), f->in);
  const double spread = std::tan(89.5 * std::numbers::pi / 180.0) * 30.0 / 27.0;  // u of column 0
  EXPECT_NEAR(r.origin_depth, (8191.0 - 8.0) / spread, 1e-6 * r.origin_depth);
}

TEST(GeometrySetup, RejectsProfilesOutsideTheSpecConstraints) {
  PrecisionProfile p = kPrecise;
  p.t_frac_bits = 20;  // 10 + 22 + 20 > 49
  EXPECT_THROW(bittrue::make_rsqrt_seed(p), Error);
  p = kVizard2;
  p.rsqrt_seed_bits = 12;
  p.dir_frac_bits = 10;
  EXPECT_THROW(bittrue::make_rsqrt_seed(p), Error);
}

}  // namespace
