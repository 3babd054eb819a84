#include "cosim/report.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cosim/engines.hpp"
#include "refmodel/error.hpp"

namespace voxcast::cosim {

namespace {

int bits_for(long long n) {  // unsigned bits holding 0..n (at least 1), as hls rm_detail::bits_for
  return n < 1 ? 1 : static_cast<int>(std::bit_width(static_cast<unsigned long long>(n)));
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

// The widths of the hls Params structs, by the same formulas (checked against
// the kernels' types for the presets in tests/report/test_report_widths.cpp).
struct Widths {
  int a, pf, df, tf, sb, wb, vb, gb, gfb, sf, tfa, cb, ab, kb, rf, ri, rwb, shb, acc, ob;
  int pixel = 13;       // GeometryParams::pixel_bits
  int dir;              // dir_t: df + 2
  int origin;           // origin_t: a + 4 + pf
  int unit;             // unit_t: df + 2
  int kreg;             // kreg_t: df + 3
  int step;             // step_t: pf + 4
  int num;              // num_t: a + 5 + tf
  int k;                // k_t = num_t / step_t (ap division type): num + pf + 1
  int pos;              // pos_t: a + 2 + pf
  int count;            // count_t: a + pf + 1
  int word_addr;        // word_addr_t: 3(a - 1)
  int grad_int;         // sample gradient integer bits (incl. sign)
  int sample_grad;      // gradient_t width: grad_int + sf
  int value;            // value_t: vb + sf
  int rm_entry;         // ri + rf
  int rm_side, rm_entries, rm_den, rm_pos, rm_cell, rm_index, rm_wb;
  int intensity;        // ShaderParams::intensity_t: shb + ri + 2
};

Widths widths(const PrecisionProfile& p) {
  Widths w{p.addr_bits, p.pos_frac_bits, p.dir_frac_bits, p.t_frac_bits, p.rsqrt_seed_bits,
           p.weight_bits, p.value_bits, p.gradient_bits, p.gradient_frac_bits,
           p.sample_frac_bits, p.tf_addr_bits, p.color_bits, p.alpha_bits, p.k_bits,
           p.rm_frac_bits, p.rm_int_bits, p.rm_weight_bits, p.shade_bits, p.acc_bits, p.out_bits,
           13, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  w.dir = w.df + 2;
  w.origin = w.a + 4 + w.pf;
  w.unit = w.df + 2;
  w.kreg = w.df + 3;
  w.step = w.pf + 4;
  w.num = w.a + 5 + w.tf;
  w.k = w.num + w.pf + 1;
  w.pos = w.a + 2 + w.pf;
  w.count = w.a + w.pf + 1;
  w.word_addr = std::max(1, 3 * (w.a - 1));
  w.grad_int = w.gb - w.gfb + (w.sf < w.gfb ? 1 : 0);
  w.sample_grad = w.grad_int + w.sf;
  w.value = w.vb + w.sf;
  w.rm_entry = w.ri + w.rf;
  const bool bil = p.rm_bilinear != 0;
  w.rm_wb = bil ? p.rm_weight_bits : 0;
  w.rm_side = bil ? p.rm_res + 1 : p.rm_res;
  w.rm_entries = 6 * w.rm_side * w.rm_side;
  w.rm_den = w.grad_int + 1 + w.sf;
  w.rm_pos = bits_for(static_cast<long long>(p.rm_res) << w.rm_wb);
  w.rm_cell = bits_for(p.rm_res - 1);
  w.rm_index = bits_for(w.rm_entries - 1);
  w.intensity = w.shb + w.ri + 2;
  return w;
}

// One lerp v0 + (v1 - v0)·f on operands of `bits` (signed difference) and a
// weight of wb + 1 unsigned bits: subtract, multiply, add.
void lerp(std::vector<Op>& ops, const std::string& what, int count, int bits, int wb,
          bool is_signed) {
  ops.push_back(add(what + ": v1 - v0", count, bits + 1));
  ops.push_back(mul(what + ": (v1 - v0)·f", count, bits + 1, true, wb + 1, false));
  ops.push_back(add(what + ": v0 + ·", count, bits + wb + (is_signed ? 1 : 0)));
}

UnitOps geometry_rsqrt(const Widths& w) {
  UnitOps u{"ray_direction+rsqrt", "§1.1-1.2", {}, 0, 1};
  auto& o = u.ops;
  o.push_back(mul("px·B, py·C", 6, w.pixel, false, w.dir, true));
  o.push_back(add("d = A + px·B + py·C", 6, w.dir + w.pixel + 2));
  o.push_back(mul("n2 = d·d", 3, w.dir, true, w.dir, true));
  o.push_back(add("n2 sum", 2, 2 * w.df + 4));
  o.push_back(mux("leading-zero count of n2", 1, bits_for(2 * w.df + 2), 2 * w.df + 2));
  o.push_back(mux("d' = d·2^e (shifter)", 3, w.df + 3, w.df + 1));
  o.push_back(mux("n2·4^e (shifter)", 1, 2 * w.df + 4, w.df + 1));
  o.push_back(mem(OpKind::Rom, "rsqrt seed ROM", 1, 1 << w.sb, w.df + 2));
  o.push_back(mul("Newton: y·y", 2, w.df + 2, false, w.df + 2, false));
  o.push_back(mul("Newton: m·t", 2, w.df + 1, false, w.df + 3, false));
  o.push_back(add("Newton: 3 - t", 2, w.df + 4));
  o.push_back(mul("Newton: y·(3 - t)", 2, w.df + 2, false, w.df + 4, true));
  o.push_back(add("Newton: rounding", 6, w.df + 3));
  o.push_back(mul("u = d'·y", 3, w.df + 3, true, w.df + 2, false));
  o.push_back(add("u rounding", 3, w.unit));
  return u;
}

UnitOps ray_setup(const Widths& w, bool parallel) {
  UnitOps u{"ray_setup", parallel ? "§1.3-1.6" : "§1.3, §1.5-1.6", {}, 0, 1};
  auto& o = u.ops;
  o.push_back(mul("s = u·K", 3, w.unit, true, w.kreg, false));
  o.push_back(add("s rounding", 3, w.step));
  if (parallel) {
    o.push_back(mul("px·P, py·R", 6, w.pixel, false, w.origin, true));
    o.push_back(add("o = O + px·P + py·R", 6, w.origin + w.pixel + 2));
  }
  o.push_back(add("LO - o, HI - o", 6, w.num));
  o.push_back(div("k = (LO|HI - o) / s", 6, w.k, w.step));
  o.push_back(cmp("k_lo < k_hi, k_near > k_in, k_far < k_out, k_in < 0, k_in > k_out", 3 + 4 + 2,
                  w.k));
  o.push_back(mux("k_near, k_far, k_in, k_out", 10, w.k, 2));
  o.push_back(cmp("s = 0 axis: LO <= o <= HI", 6, w.origin));
  o.push_back(add("n = k_out - k_in + 1", 1, w.count));
  o.push_back(mul("k_in·s", 3, w.k, true, w.step, true));
  o.push_back(add("p0 = o + Q_RND(k_in·s)", 3, w.pos));
  return u;
}

UnitOps stepping(const Widths& w) {
  UnitOps u{"stepping", "§2", {}, 0, 1};
  u.ops.push_back(add("p += s", 3, w.pos));
  u.ops.push_back(add("sample counter", 1, w.count));
  u.ops.push_back(cmp("counter = n", 1, w.count));
  u.ops.push_back(reg("p, s, n of the ray", 3 * w.pos + 3 * w.step + w.count));
  return u;
}

UnitOps address_generator(const Widths& w) {
  UnitOps u{"address_generator", "§3.1-3.3", {}, 0, 1};
  auto& o = u.ops;
  o.push_back(cmp("clamp p into [LO, HI]", 6, w.pos));
  o.push_back(mux("clamp select", 6, w.pos, 2));
  o.push_back(cmp("i0 = LAST", 3, w.a));
  o.push_back(add("i0 - 1", 3, w.a));
  o.push_back(add("f = p - i0", 3, w.pf + 1));
  o.push_back(add("fq = Q_RND(f, wb)", 3, w.wb + 1));
  o.push_back(mul("(i0y>>1)·HX", 1, std::max(1, w.a - 1), false, w.a, false));
  o.push_back(mul("(i0z>>1)·HXY", 1, std::max(1, w.a - 1), false, 2 * w.a, false));
  o.push_back(add("base word address", 2, w.word_addr));
  o.push_back(mux("odd-axis increments", 3, w.word_addr, 2));
  o.push_back(add("bank addresses (+1, +HX, +HXY)", 12, w.word_addr));
  return u;
}

UnitOps interpolation(const Widths& w, const ref::Elaboration& e) {
  UnitOps u{"interpolation", "§3.4-3.5", {}, 0, 1};
  auto& o = u.ops;
  const int word = e.value_store_bits + 3 * e.gradient_store_bits;
  o.push_back(mux("crossbar: corner j = bank j ^ parity", 8, word, 8));
  // The value's low value_bits - value_store_bits bits are constant zeros in
  // every voxel (§3.4), so the lerps run on the stored bits (elaboration).
  const int vs = e.value_store_bits;
  lerp(o, "value lerp x", 4, vs, w.wb, false);
  lerp(o, "value lerp y", 2, vs + w.wb, w.wb, false);
  lerp(o, "value lerp z", 1, vs + 2 * w.wb, w.wb, false);
  o.push_back(add("value Q_RND(·, sf)", 1, w.value));
  if (e.gradients) {
    const int gs = e.gradient_store_bits;
    lerp(o, "gradient lerp x", 12, gs, w.wb, true);
    lerp(o, "gradient lerp y", 6, gs + w.wb, w.wb, true);
    lerp(o, "gradient lerp z", 3, gs + 2 * w.wb, w.wb, true);
    o.push_back(add("gradient Q_RND(·, sf)", 3, w.sample_grad));
  }
  return u;
}

UnitOps classification(const Widths& w, const ref::Elaboration& e) {
  UnitOps u{"classification", "§4", {}, 0, 1};
  const int entry = e.class_color_fields * w.cb + (e.class_alpha_varies ? w.ab : 0) +
                    e.class_k_fields * w.kb;
  const int constant = (3 - e.class_color_fields) * w.cb + (e.class_alpha_varies ? 0 : w.ab) +
                       (3 - e.class_k_fields) * w.kb;
  u.ops.push_back(add("address Q_RND(value·2^(tf - vb))", 1, w.tfa + 1));
  u.ops.push_back(cmp("address clamp", 1, w.tfa + 1));
  u.ops.push_back(mem(OpKind::Ram, "classification table (fields that vary)", 1, e.class_entries,
                      entry));
  if (constant > 0) u.ops.push_back(reg("constant entry fields", constant));
  return u;
}

UnitOps reflectance(const Widths& w, const PrecisionProfile& p) {
  UnitOps u{"reflectance_map", p.rm_bilinear ? "§5.1-5.3, §5.5" : "§5.1-5.4", {}, 0, 1};
  auto& o = u.ops;
  o.push_back(mul("gw = g·IS", 3, w.sample_grad, true, w.df + 1, false));
  o.push_back(add("gw rounding", 3, w.sample_grad));
  o.push_back(add("N = -gw, |N|", 3, w.rm_den));
  o.push_back(cmp("major axis", 2, w.sample_grad));
  o.push_back(mux("N[a], N[b], |N[m]|", 3, w.rm_den, 3));
  o.push_back(add("N[a] + |N[m]|", 2, w.rm_den));
  o.push_back(div("t = (N + |N[m]|)·res·2^wb / 2|N[m]|", 2, w.rm_pos, w.rm_den));
  o.push_back(cmp("cell clamp", 2, w.rm_cell));
  o.push_back(add("index = face·side² + iv·side + iu", 2, w.rm_index));
  if (p.rm_bilinear) {
    const int h = (p.rm_res + 2) / 2;
    o.push_back(mem(OpKind::Ram, "diffuse + specular corner tables, 4 parity banks each", 8,
                    6 * h * h, w.rm_entry));
    o.push_back(mux("corner crossbar", 8, w.rm_entry, 4));
    o.push_back(add("fu, fv = t - (cell << wb)", 2, w.rm_wb + 1));
    for (const char* t : {"D", "S"}) {
      lerp(o, std::string(t) + " lerp u", 2, w.rm_entry, w.rm_wb, false);
      lerp(o, std::string(t) + " lerp v", 1, w.rm_entry + w.rm_wb, w.rm_wb, false);
      o.push_back(add(std::string(t) + " Q_RND(·, rf)", 1, w.rm_entry));
    }
  } else {
    o.push_back(mem(OpKind::Ram, "diffuse + specular tables", 2, w.rm_entries, w.rm_entry));
  }
  return u;
}

UnitOps shader(const Widths& w, bool shaded) {
  UnitOps u{"shader", "§6", {}, 0, 1};
  auto& o = u.ops;
  if (shaded) {
    o.push_back(mul("kd·D, ks·S", 2, w.kb, false, w.rm_entry, false));
    o.push_back(add("ka + kd·D + ks·S", 2, w.ri + 2 + w.kb + w.rf));
    o.push_back(add("I = Q_RND(·, shade_bits)", 1, w.intensity));
    o.push_back(mul("colour·I", 3, w.cb, false, w.intensity, false));
  }
  o.push_back(add("c = U(·, shade_bits) rounding", 3, w.shb + 1));
  o.push_back(cmp("c saturation", 3, w.shb + 1));
  return u;
}

UnitOps compositor(const Widths& w) {
  UnitOps u{"compositor", "§7.1-7.2", {}, 0, 1};
  auto& o = u.ops;
  o.push_back(add("1 - A", 1, w.acc + 1));
  o.push_back(mul("w = (1 - A)·alpha", 1, w.acc + 1, false, w.ab, false));
  o.push_back(add("w rounding", 1, w.acc + 1));
  o.push_back(mul("w·c", 3, w.acc + 1, false, w.shb, false));
  o.push_back(add("w·c rounding", 3, w.acc + 1));
  o.push_back(add("C += w·c, A += w", 4, w.acc + 2));
  o.push_back(cmp("saturation at 1", 4, w.acc + 2));
  o.push_back(reg("accumulators C, A", 4 * (w.acc + 1)));
  return u;
}

UnitOps ert(const Widths& w) {
  UnitOps u{"ert", "§7.3", {}, 0, 1};
  u.ops.push_back(cmp("A >= ERT_T", 1, w.acc + 1));
  u.ops.push_back(reg("ERT_T register", w.acc + 1));
  return u;
}

UnitOps mip(const Widths& w) {
  UnitOps u{"mip", "§7 MIP", {}, 0, 1};
  u.ops.push_back(cmp("value > M", 1, w.value));
  u.ops.push_back(reg("M, RM registers", w.value + w.df + 1));
  u.ops.push_back(mul("M·RM", 1, w.value, false, w.df + 1, false));
  u.ops.push_back(add("grey rounding", 1, w.acc + w.vb + 1));
  u.ops.push_back(cmp("grey saturation", 1, w.acc + w.vb + 1));
  return u;
}

UnitOps output(const Widths& w) {
  UnitOps u{"output", "§8", {}, 0, 1};
  // x·(2^out_bits - 1) = (x << out_bits) - x: a subtractor, not a multiplier.
  u.ops.push_back(add("x·(2^ob - 1) = (x << ob) - x", 4, w.acc + 1 + w.ob));
  u.ops.push_back(add("Q_RND(·, 0)", 4, w.ob + 1));
  return u;
}

// Space leaping (docs/leaping.md, hls/space_leaping_unit.hpp): the block
// look-up beside the address generator and the leaping stepper's search.
UnitOps space_leaping(const Widths& w, const ref::Elaboration& e) {
  UnitOps u{"space_leaping", "docs/leaping.md", {}, 0, 1};
  auto& o = u.ops;
  const int lb = std::countr_zero(static_cast<unsigned>(e.leap_block));
  const int bc = std::max(1, w.a - lb);  // block coordinate bits
  const int ba = bits_for(std::max(1LL, e.leap_blocks - 1));
  // Block look-up: coordinates are wiring (i0 >> lb), then the address.
  o.push_back(mul("by·BX", 1, bc, false, bc, false));
  o.push_back(mul("bz·BXY", 1, bc, false, ba, false));
  o.push_back(add("block address", 2, ba));
  o.push_back(mem(OpKind::Ram, "min-max block memory (min, max)", 1,
                  static_cast<int>(e.leap_blocks), 2 * e.value_store_bits));
  // The table addresses of min and max (as §4.1), two prefix reads, the test.
  o.push_back(add("address Q_RND(min, max)", 2, w.tfa + 1));
  o.push_back(cmp("address clamp", 2, w.tfa + 1));
  o.push_back(mem(OpKind::Ram, "opacity prefix table (2 read ports)", 1,
                  std::max(e.class_entries, 1) + 1, w.tfa + 1));
  o.push_back(cmp("prefix[hi + 1] = prefix[lo]", 1, w.tfa + 1));
  // The leap: leap_bits stages of q + 2^j·s, the candidate's block coordinates
  // (clamp, i0 = LAST) and their comparison with the block's, and the run count.
  const int stages = std::min(w.count, 10);  // hls::LeapParams::leap_bits
  o.push_back(add("leap q + 2^j·s", 3 * stages, w.pos));
  o.push_back(cmp("leap clamp", 6 * stages, w.pos));
  o.push_back(mux("leap clamp select", 6 * stages, w.pos, 2));
  o.push_back(cmp("leap i0 = LAST", 3 * stages, w.a));
  o.push_back(cmp("leap same block", 3 * stages, bc));
  o.push_back(add("leap run + 2^j", stages, w.count));
  o.push_back(cmp("leap run + 2^j <= remaining", stages, w.count));
  o.push_back(mux("leap take", stages, 3 * w.pos + w.count, 2));
  return u;
}

// render.jitter: the pixel hash (refmodel/render/jitter.hpp) and k_in + J.
UnitOps jitter(const Widths& w) {
  UnitOps u{"jitter", "docs/leaping.md", {}, 0, 1};
  u.ops.push_back(mul("lowbias32 x·C", 2, 32, false, 32, false));
  u.ops.push_back(add("k_in + J·2^-tf", 1, w.k));
  return u;
}

// The FIFOs and ray slots of the cycle model's pipeline (rtl_model/pipeline),
// at the widths of what they carry.
UnitOps pipeline_buffers(const Widths& w, const ref::Elaboration& e,
                         const rtl::pipeline::PipelineConfig& pc,
                         const rtl::pipeline::UnitLatencies& l) {
  UnitOps u{"pipeline_buffers", "rtl_model/pipeline", {}, 0, 1};
  auto& o = u.ops;
  const int slot = bits_for(pc.ray_slots - 1);
  const int word = e.value_store_bits + 3 * e.gradient_store_bits;
  const int sample = w.value + (e.gradients ? 3 * w.sample_grad : 0) + slot + w.count;
  o.push_back(mem(OpKind::Fifo, "ray slots (p0, s, n)", 1, pc.ray_slots,
                  3 * w.pos + 3 * w.step + w.count));
  o.push_back(mem(OpKind::Fifo, "sample buffer (8 voxel words, weights, parity)", 1,
                  pc.sample_buffer, 8 * word + 3 * (w.wb + 1) + 3 + slot + w.count));
  o.push_back(mem(OpKind::Fifo, "interpolation.out", 1, l.interpolation + pc.fifo_depth, sample));
  if (e.classification) {
    const int entry = 3 * w.cb + w.ab + 3 * w.kb;
    o.push_back(mem(OpKind::Fifo, "classification.out", 1, l.classification + pc.fifo_depth,
                    sample + entry));
  }
  if (e.compositor)
    o.push_back(mem(OpKind::Fifo, "shading.out", 1, l.shading + pc.fifo_depth,
                    3 * w.shb + w.ab + slot + w.count));
  o.push_back(mem(OpKind::Fifo, "output pixels", 1, pc.output_depth, 4 * w.ob + 2 * w.pixel));
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
  const PrecisionProfile& p = e.profile;
  const Widths w = widths(p);
  const rtl::pipeline::UnitLatencies l = rtl::pipeline::elaborate_latencies(
      pc.latency, {e.mip, e.reflectance_map, e.perspective, e.space_leaping});
  std::vector<UnitOps> units;
  auto put = [&](UnitOps u, int latency, int ii = 1) {
    u.latency = latency;
    u.ii = ii;
    units.push_back(std::move(u));
  };
  const int rsqrt = e.perspective ? rtl::pipeline::kRsqrtStages : 0;
  if (e.perspective) put(geometry_rsqrt(w), rsqrt, l.ray_setup_interval);
  put(ray_setup(w, e.parallel_origin), l.ray_setup - rsqrt, l.ray_setup_interval);
  put(stepping(w), 1);
  put(address_generator(w), l.address - 1);
  // Beside the address generator: adds its look-up to the requests' latency.
  if (e.space_leaping) put(space_leaping(w, e), l.leap_lookup);
  // Beside the direction and rsqrt pipeline, shorter than it: no latency.
  if (e.jitter) put(jitter(w), 0, l.ray_setup_interval);
  put(interpolation(w, e), l.interpolation);
  if (e.classification) put(classification(w, e), l.classification);
  if (e.reflectance_map) put(reflectance(w, p), l.shading - 1);
  if (e.shader) put(shader(w, e.reflectance_map), e.reflectance_map ? 1 : l.shading);
  if (e.compositor) put(compositor(w), 1);
  if (e.ert) put(ert(w), 0);
  if (e.mip) put(mip(w), 1);
  put(output(w), 1);
  put(pipeline_buffers(w, e, pc, l), 0);
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
  };
  return k;
}

const Part& find_part(const std::string& name) {
  for (const Part& p : parts())
    if (p.name == name) return p;
  std::string list;
  for (const Part& p : parts()) list += (list.empty() ? "" : ", ") + p.name;
  throw Error("unknown part \"" + name + "\" (known: " + list + ")");
}

Resources& Resources::operator+=(const Resources& r) {
  luts += r.luts;
  ffs += r.ffs;
  dsps += r.dsps;
  brams += r.brams;
  return *this;
}

int dsp_count(const Op& m, Family f) {
  if (f == Family::VirtexE) return 0;  // no multiplier blocks: LUTs
  // As Yosys synth_xilinx (mul2dsp): a product narrower than 9 bits, or a
  // 1-bit operand, stays in LUTs.
  if (m.a < 2 || m.b < 2 || m.a + m.b < 9) return 0;
  const int sa = signed_width(m.a, m.a_signed);
  const int sb = signed_width(m.b, m.b_signed);
  if (f == Family::Virtex2) return limbs(sa, 18) * limbs(sb, 18);  // MULT18X18 (DS031)
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
  // Virtex-E 4-kbit BlockSelectRAM (DS022); Virtex-II RAMB16 (DS031) and 7-series
  // RAMB18E1 (UG473, simple dual port up to 36 bits) share the 18-kbit aspect ratios.
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

Resources op_resources(const Op& op, Family f) {
  const bool lut6 = f == Family::Series7;
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

ResourceReport estimate_resources(const ref::Elaboration& e, const Part& part) {
  ResourceReport rep;
  rep.part = part;
  rep.elaboration = e;
  const rtl::pipeline::PipelineConfig pc;
  for (UnitOps& u : unit_operators(e, pc)) {
    UnitResources ur{std::move(u), {}};
    for (const Op& op : ur.unit.ops) ur.res += op_resources(op, part.family);
    rep.total += ur.res;
    rep.units.push_back(std::move(ur));
  }
  const rtl::pipeline::UnitLatencies l = rtl::pipeline::elaborate_latencies(
      pc.latency, {e.mip, e.reflectance_map, e.perspective, e.space_leaping});
  rep.latency_ray_setup = l.ray_setup;
  rep.latency_sample =
      l.address + l.leap_lookup + l.interpolation + l.classification + l.shading + 1;
  rep.ii = 1;
  return rep;
}

ResourceReport estimate_resources(const ref::Scene& scene, const Part& part) {
  const SceneVolume sv = load_scene_volume(scene);
  check_fixed_point(scene, sv, false);
  ResourceReport r = estimate_resources(ref::elaborate(scene, sv.volume, sv.gradients), part);
  r.scene = scene.origin;
  r.profile_name = scene.precision_name;
  return r;
}

double cost(const Resources& r, const Part& p) {
  double c = 0.0;
  if (p.luts > 0) c += r.luts / p.luts;
  if (p.ffs > 0) c += r.ffs / p.ffs;
  if (p.dsps > 0) c += r.dsps / p.dsps;
  if (p.brams > 0) c += r.brams / p.brams;
  return c;
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
  return f == Family::VirtexE ? "BlockRAM 4k" : f == Family::Virtex2 ? "RAMB16" : "RAMB18";
}
const char* dsp_name(Family f) {
  return f == Family::VirtexE ? "MULT (none)" : f == Family::Virtex2 ? "MULT18X18" : "DSP48E1";
}

std::string pct(double used, int cap) {
  if (cap <= 0) return used > 0 ? "n/a" : "-";
  std::ostringstream s;
  s.setf(std::ios::fixed);
  s.precision(1);
  s << 100.0 * used / cap << " %";
  return s.str();
}

}  // namespace

std::string report_markdown(const ResourceReport& r) {
  std::ostringstream s;
  const Family f = r.part.family;
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
    << " | " << pct(r.total.brams, r.part.brams) << " |\n\n";
  s << "Latency: ray set-up " << r.latency_ray_setup << " cycles; a sample " << r.latency_sample
    << " cycles from its address to the compositor (plus the SDRAM's, measured by the cycle "
       "model); initiation interval " << r.ii << " (one sample per clock).\n\n";
  s << "## Units\n\n| unit | § | latency | II | LUT | FF | DSP | BRAM |\n"
       "|---|---|---:|---:|---:|---:|---:|---:|\n";
  for (const auto& u : r.units)
    s << "| " << u.unit.name << " | " << u.unit.section << " | " << u.unit.latency << " | "
      << u.unit.ii << " | " << std::lround(u.res.luts) << " | " << std::lround(u.res.ffs) << " | "
      << std::lround(u.res.dsps) << " | " << std::lround(u.res.brams) << " |\n";
  s << "\n## Left out (elaboration)\n\n";
  if (r.elaboration.omitted.empty()) s << "Nothing: the scene uses every unit.\n";
  for (const auto& o : r.elaboration.omitted) s << "- **" << o.unit << "**: " << o.reason << "\n";
  s << "\nSizes from the data: value field " << r.elaboration.value_store_bits
    << " stored bits (profile " << r.elaboration.profile.value_bits << "), gradient field "
    << r.elaboration.gradient_store_bits << " bits per component (profile "
    << r.elaboration.profile.gradient_bits << "), classification table "
    << r.elaboration.class_entries << " entries (profile " << (1 << r.elaboration.profile.tf_addr_bits)
    << ").\n";
  s << "\n## Operators\n\n| unit | operator | kind | count | shape | LUT | FF | DSP | BRAM |\n"
       "|---|---|---|---:|---|---:|---:|---:|---:|\n";
  for (const auto& u : r.units)
    for (const Op& op : u.unit.ops) {
      const Resources x = op_resources(op, f);
      s << "| " << u.unit.name << " | " << op.what << " | " << to_string(op.kind) << " | "
        << op.count << " | " << op_shape(op) << " | " << std::lround(x.luts) << " | "
        << std::lround(x.ffs) << " | " << std::lround(x.dsps) << " | " << std::lround(x.brams)
        << " |\n";
    }
  return s.str();
}

std::string report_json(const ResourceReport& r) {
  using nlohmann::json;
  auto res = [](const Resources& x) {
    return json{{"lut", x.luts}, {"ff", x.ffs}, {"dsp", x.dsps}, {"bram", x.brams}};
  };
  json j;
  j["scene"] = r.scene;
  j["profile"] = r.profile_name;
  j["part"] = {{"name", r.part.name}, {"source", r.part.note}, {"lut", r.part.luts},
               {"ff", r.part.ffs}, {"dsp", r.part.dsps}, {"bram", r.part.brams},
               {"dsp_kind", dsp_name(r.part.family)}, {"bram_kind", bram_name(r.part.family)}};
  j["total"] = res(r.total);
  j["latency"] = {{"ray_setup", r.latency_ray_setup}, {"sample", r.latency_sample}, {"ii", r.ii}};
  json units = json::array();
  for (const auto& u : r.units) {
    json ops = json::array();
    for (const Op& op : u.unit.ops)
      ops.push_back({{"what", op.what}, {"kind", to_string(op.kind)}, {"count", op.count},
                     {"a", op.a}, {"b", op.b}, {"a_signed", op.a_signed},
                     {"b_signed", op.b_signed}, {"resources", res(op_resources(op, r.part.family))}});
    units.push_back({{"name", u.unit.name}, {"section", u.unit.section},
                     {"latency", u.unit.latency}, {"ii", u.unit.ii}, {"resources", res(u.res)},
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
  return j.dump(2);
}

}  // namespace voxcast::cosim
