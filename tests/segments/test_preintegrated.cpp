// render.classification = "preintegrated" (issue 25, docs/pipeline.md §4a):
// the pre-integration table unit in every engine of the ray caster.
//  - the table: every entry is its float twin (ref::preintegrate at the
//    address's values) within half an LSB of each field, and hls reads the
//    entry bit-true reads, for any pair of sample values;
//  - closed forms through the engines: a constant volume gives each of a
//    ray's n - 1 segments the post-classified sample's entry (the pixel is
//    post-classification's over n - 1 samples, bit for bit); a linear ramp
//    across a binary step gives the analytic segment opacity; an opaque
//    band of values between two samples is found at one sample per voxel,
//    where post-classification misses it;
//  - hls == bit-true == the cycle model on a shaded phantom in every mode and
//    profile; the cycle model's frame takes the same samples as with
//    post-classification and at most one clock per ray more;
//  - the key: round trip, refusals, elaboration and the report's price.
//  - the error budget of `voxcast paper engel2001`: its rows agree where their
//    approximations are exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "cosim/engines/engines.hpp"
#include "cosim/engines/warnings.hpp"
#include "cosim/hardware/report.hpp"
#include "cosim/hardware/synth_script.hpp"
#include "hls/host_frame.hpp"
#include "hls/preintegration_table.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/bittrue/shading.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/elaboration.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "refmodel/volume/preintegration.hpp"
#include "rtl_model/engine.hpp"
#include "tests/segments/segment_engines.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

using segments::Frame;
using segments::prepare;
using segments::small_scene;
using segments::volume_along_x;
constexpr const char* kOrigin = "pre-integration engines";

// A parallel camera looking along +x through an n^3 volume, unshaded, ERT off,
// whole steps (no partial segments: the pre-integrated scene has none either).
ref::Scene along_x(int n, const std::string& classification, const std::string& points,
                   const std::string& interpolation, const std::string& profile = "balanced") {
  const std::string c = std::to_string((n - 1) / 2.0);
  return ref::parse_scene(
      "[volume]\nsource = \"phantom:box\"\n"
      "[classification]\ninterpolation = \"" +
          interpolation + "\"\npoints = " + points +
          "\n[camera]\nprojection = \"parallel\"\neye = [-40, " + c + ", " + c +
          "]\ncenter = [" + c + ", " + c + ", " + c +
          "]\nheight = 8\n"
          "[render]\nwidth = 8\nheight = 8\nmode = \"unshaded\"\nert_threshold = 1.0\n"
          "partial_segments = false\nclassification = \"" +
          classification + "\"\n[precision]\nprofile = \"" + profile + "\"\n",
      "along x", ".");
}

// The pixel's opacity in [0, 1] from a quantized image.
double alpha_at(const ref::QuantImage& img, int x, int y) {
  return img.at(x, y)[3] / (std::ldexp(1.0, img.bits) - 1.0);
}

