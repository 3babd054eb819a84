// voxcast report and elaboration (issue 6, parts 4-5): the units a scene's
// design contains, the operators at the profile's widths (checked against the
// hls kernels' own types), their mapping to FPGA resources by closed forms and
// datasheet numbers, and the parts' capacities.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "cosim/report.hpp"
#include "hls/classification_table.hpp"
#include "hls/compositor.hpp"
#include "hls/geometry_processor.hpp"
#include "hls/interpolation_processor.hpp"
#include "hls/reflectance_map.hpp"
#include "hls/shader.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/preset_profiles.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/pipeline/config.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

using cosim::Family;
using cosim::Op;
using cosim::OpKind;

// A transfer function with two varying colours and alpha.
ref::TransferFunction test_tf() {
  return ref::TransferFunction({{0, {1, 0.5, 0.2}, 0.0}, {100, {1, 0.8, 0.9}, 0.5}},
                               ref::TfInterpolation::Ramp, ref::Material{});
}

ref::DataRange full_range(const PrecisionProfile& p) {
  return {p.value_bits, (1u << p.value_bits) - 1u, 0.0};
}

ref::Elaboration elab(ref::RenderMode mode, ref::Projection proj, double ert,
                      const PrecisionProfile& p = kBalanced) {
  ref::DataRange r = full_range(p);
  r.max_gradient = 100.0;
  return ref::elaborate(p, mode, proj, ert, test_tf(), r);
}

std::set<std::string> units_of(const ref::Elaboration& e) {
  std::set<std::string> names;
  for (const auto& u : cosim::estimate_resources(e, cosim::find_part("xc7a200t")).units)
    names.insert(u.unit.name);
  return names;
}

std::set<std::string> minus(std::set<std::string> a, const std::set<std::string>& b) {
  for (const auto& x : b) a.erase(x);
  return a;
}

const std::set<std::string> kShadedPerspective = {
    "ray_direction+rsqrt", "ray_setup",      "stepping", "address_generator", "interpolation",
    "classification",      "reflectance_map", "shader",  "compositor",        "ert",
    "output",              "pipeline_buffers"};

TEST(Elaboration, ShadedPerspectiveHasEveryUnitButMip) {
  EXPECT_EQ(units_of(elab(ref::RenderMode::Shaded, ref::Projection::Perspective, 0.98)),
            kShadedPerspective);
}

TEST(Elaboration, MipRemovesClassificationShadingAndGradients) {
  const auto e = elab(ref::RenderMode::Mip, ref::Projection::Perspective, 0.98);
  std::set<std::string> expected =
      minus(kShadedPerspective, {"classification", "reflectance_map", "shader", "compositor", "ert"});
  expected.insert("mip");
  EXPECT_EQ(units_of(e), expected);
  EXPECT_FALSE(e.gradients);
  EXPECT_EQ(e.gradient_store_bits, 0);
  // No gradient lerps in the interpolation unit; the crossbar carries the value only.
  for (const auto& u : cosim::unit_operators(e)) {
    for (const Op& op : u.ops) {
      EXPECT_EQ(op.what.find("gradient"), std::string::npos) << u.name << ": " << op.what;
      if (op.what.rfind("crossbar", 0) == 0) {
        EXPECT_EQ(op.a, kBalanced.value_bits);
      }
    }
  }
}

TEST(Elaboration, UnshadedRemovesTheReflectanceMapAndTheIntensityProducts) {
  const auto e = elab(ref::RenderMode::Unshaded, ref::Projection::Perspective, 0.98);
  EXPECT_EQ(units_of(e), minus(kShadedPerspective, {"reflectance_map"}));
  for (const auto& u : cosim::unit_operators(e)) {
    if (u.name == "shader") {
      for (const Op& op : u.ops) EXPECT_NE(op.kind, OpKind::Mul) << op.what;
    }
    for (const Op& op : u.ops) EXPECT_EQ(op.what.find("gradient"), std::string::npos) << op.what;
  }
}

