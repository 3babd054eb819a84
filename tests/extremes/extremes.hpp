// Shared helpers of the extremes suite (docs/extremes.md): one scene through the
// three engines (float reference, bit-true reference, hls kernels), the checks
// every case makes (finite, hls == bit-true, within a bound of the float
// reference derived from the widths), and the command line as a user runs it.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <glm/geometric.hpp>
#include <iostream>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include "cosim/engines/engines.hpp"
#include "refmodel/bittrue/geometry_bound.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "tests/common/error_of.hpp"
#include "tests/refmodel/render_fixtures.hpp"

namespace voxcast::test {

// --- Scenes ------------------------------------------------------------------------

// `scene` with the widths of preset `name`.
inline ref::Scene with_preset(ref::Scene scene, const std::string& name) {
  scene.precision = preset_profile(name);
  scene.precision_name = name;
  return scene;
}

// One material everywhere: a single transfer-function point (colour 0.5 grey,
// alpha `alpha`) and ka = 0.5, so the colour (0.5 unshaded, 0.5 * 0.5 shaded with
// a zero gradient) is exact in every width; ERT off. The camera is the test's.
inline ref::Scene material_scene(double alpha, ref::RenderMode mode = ref::RenderMode::Unshaded) {
  ref::Scene s;
  s.origin = "extremes";
  s.tf_points = {ref::TfPoint{0.0, {0.5, 0.5, 0.5}, alpha}};
  s.material.ka = 0.5;
  s.render.mode = mode;
  s.render.ert_threshold = 1.0;
  s.render.width = s.render.height = 16;
  s.lights = {ref::Light{}};
  // The one-material bound below is derived for whole samples (1 - (1 - a)^n);
  // partial segments have their closed form and bound in tests/segments/.
  s.render.partial_segments = false;
  return s;
}

// --- One scene through the three engines --------------------------------------------

struct Rendered {
  std::shared_ptr<cosim::SceneVolume> sv;  // RenderInputs point into it
  ref::Scene scene;
  ref::RenderInputs in;
  bittrue::FrameSetup setup;
  bittrue::VoxelMemory memory;
  ref::Image truth;         // float reference
  ref::QuantImage bt, hls;  // bit-true reference, hls kernels
};

// Throws voxcast::Error where the host would (check_fixed_point, make_frame_registers).
inline Rendered run_engines(const ref::Scene& scene, ref::Volume volume) {
  Rendered r;
  r.scene = scene;
  r.sv = std::make_shared<cosim::SceneVolume>();
  r.sv->volume = std::move(volume);
  r.sv->gradients = ref::compute_gradients(r.sv->volume, scene.volume.gradient);
  cosim::check_fixed_point(scene, *r.sv, true);
  r.in = ref::make_render_inputs(scene, r.sv->volume, r.sv->gradients, scene.camera.pose);
  r.setup = bittrue::make_frame_setup(scene.precision, scene, r.in);
  r.memory = bittrue::make_voxel_memory(scene.precision, r.sv->volume, r.sv->gradients);
  r.truth = ref::render_image(r.in, 2);
  r.bt = bittrue::bt_render_image(r.setup, r.memory, 2);
  r.hls = cosim::hls_render_image(r.setup, r.memory, 2);
  return r;
}

// No NaN or infinity anywhere in the float reference's image.
inline void expect_finite(const ref::Image& img, const std::string& what) {
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 4; ++c)
        if (!std::isfinite(img.at(x, y)[c])) {
          ADD_FAILURE() << what << ": float pixel (" << x << ", " << y << ") channel " << c
                        << " is " << img.at(x, y)[c];
          return;
        }
}

// hls == bit-true on every bit; on a mismatch, the first pixel and the unit.
inline void expect_bit_exact(const Rendered& r, const std::string& what) {
  ASSERT_EQ(r.hls.pixels.size(), r.bt.pixels.size()) << what;
  for (int y = 0; y < r.hls.height; ++y)
    for (int x = 0; x < r.hls.width; ++x)
      if (r.hls.at(x, y) != r.bt.at(x, y)) {
        bittrue::RayTrace t;
        bittrue::bt_cast_ray(r.setup, r.memory, x, y, &t);
        const auto d = bittrue::first_divergence(cosim::hls_trace_ray(r.setup, r.memory, x, y), t);
        FAIL() << what << ": hls != bit-true at pixel (" << x << ", " << y << "), sample "
               << d.sample << ", first in the " << bittrue::to_string(d.unit);
      }
}

