// render.partial_segments (issue 19 part 2, docs/pipeline.md §7a) in every
// engine of the ray caster:
//  - closed form: the opacity of a constant medium along a ray of any length
//    L (not only whole steps) is 1 - (1 - a)^(L/step): the float reference to
//    1e-12, the bit-true engine within the bound the widths give;
//  - the issue's scene: a 0.01-voxel eye move changes no pixel by more than 1
//    LSB with partial segments, in the float reference and in hls (and does
//    change some by more without them: the test can fail);
//  - hls == bit-true == the cycle model, bit for bit, with partial segments,
//    jitter and space leaping; and the cycle model's frame takes the same
//    cycles with and without partial segments in a shaded frame (the unit
//    overlaps the reflectance map and the shader).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "cosim/engines/engines.hpp"
#include "cosim/hardware/report.hpp"
#include "cosim/hardware/synth_script.hpp"
#include "hls/units.hpp"
#include "refmodel/bittrue/geometry.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/bittrue/shading.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/elaboration.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/engine.hpp"
#include "tests/segments/segment_engines.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

using segments::Frame;
using segments::prepare;
using segments::small_scene;
constexpr const char* kOrigin = "partial segments engines";

// A constant volume of edge n (stored value 100) with its gradients.
cosim::SceneVolume constant_volume(int n) {
  return segments::volume_along_x(n, [](int) { return 100; });
}

// The issue's scene: a binary transfer function of alpha 0.1 above 50 (the
// whole volume), white, unshaded, ERT off, perspective from `eye` towards the
// centre of a 64^3 volume, fov 50, at one sample per voxel.
ref::Scene issue_scene(const std::string& eye, bool partial, int n = 64, int image = 128) {
  const std::string c = std::to_string((n - 1) / 2.0);
  return ref::parse_scene(
      "[volume]\nsource = \"phantom:box\"\n"
      "[classification]\ninterpolation = \"binary\"\npoints = [ {value = 0, alpha = 0.0}, "
      "{value = 50, color = [1, 1, 1], alpha = 0.1} ]\n"
      "[camera]\neye = " +
          eye + "\ncenter = [" + c + ", " + c + ", " + c +
          "]\nfov_deg = 50\n"
          "[render]\nwidth = " +
          std::to_string(image) + "\nheight = " + std::to_string(image) +
          "\nmode = \"unshaded\"\nert_threshold = 1.0\n"
          "partial_segments = " +
          (partial ? "true" : "false") + "\n",
      "issue 19 scene", ".");
}

// The float image in output LSBs, as the fixed-point engines quantize (§8).
std::vector<long> float_lsb(const ref::Image& img, int out_bits) {
  const double top = std::ldexp(1.0, out_bits) - 1.0;
  std::vector<long> v;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 4; ++c) v.push_back(std::lround(img.at(x, y)[c] * top));
  return v;
}
std::vector<long> quant_lsb(const ref::QuantImage& img) {
  std::vector<long> v;
  for (const auto& px : img.pixels)
    for (const std::uint32_t ch : px) v.push_back(static_cast<long>(ch));
  return v;
}
long largest_change(const std::vector<long>& a, const std::vector<long>& b) {
  long d = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}
// Pixels (four channels each) with a channel that changed by more than 1 LSB.
long pixels_beyond_one_lsb(const std::vector<long>& a, const std::vector<long>& b) {
  long n = 0;
  for (std::size_t i = 0; i < a.size(); i += 4) {
    long d = 0;
    for (std::size_t c = 0; c < 4; ++c) d = std::max(d, std::abs(a[i + c] - b[i + c]));
    n += d > 1 ? 1 : 0;
  }
  return n;
}

// The largest change of a pixel channel, in output LSBs, between the eye at E
// and at E + (0.01, 0, 0): float reference and hls.
struct EyeMove {
  long ref = 0, hls = 0;
  long ref_pixels = 0, hls_pixels = 0;  // pixels changed by more than 1 LSB
};
EyeMove eye_move(bool partial, const cosim::SceneVolume& sv) {
  const ref::Scene a = issue_scene("[31.5, -60, 40]", partial);
  const ref::Scene b = issue_scene("[31.51, -60, 40]", partial);
  EyeMove m;
  const auto render_ref = [&](const ref::Scene& s) {
    return float_lsb(
        ref::render_image(ref::make_render_inputs(s, sv.volume, sv.gradients, s.camera.pose)),
        s.precision.out_bits);
  };
  const std::vector<long> ra = render_ref(a), rb = render_ref(b);
  m.ref = largest_change(ra, rb);
  m.ref_pixels = pixels_beyond_one_lsb(ra, rb);
  const Frame fa = prepare(a, sv), fb = prepare(b, sv);
  const std::vector<long> ha = quant_lsb(cosim::hls_render_image(fa.setup, fa.memory));
  const std::vector<long> hb = quant_lsb(cosim::hls_render_image(fb.setup, fb.memory));
  m.hls = largest_change(ha, hb);
  m.hls_pixels = pixels_beyond_one_lsb(ha, hb);
  return m;
}