TEST(Elaboration, ParallelCameraRemovesThePerspectiveHardware) {
  const auto e = elab(ref::RenderMode::Shaded, ref::Projection::Parallel, 0.98);
  EXPECT_EQ(units_of(e), minus(kShadedPerspective, {"ray_direction+rsqrt"}));
  // ... and its ray set-up computes the per-pixel origin instead.
  int origin_muls = 0;
  for (const auto& u : cosim::unit_operators(e))
    for (const Op& op : u.ops)
      if (op.what == "px·P, py·R") origin_muls += op.count;
  EXPECT_EQ(origin_muls, 6);
  // The cycle model's ray set-up is shorter by the rsqrt stages.
  const rtl::pipeline::UnitLatencies base;
  EXPECT_EQ(rtl::pipeline::elaborate_latencies(base, {false, true, false}).ray_setup,
            base.ray_setup - rtl::pipeline::kRsqrtStages);
}

TEST(Elaboration, ErtOffRemovesOnlyTheTerminationLogic) {
  EXPECT_EQ(units_of(elab(ref::RenderMode::Shaded, ref::Projection::Perspective, 1.0)),
            minus(kShadedPerspective, {"ert"}));
}

TEST(Elaboration, EveryOmissionHasAReason) {
  for (auto mode : {ref::RenderMode::Shaded, ref::RenderMode::Unshaded, ref::RenderMode::Mip})
    for (auto proj : {ref::Projection::Perspective, ref::Projection::Parallel})
      for (const auto& o : elab(mode, proj, 1.0).omitted) {
        EXPECT_FALSE(o.unit.empty());
        EXPECT_GT(o.reason.size(), 20u) << o.unit;
      }
}

TEST(Elaboration, SizesFollowTheDataAndTheTransferFunction) {
  // An 8-bit volume whose values reach 100 in a 12-bit value field: 7 stored
  // bits; table addresses up to round(100·16·2^(12-12)) = 1600.
  ref::DataRange r{8, 100, 3.0};
  const auto e = ref::elaborate(kBalanced, ref::RenderMode::Shaded, ref::Projection::Perspective,
                                0.98, test_tf(), r);
  EXPECT_EQ(e.value_store_bits, 7);
  EXPECT_EQ(e.class_entries, 1601);
  // Gradient 3.0 << 4 (shift) << 3 (gradient_frac_bits) = 384: 9 bits + sign.
  EXPECT_EQ(e.gradient_store_bits, 10);
  // Red is 1 at both points: a register; green, blue and alpha vary; one material: k registers.
  EXPECT_EQ(e.class_color_fields, 2);
  EXPECT_TRUE(e.class_alpha_varies);
  EXPECT_EQ(e.class_k_fields, 0);
  for (const auto& u : cosim::unit_operators(e)) {
    for (const Op& op : u.ops) {
      if (op.kind == OpKind::Ram && u.name == "classification") {
        EXPECT_EQ(op.a, 1601);
        EXPECT_EQ(op.b, 2 * kBalanced.color_bits + kBalanced.alpha_bits);
      }
    }
  }
}

TEST(Elaboration, ThroughTheSceneFile) {
  const ref::Scene s = ref::parse_scene(
      "[volume]\nsource = \"phantom:shepp-logan?size=16\"\n"
      "[classification]\npoints = [ {value = 0, alpha = 0.0}, {value = 200, alpha = 0.5} ]\n"
      "[camera]\nprojection = \"parallel\"\neye = [7.5, -30, 7.5]\ncenter = [7.5, 7.5, 7.5]\n"
      "height = 20\n[render]\nwidth = 8\nheight = 8\nmode = \"mip\"\n",
      "mip scene", ".");
  const auto r = cosim::estimate_resources(s, cosim::find_part("xcv1000e"));
  std::set<std::string> names;
  for (const auto& u : r.units) names.insert(u.unit.name);
  EXPECT_EQ(names, (std::set<std::string>{"ray_setup", "stepping", "address_generator",
                                          "interpolation", "mip", "output", "pipeline_buffers"}));
  EXPECT_NE(cosim::report_markdown(r).find("render.mode = mip"), std::string::npos);
  EXPECT_NE(cosim::report_json(r).find("\"omitted\""), std::string::npos);
}