// One pixel's per-sample trace from the bit-true engine, checked equal to the hls
// engine's. Only for rays that hit: a missed ray's traces differ in the recorded step
// vector (bit-true records s, the hls recorder 0; see Extremes.MissedRayTracesAgree),
// although both engines output (0, 0, 0, 0).
inline bittrue::RayTrace traced(const Rendered& r, int x, int y, const std::string& what) {
  bittrue::RayTrace t;
  bittrue::bt_cast_ray(r.setup, r.memory, x, y, &t);
  if (!t.hit) return t;
  const bittrue::Divergence d =
      bittrue::first_divergence(cosim::hls_trace_ray(r.setup, r.memory, x, y), t);
  EXPECT_FALSE(d.diverged) << what << ": hls and bit-true traces of pixel (" << x << ", " << y
                           << ") differ at sample " << d.sample << " in the "
                           << bittrue::to_string(d.unit);
  return t;
}

// |fixed - float| of one channel in output LSBs (docs/pipeline.md §8).
inline double error_lsb(const Rendered& r, int x, int y, int c) {
  return std::abs(static_cast<double>(r.bt.at(x, y)[static_cast<std::size_t>(c)]) -
                  r.truth.at(x, y)[c] * r.bt.full_scale());
}

inline std::uint64_t float_sample_count(const Rendered& r, int x, int y) {
  const auto seg = ref::clip(ref::primary_ray(r.in.camera, x, y), r.in.volume.world_box);
  return seg ? ref::sample_count(*seg, r.in.settings.step) : 0;
}

inline std::uint64_t fixed_sample_count(const Rendered& r, int x, int y) {
  const bittrue::BtRay ray = bittrue::bt_ray_setup(r.setup, x, y);
  return ray.hit ? ray.n : 0;
}

// --- Ray origins and directions against the float reference's -----------------------------
// The bounds are the library's (refmodel/bittrue/geometry_bound.hpp, where each is
// derived): the precision guard predicts a scene's worst case from the same ones.
inline double direction_bound(const PrecisionProfile& p, const ref::CameraFrame& cam, int x,
                              int y) {
  return bittrue::direction_error_bound(p, cam, x, y);
}
inline double origin_bound(const PrecisionProfile& p, int x, int y) {
  return bittrue::origin_error_bound(p, x, y);
}

// Pixel (x, y)'s float ray from the frame's origin plane.
inline ref::Ray plane_ray(const Rendered& r, int x, int y) {
  return ref::origin_plane_ray(r.in.camera, x, y, r.setup.regs.origin_depth);
}

// The sample counts a fixed-point ray may take. Its line stays within
//   delta(t) = origin_bound * max(world_scale) + t * direction_bound   (world units)
// of the float ray's, per component, so its chord lies between the float ray's chords
// through the volume's box shrunk and grown by delta(t_far) (t_far: the farthest box
// corner's distance from the ray origin, plus one). The step vector's relative error
// rho = sqrt 3 es / |s| (es = 2^-(pf+1) + max K * direction_bound) scales the count,
// and the clip's truncations to t_frac_bits and the floor add one sample each way.
// Away from the silhouette the range is the float count +-1; a ray grazing a face or
// an edge within delta may hit or miss.
struct CountRange {
  std::uint64_t lo = 0, hi = 0;
};

