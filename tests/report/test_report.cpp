// voxcast report and elaboration (issue 6, parts 4-5): the units a scene's
// design contains, the operators at the profile's widths (checked against the
// hls kernels' own types), their mapping to FPGA resources by closed forms and
// datasheet numbers, and the parts' capacities.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <map>
#include <ostream>
#include <set>
#include <string>

#include "cosim/hardware/report.hpp"
#include "hls/classification_table.hpp"
#include "hls/compositor.hpp"
#include "hls/geometry_processor.hpp"
#include "hls/interpolation_processor.hpp"
#include "hls/reflectance_map.hpp"
#include "hls/shader.hpp"
#include "hls/space_leaping_unit.hpp"
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
// The report sizes its operators with hls/widths.hpp's functions, as the hls
// Params structs size their types; here every width of every operator the
// report lists, for a design with every unit, is checked against the kernels'
// own types (T::width) and the cycle model's configuration, for the presets
// and for profiles no preset has. An operator without an expectation here
// fails, so a new operator is checked from its first day.

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

// Every unit the report knows, at the profile's full field widths; MIP or not
// (MIP has no classification or shading stages, so their FIFOs are shorter).
ref::Elaboration every_unit(const PrecisionProfile& p, bool mip) {
  ref::Elaboration e = full(p);
  e.parallel_direction = true;
  e.mip = mip;
  e.space_leaping = true;
  e.leap_block = 8;
  e.leap_blocks = 512;
  e.jitter = true;
  // Two colours and one k vary: the other fields are registers.
  e.class_color_fields = 2;
  e.class_alpha_varies = false;
  e.class_k_fields = 1;
  return e;
}

// An operator's expected shape: its widths (b = 0 where it has one) and, where
// the profile sets it, its count (-1: not checked).
struct Shape {
  int a = 0, b = 0, count = -1;
};
bool operator==(const Shape& s, const Op& op) {
  return s.a == op.a && s.b == op.b && (s.count < 0 || s.count == op.count);
}
std::ostream& operator<<(std::ostream& os, const Shape& s) {
  return os << "{" << s.a << ", " << s.b << ", count " << s.count << "}";
}

int bits_for(long long n) {  // as std::bit_width, at least 1
  return n < 1 ? 1 : static_cast<int>(std::bit_width(static_cast<unsigned long long>(n)));
}

