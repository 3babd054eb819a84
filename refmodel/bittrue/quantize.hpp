// The bit-true reference's own quantizers (docs/pipeline.md, "Notation"), in
// plain double. They deliberately do not use the fixed-point class: the
// bit-true model is the independent second implementation the hls kernels are
// checked against.
//
// Exactness: every function here is exact (no double rounding) whenever the
// argument is a finite double and |x·2^F| < 2^52, which the spec guarantees for
// every value of the pipeline (every intermediate fits in 53 bits). Scaling by
// 2^F is exact (a power of two), floor() is exact, and y - floor(y) is exact
// for every finite double y, so the rounding decision never depends on a
// rounded addition such as y + 0.5.
#pragma once

#include <cmath>
#include <cstdint>

namespace voxcast::bittrue {

// x · 2^F, exact (a power-of-two scaling; no overflow/underflow in range).
inline double scale2(double x, int F) { return std::ldexp(x, F); }

// Q_TRN(x, F): floor to F fraction bits (ap AP_TRN).
inline double q_trn(double x, int F) { return std::ldexp(std::floor(std::ldexp(x, F)), -F); }

// Q_RND(x, F): nearest at F fraction bits, ties towards +inf (ap AP_RND),
// floor(x·2^F + 1/2) / 2^F computed without the (possibly inexact) addition.
inline double q_rnd(double x, int F) {
  const double y = std::ldexp(x, F);
  const double t = std::floor(y);
  const double r = (y - t >= 0.5) ? t + 1.0 : t;
  return std::ldexp(r, -F);
}

// TRUNC0(x, F): toward zero at F fraction bits (the quotient rule of ap's `/`).
inline double q_trn0(double x, int F) { return std::ldexp(std::trunc(std::ldexp(x, F)), -F); }

// SAT(x, lo, hi): clamp (ap AP_SAT), after quantization.
inline double sat(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }

// U(x, F) = SAT(Q_RND(x, F), 0, 1 - 2^-F): an unsigned fraction of 1 (ufixed<F, 0>).
inline double u_frac(double x, int F) { return sat(q_rnd(x, F), 0.0, 1.0 - std::ldexp(1.0, -F)); }

// The raw integer V of a value already on the F-bit grid (value = V · 2^-F), and back.
inline std::int64_t to_raw(double x, int F) { return static_cast<std::int64_t>(std::ldexp(x, F)); }
inline double from_raw(std::int64_t v, int F) { return std::ldexp(static_cast<double>(v), -F); }

// Integer division of raw values rounded toward zero (C++ `/` on int64), and
// floor division; for TRUNC0(a / b, F) of grid values use trunc0_div.
inline std::int64_t div_trunc0(std::int64_t a, std::int64_t b) { return a / b; }
inline std::int64_t div_floor(std::int64_t a, std::int64_t b) {
  const std::int64_t q = a / b;
  return (q * b != a && ((a < 0) != (b < 0))) ? q - 1 : q;
}

// TRUNC0(a / b, F) for a on the Fa-bit grid and b on the Fb-bit grid (both
// exactly representable, |a·2^Fa| and |b·2^Fb| < 2^62 / 2^max(F+Fb-Fa, 0)):
// the exact quotient truncated toward zero at F fraction bits, by integer
// division on the raw values (a·2^Fa · 2^(F+Fb-Fa)) / (b·2^Fb). b != 0.
inline double trunc0_div(double a, int Fa, double b, int Fb, int F) {
  std::int64_t num = to_raw(a, Fa);
  std::int64_t den = to_raw(b, Fb);
  const int sh = F + Fb - Fa;
  if (sh >= 0)
    num *= std::int64_t{1} << sh;
  else
    den *= std::int64_t{1} << -sh;
  return from_raw(num / den, F);
}

}  // namespace voxcast::bittrue
