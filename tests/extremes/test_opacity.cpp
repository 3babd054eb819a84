// Extremes of opacity: faint materials at high oversampling (the opacity-corrected
// alpha underflows the table's alpha field), opacity near 1 (the accumulator
// saturates), and early-ray-termination thresholds on, next to and off the
// accumulator's grid. docs/extremes.md lists every case with its measured result.
#include <gtest/gtest.h>

#include <cmath>

#include "cosim/engines/warnings.hpp"
#include "extremes.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

// A 16^3 slab of one value seen along +y by a parallel camera: every ray of the
// 4x4 image crosses the whole slab (15 voxels: 15 * oversampling + 1 samples).
ref::Scene slab_scene(double alpha, double oversampling) {
  ref::Scene s = material_scene(alpha);
  s.camera.projection = ref::Projection::Parallel;
  s.camera.pose = {{7.5, -5.0, 7.5}, {7.5, 7.5, 7.5}, {0.0, 0.0, 1.0}};
  s.camera.height = 8.0;
  s.render.width = s.render.height = 4;
  s.render.oversampling = oversampling;
  return s;
}

// The raw opacity-corrected alpha the table stores for a one-point transfer function.
std::uint32_t table_alpha(const PrecisionProfile& p, double alpha, double step) {
  const ref::TransferFunction tf({ref::TfPoint{0.0, {0.5, 0.5, 0.5}, alpha}},
                                 ref::TfInterpolation::Ramp, ref::Material{});
  return bittrue::make_class_table(p, tf, step).front().alpha;
}

// The smallest alpha a profile represents at oversampling 16 (step 1/16): the table
// holds U(1 - (1 - alpha)^(1/16), alpha_bits), nonzero iff the step opacity is at least
// half an LSB, 2^-(alpha_bits+1) (Q_RND rounds the tie up), i.e.
//   alpha >= a_min = 1 - (1 - 2^-(alpha_bits+1))^16.
double smallest_alpha_at_16x(const PrecisionProfile& p) {
  return 1.0 - std::pow(1.0 - std::ldexp(1.0, -(p.alpha_bits + 1)), 16.0);
}

TEST(Extremes, FaintAlphaSmallestRepresentableAt16x) {
  const ref::Volume v = constant_volume(16, 100);
  for (const std::string& name : preset_names()) {
    const PrecisionProfile p = preset_profile(name);
    const double a_min = smallest_alpha_at_16x(p);
    measured("smallest alpha at 16x, " + name,
             fmt(a_min) + " (alpha_bits " + std::to_string(p.alpha_bits) + ")");
    // The closed form is the table's edge: one LSB just above, nothing just below.
    EXPECT_EQ(table_alpha(p, a_min * (1 + 1e-9), 1.0 / 16), 1u) << name;
    EXPECT_EQ(table_alpha(p, a_min * (1 - 1e-9), 1.0 / 16), 0u) << name;
    // ... and the load-time warning that it vanishes fires exactly below it
    // (just above, the step opacity rounds up to one LSB, nearly twice its
    // value: the guard's alpha-rounding hazard where that matters).
    auto vanishing = [&](const ref::Scene& s) {
      int n = 0;
      for (const cosim::Hazard& h : cosim::precision_hazards(s, v)) n += h.kind == "alpha-vanishes";
      return n;
    };
    ref::Scene s = with_preset(slab_scene(a_min * (1 + 1e-9), 16.0), name);
    EXPECT_EQ(vanishing(s), 0) << name;
    s.tf_points[0].alpha = a_min * (1 - 1e-9);
    EXPECT_EQ(vanishing(s), 1) << name;
  }
}