// §4a.3: every entry is the float twin at its two addresses' values, each field
// within half an LSB (one rounding, U(·, F), which saturates at 1 - 2^-F: an
// opaque segment's alpha and a full colour channel are that); at 8 bits per
// end, 65536 entries.
TEST(Preintegrated, TableEntriesAreTheFloatTwinWithinHalfAnLsb) {
  const PrecisionProfile p = preset_profile("vizard2");
  const ref::TransferFunction tf({{0.0, {0.0, 0.0, 0.0}, 0.0},
                                  {60.0, {0.9, 0.45, 0.4}, 0.0},
                                  {120.0, {0.95, 0.6, 0.5}, 0.9},
                                  {200.0, {1.0, 0.75, 0.65}, 1.0}},
                                 ref::TfInterpolation::Ramp, ref::Material{});
  const double step = 0.5;
  const auto table = bittrue::make_preint_table(p, tf, step);
  const int side = 1 << p.preint_addr_bits;
  ASSERT_EQ(table->size(), static_cast<std::size_t>(side * side));
  const double color_lsb = std::ldexp(1.0, -p.color_bits), alpha_lsb = std::ldexp(1.0, -p.alpha_bits);
  double worst_alpha = 0.0, worst_color = 0.0;
  for (int f = 0; f < side; f += 3)
    for (int b = 0; b < side; b += 5) {
      const double vf = std::ldexp(f, p.value_bits - p.preint_addr_bits);
      const double vb = std::ldexp(b, p.value_bits - p.preint_addr_bits);
      const ref::SegmentClass twin = ref::preintegrate(tf, vf, vb, step);
      const bittrue::ClassEntry& e = (*table)[static_cast<std::size_t>(f * side + b)];
      worst_alpha = std::max(worst_alpha, std::abs(bittrue::from_raw(e.alpha, p.alpha_bits) -
                                                   std::min(twin.alpha, 1.0 - alpha_lsb)));
      const glm::dvec3 c = twin.color();
      const std::uint32_t raw[3] = {e.r, e.g, e.b};
      for (int k = 0; k < 3; ++k)
        worst_color = std::max(worst_color, std::abs(bittrue::from_raw(raw[k], p.color_bits) -
                                                     std::min(c[k], 1.0 - color_lsb)));
    }
  EXPECT_LE(worst_alpha, 0.5 * alpha_lsb + 1e-12);
  EXPECT_LE(worst_color, 0.5 * color_lsb + 1e-12);
  // The same inputs give the same table (the cache), other steps another.
  EXPECT_EQ(bittrue::make_preint_table(p, tf, step), table);
  EXPECT_NE(bittrue::make_preint_table(p, tf, 1.0), table);
}

// §4a.1-2: the hls unit reads the entry the bit-true model reads, for sample
// values on the sf grid across the whole range (the address rounding and clamp).
TEST(Preintegrated, HlsReadsTheBitTrueEntryForAnyPairOfValues) {
  using P = BalancedTraits;
  const PrecisionProfile p = profile_value<P>();
  const ref::TransferFunction tf({{0.0, {0.2, 0.3, 0.4}, 0.0}, {2000.0, {0.9, 0.8, 0.1}, 0.7}},
                                 ref::TfInterpolation::Ramp, ref::Material{});
  bittrue::FrameSetup fs;
  fs.profile = p;
  fs.preint_table = bittrue::make_preint_table(p, tf, 1.0);
  auto table = std::make_unique<hls::PreintegrationTable<P>>();
  ASSERT_TRUE(hls::host::load_preint_table<P>(*table, *fs.preint_table));
  const double top = std::ldexp(1.0, p.value_bits) - std::ldexp(1.0, -p.sample_frac_bits);
  for (double f = 0.0; f <= top; f += 37.3125)
    for (double b = 0.0; b <= top; b += 53.0625) {
      typename hls::PreintegrationParams<P>::value_t hf = f, hb = b;
      const hls::ClassEntry<P> h = hls::classify_segment<P>(*table, hf, hb);
      const bittrue::ClassEntry& t = bittrue::bt_classify_segment(fs, f, b);
      const bittrue::ClassEntry raw = hls::host::entry_to_raw<P>(h);
      ASSERT_EQ(raw.alpha, t.alpha) << f << " -> " << b;
      ASSERT_EQ(raw.r, t.r);
      ASSERT_EQ(raw.g, t.g);
      ASSERT_EQ(raw.b, t.b);
    }
}