TEST(PartialSegments, EyeMoveOfAHundredthVoxelChangesNoPixelByMoreThanOneLsb) {
  const cosim::SceneVolume sv = constant_volume(64);
  const EyeMove on = eye_move(true, sv);
  EXPECT_LE(on.ref, 1) << "float reference";
  EXPECT_LE(on.hls, 1) << "hls";
  // Without partial segments the sample counts jump: the test can fail.
  const EyeMove off = eye_move(false, sv);
  EXPECT_GT(off.ref, 1) << "float reference, partial segments off";
  EXPECT_GT(off.hls, 1) << "hls, partial segments off";
  const auto say = [](const EyeMove& m) {
    return "ref " + std::to_string(m.ref) + " LSB (" + std::to_string(m.ref_pixels) +
           " pixels > 1 LSB), hls " + std::to_string(m.hls) + " LSB (" +
           std::to_string(m.hls_pixels) + " pixels > 1 LSB)";
  };
  RecordProperty("largest_change", "on: " + say(on) + "; off: " + say(off));
}

// Closed form on a constant volume seen by an oblique parallel camera (every
// pixel a different length through the box, at one and at 2.5 samples per
// voxel, with and without jitter): ref's opacity is 1 - (1 - a)^L with L the
// ray's length in the box (world units); the bit-true accumulator's is
// 1 - (1 - alpha_c)^(k_out - k_in0), the table's rounded alpha_c over the
// length the set-up computed, within n·2^-(acc+1) (the accumulator's roundings)
// + 2·E (the first and last samples' weighted alpha, §7a.6).
TEST(PartialSegments, ConstantMediumOpacityIsClosedFormForAnyLength) {
  const int n = 12;
  const cosim::SceneVolume sv = constant_volume(n);
  const double a = 0.1;
  for (const std::string os : {"1", "2.5"})
    for (const bool jitter : {false, true}) {
      SCOPED_TRACE("oversampling " + os + (jitter ? ", jitter" : ""));
      const ref::Scene s = ref::parse_scene(
          "[volume]\nsource = \"phantom:box\"\n"
          "[classification]\npoints = [ {value = 0, color = [1, 1, 1], alpha = 0.1} ]\n"
          "[camera]\nprojection = \"parallel\"\neye = [-9.3, -14.1, 19.7]\n"
          "center = [5.5, 5.5, 5.5]\nheight = 22\n"
          "[render]\nwidth = 24\nheight = 24\nmode = \"unshaded\"\nert_threshold = 1.0\n"
          "oversampling = " +
              os + "\npartial_segments = true\njitter = " + (jitter ? "true" : "false") + "\n",
          "closed form", ".");
      const ref::RenderInputs in =
          ref::make_render_inputs(s, sv.volume, sv.gradients, s.camera.pose);
      const Frame f = prepare(s, sv);
      const PrecisionProfile& p = s.precision;
      const double alpha_c = bittrue::from_raw(f.setup.class_table[0].alpha, p.alpha_bits);
      const double E =
          std::ldexp(1.0, -(p.alpha_bits + 1)) +
          (3.0 * std::log(2.0) + 3.0) * std::ldexp(1.0, -(bittrue::segment_frac_bits(p) + 1));
      int hits = 0;
      for (int y = 0; y < s.render.height; ++y)
        for (int x = 0; x < s.render.width; ++x) {
          const ref::Ray ray = ref::primary_ray(in.camera, x, y);
          const auto seg = ref::clip(ray, in.volume.world_box);
          const glm::dvec4 rgba =
              ref::cast_ray(in.volume, in.tf, in.shading, in.settings, ray, nullptr, nullptr,
                            ref::pixel_jitter(in.settings, x, y));
          if (!seg) continue;
          const double L = seg->length();
          if (L >= in.settings.step * ref::pixel_jitter(in.settings, x, y)) {
            EXPECT_NEAR(rgba.a, 1.0 - std::pow(1.0 - a, L), 1e-12) << x << ", " << y;
          }
          // Bit-true: the accumulator after the ray (before the output quantization).
          bittrue::RayTrace t;
          bittrue::bt_cast_ray(f.setup, f.memory, x, y, &t);
          const bittrue::BtRay br = bittrue::bt_ray_setup(f.setup, x, y);
          if (!br.hit || t.trace.empty()) continue;
          ++hits;
          const double j =
              f.setup.regs.jitter
                  ? std::ldexp(static_cast<double>(ref::jitter_raw(x, y, p.t_frac_bits)),
                               -p.t_frac_bits)
                  : 0.0;
          const double len = br.k_out - (br.k_in - j);
          const double expect = 1.0 - std::pow(1.0 - alpha_c, len);
          const double bound =
              static_cast<double>(br.n) * std::ldexp(1.0, -(p.acc_bits + 1)) + 2.0 * E;
          EXPECT_NEAR(t.trace.back().accumulator[3], expect, bound) << x << ", " << y;
        }
      EXPECT_GT(hits, 100);
    }
}