TEST(Extremes, FaintAlphaAt16xWithinBoundOrWarned) {
  // Alphas from 1e-7 to 0.1 (5 per decade) at oversampling 16: each either renders
  // within the one-material bound (extremes.hpp) with no warning, or the tool warns
  // that it vanishes, and then it does vanish from both fixed-point images, or the
  // tool warns that its step opacity rounds far (the precision guard), and the
  // error is then within the guard's predicted worst case.
  const ref::Volume v = constant_volume(16, 100);
  for (const std::string& name : preset_names()) {
    int warned = 0, rendered = 0, rounded = 0;
    double worst = 0.0;
    for (int k = 0; k <= 30; ++k) {
      const double alpha = std::pow(10.0, -7.0 + k / 5.0);
      const ref::Scene s = with_preset(slab_scene(alpha, 16.0), name);
      const std::vector<cosim::Hazard> hazards = cosim::precision_hazards(s, v);
      const Rendered r = run_engines(s, v);
      const std::string what = name + " alpha " + fmt(alpha);
      expect_finite(r.truth, what);
      expect_bit_exact(r, what);
      EXPECT_GT(r.truth.at(1, 1).a, 0.0) << what;  // the float reference sees it
      ASSERT_LE(hazards.size(), 1u) << what;
      if (!hazards.empty() && hazards[0].kind == "alpha-vanishes") {
        ++warned;
        EXPECT_LT(alpha, smallest_alpha_at_16x(s.precision)) << what;
        for (const auto& px : r.bt.pixels) EXPECT_EQ(px, (std::array<std::uint32_t, 4>{})) << what;
      } else if (!hazards.empty()) {
        ++rounded;
        EXPECT_EQ(hazards[0].kind, "alpha-rounding") << what;
        for (int y = 0; y < r.bt.height; ++y)
          for (int x = 0; x < r.bt.width; ++x)
            for (int c = 0; c < 4; ++c)
              EXPECT_LE(error_lsb(r, x, y, c), hazards[0].worst_lsb + 1.0) << what;
      } else {
        ++rendered;
        EXPECT_GE(alpha, smallest_alpha_at_16x(s.precision)) << what;
        worst = std::max(worst, expect_material_within_bound(r, what, true).max_error_lsb);
      }
    }
    measured("faint alpha sweep at 16x, " + name,
             std::to_string(warned) + " of 31 alphas warned (vanish), " + std::to_string(rounded) +
                 " warned (rounding, within the predicted worst case), " + std::to_string(rendered) +
                 " within bound, worst error " + fmt(worst) + " LSB");
    EXPECT_GT(rendered, 0);
  }
}

TEST(Extremes, FaintAlphaWarningThroughCli) {
  const auto dir = scratch_dir();
  write_text(dir / "faint.toml", R"(
[volume]
source = "phantom:box?size=16"
[classification]
points = [ { value = 0, alpha = 0.0 }, { value = 100, alpha = 0.3 },
           { value = 200, color = [1, 0.5, 0.5], alpha = 0.001 } ]
[camera]
eye = [7.5, -20, 7.5]
center = [7.5, 7.5, 7.5]
[render]
width = 8
height = 8
oversampling = 16
)");
  const std::string scene = (dir / "faint.toml").string();
  const std::string out = " -o " + (dir / "x.png").string();
  const std::string line =
      "voxcast: warning: classification.points[2].alpha 0.001 vanishes at oversampling 16: its "
      "step opacity 6.3e-05 is below half an LSB of precision.alpha_bits = 8 (0.00195); worst case ";
  // The warning, then the predicted worst case and the end of the line.
  auto is_line = [](const std::string& err, const std::string& head) {
    return err.rfind(head, 0) == 0 && err.size() > head.size() &&
           err.find(" LSB of an output channel\n", head.size()) == err.size() - 26;
  };
  const std::string def_scene = std::string(VOXCAST_SOURCE_DIR) + "/scenes/default.toml";
  const std::vector<Command> runs = voxcast_all(
      {"render " + scene + out + " --engine bittrue --set precision.profile=vizard2",
       "render " + scene + out + "2.png --engine hls --set precision.profile=vizard2",
       "cosim " + scene + " --out " + (dir / "cosim").string() + " --set precision.profile=vizard2",
       // The float reference does not quantize alpha: no warning. Nor does balanced,
       // whose 16 alpha bits hold 0.001 at 16x (smallest 1.2e-4).
       "render " + scene + out + "3.png --set precision.profile=vizard2",
       "render " + scene + out + "4.png --engine bittrue",
       // The shipped default scene's faint brain (alpha 0.02) vanishes on the 2001 card's
       // widths at 16x: its step opacity 1.3e-3 is below 2^-9 (a 16^3 phantom here, for speed).
       "render " + def_scene + out +
           "5.png --engine bittrue --set precision.profile=vizard2"
           " --set render.oversampling=16 --set render.width=4 --set render.height=4"
           " --set volume.source=phantom:shepp-logan?size=16 --set volume.crop.hi=[15,15,10]"});
  for (std::size_t i = 0; i < runs.size(); ++i)
    EXPECT_EQ(runs[i].status, 0) << i << ": " << runs[i].err;
  EXPECT_TRUE(is_line(runs[0].err, line)) << runs[0].err;
  EXPECT_TRUE(is_line(runs[1].err, line)) << runs[1].err;
  EXPECT_TRUE(is_line(runs[2].err, line)) << runs[2].err;
  EXPECT_EQ(runs[3].err, "");
  EXPECT_EQ(runs[4].err, "");
  EXPECT_TRUE(is_line(runs[5].err,
                      "voxcast: warning: classification.points[2].alpha 0.02 vanishes at oversampling "
                      "16: its step opacity 0.0013 is below half an LSB of precision.alpha_bits = 8 "
                      "(0.00195); worst case "))
      << runs[5].err;
}