// (unit, operator) -> shape, from the kernels' types of profile P.
template <class P>
std::map<std::pair<std::string, std::string>, Shape> kernel_shapes(const ref::Elaboration& e) {
  using G = hls::GeometryParams<P>;
  using I = hls::InterpolationParams<P>;
  using K = hls::ClassificationParams<P>;
  using R = hls::ReflectanceParams<P>;
  using S = hls::ShaderParams<P>;
  using C = hls::CompositorParams<P>;
  using L = hls::LeapParams<P>;
  const rtl::pipeline::PipelineConfig pc;
  const int pixel = G::pixel_t::width, dir = G::dir_t::width, origin = G::origin_t::width;
  const int unit = G::unit_t::width, step = G::step_t::width, k = G::k_t::width;
  const int pos = G::pos_t::width, count = G::count_t::width, coord = G::coord_t::width;
  const int y = G::y_t::width, sq = G::sq_t::width, dnorm = G::dnorm_t::width;
  const int weight = I::weight_t::width;
  const int word = I::packed_word_t::width;
  const int entry = R::entry_t::width;
  const int acc = C::acc_t::width;
  const int slot = bits_for(pc.ray_slots - 1);
  const int sample = I::value_t::width + 3 * I::gradient_t::width + slot + count;
  const int bc = std::max(1, static_cast<int>(L::bcoord_t::width) - 3);  // leap_block 8
  const int ba = bits_for(e.leap_blocks - 1);
  const int h = (R::res + 2) / 2;  // ceil((rm_res + 1) / 2)
  std::map<std::pair<std::string, std::string>, Shape> m = {
      // §1.1-1.2
      {{"ray_direction+rsqrt", "px·B, py·C"}, {pixel, dir}},
      {{"ray_direction+rsqrt", "d = A + px·B + py·C"}, {dir + pixel + 2}},
      {{"ray_direction+rsqrt", "n2 = d·d"}, {dir, dir}},
      {{"ray_direction+rsqrt", "n2 sum"}, {2 * dir}},
      {{"ray_direction+rsqrt", "leading-zero count of n2"},
       {bits_for(G::n2_t::width), G::n2_t::width}},
      {{"ray_direction+rsqrt", "d' = d·2^e (shifter)"}, {dnorm, G::df + 1}},
      {{"ray_direction+rsqrt", "n2·4^e (shifter)"}, {G::n2_norm_t::width, G::df + 1}},
      {{"ray_direction+rsqrt", "rsqrt seed ROM"}, {G::seed_entries, y}},
      {{"ray_direction+rsqrt", "Newton: y·y"}, {y, y}},
      {{"ray_direction+rsqrt", "Newton: m·t"}, {G::m_t::width, sq}},
      {{"ray_direction+rsqrt", "Newton: 3 - t"}, {sq + 1}},
      {{"ray_direction+rsqrt", "Newton: y·(3 - t)"}, {y, sq + 1}},
      {{"ray_direction+rsqrt", "Newton: rounding"}, {sq}},
      {{"ray_direction+rsqrt", "u = d'·y"}, {dnorm, y}},
      {{"ray_direction+rsqrt", "u rounding"}, {unit}},
      // §1.3-1.6
      {{"ray_setup", "s = u·K"}, {unit, G::kreg_t::width}},
      {{"ray_setup", "s rounding"}, {step}},
      {{"ray_setup", "px·P, py·R"}, {pixel, origin}},
      {{"ray_setup", "o = O + px·P + py·R"}, {origin + pixel + 2}},
      {{"ray_setup", "LO - o, HI - o"}, {G::num_t::width}},
      {{"ray_setup", "k = (LO|HI - o) / s"}, {k, step}},
      {{"ray_setup", "k_lo < k_hi, k_near > k_in, k_far < k_out, k_in < 0, k_in > k_out"}, {k}},
      {{"ray_setup", "k_near, k_far, k_in, k_out"}, {k, 2}},
      {{"ray_setup", "s = 0 axis: LO <= o <= HI"}, {origin}},
      {{"ray_setup", "n = k_out - k_in + 1"}, {count}},
      {{"ray_setup", "k_in·s"}, {k, step}},
      {{"ray_setup", "p0 = o + Q_RND(k_in·s)"}, {pos}},
      // §2
      {{"stepping", "p += s"}, {pos}},
      {{"stepping", "sample counter"}, {count}},
      {{"stepping", "counter = n"}, {count}},
      {{"stepping", "p, s, n of the ray"}, {3 * pos + 3 * step + count}},
      // §3.1-3.3
      {{"address_generator", "clamp p into [LO, HI]"}, {pos}},
      {{"address_generator", "clamp select"}, {pos, 2}},
      {{"address_generator", "i0 = LAST"}, {coord}},
      {{"address_generator", "i0 - 1"}, {coord}},
      {{"address_generator", "f = p - i0"}, {I::frac_t::width}},
      {{"address_generator", "fq = Q_RND(f, wb)"}, {weight}},
      {{"address_generator", "(i0y>>1)·HX"}, {std::max(1, coord - 1), G::half_t::width}},
      {{"address_generator", "(i0z>>1)·HXY"}, {std::max(1, coord - 1), G::slice_t::width}},
      {{"address_generator", "base word address"}, {G::word_addr_t::width}},
      {{"address_generator", "odd-axis increments"}, {G::word_addr_t::width, 2}},
      {{"address_generator", "bank addresses (+1, +HX, +HXY)"}, {G::word_addr_t::width}},
      // §3.4-3.5: lerps v0 + (v1 - v0)·f; a signed lerp's sum has one bit more.
      {{"interpolation", "crossbar: corner j = bank j ^ parity"}, {word, 8}},
      {{"interpolation", "value lerp x: v1 - v0"}, {I::vb + 1}},
      {{"interpolation", "value lerp x: (v1 - v0)·f"}, {I::vb + 1, weight}},
      {{"interpolation", "value lerp x: v0 + ·"}, {I::vlerp1_t::width}},
      {{"interpolation", "value lerp y: v1 - v0"}, {I::vlerp1_t::width + 1}},
      {{"interpolation", "value lerp y: (v1 - v0)·f"}, {I::vlerp1_t::width + 1, weight}},
      {{"interpolation", "value lerp y: v0 + ·"}, {I::vlerp2_t::width}},
      {{"interpolation", "value lerp z: v1 - v0"}, {I::vlerp2_t::width + 1}},
      {{"interpolation", "value lerp z: (v1 - v0)·f"}, {I::vlerp2_t::width + 1, weight}},
      {{"interpolation", "value lerp z: v0 + ·"}, {I::vlerp3_t::width}},
      {{"interpolation", "value Q_RND(·, sf)"}, {I::value_t::width}},
      {{"interpolation", "gradient lerp x: v1 - v0"}, {I::gb + 1}},
      {{"interpolation", "gradient lerp x: (v1 - v0)·f"}, {I::gb + 1, weight}},
      {{"interpolation", "gradient lerp x: v0 + ·"}, {I::glerp1_t::width + 1}},
      {{"interpolation", "gradient lerp y: v1 - v0"}, {I::glerp1_t::width + 1}},
      {{"interpolation", "gradient lerp y: (v1 - v0)·f"}, {I::glerp1_t::width + 1, weight}},
      {{"interpolation", "gradient lerp y: v0 + ·"}, {I::glerp2_t::width + 1}},
      {{"interpolation", "gradient lerp z: v1 - v0"}, {I::glerp2_t::width + 1}},
      {{"interpolation", "gradient lerp z: (v1 - v0)·f"}, {I::glerp2_t::width + 1, weight}},
      {{"interpolation", "gradient lerp z: v0 + ·"}, {I::glerp3_t::width + 1}},
      {{"interpolation", "gradient Q_RND(·, sf)"}, {I::gradient_t::width}},
      // §4: two colours and one k in the table, the rest registers.
      {{"classification", "address Q_RND(value·2^(tf - vb))"}, {K::addr_t::width + 1}},
      {{"classification", "address clamp"}, {K::addr_t::width + 1}},
      {{"classification", "classification table (fields that vary)"},
       {K::entries, 2 * K::color_t::width + K::k_t::width}},
      {{"classification", "constant entry fields"},
       {K::color_t::width + K::alpha_t::width + 2 * K::k_t::width}},
      // §5.1-5.3
      {{"reflectance_map", "gw = g·IS"}, {R::gradient_t::width, R::scale_t::width}},
      {{"reflectance_map", "gw rounding"}, {R::world_gradient_t::width}},
      {{"reflectance_map", "N = -gw, |N|"}, {R::normal_t::width}},
      {{"reflectance_map", "major axis"}, {R::magnitude_t::width}},
      {{"reflectance_map", "N[a], N[b], |N[m]|"}, {R::normal_t::width, 3}},
      {{"reflectance_map", "N[a] + |N[m]|"}, {R::offset_t::width}},
      {{"reflectance_map", "t = (N + |N[m]|)·res·2^wb / 2|N[m]|"},
       {R::pos_t::width, R::den_t::width}},
      {{"reflectance_map", "cell clamp"}, {R::cell_t::width}},
      {{"reflectance_map", "index = face·side² + iv·side + iu"}, {R::index_t::width}},
      // §5.4 nearest, or §5.5 bilinear: four parity banks of 6·h² corners per table.
      {{"reflectance_map", "diffuse + specular tables"}, {R::entries, entry}},
      {{"reflectance_map", "diffuse + specular corner tables, 4 parity banks each"},
       {6 * h * h, entry}},
      {{"reflectance_map", "corner crossbar"}, {entry, 4}},
      {{"reflectance_map", "fu, fv = t - (cell << wb)"}, {R::weight_t::width}},
      // §6
      {{"shader", "kd·D, ks·S"}, {K::k_t::width, entry}},
      {{"shader", "ka + kd·D + ks·S"}, {S::sum_bits}},
      {{"shader", "I = Q_RND(·, shade_bits)"}, {S::intensity_t::width}},
      {{"shader", "colour·I"}, {K::color_t::width, S::intensity_t::width}},
      {{"shader", "c = U(·, shade_bits) rounding"}, {S::shade_t::width + 1}},
      {{"shader", "c saturation"}, {S::shade_t::width + 1}},
      // §7-8
      {{"compositor", "1 - A"}, {acc}},
      {{"compositor", "w = (1 - A)·alpha"}, {acc, C::alpha_t::width}},
      {{"compositor", "w rounding"}, {C::weight_t::width}},
      {{"compositor", "w·c"}, {C::weight_t::width, C::shade_t::width}},
      {{"compositor", "w·c rounding"}, {C::weight_t::width}},
      {{"compositor", "C += w·c, A += w"}, {acc + 1}},
      {{"compositor", "saturation at 1"}, {acc + 1}},
      {{"compositor", "accumulators C, A"}, {4 * acc}},
      {{"ert", "A >= ERT_T"}, {acc}},
      {{"ert", "ERT_T register"}, {acc}},
      {{"mip", "value > M"}, {C::value_t::width}},
      {{"mip", "M, RM registers"}, {C::value_t::width + C::rm_t::width}},
      {{"mip", "M·RM"}, {C::value_t::width, C::rm_t::width}},
      {{"mip", "grey rounding"}, {C::grey_t::width}},
      {{"mip", "grey saturation"}, {C::grey_t::width}},
      {{"output", "x·(2^ob - 1) = (x << ob) - x"}, {acc + C::out_bits}},
      {{"output", "Q_RND(·, 0)"}, {C::out_t::width + 1}},
      // Space leaping: blocks of 8^3 (lb = 3), leap_bits search stages.
      {{"space_leaping", "by·BX"}, {bc, bc}},
      {{"space_leaping", "bz·BXY"}, {bc, ba}},
      {{"space_leaping", "block address"}, {ba}},
      {{"space_leaping", "min-max block memory (min, max)"},
       {static_cast<int>(e.leap_blocks), 2 * L::voxel_value_t::width}},
      {{"space_leaping", "address Q_RND(min, max)"}, {K::addr_t::width + 1}},
      {{"space_leaping", "address clamp"}, {K::addr_t::width + 1}},
      {{"space_leaping", "opacity prefix table (2 read ports)"},
       {K::entries + 1, L::count_t::width}},
      {{"space_leaping", "prefix[hi + 1] = prefix[lo]"}, {L::count_t::width}},
      {{"space_leaping", "leap q + 2^j·s"}, {pos, 0, 3 * L::leap_bits}},
      {{"space_leaping", "leap clamp"}, {pos, 0, 6 * L::leap_bits}},
      {{"space_leaping", "leap clamp select"}, {pos, 2, 6 * L::leap_bits}},
      {{"space_leaping", "leap i0 = LAST"}, {coord, 0, 3 * L::leap_bits}},
      {{"space_leaping", "leap same block"}, {bc, 0, 3 * L::leap_bits}},
      {{"space_leaping", "leap run + 2^j"}, {count, 0, L::leap_bits}},
      {{"space_leaping", "leap run + 2^j <= remaining"}, {count, 0, L::leap_bits}},
      {{"space_leaping", "leap take"}, {3 * pos + count, 2, L::leap_bits}},
      {{"jitter", "lowbias32 x·C"}, {32, 32}},
      {{"jitter", "k_in + J·2^-tf"}, {k}},
      // The cycle model's FIFOs: depth = the stage's latency + the skid.
      {{"pipeline_buffers", "ray slots (p0, s, n)"}, {pc.ray_slots, 3 * pos + 3 * step + count}},
      {{"pipeline_buffers", "sample buffer (8 voxel words, weights, parity)"},
       {pc.sample_buffer, 8 * word + 3 * weight + 3 + slot + count}},
      // (MIP has no classification or shading stages.)
      {{"pipeline_buffers", "interpolation.out"},
       {pc.latency.interpolation + pc.fifo_depth, sample}},
      {{"pipeline_buffers", "classification.out"},
       {(e.mip ? 0 : pc.latency.classification) + pc.fifo_depth, sample + K::entry_bits}},
      {{"pipeline_buffers", "shading.out"},
       {(e.mip ? 0 : pc.latency.shading) + pc.fifo_depth,
        3 * C::shade_t::width + C::alpha_t::width + slot + count}},
      {{"pipeline_buffers", "output pixels"}, {pc.output_depth, 4 * C::out_t::width + 2 * pixel}},
  };
  // §5.5 the blend of each table: lerps along u and v, one rounding.
  for (const std::string t : {"D", "S"}) {
    const int l1 = R::lerp1_t::width, w = R::weight_t::width;
    m[{"reflectance_map", t + " lerp u: v1 - v0"}] = {entry + 1};
    m[{"reflectance_map", t + " lerp u: (v1 - v0)·f"}] = {entry + 1, w};
    m[{"reflectance_map", t + " lerp u: v0 + ·"}] = {l1};
    m[{"reflectance_map", t + " lerp v: v1 - v0"}] = {l1 + 1};
    m[{"reflectance_map", t + " lerp v: (v1 - v0)·f"}] = {l1 + 1, w};
    m[{"reflectance_map", t + " lerp v: v0 + ·"}] = {R::lerp2_t::width};
    m[{"reflectance_map", t + " Q_RND(·, rf)"}] = {entry};
  }
  return m;
}

