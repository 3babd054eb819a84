#include "cosim/hardware/report.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include "cosim/engines/engines.hpp"
#include "hls/compositor.hpp"
#include "hls/segment_opacity.hpp"
#include "hls/widths.hpp"
#include "refmodel/error.hpp"

namespace voxcast::cosim {

namespace {

int bits_for(long long n) {  // unsigned bits holding 0..n (at least 1)
  return hls::widths::bits_for(n);
}
int ceil_div(long long a, long long b) { return static_cast<int>((a + b - 1) / b); }

Op mul(std::string what, int count, int a, bool as, int b, bool bs) {
  return {OpKind::Mul, std::move(what), count, a, b, as, bs};
}
Op add(std::string what, int count, int w) { return {OpKind::Add, std::move(what), count, w, 0}; }
Op cmp(std::string what, int count, int w) { return {OpKind::Cmp, std::move(what), count, w, 0}; }
Op mux(std::string what, int count, int w, int inputs) {
  return {OpKind::Mux, std::move(what), count, w, inputs};
}
Op div(std::string what, int count, int q, int d) {
  return {OpKind::Div, std::move(what), count, q, d};
}
Op reg(std::string what, int bits) { return {OpKind::Reg, std::move(what), 1, bits, 0}; }
Op mem(OpKind k, std::string what, int count, int depth, int width) {
  return {k, std::move(what), count, depth, width};
}

// The operators below are sized by the hls Params structs' own width functions
// (hls/widths.hpp), called on the scene's profile: `f` is the profile as the
// kernels' widths see it. tests/report/test_report.cpp checks every width of
// every operator against the kernels' types.
using hls::ProfileFields;
namespace wd = hls::widths;

// One lerp v0 + (v1 - v0)·f on operands of `bits` (signed difference) and a
// weight of wb + 1 unsigned bits: subtract, multiply, add.
void lerp(std::vector<Op>& ops, const std::string& what, int count, int bits, int wb,
          bool is_signed) {
  ops.push_back(add(what + ": v1 - v0", count, bits + 1));
  ops.push_back(mul(what + ": (v1 - v0)·f", count, bits + 1, true, wb + 1, false));
  ops.push_back(add(what + ": v0 + ·", count, bits + wb + (is_signed ? 1 : 0)));
}

UnitOps geometry_rsqrt(const ProfileFields& f) {
  UnitOps u{"ray_direction+rsqrt", "§1.1-1.2", {}, 0, 1};
  auto& o = u.ops;
  const int dir = wd::dir_bits(f);
  o.push_back(mul("px·B, py·C", 6, wd::pixel_bits, false, dir, true));
  o.push_back(add("d = A + px·B + py·C", 6, dir + wd::pixel_bits + 2));
  o.push_back(mul("n2 = d·d", 3, dir, true, dir, true));
  o.push_back(add("n2 sum", 2, 2 * dir));
  o.push_back(mux("leading-zero count of n2", 1, bits_for(wd::n2_bits(f)), wd::n2_bits(f)));
  o.push_back(mux("d' = d·2^e (shifter)", 3, wd::dnorm_bits(f), f.dir_frac_bits + 1));
  o.push_back(mux("n2·4^e (shifter)", 1, wd::n2_norm_bits(f), f.dir_frac_bits + 1));
  o.push_back(mem(OpKind::Rom, "rsqrt seed ROM", 1, wd::rsqrt_seed_entries(f), wd::y_bits(f)));
  o.push_back(mul("Newton: y·y", 2, wd::y_bits(f), false, wd::y_bits(f), false));
  o.push_back(mul("Newton: m·t", 2, wd::m_bits(f), false, wd::sq_bits(f), false));
  o.push_back(add("Newton: 3 - t", 2, wd::sq_bits(f) + 1));
  o.push_back(mul("Newton: y·(3 - t)", 2, wd::y_bits(f), false, wd::sq_bits(f) + 1, true));
  o.push_back(add("Newton: rounding", 6, wd::sq_bits(f)));
  o.push_back(mul("u = d'·y", 3, wd::dnorm_bits(f), true, wd::y_bits(f), false));
  o.push_back(add("u rounding", 3, wd::unit_bits(f)));
  return u;
}

UnitOps ray_setup(const ProfileFields& f) {
  UnitOps u{"ray_setup", "§1.3-1.6", {}, 0, 1};
  auto& o = u.ops;
  const int k = wd::clip_quotient_bits(f);
  o.push_back(mul("s = u·K", 3, wd::unit_bits(f), true, wd::kreg_bits(f), false));
  o.push_back(add("s rounding", 3, wd::step_bits(f)));
  // The pixel's point on the origin plane, for either camera (§0, §1.4).
  o.push_back(mul("px·P, py·R", 6, wd::pixel_bits, false, wd::origin_bits(f), true));
  o.push_back(add("o = O + px·P + py·R", 6, wd::origin_bits(f) + wd::pixel_bits + 2));
  o.push_back(add("LO - o, HI - o", 6, wd::clip_num_bits(f)));
  o.push_back(div("k = (LO|HI - o) / s", 6, k, wd::step_bits(f)));
  o.push_back(cmp("k_lo < k_hi, k_near > k_in, k_far < k_out, k_in < 0, k_in > k_out", 3 + 4 + 2,
                  k));
  o.push_back(mux("k_near, k_far, k_in, k_out", 10, k, 2));
  o.push_back(cmp("s = 0 axis: LO <= o <= HI", 6, wd::origin_bits(f)));
  o.push_back(add("n = k_out - k_in + 1", 1, wd::count_bits(f)));
  o.push_back(mul("k_in·s", 3, k, true, wd::step_bits(f), true));
  o.push_back(add("p0 = o + Q_RND(k_in·s)", 3, wd::pos_bits(f)));
  return u;
}

// The registers of a ray in flight: p0 (or p), s and n.
int ray_state_bits(const ProfileFields& f) {
  return 3 * wd::pos_bits(f) + 3 * wd::step_bits(f) + wd::count_bits(f);
}

UnitOps stepping(const ProfileFields& f) {
  UnitOps u{"stepping", "§2", {}, 0, 1};
  u.ops.push_back(add("p += s", 3, wd::pos_bits(f)));
  u.ops.push_back(add("sample counter", 1, wd::count_bits(f)));
  u.ops.push_back(cmp("counter = n", 1, wd::count_bits(f)));
  u.ops.push_back(reg("p, s, n of the ray", ray_state_bits(f)));
  return u;
}

UnitOps address_generator(const ProfileFields& f) {
  UnitOps u{"address_generator", "§3.1-3.3", {}, 0, 1};
  auto& o = u.ops;
  const int pos = wd::pos_bits(f);
  const int coord = wd::coord_bits(f);
  const int half_index = std::max(1, coord - 1);  // i0 >> 1
  o.push_back(cmp("clamp p into [LO, HI]", 6, pos));
  o.push_back(mux("clamp select", 6, pos, 2));
  o.push_back(cmp("i0 = LAST", 3, coord));
  o.push_back(add("i0 - 1", 3, coord));
  o.push_back(add("f = p - i0", 3, wd::cell_frac_bits(f)));
  o.push_back(add("fq = Q_RND(f, wb)", 3, wd::lerp_weight_bits(f)));
  o.push_back(mul("(i0y>>1)·HX", 1, half_index, false, wd::half_bits(f), false));
  o.push_back(mul("(i0z>>1)·HXY", 1, half_index, false, wd::slice_bits(f), false));
  o.push_back(add("base word address", 2, wd::word_addr_bits(f)));
  o.push_back(mux("odd-axis increments", 3, wd::word_addr_bits(f), 2));
  o.push_back(add("bank addresses (+1, +HX, +HXY)", 12, wd::word_addr_bits(f)));
  return u;
}

UnitOps interpolation(const ProfileFields& f, const ref::Elaboration& e) {
  UnitOps u{"interpolation", "§3.4-3.5", {}, 0, 1};
  auto& o = u.ops;
  const int wb = f.weight_bits;
  const int word = e.value_store_bits + 3 * e.gradient_store_bits;
  o.push_back(mux("crossbar: corner j = bank j ^ parity", 8, word, 8));
  // The value's low value_bits - value_store_bits bits are constant zeros in
  // every voxel (§3.4), so the lerps run on the stored bits (elaboration).
  const int vs = e.value_store_bits;
  lerp(o, "value lerp x", 4, vs, wb, false);
  lerp(o, "value lerp y", 2, vs + wb, wb, false);
  lerp(o, "value lerp z", 1, vs + 2 * wb, wb, false);
  o.push_back(add("value Q_RND(·, sf)", 1, wd::sample_value_bits(f)));
  if (e.gradients) {
    const int gs = e.gradient_store_bits;
    lerp(o, "gradient lerp x", 12, gs, wb, true);
    lerp(o, "gradient lerp y", 6, gs + wb, wb, true);
    lerp(o, "gradient lerp z", 3, gs + 2 * wb, wb, true);
    o.push_back(add("gradient Q_RND(·, sf)", 3, wd::sample_grad_bits(f)));
  }
  return u;
}

UnitOps classification(const ProfileFields& f, const ref::Elaboration& e) {
  UnitOps u{"classification", "§4", {}, 0, 1};
  const int entry = e.class_color_fields * f.color_bits +
                    (e.class_alpha_varies ? f.alpha_bits : 0) + e.class_k_fields * f.k_bits;
  const int constant = wd::class_entry_bits(f) - entry;
  u.ops.push_back(add("address Q_RND(value·2^(tf - vb))", 1, wd::class_addr_round_bits(f)));
  u.ops.push_back(cmp("address clamp", 1, wd::class_addr_round_bits(f)));
  u.ops.push_back(mem(OpKind::Ram, "classification table (fields that vary)", 1, e.class_entries,
                      entry));
  if (constant > 0) u.ops.push_back(reg("constant entry fields", constant));
  return u;
}

// render.classification = "preintegrated" (docs/pipeline.md §4a,
// hls/preintegration_table.hpp): the two addresses, the ray slot's front
// sample register, the 2-D table of the classification entry's varying
// fields (preint_side^2 entries: 2^16 x 32 bits = 2 Mbit at 8 bits per end
// and 8-bit colour and alpha), and the first sample's transparent entry.
UnitOps preintegration(const ProfileFields& f, const ref::Elaboration& e) {
  UnitOps u{"preintegration", "§4a", {}, 0, 1};
  const int entry = e.class_color_fields * f.color_bits +
                    (e.class_alpha_varies ? f.alpha_bits : 0) + e.class_k_fields * f.k_bits;
  const int address_round = f.preint_addr_bits + 1;  // Q_RND can carry, as §4.1's
  u.ops.push_back(add("front, back address Q_RND(value·2^(pb - vb))", 2, address_round));
  u.ops.push_back(cmp("front, back address clamp", 2, address_round));
  u.ops.push_back(reg("front sample (value, gradient)",
                      wd::sample_value_bits(f) + 3 * wd::sample_grad_bits(f)));
  u.ops.push_back(mem(OpKind::Ram, "pre-integration table (fields that vary)", 1,
                      e.preint_side * e.preint_side, entry));
  u.ops.push_back(mux("first sample: transparent", 1, entry, 2));
  return u;
}

UnitOps reflectance(const ProfileFields& f) {
  const bool bilinear = wd::rm_bilinear(f);
  UnitOps u{"reflectance_map", bilinear ? "§5.1-5.3, §5.5" : "§5.1-5.4", {}, 0, 1};
  auto& o = u.ops;
  const int g = wd::sample_grad_bits(f);
  const int n = wd::rm_normal_bits(f);
  const int entry = wd::rm_entry_bits(f);
  const int wb = wd::rm_pos_frac_bits(f);
  o.push_back(mul("gw = g·IS", 3, g, true, wd::rm_scale_bits(f), false));
  o.push_back(add("gw rounding", 3, g));
  o.push_back(add("N = -gw, |N|", 3, n));
  o.push_back(cmp("major axis", 2, wd::rm_magnitude_bits(f)));
  o.push_back(mux("N[a], N[b], |N[m]|", 3, n, 3));
  o.push_back(add("N[a] + |N[m]|", 2, n));
  o.push_back(
      div("t = (N + |N[m]|)·res·2^wb / 2|N[m]|", 2, wd::rm_pos_bits(f), wd::rm_den_bits(f)));
  o.push_back(cmp("cell clamp", 2, wd::rm_cell_bits(f)));
  o.push_back(add("index = face·side² + iv·side + iu", 2, wd::rm_index_bits(f)));
  if (bilinear) {
    o.push_back(mem(OpKind::Ram, "diffuse + specular corner tables, 4 parity banks each", 8,
                    wd::rm_bank_entries(f), entry));
    o.push_back(mux("corner crossbar", 8, entry, 4));
    o.push_back(add("fu, fv = t - (cell << wb)", 2, wd::rm_blend_weight_bits(f)));
    for (const char* t : {"D", "S"}) {
      lerp(o, std::string(t) + " lerp u", 2, entry, wb, false);
      lerp(o, std::string(t) + " lerp v", 1, wd::rm_lerp_bits(f, 1), wb, false);
      o.push_back(add(std::string(t) + " Q_RND(·, rf)", 1, entry));
    }
  } else {
    o.push_back(mem(OpKind::Ram, "diffuse + specular tables", 2, wd::rm_entries(f), entry));
  }
  return u;
}

UnitOps shader(const ProfileFields& f, bool shaded) {
  UnitOps u{"shader", "§6", {}, 0, 1};
  auto& o = u.ops;
  if (shaded) {
    o.push_back(mul("kd·D, ks·S", 2, f.k_bits, false, wd::rm_entry_bits(f), false));
    o.push_back(add("ka + kd·D + ks·S", 2, wd::intensity_sum_bits(f)));
    o.push_back(add("I = Q_RND(·, shade_bits)", 1, wd::intensity_bits(f)));
    o.push_back(mul("colour·I", 3, f.color_bits, false, wd::intensity_bits(f), false));
  }
  o.push_back(add("c = U(·, shade_bits) rounding", 3, f.shade_bits + 1));
  o.push_back(cmp("c saturation", 3, f.shade_bits + 1));
  return u;
}

UnitOps compositor(const ProfileFields& f) {
  UnitOps u{"compositor", "§7.1-7.2", {}, 0, 1};
  auto& o = u.ops;
  const int acc = wd::acc_word_bits(f);
  o.push_back(add("1 - A", 1, acc));
  o.push_back(mul("w = (1 - A)·alpha", 1, acc, false, f.alpha_bits, false));
  o.push_back(add("w rounding", 1, acc));
  o.push_back(mul("w·c", 3, acc, false, f.shade_bits, false));
  o.push_back(add("w·c rounding", 3, acc));
  o.push_back(add("C += w·c, A += w", 4, acc + 1));
  o.push_back(cmp("saturation at 1", 4, acc + 1));
  o.push_back(reg("accumulators C, A", 4 * acc));
  return u;
}

UnitOps ert(const ProfileFields& f) {
  UnitOps u{"ert", "§7.3", {}, 0, 1};
  u.ops.push_back(cmp("A >= ERT_T", 1, wd::acc_word_bits(f)));
  u.ops.push_back(reg("ERT_T register", wd::acc_word_bits(f)));
  return u;
}

UnitOps mip(const ProfileFields& f) {
  UnitOps u{"mip", "§7 MIP", {}, 0, 1};
  const int value = wd::sample_value_bits(f);
  u.ops.push_back(cmp("value > M", 1, value));
  u.ops.push_back(reg("M, RM registers", value + wd::mip_scale_bits(f)));
  u.ops.push_back(mul("M·RM", 1, value, false, wd::mip_scale_bits(f), false));
  u.ops.push_back(add("grey rounding", 1, wd::grey_bits(f)));
  u.ops.push_back(cmp("grey saturation", 1, wd::grey_bits(f)));
  return u;
}

UnitOps output(const ProfileFields& f) {
  UnitOps u{"output", "§8", {}, 0, 1};
  // x·(2^out_bits - 1) = (x << out_bits) - x: a subtractor, not a multiplier.
  u.ops.push_back(add("x·(2^ob - 1) = (x << ob) - x", 4, wd::acc_word_bits(f) + f.out_bits));
  u.ops.push_back(add("Q_RND(·, 0)", 4, f.out_bits + 1));
  return u;
}

// Space leaping (docs/leaping.md, hls/space_leaping_unit.hpp): the block
// look-up beside the address generator and the leaping stepper's search.
UnitOps space_leaping(const ProfileFields& f, const ref::Elaboration& e) {
  UnitOps u{"space_leaping", "docs/leaping.md", {}, 0, 1};
  auto& o = u.ops;
  const int lb = std::countr_zero(static_cast<unsigned>(e.leap_block));
  const int bc = std::max(1, wd::block_coord_bits(f) - lb);  // block coordinates the volume needs
  const int ba = bits_for(std::max(1LL, e.leap_blocks - 1));
  const int prefix = wd::prefix_count_bits(f);
  // Block look-up: coordinates are wiring (i0 >> lb), then the address.
  o.push_back(mul("by·BX", 1, bc, false, bc, false));
  o.push_back(mul("bz·BXY", 1, bc, false, ba, false));
  o.push_back(add("block address", 2, ba));
  o.push_back(mem(OpKind::Ram, "min-max block memory (min, max)", 1,
                  static_cast<int>(e.leap_blocks), 2 * e.value_store_bits));
  // The table addresses of min and max (as §4.1), two prefix reads, the test.
  o.push_back(add("address Q_RND(min, max)", 2, wd::class_addr_round_bits(f)));
  o.push_back(cmp("address clamp", 2, wd::class_addr_round_bits(f)));
  o.push_back(mem(OpKind::Ram, "opacity prefix table (2 read ports)", 1,
                  std::max(e.class_entries, 1) + 1, prefix));
  o.push_back(cmp("prefix[hi + 1] = prefix[lo]", 1, prefix));
  // The leap: leap_bits stages of q + 2^j·s, the candidate's block coordinates
  // (clamp, i0 = LAST) and their comparison with the block's, and the run count.
  const int stages = wd::leap_bits(f);
  const int pos = wd::pos_bits(f);
  const int count = wd::count_bits(f);
  o.push_back(add("leap q + 2^j·s", 3 * stages, pos));
  o.push_back(cmp("leap clamp", 6 * stages, pos));
  o.push_back(mux("leap clamp select", 6 * stages, pos, 2));
  o.push_back(cmp("leap i0 = LAST", 3 * stages, wd::coord_bits(f)));
  o.push_back(cmp("leap same block", 3 * stages, bc));
  o.push_back(add("leap run + 2^j", stages, count));
  o.push_back(cmp("leap run + 2^j <= remaining", stages, count));
  o.push_back(mux("leap take", stages, 3 * pos + count, 2));
  return u;
}

// render.jitter: the pixel hash (refmodel/render/jitter.hpp) and k_in + J.
UnitOps jitter(const ProfileFields& f) {
  UnitOps u{"jitter", "docs/leaping.md", {}, 0, 1};
  u.ops.push_back(mul("lowbias32 x·C", 2, 32, false, 32, false));
  u.ops.push_back(add("k_in + J·2^-tf", 1, wd::clip_quotient_bits(f)));
  return u;
}

// render.partial_segments (docs/pipeline.md §7a, hls/segment_opacity.hpp): the
// ray's two weights at set-up, the optical-depth table beside the
// classification table, w·tau2, the 2^-x ROM and its lerp, the shift and U(1 - v).
UnitOps segment_opacity(const ProfileFields& f, const ref::Elaboration& e) {
  UnitOps u{"segment_opacity", "§7a", {}, 0, 1};
  auto& o = u.ops;
  const int w = wd::segment_weight_bits(f);
  const int mant = wd::segment_mant_bits(f);
  const int lf = wd::segment_lerp_frac_bits(f);
  o.push_back(add("d = k_out - k_in", 1, wd::clip_quotient_bits(f)));
  o.push_back(add("first = 1 + j or frac(d) + j", 2, w));
  o.push_back(reg("the ray's first and last weights", 2 * w));
  o.push_back(cmp("k = 0, k = n - 1", 2, wd::count_bits(f)));
  o.push_back(mux("the sample's weight", 1, w, 3));
  o.push_back(cmp("w = 1 (bypass)", 1, w));
  // One tau2 per classification entry the data can address (the class table's depth).
  o.push_back(mem(OpKind::Ram, "optical depth tau2 per classification entry", 1,
                  e.class_entries, wd::segment_tau_bits(f)));
  o.push_back(mul("w·tau2", 1, w, false, wd::segment_tau_bits(f), false));
  o.push_back(add("y rounding", 1, wd::segment_y_bits(f)));
  o.push_back(mem(OpKind::Rom, "2^-x ROM (two adjacent entries per read)", 1,
                  wd::segment_rom_entries(f), mant));
  o.push_back(add("lerp: e0 - e1", 1, mant));
  o.push_back(mul("lerp: (e0 - e1)·u", 1, mant, false, lf, false));
  o.push_back(add("lerp: e0 - · and rounding", 1, mant + lf));
  o.push_back(cmp("floor(y) > ab + 2", 1, wd::segment_y_int_bits(f)));
  o.push_back(mux("m·2^-s (shifter)", 1, wd::segment_scaled_bits(f), wd::segment_max_shift(f) + 1));
  o.push_back(add("1 - v", 1, wd::segment_scaled_bits(f)));
  o.push_back(add("U(·, ab) rounding", 1, f.alpha_bits + 1));
  o.push_back(mux("alpha_c or alpha_w", 1, f.alpha_bits, 2));
  return u;
}

// The FIFOs and ray slots of the cycle model's pipeline (rtl_model/pipeline),
// at the widths of what they carry.
UnitOps pipeline_buffers(const ProfileFields& f, const ref::Elaboration& e,
                         const rtl::pipeline::PipelineConfig& pc,
                         const rtl::pipeline::UnitLatencies& l) {
  UnitOps u{"pipeline_buffers", "rtl_model/pipeline", {}, 0, 1};
  auto& o = u.ops;
  const int slot = bits_for(pc.ray_slots - 1);
  const int word = e.value_store_bits + 3 * e.gradient_store_bits;
  const int count = wd::count_bits(f);
  const int sample =
      wd::sample_value_bits(f) + (e.gradients ? 3 * wd::sample_grad_bits(f) : 0) + slot + count;
  o.push_back(mem(OpKind::Fifo, "ray slots (p0, s, n)", 1, pc.ray_slots, ray_state_bits(f)));
  o.push_back(mem(OpKind::Fifo, "sample buffer (8 voxel words, weights, parity)", 1,
                  pc.sample_buffer, 8 * word + 3 * wd::lerp_weight_bits(f) + 3 + slot + count));
  o.push_back(mem(OpKind::Fifo, "interpolation.out", 1, l.interpolation + pc.fifo_depth, sample));
  if (e.classification)
    o.push_back(mem(OpKind::Fifo, "classification.out", 1, l.classification + pc.fifo_depth,
                    sample + wd::class_entry_bits(f)));
  if (e.compositor)
    o.push_back(mem(OpKind::Fifo, "shading.out", 1, l.shading + pc.fifo_depth,
                    3 * f.shade_bits + f.alpha_bits + slot + count));
  o.push_back(mem(OpKind::Fifo, "output pixels", 1, pc.output_depth,
                  4 * f.out_bits + 2 * wd::pixel_bits));
  return u;
}

// ---- The resource model ---------------------------------------------------------------------

// Pieces of an s-bit signed operand on an n-bit signed multiplier port: the top
// piece signed (n bits), the others unsigned (n - 1 bits).
int limbs(int s, int n) { return s <= n ? 1 : 1 + ceil_div(s - n, n - 1); }

int signed_width(int w, bool is_signed) { return w + (is_signed ? 0 : 1); }

}  // namespace

const char* to_string(OpKind k) {
  switch (k) {
    case OpKind::Mul: return "mul";
    case OpKind::Add: return "add";
    case OpKind::Cmp: return "cmp";
    case OpKind::Mux: return "mux";
    case OpKind::Div: return "div";
    case OpKind::Reg: return "reg";
    case OpKind::Rom: return "rom";
    case OpKind::Ram: return "ram";
    case OpKind::Fifo: return "fifo";
  }
  return "?";
}

std::vector<UnitOps> unit_operators(const ref::Elaboration& e,
                                    const rtl::pipeline::PipelineConfig& pc) {
  const ProfileFields f = hls::profile_fields(e.profile);
  // The cycle model's elaborated latencies, whose defaults are the units' depths
  // declared next to their kernels (hls::*_depth); the units inside a stage of
  // the cycle model (rsqrt in the ray set-up, stepping in the address stage, the
  // shader in the shading stage) are split by those depths.
  const rtl::pipeline::UnitLatencies l = rtl::pipeline::elaborate_latencies(
      pc.latency, {e.mip, e.reflectance_map, e.perspective, e.space_leaping, e.partial_segments,
                   e.preintegration});
  std::vector<UnitOps> units;
  auto put = [&](UnitOps u, int latency, int ii = 1) {
    u.latency = latency;
    u.ii = ii;
    units.push_back(std::move(u));
  };
  const int rsqrt = e.perspective ? rtl::pipeline::kRsqrtStages : 0;
  if (e.perspective) put(geometry_rsqrt(f), rsqrt, l.ray_setup_interval);
  put(ray_setup(f), l.ray_setup - rsqrt, l.ray_setup_interval);
  put(stepping(f), hls::stepping_depth);
  put(address_generator(f), l.address - hls::stepping_depth);
  // Beside the address generator: adds its look-up to the requests' latency.
  if (e.space_leaping) put(space_leaping(f, e), l.leap_lookup);
  // Beside the direction and rsqrt pipeline, shorter than it: no latency.
  if (e.jitter) put(jitter(f), 0, l.ray_setup_interval);
  put(interpolation(f, e), l.interpolation);
  // The pre-integration table reads beside the classification table, one clock
  // deeper: the stage takes its depth (elaborate_latencies).
  if (e.classification)
    put(classification(f, e),
        e.preintegration ? std::min(l.classification, hls::classification_depth)
                         : l.classification);
  if (e.preintegration) put(preintegration(f, e), l.classification);
  if (e.reflectance_map) put(reflectance(f), l.shading - hls::shader_depth);
  if (e.shader)
    put(shader(f, e.reflectance_map),
        e.reflectance_map ? hls::shader_depth
                          : std::min(l.shading, rtl::pipeline::kUnshadedShadeStages));
  // Beside the reflectance map and the shader (the shading stage takes the
  // longer of the two, elaborate_latencies).
  if (e.partial_segments) put(segment_opacity(f, e), hls::segment_opacity_depth);
  if (e.compositor) put(compositor(f), hls::compositor_depth);
  if (e.ert) put(ert(f), hls::ert_depth);
  if (e.mip) put(mip(f), hls::mip_depth);
  put(output(f), hls::output_quantization_depth);
  put(pipeline_buffers(f, e, pc, l), 0);
  return units;
}

// ---- Parts ----------------------------------------------------------------------------------
const std::vector<Part>& parts() {
  static const std::vector<Part> k = {
      // Xilinx DS022 (Virtex-E 1.8 V FPGAs), table 1: XCV1000E, CLB array 64 x 96 = 6,144
      // CLBs of 2 slices, 2 LUT4 + 2 FF per slice; 96 BlockSelectRAM+ blocks of 4,096 bits
      // (393,216 bits); no multipliers. The family of the VIZARD II card's era (2001).
      {"xcv1000e", Family::VirtexE, "Xilinx DS022 Virtex-E, table 1", 24576, 24576, 0, 96},
      // Xilinx DS031 (Virtex-II), table 1: XC2V3000, 14,336 slices (2 LUT4 + 2 FF each),
      // 96 MULT18X18, 96 18-kbit SelectRAM blocks.
      {"xc2v3000", Family::Virtex2, "Xilinx DS031 Virtex-II, table 1", 28672, 28672, 96, 96},
      // Xilinx DS180 (7 Series FPGAs overview), table 3: XC7A200T, 33,650 slices (4 LUT6 +
      // 8 FF each), 740 DSP48E1, 365 RAMB36E1 = 730 RAMB18E1.
      {"xc7a200t", Family::Series7, "Xilinx DS180 7 Series, table 3 (Artix-7)", 134600, 269200,
       740, 730},
      // DS180 table 4: XC7K325T, 50,950 slices, 840 DSP48E1, 445 RAMB36E1 = 890 RAMB18E1.
      {"xc7k325t", Family::Series7, "Xilinx DS180 7 Series, table 4 (Kintex-7)", 203800, 407600,
       840, 890},
      // The Alveo U250's device (constraints/boards/alveo_u250.toml: xcu250-figd2104-2L-e), a
      // VU13P-class Virtex UltraScale+: AMD DS962 (Alveo U200 and U250 Data Center Accelerator
      // Cards Data Sheet), table 1, and DS923 (Virtex UltraScale+ FPGA Data Sheet), the VU13P
      // column: 1,728K LUT6, 3,456K FF (2 per LUT), 12,288 DSP48E2, 2,688 RAMB36E2 (94.5 Mb) =
      // 5,376 RAMB18E2, 1,280 URAM288 (360 Mb). The figures as those data sheets list them; not
      // re-read from the PDFs for this table (docs/resources.md, "The XCU250").
      {"xcu250", Family::UltraScalePlus,
       "AMD DS962 Alveo U200/U250 data sheet, table 1; DS923 Virtex UltraScale+ (VU13P)", 1728000,
       3456000, 12288, 5376, 1280},
  };
  return k;
}

namespace {
// "xcv1000e, xc2v3000, ...": the parts' names for an error message.
std::string known_part_names() {
  std::string list;
  for (const Part& p : parts()) list += (list.empty() ? "" : ", ") + p.name;
  return list;
}
}  // namespace

const Part& find_part(const std::string& name) {
  for (const Part& p : parts())
    if (p.name == name) return p;
  throw Error("unknown part \"" + name + "\" (known: " + known_part_names() + ")");
}

const Part& find_device_part(const std::string& device) {
  for (const Part& p : parts())
    if (device == p.name || device.rfind(p.name + "-", 0) == 0) return p;
  throw Error("the board's FPGA \"" + device + "\" is not a part voxcast report knows (known: " +
              known_part_names() + ")");
}

Resources& Resources::operator+=(const Resources& r) {
  luts += r.luts;
  ffs += r.ffs;
  dsps += r.dsps;
  brams += r.brams;
  urams += r.urams;
  return *this;
}

Resources operator*(double n, const Resources& r) {
  return {n * r.luts, n * r.ffs, n * r.dsps, n * r.brams, n * r.urams};
}

int dsp_count(const Op& m, Family f) {
  if (f == Family::VirtexE) return 0;  // no multiplier blocks: LUTs
  // As Yosys synth_xilinx (mul2dsp): a product narrower than 9 bits, or a
  // 1-bit operand, stays in LUTs.
  if (m.a < 2 || m.b < 2 || m.a + m.b < 9) return 0;
  const int sa = signed_width(m.a, m.a_signed);
  const int sb = signed_width(m.b, m.b_signed);
  if (f == Family::Virtex2) return limbs(sa, 18) * limbs(sb, 18);  // MULT18X18 (DS031)
  // DSP48E2: 27 x 18 signed (UG579); either operand may take the 27-bit port.
  if (f == Family::UltraScalePlus)
    return std::min(limbs(sa, 27) * limbs(sb, 18), limbs(sa, 18) * limbs(sb, 27));
  // DSP48E1: 25 x 18 signed (UG479); either operand may take the 25-bit port.
  return std::min(limbs(sa, 25) * limbs(sb, 18), limbs(sa, 18) * limbs(sb, 25));
}

namespace {
struct Aspect {
  int depth, width;
};
}  // namespace

int bram_count(int depth, int width, Family f) {
  if (depth <= 0 || width <= 0) return 0;
  // Small memories go to LUT RAM (distributed RAM): at most 2 kbit, or 32 deep.
  if (static_cast<long long>(depth) * width <= 2048 || depth <= 32) return 0;
  // Virtex-E 4-kbit BlockSelectRAM (DS022); Virtex-II RAMB16 (DS031), 7-series
  // RAMB18E1 (UG473, simple dual port up to 36 bits) and UltraScale+ RAMB18E2
  // (UG573, the same aspects) share the 18-kbit aspect ratios.
  static const std::vector<Aspect> kVirtexE = {{4096, 1}, {2048, 2}, {1024, 4}, {512, 8},
                                               {256, 16}};
  static const std::vector<Aspect> k18k = {{16384, 1}, {8192, 2}, {4096, 4}, {2048, 9},
                                           {1024, 18}, {512, 36}};
  const auto& aspects = f == Family::VirtexE ? kVirtexE : k18k;
  int best = 0;
  for (const Aspect& a : aspects) {
    const int n = ceil_div(depth, a.depth) * ceil_div(width, a.width);
    if (best == 0 || n < best) best = n;
  }
  return best;
}

int uram_count(int depth, int width, Family f) {
  if (f != Family::UltraScalePlus || bram_count(depth, width, f) == 0) return 0;
  // URAM288: one aspect, 4,096 x 72, cascaded in depth and placed side by side
  // in width (UG573, "UltraRAM").
  return ceil_div(depth, 4096) * ceil_div(width, 72);
}

bool prefers_uram(int depth, int width, const Part& part) {
  if (part.urams <= 0 || part.brams <= 0) return false;
  const int u = uram_count(depth, width, part.family);
  if (u == 0) return false;
  // URAM when it takes the smaller share of the part: a 4K-deep or deeper
  // memory usually does (the brick cache's lines, the pre-integration table),
  // a shallow one leaves most of a URAM's 4,096 rows empty and stays in BRAM.
  return static_cast<double>(u) / part.urams <
         static_cast<double>(bram_count(depth, width, part.family)) / part.brams;
}

Resources op_resources(const Op& op, Family f) {
  const bool lut6 = f == Family::Series7 || f == Family::UltraScalePlus;
  Resources r;
  const double n = op.count;
  switch (op.kind) {
    case OpKind::Mul: {
      const int d = dsp_count(op, f);
      if (d > 0) {
        r.dsps = n * d;
        // Pieces beyond one are summed in the DSP cascade up to two per column;
        // more need a LUT adder of the product width per extra piece.
        r.luts = n * std::max(0, d - 2) * (op.a + op.b);
        r.ffs = 0;  // the output register is the DSP's PREG
      } else {
        // Array multiplier in LUTs: LUT6 ~ a·b/2 (two partial-product bits per
        // LUT on the carry chain), LUT4 a·b (MULT_AND, one bit per LUT).
        r.luts = n * (lut6 ? std::ceil(op.a * op.b / 2.0) : op.a * op.b);
        r.ffs = n * (op.a + op.b);
      }
      break;
    }
    case OpKind::Add:
      r.luts = n * op.a;  // one LUT per bit on the carry chain
      r.ffs = n * op.a;   // registered result
      break;
    case OpKind::Cmp:
      // Yosys synth_xilinx maps an a-bit a < b to 3a/4 LUT6 on the carry chain
      // (docs/resources.md); LUT4: one bit pair per LUT.
      r.luts = n * std::ceil(lut6 ? 0.75 * op.a : op.a / 2.0);
      r.ffs = n;
      break;
    case OpKind::Mux:
      // LUT6: a 4:1 mux per LUT (F7/F8 muxes combine up to 16:1); LUT4: 2:1 per LUT.
      r.luts = n * op.a * (lut6 ? ceil_div(op.b, 4) : std::max(1, op.b - 1));
      r.ffs = n * op.a;
      break;
    case OpKind::Div:
      // Fully pipelined restoring divider: one (divisor + 1)-bit subtract and
      // select per quotient bit; each stage registers its remainder and the
      // quotient bits so far.
      r.luts = n * op.a * (op.b + 1);
      r.ffs = n * (op.a * (op.b + 1) + op.a * (op.a + 1) / 2.0);
      break;
    case OpKind::Reg:
      r.ffs = n * op.a;
      break;
    case OpKind::Rom:
    case OpKind::Ram:
    case OpKind::Fifo: {
      const int b = bram_count(op.a, op.b, f);
      if (b > 0) {
        r.brams = n * b;
      } else if (op.kind == OpKind::Fifo) {
        // LUT RAM, simple dual port: RAM32M (32 x 6 in 4 LUT6, UG474) or RAM16X1D (2 LUT4).
        r.luts = n * (lut6 ? ceil_div(op.a, 32) * ceil_div(op.b, 6) * 4
                           : ceil_div(op.a, 16) * op.b * 2);
      } else {
        // Distributed ROM/RAM, single read port: 64 x 1 per LUT6, 16 x 1 per LUT4.
        r.luts = n * (lut6 ? ceil_div(op.a, 64) : ceil_div(op.a, 16)) * op.b;
      }
      r.ffs = n * op.b;  // the read register
      if (op.kind == OpKind::Fifo) r.ffs += n * 2 * bits_for(op.a);  // read/write pointers
      break;
    }
  }
  return r;
}

Resources op_resources(const Op& op, const Part& part) {
  Resources r = op_resources(op, part.family);
  const bool memory = op.kind == OpKind::Rom || op.kind == OpKind::Ram || op.kind == OpKind::Fifo;
  if (memory && r.brams > 0 && prefers_uram(op.a, op.b, part)) {
    r.urams = op.count * uram_count(op.a, op.b, part.family);
    r.brams = 0;
  }
  return r;
}

ResourceReport estimate_resources(const ref::Elaboration& e, const Part& part) {
  ResourceReport rep;
  rep.part = part;
  rep.elaboration = e;
  const rtl::pipeline::PipelineConfig pc;
  for (UnitOps& u : unit_operators(e, pc)) {
    UnitResources ur{std::move(u), {}};
    for (const Op& op : ur.unit.ops) ur.res += op_resources(op, part);
    rep.total += ur.res;
    rep.units.push_back(std::move(ur));
  }
  const rtl::pipeline::UnitLatencies l = rtl::pipeline::elaborate_latencies(
      pc.latency, {e.mip, e.reflectance_map, e.perspective, e.space_leaping, e.partial_segments,
                   e.preintegration});
  rep.latency_ray_setup = l.ray_setup;
  // From a sample's address to its composited result (or the MIP register).
  rep.latency_sample = l.address + l.leap_lookup + l.interpolation + l.classification + l.shading +
                       (e.mip ? hls::mip_depth : hls::compositor_depth);
  rep.ii = 1;
  return rep;
}

ResourceReport estimate_resources(const ref::Scene& scene, const Part& part) {
  const SceneVolume sv = load_scene_volume(scene);
  check_fixed_point(scene, sv, false);
  ResourceReport r = estimate_resources(ref::elaborate(scene, sv.volume, sv.gradients), part);
  r.scene = scene.origin;
  r.profile_name = scene.precision_name;
  r.card = price_scene_card(scene, r.elaboration, part);
  return r;
}

double cost(const Resources& r, const Part& p) {
  double c = 0.0;
  if (p.luts > 0) c += r.luts / p.luts;
  if (p.ffs > 0) c += r.ffs / p.ffs;
  if (p.dsps > 0) c += r.dsps / p.dsps;
  if (p.brams > 0) c += r.brams / p.brams;
  if (p.urams > 0) c += r.urams / p.urams;
  return c;
}

namespace {
struct Share {
  const char* name;
  double used;
  int cap;
};
std::vector<Share> shares(const Resources& r, const Part& p) {
  return {{"LUT", r.luts, p.luts},
          {"FF", r.ffs, p.ffs},
          {"DSP", r.dsps, p.dsps},
          {"BRAM", r.brams, p.brams},
          {"URAM", r.urams, p.urams}};
}
// used / cap; a resource the part lacks is infinitely scarce if used.
double share_of(const Share& s) {
  if (s.cap > 0) return s.used / s.cap;
  return s.used > 0 ? std::numeric_limits<double>::infinity() : 0.0;
}
}  // namespace

double binding_share(const Resources& r, const Part& p) {
  double m = 0.0;
  for (const Share& s : shares(r, p)) m = std::max(m, share_of(s));
  return m;
}

const char* binding_resource(const Resources& r, const Part& p) {
  const char* name = "LUT";
  double m = -1.0;
  for (const Share& s : shares(r, p))
    if (share_of(s) > m) {
      m = share_of(s);
      name = s.name;
    }
  return name;
}

namespace {

std::string op_shape(const Op& op) {
  std::ostringstream s;
  switch (op.kind) {
    case OpKind::Mul:
      s << op.a << (op.a_signed ? "s" : "u") << " x " << op.b << (op.b_signed ? "s" : "u");
      break;
    case OpKind::Mux: s << op.a << " bits, " << op.b << ":1"; break;
    case OpKind::Div: s << op.a << " / " << op.b; break;
    case OpKind::Rom:
    case OpKind::Ram:
    case OpKind::Fifo: s << op.a << " x " << op.b << " (" << static_cast<long long>(op.a) * op.b
                         << " bits)"; break;
    default: s << op.a << " bits";
  }
  return s.str();
}

const char* bram_name(Family f) {
  return f == Family::VirtexE   ? "BlockRAM 4k"
         : f == Family::Virtex2 ? "RAMB16"
         : f == Family::Series7 ? "RAMB18"
                                : "RAMB18E2";
}
const char* dsp_name(Family f) {
  return f == Family::VirtexE   ? "MULT (none)"
         : f == Family::Virtex2 ? "MULT18X18"
         : f == Family::Series7 ? "DSP48E1"
                                : "DSP48E2";
}

// A share of 1 as "12.3 %".
std::string percent(double share) {
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << 100.0 * share << " %";
  return s.str();
}

std::string pct(double used, int cap) {
  if (cap <= 0) return used > 0 ? "n/a" : "-";
  return percent(used / cap);
}

}  // namespace

namespace {

// The columns of a resource row: LUT, FF, DSP, BRAM, and URAM on a part that has it.
std::string res_cells(const Resources& x, bool uram) {
  std::ostringstream s;
  s << std::lround(x.luts) << " | " << std::lround(x.ffs) << " | " << std::lround(x.dsps) << " | "
    << std::lround(x.brams);
  if (uram) s << " | " << std::lround(x.urams);
  return s.str();
}

std::string res_header(bool uram) {
  return uram ? "LUT | FF | DSP | BRAM | URAM" : "LUT | FF | DSP | BRAM";
}
std::string res_rule(bool uram) {
  return uram ? "---:|---:|---:|---:|---:" : "---:|---:|---:|---:";
}

std::string share_cells(const Resources& x, const Part& p) {
  std::string s = pct(x.luts, p.luts) + " | " + pct(x.ffs, p.ffs) + " | " + pct(x.dsps, p.dsps) +
                  " | " + pct(x.brams, p.brams);
  if (p.urams > 0) s += " | " + pct(x.urams, p.urams);
  return s;
}

// "534 FF, 36 URAM": the resources a figure uses, in words.
std::string res_words(const Resources& x) {
  std::string s;
  const std::pair<double, const char*> parts[] = {
      {x.luts, "LUT"}, {x.ffs, "FF"}, {x.dsps, "DSP"}, {x.brams, "RAMB18"}, {x.urams, "URAM"}};
  for (const auto& [n, name] : parts)
    if (n > 0) s += (s.empty() ? "" : ", ") + std::to_string(std::lround(n)) + " " + name;
  return s.empty() ? "nothing" : s;
}

void card_markdown(std::ostream& s, const CardPrice& c, const Part& p) {
  const bool u = p.urams > 0;
  s << "\n## The DDR4 card: " << c.pipelines << " pipeline" << (c.pipelines == 1 ? "" : "s")
    << " on the " << p.name << "\n\n";
  s << "Board `" << c.board << "` (rtl_model/pipeline/burst_card.hpp): N = " << c.pipelines
    << " ray pipelines (`rtl.pipelines`), " << c.channels << " DDR4 channels, each with a "
    << c.cache_lines << "-line brick cache of 64-byte lines. Total = N x per pipeline + "
       "ceil(N/2) x per two pipelines + " << c.channels << " x per channel "
       "(docs/resources.md, \"N pipelines on the U250\").\n\n";
  s << "| part of the card | " << res_header(u) << " |\n|---|" << res_rule(u) << "|\n";
  s << "| per pipeline: datapath units, ray slots, sample buffer, brick look-up | "
    << res_cells(c.per_pipeline, u) << " |\n";
  s << "| per two pipelines: tables read every clock, one dual-port block-RAM copy | "
    << res_cells(c.per_pair, u) << " |\n";
  s << "| per channel: brick cache, miss registers, crossings, DDR4 controller | "
    << res_cells(c.per_channel, u) << " |\n";
  s << "| **total, N = " << c.pipelines << "** | " << res_cells(c.total, u) << " |\n";
  s << "| available | " << p.luts << " | " << p.ffs << " | " << p.dsps << " | " << p.brams;
  if (u) s << " | " << p.urams;
  s << " |\n| share | " << share_cells(c.total, p) << " |\n\n";
  if (c.fits)
    s << "**Fits**: the scarcest resource, " << binding_resource(c.total, p) << ", at "
      << percent(binding_share(c.total, p)) << ".";
  else
    s << "**Does not fit**: N = " << c.pipelines << " needs " << binding_resource(c.total, p)
      << " at " << percent(binding_share(c.total, p)) << " of the " << p.name << ".";
  s << " The largest N that fits: **" << c.largest_fit << "**";
  if (c.largest_fit > 0)
    s << " (" << binding_resource(card_total(c, c.largest_fit), p) << " at "
      << percent(binding_share(card_total(c, c.largest_fit), p)) << ")";
  if (c.largest_fit == CardPrice::kMaxPipelines) s << ", the end of rtl.pipelines' range";
  s << ".\n\n| N | " << res_header(u) << " | scarcest | its share |\n|---:|" << res_rule(u)
    << "|---|---:|\n";
  for (int n = 1; n <= CardPrice::kMaxPipelines; n *= 2) {
    const Resources t = card_total(c, n);
    s << "| " << n << " | " << res_cells(t, u) << " | " << binding_resource(t, p) << " | "
      << percent(binding_share(t, p)) << " |\n";
  }
  s << "\n### Per channel\n\n| item | shape | " << res_header(u) << " |\n|---|---|"
    << res_rule(u) << "|\n";
  for (const CardItem& it : c.channel)
    s << "| " << it.op.what << " | " << op_shape(it.op) << " | " << res_cells(it.res, u) << " |\n";
  s << "| DDR4 controller and PHY (MIG) | " << c.controller_source << " | "
    << res_cells(c.controller, u) << " |\n";
  s << "\n### Per pipeline: the brick look-up\n\n| item | count | shape | " << res_header(u)
    << " |\n|---|---:|---|" << res_rule(u) << "|\n";
  for (const CardItem& it : c.issue)
    s << "| " << it.op.what << " | " << it.op.count << " | " << op_shape(it.op) << " | "
      << res_cells(it.res, u) << " |\n";
  const Resources ported = ported_card_total(c, c.pipelines);
  s << "\n**The look-up ports.** The cycle model lets every pipeline look up its sample's bursts "
       "in a channel's cache in the same clock; the tag and line stores above have the block "
       "RAM's two ports. A sample's cell needs at most two bursts of one channel, so N pipelines "
       "need N dual-port copies of each channel's lines and tags ("
    << res_words(c.cache_store) << " a copy): at N = " << c.pipelines << " the card then takes "
    << binding_resource(ported, p) << " at " << percent(binding_share(ported, p))
    << ", and the largest N that fits is **" << c.ported_largest_fit
    << "** (banked caches, whose conflicts the cycle model does not simulate, lie between).\n\n"
       "Not priced: the PCIe shell and the host interface.\n";
}

}  // namespace

std::string report_markdown(const ResourceReport& r) {
  std::ostringstream s;
  const Family f = r.part.family;
  const bool u = r.part.urams > 0;
  s << "# Resource report: " << r.scene << "\n\n";
  s << "Profile `" << r.profile_name << "`, part **" << r.part.name << "** (" << r.part.note
    << "). Estimates by the model of docs/resources.md.\n\n";
  s << "## Totals\n\n| resource | used | available | share |\n|---|---:|---:|---:|\n";
  s << "| LUT | " << std::lround(r.total.luts) << " | " << r.part.luts << " | "
    << pct(r.total.luts, r.part.luts) << " |\n";
  s << "| FF | " << std::lround(r.total.ffs) << " | " << r.part.ffs << " | "
    << pct(r.total.ffs, r.part.ffs) << " |\n";
  s << "| " << dsp_name(f) << " | " << std::lround(r.total.dsps) << " | " << r.part.dsps << " | "
    << pct(r.total.dsps, r.part.dsps) << " |\n";
  s << "| " << bram_name(f) << " | " << std::lround(r.total.brams) << " | " << r.part.brams
    << " | " << pct(r.total.brams, r.part.brams) << " |\n";
  if (u)
    s << "| URAM288 | " << std::lround(r.total.urams) << " | " << r.part.urams << " | "
      << pct(r.total.urams, r.part.urams) << " |\n";
  s << "\n";
  s << "Latency: ray set-up " << r.latency_ray_setup << " cycles; a sample " << r.latency_sample
    << " cycles from its address to the compositor (plus the SDRAM's, measured by the cycle "
       "model); initiation interval " << r.ii << " (one sample per clock).\n\n";
  s << "## Units\n\n| unit | § | latency | II | " << res_header(u) << " |\n"
    << "|---|---|---:|---:|" << res_rule(u) << "|\n";
  for (const auto& x : r.units)
    s << "| " << x.unit.name << " | " << x.unit.section << " | " << x.unit.latency << " | "
      << x.unit.ii << " | " << res_cells(x.res, u) << " |\n";
  s << "\n## Left out (elaboration)\n\n";
  if (r.elaboration.omitted.empty()) s << "Nothing: the scene uses every unit.\n";
  for (const auto& o : r.elaboration.omitted) s << "- **" << o.unit << "**: " << o.reason << "\n";
  s << "\nSizes from the data: value field " << r.elaboration.value_store_bits
    << " stored bits (profile " << r.elaboration.profile.value_bits << "), gradient field "
    << r.elaboration.gradient_store_bits << " bits per component (profile "
    << r.elaboration.profile.gradient_bits << "), classification table "
    << r.elaboration.class_entries << " entries (profile " << (1 << r.elaboration.profile.tf_addr_bits)
    << ").\n";
  s << "\n## Operators\n\n| unit | operator | kind | count | shape | " << res_header(u) << " |\n"
    << "|---|---|---|---:|---|" << res_rule(u) << "|\n";
  for (const auto& x : r.units)
    for (const Op& op : x.unit.ops)
      s << "| " << x.unit.name << " | " << op.what << " | " << to_string(op.kind) << " | "
        << op.count << " | " << op_shape(op) << " | " << res_cells(op_resources(op, r.part), u)
        << " |\n";
  if (r.card) card_markdown(s, *r.card, r.part);
  return s.str();
}

namespace {

nlohmann::json res_json(const Resources& x) {
  return {{"lut", x.luts}, {"ff", x.ffs}, {"dsp", x.dsps}, {"bram", x.brams}, {"uram", x.urams}};
}

nlohmann::json card_json(const CardPrice& c, const Part& p) {
  using nlohmann::json;
  auto items = [](const std::vector<CardItem>& v) {
    json a = json::array();
    for (const CardItem& it : v)
      a.push_back({{"what", it.op.what}, {"kind", to_string(it.op.kind)}, {"count", it.op.count},
                   {"a", it.op.a}, {"b", it.op.b}, {"resources", res_json(it.res)}});
    return a;
  };
  json by_n = json::array();
  for (int n = 1; n <= CardPrice::kMaxPipelines; n *= 2) {
    const Resources t = card_total(c, n);
    by_n.push_back({{"pipelines", n}, {"resources", res_json(t)},
                    {"binding", binding_resource(t, p)}, {"binding_share", binding_share(t, p)}});
  }
  return {{"board", c.board},
          {"pipelines", c.pipelines},
          {"channels", c.channels},
          {"cache_lines", c.cache_lines},
          {"per_pipeline", res_json(c.per_pipeline)},
          {"per_pair", res_json(c.per_pair)},
          {"per_channel", res_json(c.per_channel)},
          {"controller", res_json(c.controller)},
          {"controller_source", c.controller_source},
          {"issue", items(c.issue)},
          {"channel", items(c.channel)},
          {"total", res_json(c.total)},
          {"binding", binding_resource(c.total, p)},
          {"binding_share", binding_share(c.total, p)},
          {"fits", c.fits},
          {"largest_fit", c.largest_fit},
          {"cache_store", res_json(c.cache_store)},
          {"ported_largest_fit", c.ported_largest_fit},
          {"by_pipelines", by_n}};
}

}  // namespace

std::string report_json(const ResourceReport& r) {
  using nlohmann::json;
  json j;
  j["scene"] = r.scene;
  j["profile"] = r.profile_name;
  j["part"] = {{"name", r.part.name}, {"source", r.part.note}, {"lut", r.part.luts},
               {"ff", r.part.ffs}, {"dsp", r.part.dsps}, {"bram", r.part.brams},
               {"uram", r.part.urams}, {"dsp_kind", dsp_name(r.part.family)},
               {"bram_kind", bram_name(r.part.family)}};
  j["total"] = res_json(r.total);
  j["latency"] = {{"ray_setup", r.latency_ray_setup}, {"sample", r.latency_sample}, {"ii", r.ii}};
  json units = json::array();
  for (const auto& u : r.units) {
    json ops = json::array();
    for (const Op& op : u.unit.ops)
      ops.push_back({{"what", op.what}, {"kind", to_string(op.kind)}, {"count", op.count},
                     {"a", op.a}, {"b", op.b}, {"a_signed", op.a_signed},
                     {"b_signed", op.b_signed}, {"resources", res_json(op_resources(op, r.part))}});
    units.push_back({{"name", u.unit.name}, {"section", u.unit.section},
                     {"latency", u.unit.latency}, {"ii", u.unit.ii}, {"resources", res_json(u.res)},
                     {"operators", ops}});
  }
  j["units"] = units;
  json omitted = json::array();
  for (const auto& o : r.elaboration.omitted)
    omitted.push_back({{"unit", o.unit}, {"reason", o.reason}});
  j["omitted"] = omitted;
  j["sizes"] = {{"value_store_bits", r.elaboration.value_store_bits},
                {"gradient_store_bits", r.elaboration.gradient_store_bits},
                {"class_entries", r.elaboration.class_entries}};
  if (r.card) j["card"] = card_json(*r.card, r.part);
  return j.dump(2);
}

}  // namespace voxcast::cosim