TEST(Extremes, OpacityNearOneSaturates) {
  // alpha 1 (opacity_correct gives exactly 1), 0.9999 and 1 - 1e-12 at the extreme
  // oversamplings. The table saturates alpha at 1 - 2^-alpha_bits. The accumulator
  // never exceeds 1, C <= A, and with ERT off every sample is still taken. It grows
  // while w = Q_RND((1 - A) a_c, acc_bits) > 0, i.e. until 1 - A < 2^-(acc_bits+1) / a_c:
  // for a_c > 1/2 that is A = 1 exactly (the saturated alphas: the second sample adds
  // Q_RND(2^-ab (1 - 2^-ab), acc_bits) = 2^-ab as 2 ab > acc_bits + 1 in every preset);
  // 0.9999 at 16x is a step alpha of only 0.44, and A stops one LSB below 1.
  const ref::Volume v = constant_volume(16, 100);
  for (const std::string& name : preset_names())
    for (double alpha : {1.0, 0.9999, 1.0 - 1e-12})
      for (double os : {16.0, 0.25}) {
        const std::string what = name + " alpha " + fmt(alpha, 13) + " oversampling " + fmt(os);
        const Rendered r = run_engines(with_preset(slab_scene(alpha, os), name), v);
        expect_finite(r.truth, what);
        expect_bit_exact(r, what);
        expect_material_within_bound(r, what, true);
        const bittrue::RayTrace t = traced(r, 1, 1, what);
        ASSERT_EQ(t.trace.size(), t.samples) << what;  // ERT off: the whole ray
        double previous = 0.0;
        for (const bittrue::SampleTrace& st : t.trace) {
          const auto& acc = st.accumulator;
          EXPECT_LE(acc[3], 1.0) << what;
          EXPECT_GE(acc[3], previous) << what;
          for (int c = 0; c < 3; ++c) EXPECT_LE(acc[static_cast<std::size_t>(c)], acc[3]) << what;
          previous = acc[3];
        }
        const double a_c = t.trace.back().alpha;
        const double final_a = t.trace.back().accumulator[3];
        const double half = std::ldexp(1.0, -(r.scene.precision.acc_bits + 1));
        EXPECT_LT((1.0 - final_a) * a_c, half) << what;  // stalled: w rounds to 0
        if (a_c > 0.5) {
          EXPECT_EQ(final_a, 1.0) << what;
        }
        EXPECT_EQ(r.bt.at(1, 1)[3], (1u << r.scene.precision.out_bits) - 1u) << what;
      }
}