// ---- The report's widths are the kernels' widths ------------------------------------------

const Op& find_op(const std::vector<cosim::UnitOps>& units, const std::string& what) {
  for (const auto& u : units)
    for (const Op& op : u.ops)
      if (op.what == what) return op;
  throw Error("no operator " + what);
}

ref::Elaboration full(const PrecisionProfile& p) {
  ref::Elaboration e;
  e.profile = p;
  e.value_store_bits = p.value_bits;
  e.gradient_store_bits = p.gradient_bits;
  e.class_entries = 1 << p.tf_addr_bits;
  return e;
}

template <PrecisionProfile P>
void expect_kernel_widths() {
  using G = hls::GeometryParams<ProfileTraits<P>>;
  using I = hls::InterpolationParams<ProfileTraits<P>>;
  using R = hls::ReflectanceParams<ProfileTraits<P>>;
  using S = hls::ShaderParams<ProfileTraits<P>>;
  using C = hls::CompositorParams<ProfileTraits<P>>;
  using K = hls::ClassificationParams<ProfileTraits<P>>;
  const auto u = cosim::unit_operators(full(P));
  EXPECT_EQ(find_op(u, "s = u·K").a, G::unit_t::width);
  EXPECT_EQ(find_op(u, "s = u·K").b, G::kreg_t::width);
  EXPECT_EQ(find_op(u, "n2 = d·d").a, G::dir_t::width);
  EXPECT_EQ(find_op(u, "rsqrt seed ROM").a, G::seed_entries);
  EXPECT_EQ(find_op(u, "rsqrt seed ROM").b, G::y_t::width);
  EXPECT_EQ(find_op(u, "Newton: m·t").a, G::m_t::width);
  EXPECT_EQ(find_op(u, "Newton: m·t").b, G::sq_t::width);
  EXPECT_EQ(find_op(u, "u = d'·y").a, G::dnorm_t::width);
  EXPECT_EQ(find_op(u, "LO - o, HI - o").a, G::num_t::width);
  EXPECT_EQ(find_op(u, "k = (LO|HI - o) / s").a, G::k_t::width);
  EXPECT_EQ(find_op(u, "k = (LO|HI - o) / s").b, G::step_t::width);
  EXPECT_EQ(find_op(u, "k_in·s").a, G::k_t::width);
  EXPECT_EQ(find_op(u, "p += s").a, G::pos_t::width);
  EXPECT_EQ(find_op(u, "n = k_out - k_in + 1").a, G::count_t::width);
  EXPECT_EQ(find_op(u, "base word address").a, I::word_addr_t::width);
  EXPECT_EQ(find_op(u, "crossbar: corner j = bank j ^ parity").a, I::word_bits);
  EXPECT_EQ(find_op(u, "value lerp x: (v1 - v0)·f").b, I::weight_t::width);
  EXPECT_EQ(find_op(u, "value lerp z: v0 + ·").a, I::vlerp3_t::width);
  EXPECT_EQ(find_op(u, "value Q_RND(·, sf)").a, I::value_t::width);
  EXPECT_EQ(find_op(u, "gradient Q_RND(·, sf)").a, I::gradient_t::width);
  EXPECT_EQ(find_op(u, "gradient lerp x: (v1 - v0)·f").a, I::gb + 1);
  EXPECT_EQ(find_op(u, "classification table (fields that vary)").a, K::entries);
  EXPECT_EQ(find_op(u, "gw = g·IS").a, R::gradient_t::width);
  EXPECT_EQ(find_op(u, "gw = g·IS").b, R::scale_t::width);
  EXPECT_EQ(find_op(u, "N = -gw, |N|").a, R::normal_t::width);
  EXPECT_EQ(find_op(u, "t = (N + |N[m]|)·res·2^wb / 2|N[m]|").a, R::pos_t::width);
  EXPECT_EQ(find_op(u, "t = (N + |N[m]|)·res·2^wb / 2|N[m]|").b, R::den_t::width);
  EXPECT_EQ(find_op(u, "index = face·side² + iv·side + iu").a, R::index_t::width);
  if constexpr (R::bilinear) {
    EXPECT_EQ(find_op(u, "D lerp v: v0 + ·").a, R::lerp2_t::width);
    EXPECT_EQ(find_op(u, "D lerp u: (v1 - v0)·f").b, R::weight_t::width);
  } else {
    EXPECT_EQ(find_op(u, "diffuse + specular tables").a, R::entries);
    EXPECT_EQ(find_op(u, "diffuse + specular tables").b, R::entry_t::width);
  }
  EXPECT_EQ(find_op(u, "kd·D, ks·S").a, K::k_t::width);
  EXPECT_EQ(find_op(u, "kd·D, ks·S").b, R::entry_t::width);
  EXPECT_EQ(find_op(u, "colour·I").b, S::intensity_t::width);
  EXPECT_EQ(find_op(u, "w = (1 - A)·alpha").a, C::acc_t::width);
  EXPECT_EQ(find_op(u, "w = (1 - A)·alpha").b, C::alpha_t::width);
  EXPECT_EQ(find_op(u, "w·c").b, C::shade_t::width);
  EXPECT_EQ(find_op(u, "A >= ERT_T").a, C::acc_t::width);
}