// A constant volume under a one-point transfer function: every segment's entry
// is the post-classified sample's, and a ray's first sample ends no segment, so
// each pixel is post-classification's with the ray's first sample left out,
// bit for bit (bit-true traces), and the float reference's opacity is
// 1 - (1 - a)^(n - 1) over the n - 1 segments.
TEST(Preintegrated, ConstantVolumeGivesThePostClassifiedSampleForEachSegment) {
  const int n = 12;
  const cosim::SceneVolume sv = volume_along_x(n, [](int) { return 100; });
  const std::string points = "[ {value = 0, color = [1, 1, 1], alpha = 0.1} ]";
  const ref::Scene pre = along_x(n, "preintegrated", points, "binary");
  const ref::Scene post = along_x(n, "post", points, "binary");
  const Frame fp = prepare(pre, sv), fq = prepare(post, sv);
  int checked = 0;
  for (int y = 0; y < pre.render.height; ++y)
    for (int x = 0; x < pre.render.width; ++x) {
      bittrue::RayTrace tp, tq;
      bittrue::bt_cast_ray(fp.setup, fp.memory, x, y, &tp);
      bittrue::bt_cast_ray(fq.setup, fq.memory, x, y, &tq);
      if (!tp.hit || tp.trace.size() < 2) continue;
      ASSERT_EQ(tp.trace.size(), tq.trace.size());
      EXPECT_EQ(tp.trace.front().alpha, 0.0) << "the first sample ends no segment";
      for (std::size_t k = 1; k < tp.trace.size(); ++k)
        EXPECT_EQ(tp.trace[k].alpha, tq.trace[k].alpha) << k;
      // Post-classification after n - 1 samples: the same accumulator bits.
      EXPECT_EQ(tp.trace.back().accumulator, tq.trace[tq.trace.size() - 2].accumulator);
      ++checked;
    }
  EXPECT_GT(checked, 30);
  // Float: 1 - (1 - a)^(n - 1) whole steps.
  const ref::RenderInputs in = ref::make_render_inputs(pre, sv.volume, sv.gradients,
                                                       pre.camera.pose);
  ref::RayStats st;
  const glm::dvec4 rgba = ref::cast_ray(in.volume, in.tf, in.shading, in.settings,
                                        ref::primary_ray(in.camera, 4, 4), &st, nullptr, 0.0);
  ASSERT_GE(st.samples, 2u);
  EXPECT_NEAR(rgba.a, 1.0 - std::pow(0.9, static_cast<double>(st.samples - 1)), 1e-12);
}

// A ramp of 20 per voxel along the ray and a binary step at 150: a segment
// from 140 to 160 is half in the material, 1 - (1 - a)^0.5 (the table's entry
// within half an LSB), and the engines agree on where it lies.
TEST(Preintegrated, RampAcrossABinaryStepGivesTheAnalyticSegmentOpacity) {
  const PrecisionProfile p = preset_profile("vizard2");
  const ref::TransferFunction tf({{0.0, {1.0, 1.0, 1.0}, 0.0}, {150.0, {1.0, 1.0, 1.0}, 0.6}},
                                 ref::TfInterpolation::Binary, ref::Material{});
  bittrue::FrameSetup fs;
  fs.profile = p;
  fs.preint_table = bittrue::make_preint_table(p, tf, 1.0);
  for (const auto& [front, back, inside] :
       {std::tuple{140.0, 160.0, 0.5}, std::tuple{160.0, 140.0, 0.5},
        std::tuple{100.0, 200.0, 0.5}, std::tuple{145.0, 155.0, 0.5},
        std::tuple{130.0, 170.0, 0.5}, std::tuple{120.0, 160.0, 0.25}}) {
    const double want = 1.0 - std::pow(1.0 - 0.6, inside);
    const double got =
        bittrue::from_raw(bittrue::bt_classify_segment(fs, front, back).alpha, p.alpha_bits);
    EXPECT_NEAR(got, want, std::ldexp(1.0, -(p.alpha_bits + 1))) << front << " -> " << back;
  }
}