TEST(Extremes, AccumulatorStallsBelowErtThreshold) {
  // The opacity accumulator stops growing once w = Q_RND((1 - A) a_c, acc_bits) rounds
  // to 0, i.e. at a residual transparency 1 - A < r* = 2^-(acc_bits+1) / a_c, and the
  // last increment leaves 1 - A >= r* - a_c r* - 2^-(acc_bits+1). A faint material with
  // r* > 1 - 0.98 never reaches VIZARD II's ERT threshold: the fixed-point rays run to
  // the far side of the volume while the float reference stops. Here a_c = 2^-8 (vizard2:
  // r* = 2^-5) and 2^-12 (balanced: r* = 2^-5), on the longest axis the profile
  // addresses; for precise the stall needs ln(1/r*)/a_c samples with a_c <= 2^-21/0.02,
  // more than any ray of a 2^addr_bits volume at oversampling 16 takes.
  struct Case {
    std::string preset;
    double oversampling, step_alpha;
  };
  for (const Case& c :
       {Case{"vizard2", 4.0, std::ldexp(1.0, -8)}, Case{"balanced", 16.0, std::ldexp(1.0, -12)}}) {
    const PrecisionProfile p = preset_profile(c.preset);
    const int n = 1 << p.addr_bits;
    const ref::Volume v = make_volume(n, 2, 2, 8, [](int, int, int) { return std::uint16_t{100}; });
    ref::Scene s = with_preset(material_scene(0.0), c.preset);
    s.tf_points[0].alpha = 1.0 - std::pow(1.0 - c.step_alpha, c.oversampling);
    s.render.oversampling = c.oversampling;
    s.render.ert_threshold = 0.98;
    s.render.width = s.render.height = 1;
    s.camera.projection = ref::Projection::Parallel;
    s.camera.height = 1.0;
    s.camera.pose = {{-3.0, 0.5, 0.5}, {100.0, 0.5, 0.5}, {0.0, 0.0, 1.0}};
    const Rendered r = run_engines(s, v);
    expect_finite(r.truth, c.preset);
    expect_bit_exact(r, c.preset);
    const bittrue::RayTrace t = traced(r, 0, 0, c.preset);
    ASSERT_FALSE(t.trace.empty());
    const double a_c = t.trace.back().alpha;
    EXPECT_EQ(a_c, c.step_alpha) << c.preset;
    const double half = std::ldexp(1.0, -(p.acc_bits + 1));
    const double final_a = t.trace.back().accumulator[3];
    EXPECT_EQ(t.trace.size(), t.samples) << c.preset << ": ERT fired";
    EXPECT_LT((1.0 - final_a) * a_c, half) << c.preset << ": not stalled";
    EXPECT_LT(final_a, 0.98) << c.preset;
    ref::RayStats st;
    const glm::dvec4 f = ref::cast_ray(r.in.volume, r.in.tf, r.in.shading, r.in.settings,
                                       ref::primary_ray(r.in.camera, 0, 0), &st);
    EXPECT_TRUE(st.terminated_early) << c.preset;
    measured("accumulator stall, " + c.preset,
             "a_c " + fmt(a_c) + ": fixed A stalls at " + fmt(final_a, 6) + " after all " +
                 std::to_string(t.trace.size()) + " samples; float reaches " + fmt(f.a, 6) +
                 " and stops after " + std::to_string(st.samples) + "; alpha error " +
                 fmt(error_lsb(r, 0, 0, 3)) + " LSB");
    // |A' - A_f| <= the damped accumulator error r* + the float's overshoot past 0.98
    // (one step alpha) + 1/2 LSB output rounding.
    EXPECT_LE(error_lsb(r, 0, 0, 3),
              r.bt.full_scale() * (half / a_c + (1.0 - 0.98) + c.step_alpha) + 0.5);
  }
  const PrecisionProfile precise = preset_profile("precise");
  const double a_c = std::ldexp(1.0, -(precise.acc_bits + 1)) / 0.02;
  const double longest = std::sqrt(3.0) * (1 << precise.addr_bits) * 16.0;
  EXPECT_GT(std::log(0.02) / std::log(1.0 - a_c), longest);
}