TEST(ReportWidths, EqualTheKernelTypesForEveryPreset) {
  expect_kernel_widths<kVizard2>();
  expect_kernel_widths<kBalanced>();
  expect_kernel_widths<kPrecise>();
}

TEST(ReportWidths, FollowAProfileChange) {
  PrecisionProfile p = kBalanced;
  const auto before = cosim::unit_operators(full(p));
  p.weight_bits += 2;
  p.shade_bits += 3;
  const auto after = cosim::unit_operators(full(p));
  EXPECT_EQ(find_op(after, "value lerp x: (v1 - v0)·f").b,
            find_op(before, "value lerp x: (v1 - v0)·f").b + 2);
  EXPECT_EQ(find_op(after, "value lerp z: v0 + ·").a, find_op(before, "value lerp z: v0 + ·").a + 6);
  EXPECT_EQ(find_op(after, "w·c").b, find_op(before, "w·c").b + 3);
  EXPECT_EQ(find_op(after, "colour·I").b, find_op(before, "colour·I").b + 3);
  const auto part = cosim::find_part("xc7a200t");
  EXPECT_GT(cosim::estimate_resources(full(p), part).total.luts,
            cosim::estimate_resources(full(kBalanced), part).total.luts);
}

// ---- The resource model: closed forms and datasheets ----------------------------------------

Op mulop(int a, bool as, int b, bool bs) { return {OpKind::Mul, "m", 1, a, b, as, bs}; }

TEST(ResourceModel, Dsp48e1CountsFollowTheTilingClosedForm) {
  // DSP48E1 is 25 x 18 signed (UG479): an s-bit signed operand splits into
  // ceil((s - 1)/24) pieces on the 25-bit port or ceil((s - 1)/17) on the 18-bit one.
  for (int a = 2; a <= 60; ++a)
    for (int b = 2; b <= 60; ++b) {
      if (a + b < 9) {
        EXPECT_EQ(cosim::dsp_count(mulop(a, true, b, true), Family::Series7), 0);
        continue;
      }
      auto c = [](int x, int y) { return (x - 1 + y - 1) / y; };
      const int expect = std::min(c(a, 24) * c(b, 17), c(a, 17) * c(b, 24));
      EXPECT_EQ(cosim::dsp_count(mulop(a, true, b, true), Family::Series7), expect) << a << "x" << b;
    }
  EXPECT_EQ(cosim::dsp_count(mulop(25, true, 18, true), Family::Series7), 1);
  EXPECT_EQ(cosim::dsp_count(mulop(24, false, 17, false), Family::Series7), 1);
  EXPECT_EQ(cosim::dsp_count(mulop(32, true, 32, true), Family::Series7), 4);
  // Virtex-II MULT18X18 (DS031): 18 x 18 signed, 35 x 35 in four.
  EXPECT_EQ(cosim::dsp_count(mulop(18, true, 18, true), Family::Virtex2), 1);
  EXPECT_EQ(cosim::dsp_count(mulop(19, true, 18, true), Family::Virtex2), 2);
  EXPECT_EQ(cosim::dsp_count(mulop(35, true, 35, true), Family::Virtex2), 4);
  // Virtex-E has no multiplier blocks: LUTs, a·b LUT4 for an array multiplier.
  EXPECT_EQ(cosim::dsp_count(mulop(8, true, 8, true), Family::VirtexE), 0);
  EXPECT_EQ(cosim::op_resources(mulop(8, false, 6, false), Family::VirtexE).luts, 48);
}

