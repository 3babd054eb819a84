// Extremes of the geometry processor (docs/pipeline.md §0-2): the position drift of
// the longest ray, rays along axes, faces, edges and through corners, eyes on and
// inside the volume, fields of view near 0 and 180 degrees, extreme zoom, and
// images of one pixel and of extreme aspect ratios. docs/extremes.md lists every
// case with its measured result.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "extremes.hpp"
#include "hls/geometry_processor.hpp"
#include "refmodel/precision/preset_profiles.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

// --- Position drift ------------------------------------------------------------------
//
// Stepping is exact (p[j+1] = p[j] + s, §2), so the fixed-point position after j steps
// is off the exact ray by the start error e0 plus j times the step vector's error,
// per component
//   es = 2^-(pf+1)            (s = Q_RND(u K, pf))
//      + K eu                 (u's error, extremes.hpp direction_bound; K = step /
//                              world_scale = 1/16 here, exact, so K adds nothing).
// The rays below start on a corner of the volume exactly (eye or view plane on the
// corner, k_in = 0): e0 = 0.

// A 512^3 volume for the geometry processor only (no voxel data).
ref::Volume synthetic_volume(int n) {
  ref::Volume v;
  v.dims = {n, n, n};
  v.bits = 8;
  v.source = "synthetic " + std::to_string(n) + "^3 (geometry only)";
  return v;
}

struct Setup {
  std::shared_ptr<cosim::SceneVolume> sv;
  ref::RenderInputs in;
  bittrue::FrameSetup fs;
};

Setup geometry_setup(const ref::Scene& s, const ref::Volume& v) {
  Setup g;
  g.sv = std::make_shared<cosim::SceneVolume>();
  g.sv->volume = v;
  g.in = ref::make_render_inputs(s, g.sv->volume, g.sv->gradients, s.camera.pose);
  g.fs = bittrue::make_frame_setup(s.precision, s, g.in);
  return g;
}

struct Drift {
  std::uint64_t n_fixed = 0, n_float = 0;
  double err_end = 0.0, bound_end = 0.0;  // at the last sample both take
  double max_err = 0.0;
  double min_step = 0.0;  // smallest |s[a]|
};

// One ray through hls::ray_setup / hls::step_position and bittrue::bt_ray_setup /
// bt_step (bit-exact at every step) against the float reference's sample positions.
template <PrecisionProfile P>
Drift drift(const Setup& g, int px, int py, double es, const std::string& what) {
  using G = hls::GeometryParams<ProfileTraits<P>>;
  const hls::GeometryRegisters<ProfileTraits<P>> regs = hls::host::load_geometry_registers<ProfileTraits<P>>(g.fs.regs);
  auto rom = std::make_unique<hls::RsqrtRom<ProfileTraits<P>>>();
  if (g.fs.regs.perspective) hls::host::load_rsqrt_rom<ProfileTraits<P>>(g.fs.rsqrt_seed, *rom);
  const hls::RaySetup<ProfileTraits<P>> ray = hls::ray_setup<ProfileTraits<P>>(regs, rom->seed, px, py);
  const bittrue::BtRay bt = bittrue::bt_ray_setup(g.fs, px, py);
  Drift d;
  EXPECT_TRUE(bt.hit) << what;
  EXPECT_EQ(ray.hit, bt.hit) << what;
  if (!bt.hit || !ray.hit) return d;
  EXPECT_EQ(ray.n.to_uint64(), bt.n) << what;
  d.min_step = 1e9;
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(ray.p0[k].to_double(), bt.p0[k]) << what;
    EXPECT_EQ(ray.s[k].to_double(), bt.s[k]) << what;
    EXPECT_EQ(bt.p0[k], 0.0) << what << ": the ray must start on the corner";
    d.min_step = std::min(d.min_step, std::abs(bt.s[k]));
  }
  const ref::Ray fr = ref::primary_ray(g.in.camera, px, py);
  const auto seg = ref::clip(fr, g.in.volume.world_box);
  EXPECT_TRUE(seg && seg->t_enter == 0.0) << what;
  if (!seg) return d;
  const double step = g.in.settings.step;
  d.n_float = ref::sample_count(*seg, step);
  d.n_fixed = bt.n;
  typename G::pos_t p[3] = {ray.p0[0], ray.p0[1], ray.p0[2]};
  std::array<double, 3> q = bt.p0;
  const std::uint64_t n = std::min(d.n_fixed, d.n_float);
  std::uint64_t mismatches = 0;
  for (std::uint64_t j = 0; j < n; ++j) {
    if (j > 0) {
      hls::step_position<ProfileTraits<P>>(p, ray.s);
      q = bittrue::bt_step(q, bt.s);
    }
    const ref::Vec3 x =
        fr.at(seg->t_enter + static_cast<double>(j) * step) / g.in.volume.world_scale;
    double err = 0.0;
    for (std::size_t k = 0; k < 3; ++k) {
      mismatches += p[k].to_double() != q[k] ? 1 : 0;
      err = std::max(err, std::abs(q[k] - x[static_cast<int>(k)]));
    }
    // 1e-9: the float reference's own rounding over 14000 steps of t (t_enter + j step
    // is computed afresh per sample; its error is a few ulp of 900).
    const double bound = static_cast<double>(j) * es + 1e-9;
    EXPECT_LE(err, bound) << what << " sample " << j;
    if (err > bound) break;
    d.max_err = std::max(d.max_err, err);
    d.err_end = err;
    d.bound_end = bound;
  }
  EXPECT_EQ(mismatches, 0u) << what << ": hls and bit-true positions differ";
  return d;
}