inline CountRange count_range(const Rendered& r, int x, int y) {
  const PrecisionProfile& p = r.scene.precision;
  const ref::CameraFrame& cam = r.in.camera;
  const ref::Vec3 ws = r.in.volume.world_scale;
  const double ws_max = std::max({ws.x, ws.y, ws.z});
  const ref::Ray ray = plane_ray(r, x, y);
  const ref::Box& box = r.in.volume.world_box;
  double t_far = 0.0;
  for (int c = 0; c < 8; ++c) {
    const ref::Vec3 corner{(c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y,
                           (c & 4) ? box.hi.z : box.lo.z};
    t_far = std::max(t_far, glm::length(corner - ray.origin));
  }
  t_far += 1.0;
  const double du = direction_bound(p, cam, x, y);
  const double delta = origin_bound(p, x, y) * ws_max + t_far * du;
  const double step = r.in.settings.step;
  const auto count = [&](const ref::Vec3& lo, const ref::Vec3& hi) -> double {
    if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) return 0.0;
    const auto seg = ref::clip(ray, ref::Box{lo, hi});
    return seg ? static_cast<double>(ref::sample_count(*seg, step)) : 0.0;
  };
  const double n_shrunk = count(box.lo + delta, box.hi - delta);
  const double n_grown = count(box.lo - delta, box.hi + delta);
  double K = 0.0;
  for (int k = 0; k < 3; ++k) K = std::max(K, step / ws[k]);
  const double es = std::ldexp(1.0, -(p.pos_frac_bits + 1)) + K * du;
  const double rho = std::sqrt(3.0) * es / (step / ws_max);
  CountRange out;
  out.lo = static_cast<std::uint64_t>(std::max(0.0, std::floor(n_shrunk * (1.0 - rho)) - 1.0));
  out.hi = static_cast<std::uint64_t>(std::ceil(n_grown * (1.0 + rho)) + 1.0);
  return out;
}

// --- The bound of a one-material image ----------------------------------------------
//
// Every sample classifies to one colour c and one alpha (a constant volume, or a
// transfer function with a single point), ERT off. The float pixel after n_f
// samples is A_f = 1 - (1 - a_s)^n_f, C_f = c * A_f, with a_s = 1 - (1 - alpha)^step.
// The fixed-point pixel after n_x samples (its own ray setup) differs by at most
//   (1) alpha quantization, §4.2: a_c = U(a_s, alpha_bits), |a_c - a_s| <= da with
//       da = 2^-(alpha_bits+1), or a_s - (1 - 2^-alpha_bits) where U saturates;
//       by the mean value theorem on 1 - (1 - a)^n (derivative n (1 - a)^(n-1),
//       largest at the smaller alpha a_lo = max(0, a_s - da)):
//       n (1 - a_lo)^(n-1) da, n = max(n_f, n_x);
//   (2) a different sample count: |A_f(n_x) - A_f(n_f)| = (1 - a_s)^m (1 - (1 - a_s)^|dn|),
//       m = min(n_f, n_x) (exact);
//   (3) accumulator rounding, §7: each w = Q_RND((1-A) a_c, acc_bits) is off by
//       <= 2^-(acc_bits+1), and an error of A is damped by (1 - a_c) per step, so A is
//       off by <= min(n_x, 1/a_c) 2^-(acc_bits+1) (the geometric series); C = sum of
//       Q_RND(w c, acc_bits) adds one undamped rounding per sample, n_x 2^-(acc_bits+1);
//   (4) the colour, colour channels only: U(c, color_bits), ka as U(., k_bits), the
//       shader's Q_RND/U at shade_bits: <= 2^-(color_bits+1) + 2^-(k_bits+1) + 2^-shade_bits;
//   (5) output rounding §8: 1/2 LSB.
// In LSBs: (2^out_bits - 1) ((1) + (2) + (3) + (4)) + 1/2.
// The sample counts: within count_range of the float ray's; `exact_counts` demands
// n_x = n_f (every register exact).
struct MaterialBound {
  double max_error_lsb = 0.0;  // largest |fixed - float| over pixels and channels
  double max_bound_lsb = 0.0;  // largest bound
  int max_count_diff = 0;      // largest |n_x - n_f| over pixels
  int hit_pixels = 0;          // pixels the fixed-point rays hit
};

