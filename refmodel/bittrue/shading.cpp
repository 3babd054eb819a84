#include "refmodel/bittrue/shading.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/render/jitter.hpp"

namespace voxcast::bittrue {

// --- §4 Classification -----------------------------------------------------------------

namespace {

// §4.1 at `bits` address bits: SAT(Q_RND(value · 2^(bits - vb), 0), 0, 2^bits - 1).
int table_address(const PrecisionProfile& p, double value, int bits) {
  const double scaled = scale2(value, bits - p.value_bits);  // exact
  const double last = std::ldexp(1.0, bits) - 1.0;
  return static_cast<int>(sat(q_rnd(scaled, 0), 0.0, last));
}

}  // namespace

int bt_class_address(const PrecisionProfile& p, double value) {
  return table_address(p, value, p.tf_addr_bits);
}

const ClassEntry& bt_classify(const FrameSetup& fs, double value) {
  return fs.class_table[static_cast<std::size_t>(bt_class_address(fs.profile, value))];
}

int bt_preint_address(const PrecisionProfile& p, double value) {
  return table_address(p, value, p.preint_addr_bits);
}

const ClassEntry& bt_classify_segment(const FrameSetup& fs, double front, double back) {
  const auto f = static_cast<std::size_t>(bt_preint_address(fs.profile, front));
  const auto b = static_cast<std::size_t>(bt_preint_address(fs.profile, back));
  return (*fs.preint_table)[(f << fs.profile.preint_addr_bits) | b];
}

double bt_alpha(const PrecisionProfile& p, const ClassEntry& e) {
  return from_raw(e.alpha, p.alpha_bits);
}

// --- §5 Reflectance map ----------------------------------------------------------------

BtCell bt_rm_cell(const PrecisionProfile& p, const Raw3& IS, const std::array<double, 3>& g) {
  const int sf = p.sample_frac_bits;
  const int df = p.dir_frac_bits;
  // §5.1: gw = Q_RND(g·IS, sf), N = -gw. The product has up to 59 magnitude bits at the
  // profile's limits (more than a double holds), so it is formed on the raw integers:
  // g_raw·IS_raw has sf + df fraction bits, and Q_RND to sf bits is floor((x + 2^(df-1)) / 2^df),
  // an arithmetic shift.
  std::array<std::int64_t, 3> n{}, mag{};
  for (std::size_t k = 0; k < 3; ++k) {
    const std::int64_t prod = to_raw(g[k], sf) * IS[k];
    const std::int64_t gw = (prod + (std::int64_t{1} << (df - 1))) >> df;
    n[k] = -gw;
    mag[k] = std::llabs(n[k]);
  }
  // §5.3: major axis (ties to the lower axis), the other two axes a < b.
  std::size_t m = 0;
  if (mag[1] > mag[0]) m = 1;
  if (mag[2] > mag[m]) m = 2;
  BtCell cell;
  if (mag[m] == 0) return cell;  // §5.2: N = 0
  const std::size_t a = m == 0 ? 1 : 0;
  const std::size_t b = m == 2 ? 1 : 2;
  const std::int64_t res = p.rm_res;
  // §5.3 / §5.5: the position along an axis in cells, floor((N[axis] + |N[m]|)·res·2^wb /
  // (2|N[m]|)) in units of 2^-wb cells (wb = 0 in nearest mode), an exact integer division of
  // non-negative raw values (TRUNC0 = floor). At most 2^36·2^8·2^12 = 2^56 at the limits.
  const int wb = p.rm_bilinear ? p.rm_weight_bits : 0;
  struct Axis {
    std::int64_t i, f;  // cell (clamped to res - 1) and in-cell position (wb fraction bits)
  };
  auto position = [&](std::size_t axis) {
    const std::int64_t t = div_trunc0((n[axis] + mag[m]) * res * (std::int64_t{1} << wb),
                                      2 * mag[m]);
    const std::int64_t i = std::min(t >> wb, res - 1);
    return Axis{i, t - i * (std::int64_t{1} << wb)};
  };
  const Axis u = position(a), v = position(b);
  const std::int64_t face = 2 * static_cast<std::int64_t>(m) + (n[m] < 0 ? 1 : 0);
  const std::int64_t stride = p.rm_bilinear ? res + 1 : res;  // entries per face row
  cell.valid = true;
  cell.index = static_cast<int>((face * stride + v.i) * stride + u.i);
  if (p.rm_bilinear) {
    cell.fu = u.f;
    cell.fv = v.f;
  }
  return cell;
}

BtReflect bt_reflectance(const FrameSetup& fs, const std::array<double, 3>& g) {
  const PrecisionProfile& p = fs.profile;
  const BtCell cell = bt_rm_cell(p, fs.regs.IS, g);
  BtReflect r;
  if (!cell.valid) return r;
  const int rf = p.rm_frac_bits;
  const auto i = static_cast<std::size_t>(cell.index);
  if (!p.rm_bilinear) {
    r.D = from_raw(fs.rm_diffuse[i], rf);
    r.S = from_raw(fs.rm_specular[i], rf);
    return r;
  }
  // §5.5: the four corner entries with weights (1-fu)(1-fv), fu(1-fv), (1-fu)fv, fu·fv, summed
  // exactly, one Q_RND to rf bits. Each product has at most (rm_int_bits + rf) + 2(wb + 1) <= 50
  // significant bits and every term lies on the 2^-(rf + 2wb) grid, so the products, the
  // partial sums (non-negative, at most the total) and the total (below 2^rm_int_bits, at most
  // rm_int_bits + rf + 2wb <= 48 bits) are exact doubles. The result is a convex combination of
  // entries on the rf grid, so it never exceeds the largest of them: no saturation.
  const int wb = p.rm_weight_bits;
  const double fu = from_raw(cell.fu, wb), fv = from_raw(cell.fv, wb);
  const std::array<double, 4> w = {(1.0 - fu) * (1.0 - fv), fu * (1.0 - fv), (1.0 - fu) * fv,
                                   fu * fv};
  const std::size_t row = static_cast<std::size_t>(p.rm_res) + 1;
  const std::array<std::size_t, 4> corner = {i, i + 1, i + row, i + row + 1};
  auto bilerp = [&](const std::vector<std::uint32_t>& table) {
    double sum = 0.0;
    for (std::size_t c = 0; c < 4; ++c) sum += from_raw(table[corner[c]], rf) * w[c];
    return q_rnd(sum, rf);
  };
  r.D = bilerp(fs.rm_diffuse);
  r.S = bilerp(fs.rm_specular);
  return r;
}

// --- §6 Shader ---------------------------------------------------------------------------

std::array<double, 3> bt_shade(const PrecisionProfile& p, const ClassEntry& e, const BtReflect& r,
                               bool shaded) {
  const int kb = p.k_bits, cb = p.color_bits, sb = p.shade_bits;
  const std::array<double, 3> colour{from_raw(e.r, cb), from_raw(e.g, cb), from_raw(e.b, cb)};
  std::array<double, 3> c{};
  if (!shaded) {
    for (std::size_t k = 0; k < 3; ++k) c[k] = u_frac(colour[k], sb);
    return c;
  }
  // Every product and the sum are exact (at most 42 bits, §7's closing note).
  const double sum = from_raw(e.ka, kb) + from_raw(e.kd, kb) * r.D + from_raw(e.ks, kb) * r.S;
  const double intensity = q_rnd(sum, sb);
  for (std::size_t k = 0; k < 3; ++k) c[k] = u_frac(colour[k] * intensity, sb);
  return c;
}

// --- §7 Compositor -----------------------------------------------------------------------

std::ostream& operator<<(std::ostream& os, const BtAccumulator& acc) {
  return os << "BtAccumulator{C=(" << acc.C[0] << ", " << acc.C[1] << ", " << acc.C[2]
            << "), A=" << acc.A << "}";
}

bool bt_composite(const PrecisionProfile& p, BtAccumulator& acc, const std::array<double, 3>& c,
                  double alpha_c) {
  if (alpha_c == 0.0) return false;
  const int F = p.acc_bits;
  const double w = q_rnd((1.0 - acc.A) * alpha_c, F);
  for (std::size_t k = 0; k < 3; ++k) acc.C[k] = sat(acc.C[k] + q_rnd(w * c[k], F), 0.0, 1.0);
  acc.A = sat(acc.A + w, 0.0, 1.0);
  return true;
}

bool bt_ert(const FrameSetup& fs, const BtAccumulator& acc) {
  return fs.regs.ert_enabled && acc.A >= from_raw(fs.regs.ert_threshold, fs.profile.acc_bits);
}

// --- §7a Segment opacity ----------------------------------------------------------------

BtSegmentWeights bt_segment_weights(const FrameSetup& fs, const BtRay& ray, int px, int py) {
  BtSegmentWeights w;
  if (!fs.segments || !ray.hit) return w;
  const int tf = fs.profile.t_frac_bits;
  const double j =
      fs.regs.jitter ? std::ldexp(static_cast<double>(ref::jitter_raw(px, py, tf)), -tf) : 0.0;
  const double d = ray.k_out - ray.k_in;  // exact, tf bits
  const double frac = d - std::floor(d);
  if (ray.n == 1) {
    w.first = frac + j;
  } else {
    w.first = 1.0 + j;
    w.last = frac;
  }
  return w;
}

double bt_sample_weight(const BtSegmentWeights& w, std::uint64_t k, std::uint64_t n) {
  if (k == 0) return w.first;
  if (k + 1 == n) return w.last;
  return 1.0;
}

double bt_segment_alpha(const FrameSetup& fs, int addr, double alpha_c, double w) {
  if (w == 1.0) return alpha_c;
  const PrecisionProfile& p = fs.profile;
  const int F = segment_frac_bits(p);
  const int r = segment_rom_index_bits(p);
  // §7a.3: w·tau2 is exact (at most 45 bits), one rounding.
  const double y = q_rnd(w * from_raw(fs.segments->tau[static_cast<std::size_t>(addr)], F), F);
  // §7a.4: the ROM cell of frac(y) and the position in it; the lerp exact, one rounding.
  const double fl = std::floor(y);
  const double cell = std::ldexp(y - fl, r);
  const double i = std::floor(cell);
  const double u = cell - i;
  const auto at = static_cast<std::size_t>(i);
  const double e0 = from_raw(fs.segments->rom[at], F);
  const double e1 = from_raw(fs.segments->rom[at + 1], F);
  const double m = q_rnd(e0 - (e0 - e1) * u, F);
  // §7a.5: 2^-floor(y) clamped at ab + 2 (exact), then U(1 - v, ab).
  const double s = std::min(fl, static_cast<double>(segment_max_shift(p)));
  const double v = std::ldexp(m, -static_cast<int>(s));
  return u_frac(1.0 - v, p.alpha_bits);
}

BtAccumulator bt_mip_pixel(const FrameSetup& fs, double M) {
  const double rm = from_raw(fs.regs.RM, fs.profile.dir_frac_bits);
  const double grey = sat(q_rnd(M * rm, fs.profile.acc_bits), 0.0, 1.0);
  BtAccumulator px;
  px.C = {grey, grey, grey};
  px.A = 1.0;
  return px;
}

// --- §8 Output ---------------------------------------------------------------------------

std::uint32_t bt_output_channel(const PrecisionProfile& p, double x) {
  const double top = std::ldexp(1.0, p.out_bits) - 1.0;
  return static_cast<std::uint32_t>(sat(q_rnd(x * top, 0), 0.0, top));
}

std::array<std::uint32_t, 4> bt_output(const PrecisionProfile& p, const BtAccumulator& acc) {
  return {bt_output_channel(p, acc.C[0]), bt_output_channel(p, acc.C[1]),
          bt_output_channel(p, acc.C[2]), bt_output_channel(p, acc.A)};
}

}  // namespace voxcast::bittrue
