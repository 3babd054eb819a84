// Extremes of the volume, its values and gradients, the transfer function, and the
// widths that must hold them: volumes of 1 and 2^3 voxels, odd sizes, sizes at the
// address width and one past it, anisotropic spacing, values at 0 and full scale,
// zero and maximal gradients, degenerate transfer functions, and widths too narrow.
// docs/extremes.md lists every case with its measured result.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cosim/engines/warnings.hpp"
#include "extremes.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

const ref::CameraPose kOblique{{-3.0, -4.0, -5.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};

ref::CameraPose oblique_at(double cx, double cy, double cz) {
  return {{cx - 20.0, cy - 24.0, cz + 14.0}, {cx, cy, cz}, {0.0, 0.0, 1.0}};
}

// --- Sizes ------------------------------------------------------------------------

TEST(Extremes, VolumeOneVoxel) {
  // The box is a single point: a parallel ray through it has a chord of length 0 and
  // one sample (both engines); every other ray misses. The interpolation's +1 corners
  // are padding words with weight 0 (§3.3).
  const ref::Volume v = make_volume(1, 1, 1, 8, [](int, int, int) { return std::uint16_t{100}; });
  const ref::Scene along_y =
      parallel_scene({{0.0, -3.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}}, 5.0, 5, 5);
  check_presets(along_y, v, "1^3 parallel through the voxel", true);
  for (const std::string& name : preset_names()) {
    const Rendered r = run_engines(with_preset(along_y, name), v);
    EXPECT_EQ(r.bt.at(2, 2)[3], static_cast<std::uint32_t>(std::lround(r.bt.full_scale() * 0.05)))
        << name;
    expect_mip_within_bound(with_preset(along_y, name), v, "1^3 mip, " + name);
  }
  check_presets(perspective_scene({{0.0, -5.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 1.0}}, 10.0, 5, 5),
                v, "1^3 perspective on axis");
  check_presets(perspective_scene(kOblique, 10.0, 5, 5), v, "1^3 perspective oblique");
}

TEST(Extremes, VolumeTwoCubed) {
  const ref::Volume v = constant_volume(2, 100);
  check_presets(perspective_scene(oblique_at(0.5, 0.5, 0.5), 8.0, 16, 16), v, "2^3 perspective");
  check_presets(parallel_scene({{0.5, -3.0, 0.5}, {0.5, 0.5, 0.5}, {0.0, 0.0, 1.0}}, 2.0, 4, 4), v,
                "2^3 parallel", true);
}

// A linear ramp, exact under trilinear interpolation: v = 3 + 10 x + 20 y + 30 z.
std::uint16_t ramp(int x, int y, int z) {
  return static_cast<std::uint16_t>(3 + 10 * x + 20 * y + 30 * z);
}

TEST(Extremes, VolumeOddSizes) {
  // 7x5x3: every axis odd, so every bank has padding words (§3.3).
  check_presets(perspective_scene(oblique_at(3.0, 2.0, 1.0), 30.0, 16, 16),
                make_volume(7, 5, 3, 8, [](int, int, int) { return std::uint16_t{100}; }),
                "7x5x3 perspective");
  const ref::Volume v = make_volume(7, 5, 3, 8, ramp);
  // (1) Rays along each axis through every column of voxel centres (MIP, oversampling
  // 1): every sample sits on a voxel centre, where both engines must read exactly the
  // stored value (scaled into the value field), whatever bank and word it lives in.
  struct View {
    ref::CameraPose pose;
    int w, h, axis;
  };
  const View views[] = {{{{-2.0, 2.0, 1.0}, {3.0, 2.0, 1.0}, {0.0, 0.0, 1.0}}, 5, 3, 0},
                        {{{3.0, -2.0, 1.0}, {3.0, 2.0, 1.0}, {0.0, 0.0, 1.0}}, 7, 3, 1},
                        {{{3.0, 2.0, -2.0}, {3.0, 2.0, 1.0}, {0.0, 1.0, 0.0}}, 7, 5, 2}};
  for (const std::string& name : preset_names())
    for (const View& view : views) {
      ref::Scene s = with_preset(parallel_scene(view.pose, view.h, view.w, view.h), name);
      s.render.mode = ref::RenderMode::Mip;
      const Rendered r = run_engines(s, v);
      const std::string what = name + " along axis " + std::to_string(view.axis);
      expect_finite(r.truth, what);
      expect_bit_exact(r, what);
      const int shift = bittrue::value_shift(s.precision, v);
      int samples = 0;
      for (int py = 0; py < view.h; ++py)
        for (int px = 0; px < view.w; ++px) {
          const bittrue::RayTrace t = traced(r, px, py, what);
          for (const bittrue::SampleTrace& st : t.trace) {
            const auto& p = st.position;
            ASSERT_TRUE(p[0] == std::floor(p[0]) && p[1] == std::floor(p[1]) &&
                        p[2] == std::floor(p[2]))
                << what;
            EXPECT_EQ(st.value, std::ldexp(ramp(static_cast<int>(p[0]), static_cast<int>(p[1]),
                                                static_cast<int>(p[2])),
                                           shift))
                << what << " at (" << p[0] << ", " << p[1] << ", " << p[2] << ")";
            ++samples;
          }
        }
      EXPECT_EQ(samples, 7 * 5 * 3) << what;
    }
  // (2) Anywhere inside: trilinear interpolation of a ramp is the ramp, so the only
  // errors are the weights' rounding Q_RND(f, wb) (slope 10, 20, 30 per axis times
  // 2^-(wb+1), in the value field: times 2^shift) and the result's Q_RND to sf bits.
  std::mt19937_64 rng(20010701);
  std::uniform_real_distribution<double> ux(0.0, 6.0), uy(0.0, 4.0), uz(0.0, 2.0);
  for (const std::string& name : preset_names()) {
    const Rendered r =
        run_engines(with_preset(perspective_scene(oblique_at(3.0, 2.0, 1.0), 30.0, 2, 2), name), v);
    const PrecisionProfile& p = r.scene.precision;
    const double scale = std::ldexp(1.0, bittrue::value_shift(p, v));
    const double bound = scale * 60.0 * std::ldexp(1.0, -(p.weight_bits + 1)) +
                         std::ldexp(1.0, -(p.sample_frac_bits + 1));
    double worst = 0.0;
    for (int i = 0; i < 4000; ++i) {
      const std::array<double, 3> q{ux(rng), uy(rng), uz(rng)};
      const double exact = scale * (3.0 + 10.0 * q[0] + 20.0 * q[1] + 30.0 * q[2]);
      const double e =
          std::abs(bittrue::bt_interpolate(p, r.setup.regs, r.memory, q).value - exact);
      worst = std::max(worst, e);
      ASSERT_LE(e, bound) << name << " at (" << q[0] << ", " << q[1] << ", " << q[2] << ")";
    }
    measured(
        "7x5x3 ramp interpolation, " + name,
        "worst error " + fmt(worst / scale) + " stored units (bound " + fmt(bound / scale) + ")");
  }
}

TEST(Extremes, VolumeAtAddressLimit) {
  // 2^addr_bits voxels along x (then z): the largest volume axis the profile addresses
  // (512 for vizard2, 1024 for balanced and precise). Parallel rays along the long axis
  // at oversampling 4 through the centre and along the faces (3x3, view height 1.5):
  // every register exact, so the sample counts equal the float reference's.
  for (const std::string& name : preset_names()) {
    const int n = 1 << preset_profile(name).addr_bits;
    const ref::Volume vx =
        make_volume(n, 2, 2, 8, [](int, int, int) { return std::uint16_t{100}; });
    ref::Scene s =
        parallel_scene({{-2.0, 0.5, 0.5}, {1.0 * n, 0.5, 0.5}, {0.0, 0.0, 1.0}}, 1.5, 3, 3, 4.0);
    const Outcome ox =
        check_case(with_preset(s, name), vx, std::to_string(n) + "x2x2, " + name, true);
    EXPECT_EQ(ox.bound.hit_pixels, 9) << name;
    const ref::Volume vz =
        make_volume(2, 2, n, 8, [](int, int, int) { return std::uint16_t{100}; });
    s = parallel_scene({{0.5, 0.5, -2.0}, {0.5, 0.5, 1.0 * n}, {0.0, 1.0, 0.0}}, 1.5, 3, 3, 4.0);
    const Outcome oz =
        check_case(with_preset(s, name), vz, "2x2x" + std::to_string(n) + ", " + name, true);
    EXPECT_EQ(oz.bound.hit_pixels, 9) << name;
    measured("volume at the address limit, " + name,
             std::to_string(n) + "x2x2 and 2x2x" + std::to_string(n) + ": max error " +
                 fmt(std::max(ox.bound.max_error_lsb, oz.bound.max_error_lsb)) + " LSB (bound " +
                 fmt(ox.bound.max_bound_lsb) + ")");
  }
}

TEST(Extremes, VolumeOnePastAddressLimit) {
  for (const std::string& name : preset_names()) {
    const ref::Scene s = with_preset(material_scene(0.05), name);
    const int n = (1 << s.precision.addr_bits) + 1;
    const std::string a = std::to_string(s.precision.addr_bits), most = std::to_string(n - 1);
    for (int axis = 0; axis < 3; ++axis) {
      std::array<int, 3> d{2, 2, 2};
      d[static_cast<std::size_t>(axis)] = n;
      cosim::SceneVolume sv;
      sv.volume = make_volume(d[0], d[1], d[2], 8, [](int, int, int) { return std::uint16_t{1}; });
      sv.gradients = ref::compute_gradients(sv.volume, ref::GradientOperator::Central);
      EXPECT_EQ(error_of([&] { cosim::check_fixed_point(s, sv, true); }),
                "precision.addr_bits = " + a + " cannot address " + std::to_string(n) +
                    " voxels along " + "xyz"[axis] + " (at most " + most + ")")
          << name;
    }
  }
  // Through the command line: a 513x2x2 raw file on the 2001 card's widths.
  const auto dir = scratch_dir();
  {
    std::ofstream raw(dir / "long.raw", std::ios::binary);
    raw << std::string(513 * 2 * 2, '\x01');
  }
  write_text(dir / "long.toml", R"([volume]
source = "long.raw"
dims = [513, 2, 2]
type = "u8"
[classification]
points = [ { value = 0, alpha = 0.5 } ]
[camera]
eye = [-5, 0.5, 0.5]
center = [256, 0.5, 0.5]
[render]
width = 4
height = 4
)");
  const std::string args = "render " + (dir / "long.toml").string() + " -o ";
  const std::vector<Command> c = voxcast_all(
      {args + (dir / "x.png").string() + " --engine bittrue --set precision.profile=vizard2",
       args + (dir / "y.png").string() + " --set precision.profile=vizard2"});
  EXPECT_EQ(c[0].status, 1);
  EXPECT_EQ(c[0].err,
            "voxcast: precision.addr_bits = 9 cannot address 513 voxels along x (at most 512)\n");
  EXPECT_EQ(c[1].status, 0) << c[1].err;  // the float reference ignores the widths
}

TEST(Extremes, AnisotropicSpacing1To10) {
  // Spacing 1:1:10 (and permutations): world_scale 10 along one axis, so K and IS along
  // it are Q_RND(step / 10, df) and Q_RND(1/10, df), inexact. Perspective from outside
  // and parallel along the long axis.
  const std::array<glm::dvec3, 3> spacings{glm::dvec3{1, 1, 10}, glm::dvec3{10, 1, 1},
                                           glm::dvec3{1, 10, 1}};
  for (const glm::dvec3& sp : spacings) {
    ref::Volume v = make_volume(8, 8, 4, 8, [](int, int, int) { return std::uint16_t{100}; });
    if (sp.x > 1) v = make_volume(4, 8, 8, 8, [](int, int, int) { return std::uint16_t{100}; });
    if (sp.y > 1) v = make_volume(8, 4, 8, 8, [](int, int, int) { return std::uint16_t{100}; });
    v.spacing = sp;
    const double cx = (v.dims[0] - 1) / 2.0, cy = (v.dims[1] - 1) / 2.0, cz = (v.dims[2] - 1) / 2.0;
    const std::string label = "spacing " + fmt(sp.x) + ":" + fmt(sp.y) + ":" + fmt(sp.z);
    // The eye 20, 24 and 14 world units off the centre (camera positions are in voxels).
    const ref::CameraPose pose{
        {cx - 20.0 / sp.x, cy - 24.0 / sp.y, cz + 14.0 / sp.z}, {cx, cy, cz}, {0.0, 0.0, 1.0}};
    check_presets(perspective_scene(pose, 60.0, 16, 16, 2.0), v, label + " perspective");
    ref::CameraPose along{{cx, cy, cz}, {cx, cy, cz}, {0.0, 0.0, 1.0}};
    if (sp.z > 1) along = {{cx, cy, cz + 8.0}, {cx, cy, cz}, {0.0, 1.0, 0.0}};
    if (sp.x > 1) along.eye.x -= 8.0;
    if (sp.y > 1) along.eye.y -= 8.0;
    check_presets(parallel_scene(along, 8.0, 8, 8, 2.0), v,
                  label + " parallel along the long axis");
  }
}

// --- Values and gradients -------------------------------------------------------------

TEST(Extremes, VoxelValuesZeroAndFullScale) {
  // Constant volumes at 0 and at full scale (8-bit 255; a 1-bit volume's 1, shifted to
  // the top of the value field; a 16-bit 65535 in precise, the only preset whose value
  // field holds 16 bits: tf_addr_bits = 14 < 16, so its address Q_RND(65535 / 4) = 16384
  // is clamped to the last entry 16383, §4.1). One material, and MIP (grey 0 and 1).
  const ref::CameraPose pose = oblique_at(3.5, 3.5, 3.5);
  struct Case {
    std::string label;
    ref::Volume v;
    std::vector<std::string> presets;
  };
  std::vector<Case> cases = {
      {"8-bit 0", make_volume(8, 8, 8, 8, [](int, int, int) { return std::uint16_t{0}; }),
       preset_names()},
      {"8-bit 255", make_volume(8, 8, 8, 8, [](int, int, int) { return std::uint16_t{255}; }),
       preset_names()},
      {"1-bit 1", make_volume(8, 8, 8, 1, [](int, int, int) { return std::uint16_t{1}; }),
       preset_names()},
      {"16-bit 65535",
       make_volume(8, 8, 8, 16, [](int, int, int) { return std::uint16_t{65535}; }),
       {"precise"}},
  };
  for (const Case& c : cases)
    for (const std::string& name : c.presets) {
      const ref::Scene s = with_preset(perspective_scene(pose, 30.0, 16, 16), name);
      const std::string what = c.label + ", " + name;
      const Outcome o = check_case(s, c.v, what);
      EXPECT_GT(o.bound.hit_pixels, 40) << what;
      expect_mip_within_bound(s, c.v, what + " mip");
      const Rendered r = run_engines(s, c.v);
      bittrue::RayTrace t;
      bittrue::bt_cast_ray(r.setup, r.memory, 8, 8, &t);
      ASSERT_FALSE(t.trace.empty()) << what;
      const double field =
          std::ldexp(static_cast<double>(c.v.data[0]), bittrue::value_shift(s.precision, c.v));
      const int entries = 1 << s.precision.tf_addr_bits;
      for (const bittrue::SampleTrace& st : t.trace) {
        EXPECT_EQ(st.value, field) << what;
        EXPECT_GE(st.class_address, 0) << what;
        EXPECT_LT(st.class_address, entries) << what;
      }
      if (c.label == "16-bit 65535") {
        EXPECT_EQ(t.trace[0].class_address, entries - 1) << what;
      }
      measured("values at the extremes, " + what,
               "value field " + fmt(field, 8) + ", table address " +
                   std::to_string(t.trace[0].class_address) + ", max error " +
                   fmt(o.bound.max_error_lsb) + " LSB (bound " + fmt(o.bound.max_bound_lsb) + ")");
    }
}

TEST(Extremes, ZeroGradientsShadeAmbientOnly) {
  // A constant volume has a zero gradient everywhere: the float reference's normal is
  // 0 (no NaN from normalising), the fixed point's N = 0 selects D = S = 0 (§5.2), and
  // the shaded colour is colour * ka = 0.5 * 0.5 = 0.25 exactly in every width.
  const ref::Volume v = constant_volume(16, 100);
  for (const std::string& name : preset_names()) {
    ref::Scene s = with_preset(perspective_scene(oblique_at(7.5, 7.5, 7.5), 30.0, 16, 16), name);
    s.render.mode = ref::RenderMode::Shaded;
    s.lights = {ref::Light{}, ref::Light{ref::LightType::Directional, {1.0, -1.0, 1.0}, 2.0}};
    const Outcome o = check_case(s, v, "zero gradients, " + name);
    const Rendered r = run_engines(s, v);
    int composited = 0;
    for (int py = 0; py < 16; py += 5)
      for (int px = 0; px < 16; px += 5) {
        const bittrue::RayTrace t = traced(r, px, py, name);
        for (const bittrue::SampleTrace& st : t.trace) {
          if (st.alpha == 0.0) continue;
          ++composited;
          EXPECT_EQ(st.gradient, (std::array<double, 3>{0.0, 0.0, 0.0})) << name;
          EXPECT_EQ(st.diffuse, 0.0) << name;
          EXPECT_EQ(st.specular, 0.0) << name;
          EXPECT_EQ(st.shaded, (std::array<double, 3>{0.25, 0.25, 0.25})) << name;
        }
      }
    EXPECT_GT(composited, 100) << name;
    measured("zero gradients, " + name, "max error " + fmt(o.bound.max_error_lsb) + " LSB (bound " +
                                            fmt(o.bound.max_bound_lsb) + ")");
  }
}

// A 0/255 checkerboard: central differences vanish inside (both neighbours have the
// same parity) and are +-255/2 = +-127.5 on the border voxels (clamped one-sided
// differences), the largest an 8-bit volume can produce; the corner voxels have all
// three components at +-127.5.
ref::Volume checkerboard(int n) {
  return make_volume(n, n, n, 8, [](int x, int y, int z) {
    return static_cast<std::uint16_t>(((x + y + z) & 1) ? 255 : 0);
  });
}

TEST(Extremes, MaximalGradientsCheckerboard) {
  const ref::Volume v = checkerboard(8);
  for (const std::string& name : preset_names()) {
    const PrecisionProfile p = preset_profile(name);
    const int shift = bittrue::value_shift(p, v);
    // Stored gradient of the corner voxel: SAT(Q_RND(127.5 2^shift, gfb)) in
    // gradient_bits signed (vizard2: 128 saturates to 127).
    const bittrue::Raw gmax = (bittrue::Raw{1} << (p.gradient_bits - 1)) - 1;
    const bittrue::Raw expected =
        std::min(gmax, bittrue::quantize_rnd(std::ldexp(127.5, shift), p.gradient_frac_bits));
    for (const char* mode : {"shaded", "unshaded", "mip"}) {
      ref::Scene s = with_preset(perspective_scene(oblique_at(3.5, 3.5, 3.5), 30.0, 24, 24), name);
      s.tf_points = {ref::TfPoint{0.0, {0.2, 0.4, 0.9}, 0.1},
                     ref::TfPoint{255.0, {1.0, 0.8, 0.3}, 0.6}};
      s.render.mode = std::string(mode) == "shaded" ? ref::RenderMode::Shaded
                      : std::string(mode) == "mip"  ? ref::RenderMode::Mip
                                                    : ref::RenderMode::Unshaded;
      s.lights = {ref::Light{}, ref::Light{ref::LightType::Directional, {1.0, -1.0, 1.0}, 0.8}};
      const std::string what = name + " " + mode;
      const Rendered r = run_engines(s, v);
      expect_finite(r.truth, what);
      expect_bit_exact(r, what);
      // The corner voxel (0,0,0) (value 0, neighbours 255) sits in bank 0, word 0.
      for (int c = 0; c < 3; ++c)
        EXPECT_EQ(r.memory.banks[0][0].gradient[static_cast<std::size_t>(c)], expected) << what;
      // Per sample, against the float interpolation at the same (fixed-point) position:
      // the weights Q_RND(f, wb) move a trilinear interpolant by <= 2^-(wb+1) times its
      // span along each axis (255 for values, 255 for gradients, -127.5..127.5); the
      // stored gradient is off by 2^-(gfb+1) (rounding) or 127.5 2^shift - gmax 2^-gfb
      // (saturation); the results by 2^-(sf+1).
      const double scale = std::ldexp(1.0, shift);
      const double w = 3.0 * 255.0 * std::ldexp(1.0, -(p.weight_bits + 1)) * scale;
      const double sf = std::ldexp(1.0, -(p.sample_frac_bits + 1));
      const double stored =
          std::max(std::ldexp(1.0, -(p.gradient_frac_bits + 1)),
                   127.5 * scale - std::ldexp(static_cast<double>(gmax), -p.gradient_frac_bits));
      const double field_limit = std::ldexp(1.0, p.gradient_bits - 1 - p.gradient_frac_bits);
      double worst_v = 0.0, worst_g = 0.0;
      for (int py = 0; py < 24; py += 3)
        for (int px = 0; px < 24; px += 3) {
          const bittrue::RayTrace t = traced(r, px, py, what);
          for (const bittrue::SampleTrace& st : t.trace) {
            const ref::Sample f = ref::interpolate(
                v, r.sv->gradients, {st.position[0], st.position[1], st.position[2]});
            const double ev = std::abs(st.value - scale * f.value);
            worst_v = std::max(worst_v, ev);
            EXPECT_LE(ev, w + sf) << what;
            for (int c = 0; c < 3; ++c) {
              const double g = st.gradient[static_cast<std::size_t>(c)];
              const double eg = std::abs(g - scale * f.gradient[c]);
              worst_g = std::max(worst_g, eg);
              EXPECT_LE(eg, stored + w + sf) << what;
              EXPECT_LE(std::abs(g), field_limit) << what;  // no overflow
            }
          }
        }
      if (std::string(mode) == "shaded")
        measured("checkerboard gradients, " + name,
                 "stored corner gradient " + std::to_string(expected) +
                     " (raw), worst value error " + fmt(worst_v / scale) + " stored units (bound " +
                     fmt((w + sf) / scale) + "), worst gradient error " + fmt(worst_g / scale) +
                     " (bound " + fmt((stored + w + sf) / scale) + ")");
    }
  }
}

// --- Widths too narrow ---------------------------------------------------------------

cosim::SceneVolume scene_volume(ref::Volume v) {
  cosim::SceneVolume sv;
  sv.volume = std::move(v);
  sv.gradients = ref::compute_gradients(sv.volume, ref::GradientOperator::Central);
  return sv;
}

TEST(Extremes, ValueBitsTooNarrow) {
  const cosim::SceneVolume v8 = scene_volume(checkerboard(4));
  ref::Scene s = with_preset(material_scene(0.5), "vizard2");
  s.precision.value_bits = 7;
  EXPECT_EQ(error_of([&] { cosim::check_fixed_point(s, v8, false); }),
            "precision.value_bits = 7 cannot hold the volume's 8-bit values (test volume)");
  const cosim::SceneVolume v16 =
      scene_volume(make_volume(2, 2, 2, 16, [](int, int, int) { return std::uint16_t{40000}; }));
  for (const std::string& name : {std::string("vizard2"), std::string("balanced")}) {
    const ref::Scene p = with_preset(material_scene(0.5), name);
    EXPECT_EQ(error_of([&] { cosim::check_fixed_point(p, v16, true); }),
              "precision.value_bits = " + std::to_string(p.precision.value_bits) +
                  " cannot hold the volume's 16-bit values (test volume)");
  }
  EXPECT_NO_THROW(cosim::check_fixed_point(with_preset(material_scene(0.5), "precise"), v16, true));
  const auto dir = scratch_dir();
  const Command c = voxcast("render " + std::string(VOXCAST_SOURCE_DIR) + "/scenes/mip.toml -o " +
                            (dir / "x.png").string() +
                            " --engine bittrue --set volume.source=phantom:box?size=16 --set "
                            "precision.value_bits=4");
  EXPECT_EQ(c.status, 1);
  EXPECT_EQ(c.err,
            "voxcast: precision.value_bits = 4 cannot hold the volume's 8-bit values "
            "(phantom:box?size=16)\n");
}

TEST(Extremes, GradientBitsTooNarrow) {
  // The checkerboard's largest component 127.5, in the value field 127.5 2^shift, needs
  // gradient_bits >= floor(log2(127.5 2^shift)) + 2 + gradient_frac_bits (sign, integer
  // bits, fraction bits): 8 for vizard2 (every preset's own width suffices); one less
  // is an error naming the width, the value and the limit.
  const cosim::SceneVolume sv = scene_volume(checkerboard(4));
  for (const std::string& name : preset_names()) {
    ref::Scene s = with_preset(material_scene(0.5), name);
    const double g = std::ldexp(127.5, bittrue::value_shift(s.precision, sv.volume));
    const int need =
        static_cast<int>(std::floor(std::log2(g))) + 2 + s.precision.gradient_frac_bits;
    EXPECT_LE(need, s.precision.gradient_bits) << name;
    s.precision.gradient_bits = need;
    EXPECT_NO_THROW(cosim::check_fixed_point(s, sv, false)) << name;
    s.precision.gradient_bits = need - 1;
    EXPECT_EQ(error_of([&] { cosim::check_fixed_point(s, sv, false); }),
              "precision.gradient_bits = " + std::to_string(need - 1) + " (with " +
                  std::to_string(s.precision.gradient_frac_bits) +
                  " fraction bits) cannot hold the volume's gradient component " +
                  std::to_string(g) + " (limit " +
                  std::to_string(std::ldexp(1.0, need - 2 - s.precision.gradient_frac_bits)) + ")")
        << name;
    measured("gradient width needed by the checkerboard, " + name,
             std::to_string(need) + " bits (preset has " +
                 std::to_string(preset_profile(name).gradient_bits) + ")");
  }
  const auto dir = scratch_dir();
  const Command c = voxcast("render " + std::string(VOXCAST_SOURCE_DIR) + "/scenes/mip.toml -o " +
                            (dir / "x.png").string() +
                            " --engine bittrue --set volume.source=phantom:box?size=16 --set "
                            "precision.profile=vizard2 --set precision.gradient_bits=6");
  EXPECT_EQ(c.status, 1);
  EXPECT_EQ(c.err,
            "voxcast: precision.gradient_bits = 6 (with 0 fraction bits) cannot hold the "
            "volume's gradient component 100.000000 (limit 32.000000)\n");
}

TEST(Extremes, AddrBitsTooNarrow) {
  const cosim::SceneVolume sv = scene_volume(constant_volume(32, 1));
  ref::Scene s = with_preset(material_scene(0.5), "vizard2");
  s.precision.addr_bits = 5;
  EXPECT_NO_THROW(cosim::check_fixed_point(s, sv, false));
  s.precision.addr_bits = 4;
  EXPECT_EQ(error_of([&] { cosim::check_fixed_point(s, sv, false); }),
            "precision.addr_bits = 4 cannot address 32 voxels along x (at most 16)");
  const auto dir = scratch_dir();
  const Command c = voxcast("render " + std::string(VOXCAST_SOURCE_DIR) + "/scenes/mip.toml -o " +
                            (dir / "x.png").string() +
                            " --engine bittrue --set volume.source=phantom:box?size=32 --set "
                            "precision.addr_bits=4");
  EXPECT_EQ(c.status, 1);
  EXPECT_EQ(c.err,
            "voxcast: precision.addr_bits = 4 cannot address 32 voxels along x (at most 16)\n");
}

// --- Transfer functions ---------------------------------------------------------------
//
// The classification of every value on the interpolator's output grid (vb.sf bits,
// the value field), fixed point (the table entry the address selects) against the
// float reference's U(opacity_correct(tf(v)), alpha_bits) — the same quantization of
// alpha, so any difference is the table's: the address Q_RND(v 2^(tfa - vb)) moves a
// value by at most half an entry spacing, 2^(vb - tfa - 1), so the two may differ
// only within that distance of a step. Exhaustive for vizard2 (4096 values), strided
// elsewhere, exhaustive within 2 stored units of each step.
struct SweepResult {
  std::uint64_t values = 0, differ = 0;
};

SweepResult sweep_classification(const ref::Scene& scene, const ref::Volume& v,
                                 const std::vector<double>& steps_stored, const std::string& what) {
  const PrecisionProfile& p = scene.precision;
  const cosim::SceneVolume sv = scene_volume(v);
  const ref::RenderInputs in =
      ref::make_render_inputs(scene, sv.volume, sv.gradients, scene.camera.pose);
  const bittrue::FrameSetup fs = bittrue::make_frame_setup(p, scene, in);
  const double scale = std::ldexp(1.0, bittrue::value_shift(p, v));
  const double ulp = std::ldexp(1.0, -p.sample_frac_bits);
  const double half_entry = std::ldexp(1.0, p.value_bits - p.tf_addr_bits - 1);
  const double top = std::ldexp(1.0, p.value_bits) - ulp;
  SweepResult out;
  const auto check = [&](double value) {
    ++out.values;
    const double fixed = bittrue::bt_alpha(p, bittrue::bt_classify(fs, value));
    const double truth = bittrue::u_frac(
        ref::opacity_correct(in.tf.classify(value / scale).alpha, in.settings.step), p.alpha_bits);
    if (fixed == truth) return;
    ++out.differ;
    bool near_step = false;
    for (double st : steps_stored)
      near_step = near_step || std::abs(value - st * scale) <= half_entry;
    EXPECT_TRUE(near_step) << what << ": value " << value / scale << " (field " << value
                           << ") classifies to alpha " << fixed << ", float " << truth;
  };
  const double stride =
      std::max(ulp, std::ldexp(1.0, p.value_bits + p.sample_frac_bits - 12) * ulp);
  for (double x = 0.0; x <= top; x += stride) check(x);
  for (double st : steps_stored)
    for (double x = std::max(0.0, (st - 2.0) * scale); x <= std::min(top, (st + 2.0) * scale);
         x += ulp)
      check(x);
  return out;
}

// Constant volumes on either side of a step: transparent (both images empty) and
// opaque (the one-material bound). The rays run along +y through voxel centres
// (oversampling 1, pixel centres on the integer grid), where the float reference's
// interpolation is exact; elsewhere it is not, and a step at exactly the data value
// flickers (Extremes.FloatReferenceConstantAtStepValue).
void expect_sides(const ref::Scene& base, int bits, std::uint16_t below, std::uint16_t at,
                  const std::string& what) {
  for (const std::string& name : preset_names()) {
    if (bits > preset_profile(name).value_bits) continue;
    ref::Scene s = with_preset(base, name);
    s.camera =
        parallel_scene({{3.5, -4.0, 3.5}, {3.5, 3.5, 3.5}, {0.0, 0.0, 1.0}}, 10.0, 10, 10).camera;
    s.render.width = s.render.height = 10;
    s.render.oversampling = 1.0;
    const ref::Volume vb = make_volume(8, 8, 8, bits, [=](int, int, int) { return below; });
    const Rendered r = run_engines(s, vb);
    expect_bit_exact(r, what + " below, " + name);
    for (std::size_t i = 0; i < r.bt.pixels.size(); ++i) {
      EXPECT_EQ(r.bt.pixels[i], (std::array<std::uint32_t, 4>{})) << what << " below, " << name;
      EXPECT_EQ(r.truth.pixels[i], glm::dvec4(0.0)) << what << " below, " << name;
    }
    const Outcome o = check_case(s, make_volume(8, 8, 8, bits, [=](int, int, int) { return at; }),
                                 what + " at, " + name, true);
    EXPECT_EQ(o.bound.hit_pixels, 64) << what << ", " << name;
  }
}

ref::Scene tf_scene(std::vector<ref::TfPoint> points, ref::TfInterpolation interpolation) {
  ref::Scene s = perspective_scene(oblique_at(3.5, 3.5, 3.5), 30.0, 16, 16);
  s.tf_points = std::move(points);
  s.tf_interpolation = interpolation;
  return s;
}

const glm::dvec3 kGrey{0.5, 0.5, 0.5};

TEST(Extremes, TransferFunctionSinglePoint) {
  // One point at 128 holds over the whole range: every table entry is the same, and
  // constant volumes at 0, 128 and 255 render the same material.
  const ref::Scene base = tf_scene({ref::TfPoint{128.0, kGrey, 0.3}}, ref::TfInterpolation::Ramp);
  for (std::uint16_t value : {std::uint16_t{0}, std::uint16_t{128}, std::uint16_t{255}}) {
    const ref::Volume v = make_volume(8, 8, 8, 8, [=](int, int, int) { return value; });
    check_presets(base, v, "single point, value " + std::to_string(value));
    for (const std::string& name : preset_names()) {
      const ref::Scene s = with_preset(base, name);
      const cosim::SceneVolume sv = scene_volume(v);
      const bittrue::FrameSetup fs = bittrue::make_frame_setup(
          s.precision, s, ref::make_render_inputs(s, sv.volume, sv.gradients, s.camera.pose));
      for (const bittrue::ClassEntry& e : fs.class_table) {
        EXPECT_EQ(e.alpha, fs.class_table.front().alpha) << name;
        EXPECT_EQ(e.r, fs.class_table.front().r) << name;
      }
    }
  }
}

TEST(Extremes, TransferFunctionDuplicatePointsVerticalStep) {
  // Two points at 100 (alpha 0 then 0.6): a vertical step. The ramp between equal
  // values is never evaluated (no division by zero); 99 is transparent, 100 opaque.
  const ref::Scene base =
      tf_scene({ref::TfPoint{0.0, kGrey, 0.0}, ref::TfPoint{100.0, kGrey, 0.0},
                ref::TfPoint{100.0, kGrey, 0.6}, ref::TfPoint{255.0, kGrey, 0.6}},
               ref::TfInterpolation::Ramp);
  expect_sides(base, 8, 99, 100, "vertical step at 100");
  for (const std::string& name : preset_names()) {
    const SweepResult sw = sweep_classification(with_preset(base, name), checkerboard(2), {100.0},
                                                "vertical step, " + name);
    measured("vertical step classification sweep, " + name,
             std::to_string(sw.values) + " values, " + std::to_string(sw.differ) +
                 " differ from the float (all within half an entry of the step)");
  }
}

TEST(Extremes, TransferFunctionBinaryStepAtFirstValue) {
  // Binary: transparent at 0, opaque from 1 on (the step between the first two
  // stored values).
  const ref::Scene base = tf_scene({ref::TfPoint{0.0, kGrey, 0.0}, ref::TfPoint{1.0, kGrey, 0.5}},
                                   ref::TfInterpolation::Binary);
  expect_sides(base, 8, 0, 1, "binary step at 1");
  for (const std::string& name : preset_names()) {
    const ref::Scene s = with_preset(base, name);
    EXPECT_TRUE(cosim::fixed_point_warnings(s, checkerboard(2)).empty()) << name;
    const SweepResult sw =
        sweep_classification(s, checkerboard(2), {1.0}, "binary step at 1, " + name);
    measured("binary step at the first value, " + name,
             std::to_string(sw.values) + " values swept, " + std::to_string(sw.differ) +
                 " differ (within half an entry of the step)");
  }
}

TEST(Extremes, TransferFunctionBinaryStepAtLastValue) {
  // Binary: opaque only at the last value, 255 of an 8-bit volume. Every preset's
  // table has an entry there (255 2^shift is a multiple of the entry spacing).
  const ref::Scene base = tf_scene({ref::TfPoint{0.0, kGrey, 0.0}, ref::TfPoint{255.0, kGrey, 0.5}},
                                   ref::TfInterpolation::Binary);
  expect_sides(base, 8, 254, 255, "binary step at 255");
  for (const std::string& name : preset_names()) {
    const ref::Scene s = with_preset(base, name);
    EXPECT_TRUE(cosim::fixed_point_warnings(s, checkerboard(2)).empty()) << name;
    sweep_classification(s, checkerboard(2), {255.0}, "binary step at 255, " + name);
  }
  // A 16-bit volume in precise: entries every 2^(16-14) = 4 values, the last at 65532;
  // 65533..65535 read it (the address clamps, §4.1). A step at 65532 renders; a step at
  // 65535 (or 65533) holds no entry: its material vanishes from the fixed-point image,
  // and the tool warns at load time.
  const ref::Volume full =
      make_volume(8, 8, 8, 16, [](int, int, int) { return std::uint16_t{65535}; });
  ref::Scene s = with_preset(base, "precise");
  s.tf_points[1].value = 65532.0;
  EXPECT_TRUE(cosim::fixed_point_warnings(s, full).empty());
  check_case(s, full, "16-bit step at 65532, precise");
  for (double step : {65533.0, 65535.0}) {
    s.tf_points[1].value = step;
    const std::vector<std::string> w = cosim::fixed_point_warnings(s, full);
    ASSERT_EQ(w.size(), 1u);
    EXPECT_EQ(w[0].rfind("classification.points[1].value " + fmt(step, 6) +
                             " vanishes: no classification-table entry lies between it and the "
                             "data's largest value 65535 (precision.tf_addr_bits = 14: entries "
                             "every 4 stored values, the last at 65532); worst case ",
                         0),
              0u)
        << w[0];
    const Rendered r = run_engines(s, full);
    expect_bit_exact(r, "16-bit step at " + fmt(step, 6));
    EXPECT_GT(r.truth.at(8, 8).a, 0.0);
    for (const auto& px : r.bt.pixels) EXPECT_EQ(px, (std::array<std::uint32_t, 4>{}));
  }
  // Through the command line: the warning is printed once, the render goes on.
  const auto dir = scratch_dir();
  {
    std::ofstream raw(dir / "full.raw", std::ios::binary);
    for (int i = 0; i < 8 * 8 * 8; ++i) raw << '\xff' << '\xff';
  }
  write_text(dir / "step.toml", R"([volume]
source = "full.raw"
dims = [8, 8, 8]
type = "u16"
[classification]
interpolation = "binary"
points = [ { value = 0, alpha = 0.0 }, { value = 65535, alpha = 0.5 } ]
[camera]
eye = [-16, -20, 17]
center = [3.5, 3.5, 3.5]
[render]
width = 8
height = 8
[precision]
profile = "precise"
)");
  const Command c = voxcast("render " + (dir / "step.toml").string() + " -o " +
                            (dir / "x.png").string() + " --engine hls");
  EXPECT_EQ(c.status, 0) << c.err;
  EXPECT_EQ(c.err,
            "voxcast: warning: classification.points[1].value 65535 vanishes: no "
            "classification-table entry lies between it and the data's largest value 65535 "
            "(precision.tf_addr_bits = 14: entries every 4 stored values, the last at 65532); "
            "worst case 128 LSB of an output channel\n");  // alpha 0.5 of 255
}

TEST(Extremes, FloatReferenceConstantAtStepValue) {
  // Fixed: FloatReferenceConstantAtStepValue was a bug found by this suite (docs/extremes.md).
  const ref::Volume v = make_volume(8, 8, 8, 8, [](int, int, int) { return std::uint16_t{255}; });
  const ref::GradientField g = ref::compute_gradients(v, ref::GradientOperator::Central);
  std::mt19937_64 rng(255);
  std::uniform_real_distribution<double> u(0.0, 7.0);
  for (int i = 0; i < 1000; ++i)
    ASSERT_EQ(ref::interpolate(v, g, {u(rng), u(rng), u(rng)}).value, 255.0) << "sample " << i;
}

}  // namespace
}  // namespace voxcast::test