// An opaque band of values [150, 152] between two samples of a ramp of 20 per
// voxel: no sample falls in it (post-classification sees nothing), but every
// segment from 140 to 160 crosses it (pre-integration finds it, opaque), in the
// float reference, bit-true, hls and the cycle model.
TEST(Preintegrated, OpaqueBandBetweenTwoSamplesIsFoundAtOneSamplePerVoxel) {
  const int n = 13;
  const cosim::SceneVolume sv = volume_along_x(n, [](int x) { return 20 * x; });
  const std::string points =
      "[ {value = 0, alpha = 0.0}, {value = 150, color = [1, 0, 0], alpha = 1.0}, "
      "{value = 152, alpha = 0.0} ]";
  for (const std::string profile : {"vizard2", "balanced"}) {
    SCOPED_TRACE(profile);
    const ref::Scene pre = along_x(n, "preintegrated", points, "binary", profile);
    const ref::Scene post = along_x(n, "post", points, "binary", profile);
    const Frame fp = prepare(pre, sv), fq = prepare(post, sv);
    const ref::QuantImage hp = cosim::hls_render_image(fp.setup, fp.memory, 2);
    const ref::QuantImage hq = cosim::hls_render_image(fq.setup, fq.memory, 2);
    EXPECT_EQ(hp.pixels, bittrue::bt_render_image(fp.setup, fp.memory, 2).pixels);
    EXPECT_EQ(hp.pixels, rtl::rtl_render(fp.setup, fp.memory).image.pixels);
    const ref::RenderInputs in =
        ref::make_render_inputs(pre, sv.volume, sv.gradients, pre.camera.pose);
    const ref::RenderInputs iq =
        ref::make_render_inputs(post, sv.volume, sv.gradients, post.camera.pose);
    const ref::Image fpre = ref::render_image(in), fpost = ref::render_image(iq);
    for (int y = 2; y < 6; ++y)
      for (int x = 2; x < 6; ++x) {
        EXPECT_GE(alpha_at(hp, x, y), 0.99) << x << ", " << y;
        EXPECT_EQ(alpha_at(hq, x, y), 0.0) << x << ", " << y;
        EXPECT_GE(fpre.at(x, y).a, 0.99);
        EXPECT_EQ(fpost.at(x, y).a, 0.0);
        EXPECT_GE(hp.at(x, y)[0], hp.at(x, y)[3] - 1);  // red
      }
  }
}

// The error budget's rows (`voxcast paper engel2001`, RenderSettings::study)
// where their approximations are exact: on a field linear along the ray the
// trilinear value is the linear one, so the row with the true value along the
// ray is every linear-value row (unshaded: lighting plays no part) to rounding;
// and the 16 sub-samples of a segment, each a slab of constant opacity at its
// midpoint, give the exact table integral (RenderSettings::study = None) within
// the composite midpoint rule's error. The ramp's knots (60, 120) fall on
// samples (x = 3, 6), so along every segment alpha is linear, of slope
// 0.6/60 per value x 20 values per voxel = 0.2, and the optical depth
// -ln(1 - alpha) has second derivative 0.2^2 / (1 - alpha)^2 <= 0.25: the
// rule's error in depth is at most 0.25 / (24 * 16^2) = 4.1e-5 a segment, on
// the three segments inside the ramp (elsewhere alpha is constant and the rule
// exact): 1.3e-4 a ray, and in opacity (1-Lipschitz in depth) no more. The
// colour's integrand c tau e^-D is as smooth (c linear, |c'| <= 0.8/60 per
// value); measured, both are within 1.7e-5.
TEST(Preintegrated, ErrorBudgetRowsAgreeWhereTheirApproximationsAreExact) {
  using Study = ref::RenderSettings::SegmentStudy;
  const int n = 13;
  const cosim::SceneVolume sv = volume_along_x(n, [](int x) { return 20 * x; });
  const std::string points =
      "[ {value = 0, color = [1, 0.5, 0.2], alpha = 0.0}, "
      "{value = 60, color = [1, 0.5, 0.2], alpha = 0.0}, "
      "{value = 120, color = [0.2, 0.5, 1], alpha = 0.6} ]";
  const ref::Scene pre = along_x(n, "preintegrated", points, "ramp");
  ref::RenderInputs in = ref::make_render_inputs(pre, sv.volume, sv.gradients, pre.camera.pose);
  const auto pixel = [&](Study study, int x, int y) {
    in.settings.study = study;
    return ref::cast_ray(in.volume, in.tf, in.shading, in.settings,
                         ref::primary_ray(in.camera, x, y), nullptr, nullptr, 0.0);
  };
  int visible = 0;
  for (int y = 1; y < 7; ++y)
    for (int x = 1; x < 7; ++x) {
      const glm::dvec4 exact_value = pixel(Study::ExactValue, x, y);
      for (Study s : {Study::ExactLighting, Study::GradientLerp, Study::IlluminationLerp}) {
        const glm::dvec4 linear = pixel(s, x, y);
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(linear[c], exact_value[c], 1e-12) << x << ", " << y;
      }
      const glm::dvec4 table = pixel(Study::None, x, y);
      for (int c = 0; c < 4; ++c) EXPECT_NEAR(table[c], exact_value[c], 1.3e-4) << x << ", " << y;
      visible += table.a > 0.5;
    }
  EXPECT_GT(visible, 30) << "the rays cross the material";
}