template <PrecisionProfile P>
void drift_longest_ray(const std::string& name) {
  // Parallel, 1x1: the one ray runs along the diagonal of the 512^3 volume from voxel
  // (0,0,0) to (511,511,511), 16 * 511 sqrt(3) + 1 = 14162 samples. U = Q_RND(forward,
  // df) is off by <= 2^-(df+1) per component.
  ref::Scene s = with_preset(material_scene(0.5), name);
  s.camera.projection = ref::Projection::Parallel;
  s.camera.height = 1.0;
  s.camera.pose = {{0.0, 0.0, 0.0}, {511.0, 511.0, 511.0}, {0.0, 0.0, 1.0}};
  s.render.width = s.render.height = 1;
  s.render.oversampling = 16.0;
  const Setup g = geometry_setup(s, synthetic_volume(512));
  const double es = std::ldexp(1.0, -(P.pos_frac_bits + 1)) +
                    (1.0 / 16.0) * std::ldexp(1.0, -(P.dir_frac_bits + 1));
  const Drift d = drift<P>(g, 0, 0, es, name + " diagonal");
  // The sample count: k_out = 511 / s[a] (truncated to tf bits) is off the exact
  // 511 / s_exact[a] by k es / |s[a]| + 2^-tf, and n = floor(k_out) + 1.
  const double dk =
      static_cast<double>(d.n_float) * es / d.min_step + std::ldexp(1.0, -P.t_frac_bits);
  const auto dn =
      static_cast<double>(std::max(d.n_fixed, d.n_float) - std::min(d.n_fixed, d.n_float));
  EXPECT_LE(dn, std::floor(dk) + 1.0) << name;
  measured("drift of the 512^3 diagonal at 16x, " + name,
           std::to_string(d.n_fixed) + " samples (float " + std::to_string(d.n_float) +
               "), position error at the end " + fmt(d.err_end) + " voxel, bound " +
               fmt(d.bound_end) + " (n 2^-(pf+1) = " +
               fmt(static_cast<double>(d.n_fixed) * std::ldexp(1.0, -(P.pos_frac_bits + 1))) +
               " + step-vector rounding)");
}

TEST(Extremes, PositionDriftLongestRay) {
  drift_longest_ray<kVizard2>("vizard2");
  drift_longest_ray<kBalanced>("balanced");
  drift_longest_ray<kPrecise>("precise");
}