// The pixel bound of extremes.hpp with the samples each engine took (ERT on).
void expect_ert_pixel_within_bound(const Rendered& r, int x, int y, std::uint64_t n_float,
                                   std::uint64_t n_fixed, const std::string& what) {
  const PrecisionProfile& p = r.scene.precision;
  const double a_s = ref::opacity_correct(r.scene.tf_points[0].alpha, r.in.settings.step);
  const double da = std::ldexp(1.0, -(p.alpha_bits + 1));
  const double n = static_cast<double>(std::max(n_float, n_fixed));
  const double m = static_cast<double>(std::min(n_float, n_fixed));
  const double bound =
      r.bt.full_scale() * (n * std::pow(1.0 - (a_s - da), n - 1.0) * da +
                           std::pow(1.0 - a_s, m) * (1.0 - std::pow(1.0 - a_s, n - m)) +
                           2.0 * static_cast<double>(n_fixed) * std::ldexp(1.0, -(p.acc_bits + 1)) +
                           std::ldexp(1.0, -(p.color_bits + 1)) + std::ldexp(1.0, -(p.k_bits + 1)) +
                           std::ldexp(1.0, -p.shade_bits)) +
      0.5;
  for (int c = 0; c < 4; ++c) EXPECT_LE(error_lsb(r, x, y, c), bound) << what << " channel " << c;
}

TEST(Extremes, ErtThresholdAtAndNextToRepresentable) {
  // The threshold register is ERT_T = Q_RND(t, acc_bits) (docs/pipeline.md §7.3): on
  // the grid it is exact, a quarter LSB either side rounds back to it, the half-LSB tie
  // rounds up; 0.98 (VIZARD II's) is off the grid. The ray must stop at exactly the
  // first composited sample with A >= ERT_T, and within one sample of the float
  // reference's stop (a material of step alpha 0.2: one sample moves A by at least
  // 0.2 (1 - A) > 0.004 near 0.98, far more than the accumulators' difference).
  const ref::Volume v = constant_volume(32, 100);
  for (const std::string& name : preset_names()) {
    const PrecisionProfile prof = preset_profile(name);
    const double lsb = std::ldexp(1.0, -prof.acc_bits);
    struct Threshold {
      double t;
      double expected;  // ERT_T
    };
    const Threshold cases[] = {
        {0.5, 0.5},
        {0.5 - lsb / 4, 0.5},
        {0.5 + lsb / 4, 0.5},
        {0.5 + lsb / 2, 0.5 + lsb},
        {0.5 - lsb / 2, 0.5},  // the tie rounds up
        {0.98, std::floor(0.98 / lsb + 0.5) * lsb},
        {1.0 - 2 * lsb, 1.0 - 2 * lsb},
    };
    for (const Threshold& c : cases) {
      ref::Scene s = with_preset(slab_scene(0.2, 1.0), name);
      s.camera.pose = {{15.5, -5.0, 15.5}, {15.5, 15.5, 15.5}, {0.0, 0.0, 1.0}};
      s.render.ert_threshold = c.t;
      const std::string what = name + " threshold " + fmt(c.t, 12);
      const Rendered r = run_engines(s, v);
      ASSERT_TRUE(r.setup.regs.ert_enabled) << what;
      EXPECT_EQ(static_cast<double>(r.setup.regs.ert_threshold) * lsb, c.expected) << what;
      expect_finite(r.truth, what);
      expect_bit_exact(r, what);
      const bittrue::RayTrace t = traced(r, 1, 1, what);
      for (std::size_t j = 0; j + 1 < t.trace.size(); ++j)
        EXPECT_LT(t.trace[j].accumulator[3], c.expected) << what << " sample " << j;
      EXPECT_TRUE(t.trace.back().accumulator[3] >= c.expected || t.trace.size() == t.samples)
          << what;
      ref::RayStats st;
      ref::cast_ray(r.in.volume, r.in.tf, r.in.shading, r.in.settings,
                    ref::primary_ray(r.in.camera, 1, 1), &st);
      const auto diff = static_cast<long>(t.trace.size()) - static_cast<long>(st.samples);
      EXPECT_LE(std::abs(diff), 1) << what << ": fixed stops after " << t.trace.size()
                                   << " samples, float after " << st.samples;
      expect_ert_pixel_within_bound(r, 1, 1, st.samples, t.trace.size(), what);
    }
  }
}

