#include "refmodel/bittrue/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/render/space_leaping.hpp"

namespace voxcast::bittrue {

namespace {

std::array<double, 3> vec(const Raw3& raw, int frac_bits) {
  return {from_raw(raw[0], frac_bits), from_raw(raw[1], frac_bits), from_raw(raw[2], frac_bits)};
}

// §1.2: two Newton steps from the seed, y ~ 1/sqrt(m), m in [1/4, 1].
double rsqrt(const PrecisionProfile& pr, const std::vector<Raw>& seed, double m) {
  const int df = pr.dir_frac_bits;
  const int entries = 1 << pr.rsqrt_seed_bits;
  const int i =
      std::min(static_cast<int>(std::floor(std::ldexp(m, pr.rsqrt_seed_bits))), entries - 1);
  double y = from_raw(seed[static_cast<std::size_t>(i)], df);
  for (int it = 0; it < 2; ++it) {
    double t = q_rnd(y * y, df);
    t = q_rnd(m * t, df);
    y = q_rnd(y * (3.0 - t) / 2.0, df);
  }
  return y;
}

}  // namespace

std::array<double, 3> bt_unit_direction(const PrecisionProfile& pr, const FrameRegisters& r,
                                        const std::vector<Raw>& seed, int px, int py) {
  const int df = pr.dir_frac_bits;
  const std::array<double, 3> A = vec(r.A, df), B = vec(r.B, df), C = vec(r.C, df);
  std::array<double, 3> d{};
  for (int k = 0; k < 3; ++k) d[k] = A[k] + px * B[k] + py * C[k];  // §1.1, exact
  const double n2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];        // exact
  if (n2 == 0.0) return {0.0, 0.0, 0.0};
  // n2 = f·2^x with f in [1/2, 1); n2·4^e in [1/4, 1) for e = floor(-x/2).
  int x = 0;
  std::frexp(n2, &x);
  const int e = static_cast<int>(std::floor(-x / 2.0));
  const double m = q_rnd(std::ldexp(n2, 2 * e), df);
  const double y = rsqrt(pr, seed, m);
  std::array<double, 3> u{};
  for (int k = 0; k < 3; ++k) u[k] = q_rnd(std::ldexp(d[k], e) * y, df);
  return u;
}

std::array<double, 3> bt_ray_origin(const PrecisionProfile& pr, const FrameRegisters& r, int px,
                                    int py) {
  const int pf = pr.pos_frac_bits;
  const std::array<double, 3> O = vec(r.O, pf), P = vec(r.P, pf), R = vec(r.R, pf);
  std::array<double, 3> o{};
  for (int k = 0; k < 3; ++k) o[k] = O[k] + px * P[k] + py * R[k];  // exact
  return o;
}

BtRay bt_ray_setup(const PrecisionProfile& pr, const FrameRegisters& r,
                   const std::vector<Raw>& seed, int px, int py) {
  const int pf = pr.pos_frac_bits, df = pr.dir_frac_bits, tf = pr.t_frac_bits;
  const std::array<double, 3> u =
      r.perspective ? bt_unit_direction(pr, r, seed, px, py) : vec(r.U, df);
  const std::array<double, 3> K = vec(r.K, df);
  const std::array<double, 3> o = bt_ray_origin(pr, r, px, py);
  BtRay ray;
  for (int k = 0; k < 3; ++k) ray.s[k] = q_rnd(u[k] * K[k], pf);  // §1.3

  // §1.5: per-axis entry/exit in samples.
  bool any = false, inside = true;
  double k_in = 0.0, k_out = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double lo = r.LO[k], hi = r.HI[k];
    if (ray.s[k] == 0.0) {
      inside = inside && lo <= o[k] && o[k] <= hi;
      continue;
    }
    const double k_lo = trunc0_div(q_trn(lo - o[k], tf), tf, ray.s[k], pf, tf);
    const double k_hi = trunc0_div(q_trn(hi - o[k], tf), tf, ray.s[k], pf, tf);
    const double k_near = std::min(k_lo, k_hi), k_far = std::max(k_lo, k_hi);
    k_in = any ? std::max(k_in, k_near) : k_near;
    k_out = any ? std::min(k_out, k_far) : k_far;
    any = true;
  }
  k_in = std::max(k_in, 0.0);
  // render.jitter: the first sample J·2^-tf of a step later (exact, tf bits).
  if (r.jitter) k_in += std::ldexp(static_cast<double>(ref::jitter_raw(px, py, tf)), -tf);
  ray.hit = any && inside && k_in <= k_out;
  if (!ray.hit) return ray;
  // §1.6.
  ray.k_in = k_in;
  ray.k_out = k_out;
  ray.n = static_cast<std::uint64_t>(std::floor(k_out - k_in)) + 1u;
  for (int k = 0; k < 3; ++k) ray.p0[k] = o[k] + q_rnd(k_in * ray.s[k], pf);
  return ray;
}

std::ostream& operator<<(std::ostream& os, const BtRay& r) {
  os << "BtRay{hit " << r.hit << ", n " << r.n << ", k_in " << r.k_in << ", k_out " << r.k_out
     << ", p0 (" << r.p0[0] << ", " << r.p0[1] << ", " << r.p0[2] << "), s (" << r.s[0] << ", "
     << r.s[1] << ", " << r.s[2] << ")}";
  return os;
}

BtRay bt_ray_setup(const FrameSetup& setup, int px, int py) {
  return bt_ray_setup(setup.profile, setup.regs, setup.rsqrt_seed, px, py);
}

std::array<double, 3> bt_step(const std::array<double, 3>& p, const std::array<double, 3>& s) {
  return {p[0] + s[0], p[1] + s[1], p[2] + s[2]};
}

}  // namespace voxcast::bittrue