template <PrecisionProfile P>
void drift_perspective_corners(const std::string& name) {
  // The eye on the volume's corner (0,0,0) looking along the diagonal, fov 30: the four
  // corner pixels' rays are the image's longest and least precise (the pixel direction
  // A + px B + py C collects px + py register roundings), all starting at the eye.
  for (int size : {256, 2048, 8192}) {
    ref::Scene s = with_preset(material_scene(0.5), name);
    s.camera.fov_deg = 30.0;
    s.camera.pose = {{0.0, 0.0, 0.0}, {511.0, 511.0, 511.0}, {0.0, 0.0, 1.0}};
    s.render.width = s.render.height = size;
    s.render.oversampling = 16.0;
    const Setup g = geometry_setup(s, synthetic_volume(512));
    double worst_err = 0.0, worst_bound = 0.0;
    std::uint64_t longest = 0;
    for (const auto& [px, py] : {std::pair{0, 0}, std::pair{size - 1, 0}, std::pair{0, size - 1},
                                 std::pair{size - 1, size - 1}}) {
      const double es = std::ldexp(1.0, -(P.pos_frac_bits + 1)) +
                        (1.0 / 16.0) * direction_bound(P, g.in.camera, px, py);
      const std::string what = name + " " + std::to_string(size) + "^2 corner (" +
                               std::to_string(px) + ", " + std::to_string(py) + ")";
      const Drift d = drift<P>(g, px, py, es, what);
      const double dk =
          static_cast<double>(d.n_float) * es / d.min_step + std::ldexp(1.0, -P.t_frac_bits);
      const auto dn =
          static_cast<double>(std::max(d.n_fixed, d.n_float) - std::min(d.n_fixed, d.n_float));
      EXPECT_LE(dn, std::floor(dk) + 1.0) << what;
      if (d.err_end > worst_err) {
        worst_err = d.err_end;
        worst_bound = d.bound_end;
      }
      longest = std::max(longest, d.n_fixed);
    }
    measured("drift of perspective corner rays, " + name + " " + std::to_string(size) + "^2",
             "worst position error at the end " + fmt(worst_err) + " voxel (bound " +
                 fmt(worst_bound) + "), longest ray " + std::to_string(longest) + " samples");
  }
}

TEST(Extremes, PositionDriftPerspectiveCorners) {
  drift_perspective_corners<kVizard2>("vizard2");
  drift_perspective_corners<kBalanced>("balanced");
  drift_perspective_corners<kPrecise>("precise");
}

// --- Whole images at geometric extremes (helpers: extremes.hpp check_presets) ---------

TEST(Extremes, RaysAlongAxesFacesAndEdges) {
  // Parallel rays along +y, +x and -z of an 8^3 volume, pixel centres on the integer
  // grid (10x10, view height 10): rows and columns 1 and 8 run exactly along the faces,
  // the four corner pixels of that square along the edges, and two direction
  // components are exactly 0. At oversampling 1 every register is exact, so the fixed
  // point and the float reference take the same samples (dn = 0) and hit the same 64
  // pixels; at oversampling 3 (K = Q_RND(1/3, df)) the counts stay within count_range.
  const ref::Volume v = constant_volume(8, 100);
  const ref::CameraPose poses[] = {{{3.5, -4.0, 3.5}, {3.5, 3.5, 3.5}, {0.0, 0.0, 1.0}},
                                   {{-4.0, 3.5, 3.5}, {3.5, 3.5, 3.5}, {0.0, 0.0, 1.0}},
                                   {{3.5, 3.5, 12.0}, {3.5, 3.5, 3.5}, {0.0, 1.0, 0.0}}};
  const char* const axis[] = {"+y", "+x", "-z"};
  for (int a = 0; a < 3; ++a) {
    for (const std::string& name : preset_names()) {
      const std::string what = std::string("along ") + axis[a] + ", " + name;
      const ref::Scene s = with_preset(parallel_scene(poses[a], 10.0, 10, 10), name);
      const Outcome o = check_case(s, v, what, true);
      EXPECT_EQ(o.bound.hit_pixels, 64) << what;
      EXPECT_EQ(o.dirs.max_error, 0.0) << what;
      expect_mip_within_bound(s, v, what + " mip");
    }
    check_presets(parallel_scene(poses[a], 10.0, 10, 10, 3.0), v,
                  std::string("along ") + axis[a] + " at oversampling 3");
  }
}