TEST(ResourceModel, BlockRamForDepthTimesWidth) {
  // Widths in multiples of 36 and depths in multiples of 512: (D/512)·(W/36) RAMB18E1.
  for (int d = 512; d <= 4096; d += 512)
    for (int w = 36; w <= 144; w += 36)
      EXPECT_EQ(cosim::bram_count(d, w, Family::Series7), (d / 512) * (w / 36)) << d << "x" << w;
  // Deep and narrow: 16K x 1 per RAMB18.
  EXPECT_EQ(cosim::bram_count(65536, 1, Family::Series7), 4);
  // VIZARD II's 2 KB classification table (256 x 64 bits) in Virtex-E 4-kbit
  // blocks (256 x 16): 4; its 3 KB of reflectance maps (2 x 1536 x 8, 512 x 8): 6.
  EXPECT_EQ(cosim::bram_count(256, 64, Family::VirtexE), 4);
  EXPECT_EQ(2 * cosim::bram_count(1536, 8, Family::VirtexE), 6);
  // At most 2 kbit, or 32 deep: LUT RAM.
  EXPECT_EQ(cosim::bram_count(64, 32, Family::Series7), 0);
  EXPECT_EQ(cosim::bram_count(32, 200, Family::Series7), 0);
}

TEST(ResourceModel, PartsCarryTheirDatasheetCapacities) {
  const auto& a7 = cosim::find_part("xc7a200t");  // DS180: 33,650 slices, 740 DSP, 365 RAMB36
  EXPECT_EQ(a7.luts, 33650 * 4);
  EXPECT_EQ(a7.ffs, 33650 * 8);
  EXPECT_EQ(a7.dsps, 740);
  EXPECT_EQ(a7.brams, 2 * 365);
  const auto& k7 = cosim::find_part("xc7k325t");  // DS180: 50,950 slices, 840 DSP, 445 RAMB36
  EXPECT_EQ(k7.luts, 50950 * 4);
  EXPECT_EQ(k7.dsps, 840);
  EXPECT_EQ(k7.brams, 2 * 445);
  const auto& ve = cosim::find_part("xcv1000e");  // DS022: 64 x 96 CLBs, 4 LUT4 each; 96 x 4 kbit
  EXPECT_EQ(ve.luts, 64 * 96 * 4);
  EXPECT_EQ(ve.brams * 4096, 393216);
  EXPECT_EQ(ve.dsps, 0);
  EXPECT_THROW(cosim::find_part("xc9000"), Error);
}

TEST(ResourceModel, TotalsAreTheSumOfTheUnits) {
  for (const auto& part : cosim::parts()) {
    const auto r = cosim::estimate_resources(full(kVizard2), part);
    cosim::Resources sum;
    for (const auto& u : r.units) sum += u.res;
    EXPECT_DOUBLE_EQ(sum.luts, r.total.luts);
    EXPECT_DOUBLE_EQ(sum.ffs, r.total.ffs);
    EXPECT_DOUBLE_EQ(sum.dsps, r.total.dsps);
    EXPECT_DOUBLE_EQ(sum.brams, r.total.brams);
    EXPECT_DOUBLE_EQ(cosim::cost(r.total, part),
                     r.total.luts / part.luts + r.total.ffs / part.ffs +
                         (part.dsps ? r.total.dsps / part.dsps : 0.0) + r.total.brams / part.brams);
  }
}

}  // namespace
}  // namespace voxcast::test