TEST(Extremes, ErtThresholdOneIsOff) {
  // 1.0 disables ERT: an opaque material saturates A at exactly 1 on the second
  // sample, and the ray still takes all 16 * 15 + 1 samples. A threshold just below 1
  // that rounds to 1.0 (1 - 2^-(acc_bits+2)) is enabled with ERT_T = 1.0 and stops at
  // the sample where A reaches exactly 1 (the second), one after the float reference
  // (whose alpha-1 sample reaches A = 1 at once); both pixels are fully opaque.
  const ref::Volume v = constant_volume(16, 100);
  for (const std::string& name : preset_names()) {
    const PrecisionProfile prof = preset_profile(name);
    for (double t : {1.0, 1.0 - std::ldexp(1.0, -(prof.acc_bits + 2))}) {
      ref::Scene s = with_preset(slab_scene(1.0, 16.0), name);
      s.render.ert_threshold = t;
      const std::string what = name + " threshold " + fmt(t, 12);
      const Rendered r = run_engines(s, v);
      expect_finite(r.truth, what);
      expect_bit_exact(r, what);
      EXPECT_EQ(r.setup.regs.ert_enabled, t < 1.0) << what;
      EXPECT_EQ(r.setup.regs.ert_threshold, bittrue::Raw{1} << prof.acc_bits) << what;
      const bittrue::RayTrace tr = traced(r, 1, 1, what);
      EXPECT_EQ(tr.samples, 241u) << what;
      EXPECT_EQ(tr.trace.size(), t < 1.0 ? 2u : 241u) << what;
      EXPECT_EQ(tr.trace.back().accumulator[3], 1.0) << what;
      for (int c = 0; c < 4; ++c) EXPECT_LE(error_lsb(r, 1, 1, c), 1.0) << what;
      EXPECT_EQ(r.bt.at(1, 1)[3], (1u << prof.out_bits) - 1u) << what;
    }
  }
}

TEST(Extremes, ErtThresholdRoundingToZero) {
  // A threshold below half an accumulator LSB rounds to ERT_T = 0 (enabled): the ray
  // stops after its first composited sample. The transparent samples before it are
  // skipped without an ERT test (§7), so the pixel is that one sample's colour and
  // opacity, as in the float reference (which stops there too).
  const ref::Volume v = make_volume(
      16, 16, 16, 8, [](int, int y, int) { return static_cast<std::uint16_t>(y < 8 ? 0 : 100); });
  for (const std::string& name : preset_names()) {
    const PrecisionProfile prof = preset_profile(name);
    ref::Scene s = with_preset(slab_scene(0.3, 1.0), name);
    s.tf_points = {ref::TfPoint{0.0, {0.5, 0.5, 0.5}, 0.0},
                   ref::TfPoint{50.0, {0.5, 0.5, 0.5}, 0.3}};
    s.tf_interpolation = ref::TfInterpolation::Binary;
    s.render.ert_threshold = std::ldexp(1.0, -(prof.acc_bits + 2));
    const Rendered r = run_engines(s, v);
    expect_finite(r.truth, name);
    expect_bit_exact(r, name);
    EXPECT_TRUE(r.setup.regs.ert_enabled);
    EXPECT_EQ(r.setup.regs.ert_threshold, 0);
    const bittrue::RayTrace t = traced(r, 1, 1, name);
    ASSERT_EQ(t.trace.size(), 9u) << name;  // y = 0..7 transparent, y = 8 composited
    EXPECT_EQ(t.trace[7].alpha, 0.0);
    EXPECT_GT(t.trace[8].alpha, 0.0);
    // One sample: |a_c - a_s| <= 2^-(alpha_bits+1), w and w c rounded, output 1/2.
    const double bound = r.bt.full_scale() * (std::ldexp(1.0, -(prof.alpha_bits + 1)) +
                                              2 * std::ldexp(1.0, -(prof.acc_bits + 1))) +
                         0.5;
    for (int c = 0; c < 4; ++c) EXPECT_LE(error_lsb(r, 1, 1, c), bound) << name << " " << c;
  }
}

}  // namespace
}  // namespace voxcast::test