TEST(Extremes, RaysThroughEdgesAndCorners) {
  // The 8^3 volume: (a) parallel along (1,1,0), the centre column (9 wide) through the
  // vertical edges x = y = 0 and x = y = 7, rows 1 and 8 along the faces z = 7 and 0;
  // (b) parallel along the body diagonal, the centre pixel through the corners (0,0,0)
  // and (7,7,7); (c) the same in perspective from the diagonal's extension. The
  // directions are irrational: counts within count_range.
  const ref::Volume v = constant_volume(8, 100);
  check_presets(parallel_scene({{-4.0, -4.0, 3.5}, {3.5, 3.5, 3.5}, {0.0, 0.0, 1.0}}, 10.0, 9, 10),
                v, "parallel along (1,1,0) through edges");
  check_presets(parallel_scene({{-4.0, -4.0, -4.0}, {3.5, 3.5, 3.5}, {0.0, 0.0, 1.0}}, 9.0, 9, 9),
                v, "parallel along (1,1,1) through corners");
  check_presets(
      perspective_scene({{-2.0, -2.0, -2.0}, {3.5, 3.5, 3.5}, {0.0, 0.0, 1.0}}, 60.0, 9, 9), v,
      "perspective along (1,1,1) through corners");
}

TEST(Extremes, PerspectiveCentreRayAlongAxis) {
  // Odd images centred on an axis: the float reference's centre ray has two direction
  // components of exactly 0; the fixed-point d = A + 4 B + 4 C need not cancel to 0,
  // leaving components of a few 2^-df, whose step components Q_RND(u K, pf) may be a
  // tiny non-zero s (clip quotients (LO - o)/s near 2^(a+pf)). Eyes on the axis through
  // the volume's centre and off it, fov 30 and 1.
  const ref::Volume v = constant_volume(8, 100);
  check_presets(
      perspective_scene({{3.5, -10.0, 3.5}, {3.5, 3.5, 3.5}, {0.0, 0.0, 1.0}}, 30.0, 9, 9), v,
      "perspective centre ray along +y");
  check_presets(perspective_scene({{3.3, -10.0, 3.6}, {3.3, 3.5, 3.6}, {0.0, 0.0, 1.0}}, 1.0, 9, 9),
                v, "perspective centre ray along +y, fov 1");
  check_presets(perspective_scene({{3.5, 3.5, -9.0}, {3.5, 3.5, 3.5}, {0.0, 1.0, 0.0}}, 30.0, 9, 9),
                v, "perspective centre ray along +z");
}

