// An independent model of hls/fixed_point.hpp's conversions, written from the
// tables of /work/shared/fixed-point-semantics.md sections 2, 3 and 9 ("section
// N" below): value arithmetic in long double with floorl / fmodl, not the
// clone's shifts and masks. Every value it meets has at most 64 significant
// bits, so long double (64-bit mantissa, 15-bit exponent) holds it exactly.
//
// The one oracle of two checks: the exhaustive sweep of small widths
// (tests/hls/test_fixed_quantize.cpp) and the fixed-point fuzz target's random
// wide types (fuzz/targets/fixed_point.cpp).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>

#include "hls/fixed_point.hpp"

namespace voxcast::fixed_model {

using hls::o_mode;
using hls::q_mode;
using ld = long double;

// A target type fixed_base<w, i, s, q, o, n>.
struct Format {
  int w;
  int i;
  bool s;
  q_mode q;
  o_mode o;
  int n;
};

inline std::string describe(const Format& t) {
  static const char* const qn[] = {"RND", "RND_ZERO", "RND_MIN_INF", "RND_INF",
                                   "RND_CONV", "TRN", "TRN_ZERO"};
  static const char* const on[] = {"SAT", "SAT_ZERO", "SAT_SYM", "WRAP", "WRAP_SM"};
  std::ostringstream os;
  os << (t.s ? "fixed<" : "ufixed<") << t.w << "," << t.i << "," << qn[t.q] << "," << on[t.o]
     << "," << t.n << ">";
  return os.str();
}

inline std::uint64_t low_mask(int w) {
  return w >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << w) - 1;
}
inline bool bit(std::uint64_t v, int k) { return ((v >> k) & 1u) != 0; }
inline std::uint64_t set_bit(std::uint64_t v, int k, bool b) {
  return b ? v | (std::uint64_t{1} << k) : v & ~(std::uint64_t{1} << k);
}

// floor(y) mod 2^w as a W-bit pattern, by value (fmodl is exact).
inline std::uint64_t pattern_of(ld y, int w) {
  const ld m = std::ldexp(1.0L, w);
  ld r = std::fmod(y, m);
  if (r < 0) r += m;
  // r < 2^w <= 2^64; for w == 64 split to stay inside uint64's conversion range.
  if (w == 64) {
    const ld hi = std::floor(r / 4294967296.0L);
    return (static_cast<std::uint64_t>(hi) << 32) |
           static_cast<std::uint64_t>(r - hi * 4294967296.0L);
  }
  return static_cast<std::uint64_t>(r);
}

// Section 2: the rounded value in LSBs of t (floor, first dropped bit qb,
// sticky r, sign s of the source). `fl` receives floor(x / LSB).
inline ld quantize(ld x, const Format& t, ld& fl) {
  const ld y = std::ldexp(x, t.w - t.i);  // exact: the LSB is a power of two
  fl = std::floor(y);
  const ld frac = y - fl;  // exact
  const bool qb = frac >= 0.5L;
  const bool r = qb ? frac > 0.5L : frac > 0.0L;
  const bool s = x < 0;
  const bool lsb = std::fmod(fl, 2.0L) != 0;
  bool inc = false;
  switch (t.q) {
    case hls::TRN: inc = false; break;
    case hls::TRN_ZERO: inc = s && (qb || r); break;
    case hls::RND: inc = qb; break;
    case hls::RND_ZERO: inc = qb && (s || r); break;
    case hls::RND_MIN_INF: inc = qb && r; break;
    case hls::RND_INF: inc = qb && (!s || r); break;
    case hls::RND_CONV: inc = qb && (lsb || r); break;
  }
  return fl + (inc ? 1.0L : 0.0L);
}

// The W-bit pattern that converting the exact value x (from a source of
// signedness src_signed) into t gives. Sections 2 and 3.
inline std::uint64_t model_bits(ld x, bool src_signed, const Format& t) {
  ld fl = 0;
  const ld rounded = quantize(x, t, fl);
  std::uint64_t v = pattern_of(rounded, t.w);
  if (t.o == hls::WRAP && t.n == 0) return v;

  const ld max_v = t.s ? std::ldexp(1.0L, t.w - 1) - 1 : std::ldexp(1.0L, t.w) - 1;
  const ld min_v = t.s ? -std::ldexp(1.0L, t.w - 1) : 0.0L;
  const bool ovf = rounded > max_v, unf = rounded < min_v;
  const std::uint64_t mask = low_mask(t.w);
  const std::uint64_t max_bits = pattern_of(max_v, t.w), min_bits = pattern_of(min_v, t.w);
  // -MAX is MIN with the LSB set (the headers set bit W-1 and bit 0): for W = 1
  // both are bit 0, so -MAX is -1 there, the spec's "W = 1: -1 stays -1".
  const std::uint64_t neg_max_bits = min_bits | 1u;
  if (!ovf && !unf) {
    // SAT_SYM maps an exact MIN from a signed source to -MAX.
    if (t.o == hls::SAT_SYM && t.s && src_signed && rounded == min_v) return neg_max_bits;
    return v;
  }
  const bool neg = rounded < 0;
  switch (t.o) {
    case hls::SAT: return ovf ? max_bits : min_bits;
    case hls::SAT_ZERO: return 0;
    case hls::SAT_SYM: return ovf ? max_bits : (t.s ? neg_max_bits : 0);
    case hls::WRAP:  // N > 0: saturate the top N bits
      if (t.s) {
        v = set_bit(v, t.w - 1, neg);
        for (int k = t.w - t.n; k <= t.w - 2; ++k) v = set_bit(v, k, !neg);
      } else {
        for (int k = t.w - t.n; k <= t.w - 1; ++k) v = set_bit(v, k, true);
      }
      return v;
    case hls::WRAP_SM: {
      const bool ro = bit(v, t.w - 1);
      if (t.n == 0) {
        // lD: bit W of the aligned unrounded source.
        const bool ld_bit = std::fmod(std::floor(std::ldexp(fl, -t.w)), 2.0L) != 0;
        if (ld_bit != ro) v = ~v & mask;
        return set_bit(v, t.w - 1, ld_bit);
      }
      if (t.n == 1) {
        if (neg != ro) v = ~v & mask;
        return set_bit(v, t.w - 1, neg);
      }
      if (bit(v, t.w - t.n) == neg) v = ~v & mask;
      for (int k = t.w - t.n; k <= t.w - 2; ++k) v = set_bit(v, k, !neg);
      return set_bit(v, t.w - 1, neg);
    }
  }
  return v;
}

// model_bits as the canonical raw integer (sign-extended for signed targets), W < 64.
inline std::int64_t model_raw(ld x, bool src_signed, const Format& t) {
  const std::uint64_t v = model_bits(x, src_signed, t);
  if (t.s && bit(v, t.w - 1))
    return static_cast<std::int64_t>(v) - static_cast<std::int64_t>(std::uint64_t{1} << t.w);
  return static_cast<std::int64_t>(v);
}

// Section 9: the exact value of a double; NaN decodes as +-1.mant * 2^1024 and
// inf as +-2^1024.
inline ld model_value(double d) {
  if (std::isfinite(d)) return static_cast<ld>(d);
  std::uint64_t bits;
  std::memcpy(&bits, &d, sizeof bits);
  const ld mant = 1.0L + std::ldexp(static_cast<ld>(bits & low_mask(52)), -52);
  const ld mag = std::ldexp(std::isnan(d) ? mant : 1.0L, 1024);
  return std::signbit(d) ? -mag : mag;
}

}  // namespace voxcast::fixed_model