// The precision guard (cosim/engines/warnings.cpp): a faint material whose
// segments' opacities round to 0 in 8 alpha bits is reported against the key,
// with the 1-D table's alpha warnings (unused) left out; 16 bits keep them.
TEST(Preintegrated, GuardReportsSegmentOpacitiesThatVanish) {
  const cosim::SceneVolume sv = volume_along_x(16, [](int x) { return 10 * x; });
  const auto hazards = [&](const std::string& profile, const std::string& classification) {
    const ref::Scene s = along_x(16, classification,
                                 "[ {value = 0, alpha = 0.0}, {value = 100, color = [1, 1, 1], "
                                 "alpha = 0.0015}, {value = 255, color = [1, 1, 1], alpha = 0.0015} ]",
                                 "ramp", profile);
    std::vector<std::string> kinds;
    for (const cosim::Hazard& h : cosim::precision_hazards(s, sv.volume)) kinds.push_back(h.kind);
    return kinds;
  };
  const auto has = [](const std::vector<std::string>& v, const std::string& k) {
    return std::find(v.begin(), v.end(), k) != v.end();
  };
  const std::vector<std::string> pre8 = hazards("vizard2", "preintegrated");
  EXPECT_TRUE(has(pre8, "preint-alpha-vanishes"));
  EXPECT_FALSE(has(pre8, "alpha-vanishes"));
  EXPECT_TRUE(has(hazards("vizard2", "post"), "alpha-vanishes"));
  EXPECT_FALSE(has(hazards("precise", "preintegrated"), "preint-alpha-vanishes"));
}

// hls == bit-true == the cycle model with pre-integration in every mode and
// with jitter and the vizard2 widths; the cycle model takes the same samples
// as post-classification, in at most one clock per ray more (the deeper stage).
TEST(Preintegrated, EnginesBitExactAndCyclesOfTheDeeperStage) {
  int changed = 0;
  for (const std::string extra : {"", "render.jitter=true", "render.mode=\"unshaded\"",
                                  "render.mode=\"mip\"", "precision.profile=\"vizard2\"",
                                  "precision.profile=\"precise\""}) {
    SCOPED_TRACE(extra);
    ref::Overrides on = {"render.classification=\"preintegrated\""};
    ref::Overrides off = {"render.classification=\"post\"", "render.partial_segments=false"};
    if (!extra.empty()) {
      on.push_back(extra);
      off.push_back(extra);
    }
    const ref::Scene s = small_scene(on, kOrigin), s0 = small_scene(off, kOrigin);
    static const cosim::SceneVolume sv = cosim::load_scene_volume(s);
    const Frame f = prepare(s, sv), f0 = prepare(s0, sv);
    const segments::EngineRun run = segments::expect_engines_agree(f);
    const ref::QuantImage& h = run.hls;
    const ref::QuantImage h0 = cosim::hls_render_image(f0.setup, f0.memory, 2);
    if (s.render.mode == ref::RenderMode::Mip) {
      EXPECT_EQ(h.pixels, h0.pixels) << "MIP is unaffected";
    } else {
      changed += h.pixels != h0.pixels ? 1 : 0;
    }
    // The frame's cost, ERT off (ERT ends rays at other samples when the
    // images differ): the same samples, the deeper stage's clocks at most.
    on.push_back("render.ert_threshold=1.0");
    off.push_back("render.ert_threshold=1.0");
    const Frame g = prepare(small_scene(on, kOrigin), sv);
    const Frame g0 = prepare(small_scene(off, kOrigin), sv);
    const rtl::RtlResult c = rtl::rtl_render(g.setup, g.memory);
    const rtl::RtlResult c0 = rtl::rtl_render(g0.setup, g0.memory);
    EXPECT_EQ(c.image.pixels, cosim::hls_render_image(g.setup, g.memory, 2).pixels);
    EXPECT_EQ(c.stats.samples, c0.stats.samples);
    EXPECT_GE(c.stats.cycles, c0.stats.cycles);
    EXPECT_LE(c.stats.cycles, c0.stats.cycles + 20u * 20u);
  }
  EXPECT_GE(changed, 4);
}