template <PrecisionProfile V>
void expect_kernel_widths() {
  using P = ProfileTraits<V>;
  for (const bool mip : {false, true}) {
    const ref::Elaboration e = every_unit(V, mip);
    const auto shapes = kernel_shapes<P>(e);
    std::set<std::string> units;
    int checked = 0;
    for (const auto& u : cosim::unit_operators(e)) {
      units.insert(u.name);
      for (const Op& op : u.ops) {
        const auto it = shapes.find({u.name, op.what});
        if (it == shapes.end()) {
          ADD_FAILURE() << u.name << ": operator \"" << op.what << "\" has no expected shape";
          continue;
        }
        EXPECT_TRUE(it->second == op) << u.name << ": " << op.what << ": expected " << it->second
                                      << ", report {" << op.a << ", " << op.b << ", count "
                                      << op.count << "} (mip " << mip << ")";
        ++checked;
      }
    }
    // Every unit is in the design (MIP only in the MIP design).
    EXPECT_EQ(units.size(), mip ? 15u : 14u);
    EXPECT_GT(checked, 100);
  }
}

constexpr PrecisionProfile odd_profile(int variant) {
  PrecisionProfile p = kBalanced;
  if (variant == 1) {
    // Nearest reflectance map with integer bits; stored gradients finer than the
    // samples (one more integer bit after rounding); a small volume.
    p.rm_bilinear = 0;
    p.rm_res = 12;
    p.rm_int_bits = 1;
    p.gradient_frac_bits = 5;
    p.sample_frac_bits = 2;
    p.addr_bits = 7;
    p.pos_frac_bits = 3;
    p.tf_addr_bits = 5;
  } else if (variant == 2) {
    // A tiny volume (one word address bit, fewer than 10 leap stages), an odd
    // bilinear grid, narrow everything.
    p = kVizard2;
    p.rm_bilinear = 1;
    p.rm_res = 5;
    p.rm_weight_bits = 3;
    p.addr_bits = 1;
    p.pos_frac_bits = 2;
    p.t_frac_bits = 4;
    p.weight_bits = 2;
    p.out_bits = 12;
  } else {
    // Wide words: 16-bit values and gradients with more fraction bits than the samples keep.
    p = kPrecise;
    p.gradient_frac_bits = 12;
    p.sample_frac_bits = 6;
    p.acc_bits = 24;
    p.shade_bits = 10;
    p.k_bits = 5;
  }
  return p;
}

TEST(ReportWidths, EqualTheKernelTypesForEveryPreset) {
  expect_kernel_widths<kVizard2>();
  expect_kernel_widths<kBalanced>();
  expect_kernel_widths<kPrecise>();
}

TEST(ReportWidths, EqualTheKernelTypesForProfilesNoPresetHas) {
  expect_kernel_widths<odd_profile(1)>();
  expect_kernel_widths<odd_profile(2)>();
  expect_kernel_widths<odd_profile(3)>();
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