// hls == bit-true == the cycle model with partial segments on, in every mode
// and with jitter and space leaping; a shaded frame's cycles do not change.
TEST(PartialSegments, EnginesBitExactAndShadedCyclesUnchanged) {
  int changed = 0;
  for (const std::string extra :
       {"", "render.jitter=true", "render.space_leaping=true", "render.mode=\"unshaded\"",
        "render.mode=\"mip\"", "precision.profile=\"vizard2\""}) {
    SCOPED_TRACE(extra);
    ref::Overrides on = {"render.partial_segments=true"};
    ref::Overrides off = {"render.partial_segments=false"};
    if (!extra.empty()) {
      on.push_back(extra);
      off.push_back(extra);
    }
    const ref::Scene s = small_scene(on, kOrigin);
    const ref::Scene s0 = small_scene(off, kOrigin);
    static const cosim::SceneVolume sv = cosim::load_scene_volume(s);
    const Frame f = prepare(s, sv), f0 = prepare(s0, sv);
    const segments::EngineRun run = segments::expect_engines_agree(f);
    const ref::QuantImage& h = run.hls;
    const rtl::RtlResult& r = run.rtl;
    // The weights change the image (somewhere; not in MIP), never the samples.
    const ref::QuantImage h0 = cosim::hls_render_image(f0.setup, f0.memory, 2);
    if (s.render.mode != ref::RenderMode::Mip) {
      changed += h.pixels != h0.pixels ? 1 : 0;
    } else {
      EXPECT_EQ(h.pixels, h0.pixels);
    }
    const rtl::RtlResult r0 = rtl::rtl_render(f0.setup, f0.memory);
    EXPECT_EQ(r.stats.samples, r0.stats.samples);
    if (s.render.mode != ref::RenderMode::Unshaded) {
      EXPECT_EQ(r.stats.cycles, r0.stats.cycles);
    }
  }
  EXPECT_GE(changed, 3);
}

// The key round-trips through the scene file and is on by default (chosen from
// the measurements in docs/accuracy.md, "Partial segments"); a scene with it off
// (or in MIP) elaborates no segment-opacity unit, one with it does, and the
// synthesized top's unit set says so; the resource report prices the unit only
// when present.
TEST(PartialSegments, SceneKeyElaborationAndReport) {
  const ref::Scene on = ref::default_scene({"render.partial_segments=true"});
  EXPECT_TRUE(ref::parse_scene(ref::scene_to_toml(on), "round trip", ".").render.partial_segments);
  const ref::Scene off_scene = ref::default_scene({"render.partial_segments=false"});
  EXPECT_FALSE(
      ref::parse_scene(ref::scene_to_toml(off_scene), "round trip", ".").render.partial_segments);
  EXPECT_TRUE(ref::default_scene().render.partial_segments);
  const cosim::SceneVolume sv = constant_volume(8);
  const auto elaborate = [&](const ref::Overrides& sets) {
    return ref::elaborate(ref::default_scene(sets), sv.volume, sv.gradients);
  };
  const auto omitted = [](const ref::Elaboration& e) {
    for (const ref::Omission& o : e.omitted)
      if (o.unit == "segment_opacity") return true;
    return false;
  };
  const ref::Elaboration off = elaborate({"render.partial_segments=false"}),
                         with = elaborate({}),
                         mip = elaborate({"render.partial_segments=true", "render.mode=mip"});
  EXPECT_FALSE(off.partial_segments);
  EXPECT_TRUE(omitted(off));
  EXPECT_TRUE(with.partial_segments);
  EXPECT_FALSE(omitted(with));
  EXPECT_FALSE(mip.partial_segments);
  EXPECT_TRUE(omitted(mip));
  EXPECT_TRUE(cosim::elaborated_units(with).partial_segments);
  EXPECT_FALSE(cosim::elaborated_units(off).partial_segments);
  EXPECT_TRUE(hls::consistent(cosim::elaborated_units(mip)));
  const auto priced = [](const ref::Elaboration& e) {
    for (const cosim::UnitOps& u : cosim::unit_operators(e, rtl::pipeline::PipelineConfig{}))
      if (u.name == "segment_opacity") return true;
    return false;
  };
  EXPECT_TRUE(priced(with));
  EXPECT_FALSE(priced(off));
}

}  // namespace VOXCAST_UNITY_ID
}  // namespace voxcast::test