inline MaterialBound expect_material_within_bound(const Rendered& r, const std::string& what,
                                                  bool exact_counts = false) {
  const PrecisionProfile& p = r.scene.precision;
  const ref::Volume& v = r.sv->volume;
  const ref::Classified cl = r.in.tf.classify(v.data.front());
  for (std::uint16_t value : v.data)
    if (r.in.tf.classify(value).alpha != cl.alpha) {
      ADD_FAILURE() << what << ": not a one-material scene";
      return {};
    }
  const double step = r.in.settings.step;
  const double a_s = ref::opacity_correct(cl.alpha, step);
  const double da =
      std::max(std::ldexp(1.0, -(p.alpha_bits + 1)), a_s - (1.0 - std::ldexp(1.0, -p.alpha_bits)));
  const double a_lo = std::max(0.0, a_s - da);
  const double a_c = bittrue::u_frac(a_s, p.alpha_bits);  // the table's alpha
  const double acc_half = std::ldexp(1.0, -(p.acc_bits + 1));
  const double dc = std::ldexp(1.0, -(p.color_bits + 1)) + std::ldexp(1.0, -(p.k_bits + 1)) +
                    std::ldexp(1.0, -p.shade_bits);
  const double F = r.bt.full_scale();
  MaterialBound out;
  for (int y = 0; y < r.bt.height; ++y)
    for (int x = 0; x < r.bt.width; ++x) {
      const std::uint64_t nf = float_sample_count(r, x, y), nx = fixed_sample_count(r, x, y);
      const std::uint64_t n = std::max(nf, nx), m = std::min(nf, nx);
      const int dn = static_cast<int>(n - m);
      out.max_count_diff = std::max(out.max_count_diff, dn);
      out.hit_pixels += nx > 0 ? 1 : 0;
      const CountRange range = exact_counts ? CountRange{nf, nf} : count_range(r, x, y);
      EXPECT_TRUE(nx >= range.lo && nx <= range.hi)
          << what << ": pixel (" << x << ", " << y << ") float " << nf << " samples, fixed " << nx
          << ", allowed " << range.lo << ".." << range.hi;
      const double nd = static_cast<double>(n);
      const double t1 = n > 0 ? nd * std::pow(1.0 - a_lo, nd - 1.0) * da : 0.0;
      const double t2 = std::pow(1.0 - a_s, static_cast<double>(m)) *
                        (1.0 - std::pow(1.0 - a_s, static_cast<double>(dn)));
      const double ta = a_c > 0.0 ? std::min(static_cast<double>(nx), 1.0 / a_c) * acc_half : 0.0;
      const double tc = a_c > 0.0 ? static_cast<double>(nx) * acc_half + dc : 0.0;
      for (int c = 0; c < 4; ++c) {
        const double bound = F * (t1 + t2 + ta + (c < 3 ? tc : 0.0)) + 0.5;
        const double e = error_lsb(r, x, y, c);
        out.max_error_lsb = std::max(out.max_error_lsb, e);
        out.max_bound_lsb = std::max(out.max_bound_lsb, bound);
        EXPECT_LE(e, bound) << what << ": pixel (" << x << ", " << y << ") channel " << c
                            << ", float " << r.truth.at(x, y)[c] * F << " LSB, fixed "
                            << r.bt.at(x, y)[static_cast<std::size_t>(c)] << ", samples float "
                            << nf << " fixed " << nx;
      }
    }
  return out;
}

struct RayCheck {
  double max_error = 0.0;         // largest |u_fixed - u_float| over pixels and components
  double max_error_ratio = 0.0;   // largest error / bound
  double max_origin_error = 0.0;  // largest |o_fixed - o_float| (index space)
};