// The key: its round trip, what it refuses (with the key named), the
// elaboration (MIP and post scenes have no table) and the report's price.
TEST(Preintegrated, SceneKeyRefusalsElaborationAndPrice) {
  const ref::Scene on = ref::default_scene({"render.classification=\"preintegrated\""});
  EXPECT_TRUE(on.render.preintegrated());
  EXPECT_FALSE(on.render.partial_segments) << "whole segments: off unless asked for";
  const ref::Scene back = ref::parse_scene(ref::scene_to_toml(on), "round trip", ".");
  EXPECT_TRUE(back.render.preintegrated());
  EXPECT_FALSE(ref::default_scene().render.preintegrated());
  const auto refused = [](const ref::Overrides& o, const std::string& key) {
    try {
      ref::default_scene(o);
    } catch (const Error& e) {
      return std::string(e.what()).find(key) != std::string::npos;
    }
    return false;
  };
  EXPECT_TRUE(refused({"render.classification=\"pre\""}, "render.classification"));
  EXPECT_TRUE(refused({"render.classification=\"preintegrated\"", "render.space_leaping=true"},
                      "render.space_leaping"));
  EXPECT_TRUE(refused({"render.classification=\"preintegrated\"",
                       "render.partial_segments=true"},
                      "render.partial_segments"));
  const cosim::SceneVolume sv = volume_along_x(8, [](int x) { return 30 * x; });
  const auto elaborate = [&](const ref::Overrides& sets) {
    return ref::elaborate(ref::default_scene(sets), sv.volume, sv.gradients);
  };
  const ref::Elaboration with = elaborate({"render.classification=\"preintegrated\""});
  const ref::Elaboration post = elaborate({});
  const ref::Elaboration mip =
      elaborate({"render.classification=\"preintegrated\"", "render.mode=mip"});
  EXPECT_TRUE(with.preintegration);
  EXPECT_FALSE(post.preintegration);
  EXPECT_FALSE(mip.preintegration);
  // Values up to 210 of 8 bits at 8 bits per end: 211 addresses per end.
  EXPECT_EQ(with.preint_side, 211);
  EXPECT_TRUE(cosim::elaborated_units(with).preintegration);
  EXPECT_FALSE(cosim::elaborated_units(post).preintegration);
  EXPECT_TRUE(hls::consistent(cosim::elaborated_units(with)));
  const auto table_bits = [](const ref::Elaboration& e) {
    for (const cosim::UnitOps& u : cosim::unit_operators(e, rtl::pipeline::PipelineConfig{}))
      if (u.name == "preintegration")
        for (const cosim::Op& op : u.ops)
          if (op.kind == cosim::OpKind::Ram) return static_cast<long long>(op.a) * op.b;
    return 0LL;
  };
  const int fields = with.class_color_fields * with.profile.color_bits +
                     (with.class_alpha_varies ? with.profile.alpha_bits : 0);
  EXPECT_EQ(table_bits(with), 211LL * 211 * fields);
  EXPECT_EQ(table_bits(post), 0);
  EXPECT_EQ(table_bits(mip), 0);
  // The cycle model's classification stage takes the table's depth.
  const cosim::ResourceReport a = cosim::estimate_resources(with, cosim::find_part("xc7a200t"));
  const cosim::ResourceReport b = cosim::estimate_resources(post, cosim::find_part("xc7a200t"));
  EXPECT_EQ(a.latency_sample - b.latency_sample,
            hls::preintegration_depth - hls::classification_depth);
  EXPECT_GT(a.total.brams, b.total.brams);
}

}  // namespace VOXCAST_UNITY_ID
}  // namespace voxcast::test