TEST(Extremes, EyeOnVolumeBoundary) {
  // The eye on the face x = 0 of a 16^3 volume looking in (+x) and out (-x), and on the
  // corner (0,0,0). Looking out, every ray's chord is the eye itself: one sample at
  // t = 0 in both engines (k_in = k_out = 0).
  const ref::Volume v = constant_volume(16, 100);
  check_presets(
      perspective_scene({{0.0, 7.5, 7.5}, {15.0, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 60.0, 16, 16), v,
      "eye on a face looking in");
  check_presets(
      perspective_scene({{0.0, 7.5, 7.5}, {-15.0, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 60.0, 16, 16), v,
      "eye on a face looking out", true);
  check_presets(
      perspective_scene({{0.0, 0.0, 0.0}, {15.0, 15.0, 15.0}, {0.0, 0.0, 1.0}}, 60.0, 16, 16), v,
      "eye on a corner");
}

TEST(Extremes, EyeInsideVolume) {
  const ref::Volume v = constant_volume(16, 100);
  for (double fov : {90.0, 150.0})
    check_presets(
        perspective_scene({{7.5, 7.5, 7.5}, {15.0, 10.0, 7.5}, {0.0, 0.0, 1.0}}, fov, 16, 16), v,
        "eye inside, fov " + fmt(fov));
}

TEST(Extremes, FieldOfViewNearZero) {
  // fov 0.01 degrees: the image spans 0.004 voxels at the volume; B and C are a few
  // thousand LSBs of dir_frac_bits, every ray crosses the same 15-voxel chord.
  const ref::Volume v = constant_volume(16, 100);
  check_presets(
      perspective_scene({{7.5, -20.0, 7.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 0.01, 16, 16), v,
      "fov 0.01");
}

TEST(Extremes, FieldOfViewNear180) {
  // fov 179.9 degrees: tan(89.95 deg) = 1146, so the registers are scaled by 1/M with
  // M = |d(0,0)| = 1519 (16x16) and the centre pixels' directions have length 6.6e-4:
  // they keep 10.6 bits fewer than the corners, and their error bound (1 + sqrt 3) dd /
  // |d| grows accordingly (extremes.hpp). The eye inside the volume (every ray hits) and
  // outside (the wide rays miss, as in the float reference).
  const ref::Volume v = constant_volume(16, 100);
  check_presets(
      perspective_scene({{7.5, 7.5, 7.5}, {7.5, 15.0, 7.5}, {0.0, 0.0, 1.0}}, 179.9, 16, 16), v,
      "fov 179.9, eye inside");
  check_presets(
      perspective_scene({{7.5, -20.0, 7.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 179.9, 16, 16), v,
      "fov 179.9, eye outside");
}

TEST(Extremes, ParallelZoomTiny) {
  // View height 0.01 voxels: P and R are about 40 LSBs of pos_frac_bits at vizard2.
  const ref::Volume v = constant_volume(16, 100);
  check_presets(parallel_scene({{7.5, -5.0, 7.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 0.01, 16, 16),
                v, "parallel height 0.01");
}

TEST(Extremes, ParallelZoomHuge) {
  // View height 1e5 voxels: the view plane's corner origins lie ~5e4 voxels out on
  // any plane normal to the view, beyond the origin register's +-2^(addr_bits+3)
  // (§0): the host refuses the frame. A 1x1 image's only origin is the centre ray's
  // point on the plane: it renders.
  const ref::Volume v = constant_volume(16, 100);
  for (const std::string& name : preset_names()) {
    const ref::Scene s = with_preset(
        parallel_scene({{7.5, -5.0, 7.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 1e5, 16, 16), name);
    const std::string limit = std::to_string(1 << (s.precision.addr_bits + 3));
    EXPECT_EQ(error_of([&] { run_engines(s, v); }),
              "camera: no plane normal to the view direction between camera.eye and the volume "
              "keeps the rays' origins inside the geometry processor's origin register range of "
              "+-" + limit + " voxels per axis (docs/pipeline.md §0); narrow camera.fov_deg or "
              "camera.height, or move camera.eye closer")
        << name;
  }
  check_presets(parallel_scene({{7.5, -5.0, 7.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 1e5, 1, 1), v,
                "parallel height 1e5, 1x1", true);
}

TEST(Extremes, ImageOnePixel) {
  const ref::Volume v = constant_volume(16, 100);
  check_presets(
      perspective_scene({{7.5, -20.0, 7.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 40.0, 1, 1), v,
      "1x1 perspective");
  check_presets(parallel_scene({{7.5, -5.0, 7.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 64.0, 1, 1), v,
                "1x1 parallel", true);
}

TEST(Extremes, ImageWide2048x1) {
  // 2048x1: perspective with fov 0.02 (a horizontal fan of +-19.7 degrees), parallel
  // with view height 0.01 (20.48 voxels wide).
  const ref::Volume v = constant_volume(16, 100);
  check_presets(
      perspective_scene({{7.5, -20.0, 7.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 0.02, 2048, 1), v,
      "2048x1 perspective");
  check_presets(parallel_scene({{7.5, -5.0, 7.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 0.01, 2048, 1),
                v, "2048x1 parallel");
}

TEST(Extremes, ImageTall1x1024) {
  const ref::Volume v = constant_volume(16, 100);
  check_presets(
      perspective_scene({{7.5, -20.0, 7.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 40.0, 1, 1024), v,
      "1x1024 perspective");
  check_presets(parallel_scene({{7.5, -5.0, 7.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 20.0, 1, 1024),
                v, "1x1024 parallel");
}

TEST(Extremes, MissedRayTracesAgree) {
  // Fixed: MissedRayTracesAgree was a bug found by this suite (docs/extremes.md).
  // Pixel (0, 0) of this view misses the volume.
  const Rendered r = run_engines(
      with_preset(
          perspective_scene({{-12.5, -16.5, 21.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}}, 30.0, 16, 16),
          "vizard2"),
      constant_volume(16, 100));
  bittrue::RayTrace t;
  bittrue::bt_cast_ray(r.setup, r.memory, 0, 0, &t);
  ASSERT_FALSE(t.hit);
  EXPECT_FALSE(
      bittrue::first_divergence(cosim::hls_trace_ray(r.setup, r.memory, 0, 0), t).diverged);
}

}  // namespace
}  // namespace voxcast::test