// The fixed-point ray origin and unit direction of every pixel against the float
// reference's (origin_bound, direction_bound).
inline RayCheck expect_rays_within_bound(const Rendered& r, const std::string& what) {
  RayCheck out;
  const int df = r.scene.precision.dir_frac_bits;
  for (int y = 0; y < r.bt.height; ++y)
    for (int x = 0; x < r.bt.width; ++x) {
      const ref::Ray ray = plane_ray(r, x, y);
      std::array<double, 3> u{};
      if (r.setup.regs.perspective) {
        u = bittrue::bt_unit_direction(r.setup.profile, r.setup.regs, r.setup.rsqrt_seed, x, y);
      } else {
        for (std::size_t k = 0; k < 3; ++k)
          u[k] = std::ldexp(static_cast<double>(r.setup.regs.U[k]), -df);
      }
      const std::array<double, 3> o = bittrue::bt_ray_origin(r.setup.profile, r.setup.regs, x, y);
      const double ob = origin_bound(r.scene.precision, x, y);
      for (int k = 0; k < 3; ++k) {
        const double e =
            std::abs(o[static_cast<std::size_t>(k)] - ray.origin[k] / r.in.volume.world_scale[k]);
        out.max_origin_error = std::max(out.max_origin_error, e);
        EXPECT_LE(e, ob) << what << ": pixel (" << x << ", " << y << ") origin component " << k;
      }
      const double bound = direction_bound(r.scene.precision, r.in.camera, x, y);
      for (int k = 0; k < 3; ++k) {
        const double e = std::abs(u[static_cast<std::size_t>(k)] - ray.direction[k]);
        out.max_error = std::max(out.max_error, e);
        out.max_error_ratio = std::max(out.max_error_ratio, e / bound);
        EXPECT_LE(e, bound) << what << ": pixel (" << x << ", " << y << ") direction component "
                            << k << " fixed " << u[static_cast<std::size_t>(k)] << " float "
                            << ray.direction[k];
      }
    }
  return out;
}

// A measured figure for docs/extremes.md, printed and recorded in the XML report.
inline void measured(const std::string& key, const std::string& text) {
  // The XML report holds the key as an attribute name: letters, digits and '_' only.
  std::string name = "measured_";
  for (char c : key) name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  ::testing::Test::RecordProperty(name, text);
  std::cout << "[ measured ] " << key << ": " << text << "\n";
}

inline std::string fmt(double x, int precision = 4) {
  std::ostringstream os;
  os.precision(precision);
  os << x;
  return os.str();
}

// --- Whole images: one material, every preset ---------------------------------------
//
// A constant volume and one material (extremes.hpp material_scene, alpha 0.05 unless
// stated): the image depends only on each ray's sample count, so each case asserts
// finite pixels, hls == bit-true, every ray origin and direction within its bound of
// the float reference's (origin_bound, direction_bound), every sample count within its
// count_range (equal to the float's where every register is exact: `exact_counts`),
// and every pixel within the one-material bound (expect_material_within_bound).
struct Outcome {
  MaterialBound bound;
  RayCheck dirs;
};

inline Outcome check_case(const ref::Scene& scene, const ref::Volume& v, const std::string& what,
                          bool exact_counts = false) {
  const Rendered r = run_engines(scene, v);
  expect_finite(r.truth, what);
  expect_bit_exact(r, what);
  Outcome o;
  o.dirs = expect_rays_within_bound(r, what);
  o.bound = expect_material_within_bound(r, what, exact_counts);
  return o;
}

// Every preset; one measured line per preset.
inline void check_presets(const ref::Scene& scene, const ref::Volume& v, const std::string& what,
                          bool exact_counts = false) {
  for (const std::string& name : preset_names()) {
    const Outcome o = check_case(with_preset(scene, name), v, what + ", " + name, exact_counts);
    measured(what + ", " + name, "max error " + fmt(o.bound.max_error_lsb) + " LSB (bound " +
                                     fmt(o.bound.max_bound_lsb) + "), max |dn| " +
                                     std::to_string(o.bound.max_count_diff) + ", " +
                                     std::to_string(o.bound.hit_pixels) +
                                     " rays hit, direction error " + fmt(o.dirs.max_error) + " (" +
                                     fmt(100.0 * o.dirs.max_error_ratio, 3) + "% of its bound)");
  }
}

inline ref::Scene parallel_scene(const ref::CameraPose& pose, double height, int w, int h,
                                 double oversampling = 1.0) {
  ref::Scene s = material_scene(0.05);
  s.camera.projection = ref::Projection::Parallel;
  s.camera.pose = pose;
  s.camera.height = height;
  s.render.width = w;
  s.render.height = h;
  s.render.oversampling = oversampling;
  return s;
}

inline ref::Scene perspective_scene(const ref::CameraPose& pose, double fov, int w, int h,
                                    double oversampling = 1.0) {
  ref::Scene s = material_scene(0.05);
  s.camera.pose = pose;
  s.camera.fov_deg = fov;
  s.render.width = w;
  s.render.height = h;
  s.render.oversampling = oversampling;
  return s;
}

// The MIP image of a constant volume V: grey V / max_stored wherever the ray hits.
// Fixed: M = V 2^shift exactly, RM = Q_RND(1 / (max_stored 2^shift), df), so
// |M RM - V / max_stored| <= M 2^-(df+1); Q_RND to acc_bits and the output add
// 2^-(acc_bits+1) and 1/2 LSB. Alpha is exact when both engines agree on the hit.
inline void expect_mip_within_bound(const ref::Scene& scene, const ref::Volume& v,
                                    const std::string& what) {
  ref::Scene s = scene;
  s.render.mode = ref::RenderMode::Mip;
  const Rendered r = run_engines(s, v);
  expect_finite(r.truth, what);
  expect_bit_exact(r, what);
  const PrecisionProfile& p = s.precision;
  const double M = std::ldexp(static_cast<double>(v.data.front()), bittrue::value_shift(p, v));
  const double bound = r.bt.full_scale() * (M * std::ldexp(1.0, -(p.dir_frac_bits + 1)) +
                                            std::ldexp(1.0, -(p.acc_bits + 1))) +
                       0.5;
  for (int y = 0; y < r.bt.height; ++y)
    for (int x = 0; x < r.bt.width; ++x) {
      ASSERT_EQ(fixed_sample_count(r, x, y) > 0, float_sample_count(r, x, y) > 0)
          << what << " pixel (" << x << ", " << y << "): hit differs";
      for (int c = 0; c < 3; ++c) EXPECT_LE(error_lsb(r, x, y, c), bound) << what;
      EXPECT_EQ(error_lsb(r, x, y, 3), 0.0) << what;
    }
}

// --- The command line ---------------------------------------------------------------

// A fresh folder for one test's files, removed when the program ends.
struct ScratchDirs {
  std::mutex mutex;
  std::vector<std::filesystem::path> dirs;
  ~ScratchDirs() {
    std::error_code ec;
    for (const auto& d : dirs) std::filesystem::remove_all(d, ec);
  }
};

inline std::filesystem::path scratch_dir() {
  static ScratchDirs all;
  static std::atomic<int> counter{0};
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto d = std::filesystem::temp_directory_path() /
                 ("voxcast_extremes_" + std::string(info ? info->name() : "x") + "_" +
                  std::to_string(::getpid()) + "_" + std::to_string(counter++));
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  const std::lock_guard<std::mutex> lock(all.mutex);
  all.dirs.push_back(d);
  return d;
}

struct Command {
  int status = -1;  // exit code; -1 if killed by a signal
  int signal = 0;
  std::string out, err;
};

// Runs `voxcast ARGS` with stdout and stderr captured separately.
inline Command voxcast(const std::string& args) {
  const auto dir = scratch_dir();
  const std::string cmd = std::string(VOXCAST_EXE) + " " + args + " >" + (dir / "out").string() +
                          " 2>" + (dir / "err").string();
  const int raw = std::system(cmd.c_str());
  Command r;
  if (WIFEXITED(raw)) r.status = WEXITSTATUS(raw);
  if (WIFSIGNALED(raw)) r.signal = WTERMSIG(raw);
  const auto slurp = [](const std::filesystem::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  r.out = slurp(dir / "out");
  r.err = slurp(dir / "err");
  std::filesystem::remove_all(dir);
  return r;
}

// Several independent invocations at once (the command's start-up dominates their
// time); results in the order of `args`.
inline std::vector<Command> voxcast_all(const std::vector<std::string>& args) {
  std::vector<std::future<Command>> running;
  for (const std::string& a : args) running.push_back(std::async(std::launch::async, voxcast, a));
  std::vector<Command> out;
  for (auto& f : running) out.push_back(f.get());
  return out;
}

inline void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
}

}  // namespace voxcast::test
