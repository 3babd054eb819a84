// The differential test's driver (issue 16; docs/fixed-point.md, "Differential test"): runs the
// operations of differential.hpp on every pair of pairs.hpp with random operands (fixed seed),
// on the clone, on Xilinx's ap_fixed and on Catapult's ac_fixed (engine.cpp, one object per
// engine and chunk), and compares each result's bits and type (W, I, signedness) of the clone
// with ap's and with ac's. A mismatch must be explained by a TAG: a named predicate for one
// documented difference (docs/fixed-point.md: the ap/ac table of "Catapult's ac_fixed" and the
// table "Deliberate differences from ap C simulation"), which checks the vendor's result
// against what that documented rule predicts. Any other mismatch fails the run, printing a
// reproducer (types with modes, operands as bit patterns, the operation, each engine's result).
//
//   voxcast_differential [--records N] [--seed S] [--max-reports K] [--keep-stderr]
//
// N: operation records to compare (each against ap and against ac; default 150000), S: the
// seed of the std::mt19937_64 (default 16). Exit status 0 when no mismatch is untagged.
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "tests/differential/differential.hpp"
#include "tests/differential/pairs.hpp"

namespace voxcast_diff {

const char* op_name(int o) {
  static const char* const names[] = {
#define X(name) #name,
      VOXCAST_DIFF_OPS(X)
#undef X
  };
  return o >= 0 && o < op_count ? names[o] : "?";
}

std::vector<engine_chunk>& chunks() {
  static std::vector<engine_chunk> list;
  return list;
}
bool register_chunk(const engine_chunk& c) {
  chunks().push_back(c);
  return true;
}

namespace {

const char* const q_names[] = {"RND", "RND_ZERO", "RND_MIN_INF", "RND_INF", "RND_CONV", "TRN",
                               "TRN_ZERO"};
const char* const o_names[] = {"SAT", "SAT_ZERO", "SAT_SYM", "WRAP", "WRAP_SM"};

}  // namespace

std::string type_name(const type_desc& t) {
  if (t.is_int) return std::string(t.s ? "int_t<" : "uint_t<") + std::to_string(t.w) + ">";
  std::string s = std::string(t.s ? "fixed<" : "ufixed<") + std::to_string(t.w) + ", " +
                  std::to_string(t.i) + ", " + q_names[t.q] + ", " + o_names[t.o];
  if (t.n != 0) s += ", " + std::to_string(t.n);
  return s + ">";
}

namespace {

template <class... P>
std::vector<pair_desc> describe(list<P...>) {
  return {pair_desc{desc_of<typename P::A>(), desc_of<typename P::B>(), P::kind}...};
}

// ---- Values ------------------------------------------------------------------------------------
u128 mask(int w) { return w >= 128 ? ~u128(0) : (u128(1) << w) - 1; }
i128 signed_value(u128 bits, int w, bool s) {  // the pattern as a number (unsigned: < 2^127 only)
  bits &= mask(w);
  if (s && w < 128 && ((bits >> (w - 1)) & 1) != 0) bits |= ~mask(w);
  return static_cast<i128>(bits);
}
bool is_negative(u128 bits, const type_desc& t) {
  return t.s && ((bits >> (t.w - 1)) & 1) != 0;
}
double to_double_exact_round(u128 bits, const type_desc& t) {
  const int f = t.w - t.i;
  double m = 0;
  if (t.s) {
    m = static_cast<double>(signed_value(bits, t.w, true));
  } else {
    m = static_cast<double>(bits & mask(t.w));
  }
  return std::ldexp(m, -f);
}
std::string hex(u128 x, int w) {
  std::string s;
  const int digits = (w + 3) / 4;
  for (int k = digits - 1; k >= 0; --k) s += "0123456789abcdef"[static_cast<int>((x >> (4 * k)) & 15)];
  return "0x" + s;
}

struct generator {
  std::mt19937_64 rng;
  u128 r128() { return (static_cast<u128>(rng()) << 64) | rng(); }
  int below(int n) { return static_cast<int>(rng() % static_cast<std::uint64_t>(n)); }

  u128 pattern(const type_desc& t) {
    const int w = t.w, f = t.w - t.i;
    const u128 m = mask(w);
    const u128 min = t.s ? u128(1) << (w - 1) : u128(0);
    const u128 max = t.s ? (min - 1) & m : m;
    switch (below(24)) {
      case 0: return 0;
      case 1: return 1;  // +1 LSB
      case 2: return max;
      case 3: return min;
      case 4: return m;  // -1 LSB (signed), MAX (unsigned)
      case 5: return (min + 1) & m;
      case 6: return (max - 1) & m;
      case 7: return (f >= 0 && f < w - (t.s ? 1 : 0)) ? (u128(1) << f) : 1;  // 1.0
      case 8: return (f >= 0 && f < w) ? ((u128(0) - (u128(1) << f)) & m) : m;  // -1.0
      default: {
        const int k = 1 + below(w);  // a random magnitude
        u128 x = r128() & mask(k);
        if (t.s && (rng() & 1) != 0) x = u128(0) - x;
        return x & m;
      }
    }
  }

  inputs make(const pair_desc& p) {
    inputs in;
    in.a = pattern(p.a);
    in.b = pattern(p.b);
    const int w = p.a.w;
    in.n = below(4) == 0 ? below(4 * w + 7) - (2 * w + 3) : below(2 * w + 5) - (w + 2);
    in.un = static_cast<unsigned>(below(2 * w + 4));
    switch (below(10)) {
      case 0: case 1: in.c = below(11) - 5; break;
      case 2: {
        const long long edge[] = {INT32_MIN, INT32_MAX, -1, UINT32_MAX, INT64_MIN, INT64_MAX,
                                  1LL << 31, -(1LL << 31) - 1};
        in.c = edge[below(8)];
        break;
      }
      case 3: in.c = static_cast<long long>(rng()); break;
      default: {
        const int k = below(63);
        in.c = static_cast<long long>(rng() & ((std::uint64_t{1} << k) - 1));
        if ((rng() & 1) != 0) in.c = -in.c;
      }
    }
    // Doubles: a's value (exactly or rounded), ties and near-ties of A's LSB, random values
    // around A's range, B's value.
    const double va = to_double_exact_round(in.a, p.a);
    const double lsb = std::ldexp(1.0, p.a.i - p.a.w);
    switch (below(8)) {
      case 0: case 1: in.d = va; break;
      case 2: in.d = va + lsb * (below(2) == 0 ? 0.5 : -0.5); break;
      case 3: in.d = va + lsb * std::ldexp(static_cast<double>(below(7) - 3), -below(4)); break;
      case 4: in.d = std::ldexp(std::ldexp(static_cast<double>(rng() >> 11), -53) * 2 - 1,
                                p.a.i + 2 - below(8)); break;
      case 5: in.d = to_double_exact_round(in.b, p.b); break;
      case 6: {
        const double special[] = {0.0, -0.0, 0.5, -0.5, 1.0, -1.0, 0.25 * lsb, -0.75 * lsb};
        in.d = special[below(8)];
        break;
      }
      default: in.d = std::ldexp(static_cast<double>(static_cast<std::int64_t>(rng()) >> below(60)),
                                 -below(70));
    }
    if (!std::isfinite(in.d)) in.d = 0;
    in.bit = below(w);
    in.lo = below(w);
    in.hi = in.lo + below(std::min(64, w - in.lo));
    in.v = below(3) == 0 ? static_cast<std::uint64_t>(below(16)) : rng();
    in.bv = (rng() & 1) != 0;
    return in;
  }
};

// ---- Tags: the documented differences ------------------------------------------------------------
struct ctx {
  const pair_desc& p;
  int op;
  const inputs& in;
  const outputs& clone;
  const result& c;  // the clone's result
  const result& v;  // the vendor's result
};

bool is_to_int_family(int op) {
  return op == op_to_int || op == op_to_uint || op == op_to_int64 || op == op_to_uint64 ||
         op == op_to_long || op == op_to_ulong;
}

// Comparisons as (left operand, right operand, relation) for the sign-based exact answer.
enum operand_id { kA, kB, kCI, kCU, kD };
enum relation { kEq, kNe, kLt, kLe, kGt, kGe };
struct comparison {
  int op, lhs, rhs, rel;
};
const comparison comparisons[] = {
    {op_eq, kA, kB, kEq},      {op_ne, kA, kB, kNe},      {op_lt, kA, kB, kLt},
    {op_le, kA, kB, kLe},      {op_gt, kA, kB, kGt},      {op_ge, kA, kB, kGe},
    {op_eq_ba, kB, kA, kEq},   {op_ne_ba, kB, kA, kNe},   {op_lt_ba, kB, kA, kLt},
    {op_le_ba, kB, kA, kLe},   {op_gt_ba, kB, kA, kGt},   {op_ge_ba, kB, kA, kGe},
    {op_eq_c, kA, kCI, kEq},   {op_lt_c, kA, kCI, kLt},   {op_gt_c, kA, kCI, kGt},
    {op_c_eq, kCI, kA, kEq},   {op_c_lt, kCI, kA, kLt},   {op_c_ge, kCI, kA, kGe},
    {op_eq_u, kA, kCU, kEq},   {op_lt_u, kA, kCU, kLt},   {op_u_lt, kCU, kA, kLt},
    {op_u_eq, kCU, kA, kEq},   {op_eq_d, kA, kD, kEq},    {op_ne_d, kA, kD, kNe},
    {op_lt_d, kA, kD, kLt},    {op_le_d, kA, kD, kLe},    {op_gt_d, kA, kD, kGt},
    {op_ge_d, kA, kD, kGe},    {op_d_lt, kD, kA, kLt},    {op_d_eq, kD, kA, kEq},
};
const comparison* find_comparison(int op) {
  for (const comparison& c : comparisons) {
    if (c.op == op) return &c;
  }
  return nullptr;
}
bool operand_signed(const ctx& x, int id) {
  return id == kA ? x.p.a.s : id == kB ? x.p.b.s : id == kCI;
}
bool operand_negative(const ctx& x, int id) {
  if (id == kA) return is_negative(x.in.a, x.p.a);
  if (id == kB) return is_negative(x.in.b, x.p.b);
  if (id == kCI) return static_cast<int>(x.in.c) < 0;
  return false;
}
bool holds(int rel, int sign) {  // sign: -1 lhs < rhs, 0 equal, 1 lhs > rhs
  switch (rel) {
    case kEq: return sign == 0;
    case kNe: return sign != 0;
    case kLt: return sign < 0;
    case kLe: return sign <= 0;
    case kGt: return sign > 0;
    default: return sign >= 0;
  }
}

// floor(a) in the width of a to_int()-family result.
u128 floor_of_a(const ctx& x) {
  const int f = x.p.a.w - x.p.a.i;
  const i128 v = x.p.a.s ? signed_value(x.in.a, x.p.a.w, true)
                         : static_cast<i128>(x.in.a & mask(x.p.a.w));
  if (f <= 0) return f >= 128 ? 0 : static_cast<u128>(v) << -f;
  if (f >= 128) return v < 0 ? ~u128(0) : 0;
  return static_cast<u128>(v >> f);  // arithmetic: floor
}
bool a_is_integer(const ctx& x) {
  const int f = x.p.a.w - x.p.a.i;
  return f <= 0 || (x.in.a & mask(std::min(f, 128))) == 0;
}

// value * 2^-f_src converted into <w_t, f_t fraction bits, s_t> with TRN (floor) and WRAP.
u128 convert_trn_wrap(u128 bits, int f_src, int w_t, int f_t, bool s_t) {
  const int d = f_t - f_src;
  const i128 v = static_cast<i128>(bits);
  u128 r = 0;
  if (d >= 0) {
    r = d >= 128 ? 0 : static_cast<u128>(v) << d;
  } else {
    r = -d >= 128 ? (v < 0 ? ~u128(0) : 0) : static_cast<u128>(v >> -d);
  }
  r &= mask(w_t);
  if (s_t && w_t < 128 && ((r >> (w_t - 1)) & 1) != 0) r |= ~mask(w_t);
  return r;
}

struct tag {
  const char* engine;
  const char* name;
  const char* doc;
  bool (*explains)(const ctx&);
};

const tag tags[] = {
    // ---- ap: "Deliberate differences from ap C simulation" --------------------------------------
    {"ap", "ap.to_int_without_integer_bits",
     "Deliberate differences: to_int() etc. with I <= 0 (ap: -1 or stack garbage; clone: 0)",
     [](const ctx& x) {
       if (x.c.bits != 0) return false;  // the value is in (-1, 1): toward zero is 0
       if (is_to_int_family(x.op) || x.op == op_int_cast_s12 || x.op == op_int_cast_u16 ||
           x.op == op_int_cast_s64 || x.op == op_int_cast_u70 || x.op == op_int_cast_s128 ||
           x.op == op_conv_a_to_b)
         return !x.p.a.is_int && x.p.a.i <= 0 && (x.op != op_conv_a_to_b || x.p.b.is_int);
       if (x.op == op_conv_b || x.op == op_assign_b)
         return x.p.a.is_int && !x.p.b.is_int && x.p.b.i <= 0;
       return false;
     }},
    {"ap", "ap.int_from_small_negative_double",
     "Deliberate differences: int_t<W>(d) for d in (-0.5, 0) (ap: +1; clone: 0)",
     [](const ctx& x) {
       const double d = x.op == op_conv_float ? static_cast<double>(static_cast<float>(x.in.d)) : x.in.d;
       return (x.op == op_conv_double || x.op == op_conv_float) && x.p.a.is_int && d > -0.5 &&
              d < 0 && x.c.bits == 0 && x.v.bits == convert_trn_wrap(1, 0, x.p.a.w, 0, x.p.a.s);
     }},
    {"ap", "ap.min_divided_by_minus_lsb",
     "Deliberate differences: MIN / (-1 LSB) (ap sim wraps to MIN; clone: the exact quotient)",
     [](const ctx& x) {
       const bool a_min = x.p.a.s && (x.in.a & mask(x.p.a.w)) == (u128(1) << (x.p.a.w - 1));
       const bool b_minus_lsb = x.p.b.s && (x.in.b & mask(x.p.b.w)) == mask(x.p.b.w);
       const u128 wrapped = convert_trn_wrap(u128(0) - x.c.bits, 0, x.c.w, 0, x.c.s);
       // int(MIN) / a with a = -1 LSB
       if (x.op == op_c_div && static_cast<int>(x.in.c) == INT32_MIN && x.p.a.s &&
           (x.in.a & mask(x.p.a.w)) == mask(x.p.a.w))
         return x.v.w == x.c.w && x.v.i == x.c.i && x.v.bits == wrapped;
       if (!a_min) return false;
       // a / b and a / int(-1): ap's quotient is the clone's, negated (wrapped) in its type.
       if ((x.op == op_div && b_minus_lsb) || (x.op == op_div_c && static_cast<int>(x.in.c) == -1))
         return x.v.w == x.c.w && x.v.i == x.c.i && x.v.s == x.c.s && x.v.bits == wrapped;
       // a /= b: that quotient converted into A.
       const result& nqa = x.clone.r[op_AUX_neg_quotient_in_a];
       if (x.op == op_div_assign && b_minus_lsb) return nqa.present && same(x.v, nqa);
       return false;
     }},
    {"ap", "ap.c_integer_divided_by_ap_type",
     "Deliberate differences: C integer / ap type (ap sim returns the quotient in the type of "
     "ap type / C integer, <W + 1, I + 1>: it wraps)",
     [](const ctx& x) {
       if (x.op != op_c_div) return false;
       const int w = x.p.a.w + 1, i = x.p.a.i + 1;  // RType<32, 32, true>::div of A
       return x.v.w == w && x.v.i == i && x.v.s &&
              x.v.bits == convert_trn_wrap(x.c.bits, x.c.w - x.c.i, w, w - i, true);
     }},
    {"ap", "ap.to_string_with_i_above_w",
     "Deliberate differences: to_string() wrong for I > W in ap (fixed<4,8>(-32) prints -0)",
     [](const ctx& x) { return x.op == op_to_string && !x.p.a.is_int && x.p.a.i > x.p.a.w; }},
    {"ap", "ap.mixed_sign_integer_division",
     "Deliberate differences: integer / and % with a negative signed and an unsigned operand "
     "(ap divides unsigned in several width combinations)",
     [](const ctx& x) {
       bool sa = x.p.a.s, sb = x.p.b.s, na = is_negative(x.in.a, x.p.a), nb = is_negative(x.in.b, x.p.b);
       if (x.op == op_div_c || x.op == op_c_div) {
         sb = true;
         nb = static_cast<int>(x.in.c) < 0;
       } else if (!(x.op == op_div || x.op == op_mod || x.op == op_div_assign ||
                    x.op == op_mod_assign) || !x.p.b.is_int) {
         return false;
       }
       return x.p.a.is_int && sa != sb && ((sa && na) || (sb && nb));
     }},
    {"ap", "ap.wide_int_to_double",
     "Deliberate differences: to_double() of an ap_int wider than 64 bits beyond the int64 range "
     "(ap: garbage; comparisons with double go through it)",
     [](const ctx& x) {
       const comparison* c = find_comparison(x.op);
       if (x.op != op_to_double && (c == nullptr || (c->lhs != kD && c->rhs != kD))) return false;
       if (!x.p.a.is_int || x.p.a.w <= 64) return false;
       const i128 v = x.p.a.s ? signed_value(x.in.a, x.p.a.w, true) : static_cast<i128>(x.in.a);
       return !x.p.a.s ? (x.in.a >> 63) != 0 : (v < -(i128(1) << 63) || v >= (i128(1) << 63));
     }},
    {"ap", "ap.to_string_beyond_128_bits",
     "Printing: the clone prints the shortest double where the value leaves its 128-bit "
     "arithmetic (ap: exact digits)",
     [](const ctx& x) {
       return x.op == op_to_string && x.c.text.find('e') != std::string::npos &&
              std::strtod(x.c.text.c_str(), nullptr) == std::strtod(x.v.text.c_str(), nullptr);
     }},
    // ---- ac: "Catapult's ac_fixed", the table's rows -------------------------------------------
    {"ac", "ac.increment_adds_one_lsb", "Catapult's ac_fixed #1: ++/-- on a fixed add one LSB",
     [](const ctx& x) {
       if (x.p.a.is_int) return false;
       if (x.op == op_pre_inc || x.op == op_post_inc) return same(x.v, x.clone.r[op_AUX_a_plus_lsb]);
       if (x.op == op_pre_dec || x.op == op_post_dec) return same(x.v, x.clone.r[op_AUX_a_minus_lsb]);
       return false;
     }},
    {"ac", "ac.to_int_floors",
     "Catapult's ac_fixed #2: to_int() & co. on a negative non-integer fixed floor",
     [](const ctx& x) {
       if (!is_to_int_family(x.op) || x.p.a.is_int || !is_negative(x.in.a, x.p.a) || a_is_integer(x))
         return false;
       const int w = x.c.w;  // the C result type's width
       return (x.v.bits & mask(w)) == (floor_of_a(x) & mask(w));
     }},
    {"ac", "ac.mixed_signedness_compares_values",
     "Catapult's ac_fixed #4: signed vs unsigned comparisons (ap: C's unsigned conversion)",
     [](const ctx& x) {
       const comparison* c = find_comparison(x.op);
       if (c == nullptr || c->lhs == kD || c->rhs == kD) return false;
       if (operand_signed(x, c->lhs) == operand_signed(x, c->rhs)) return false;
       const bool ln = operand_negative(x, c->lhs), rn = operand_negative(x, c->rhs);
       if (ln == rn) return false;  // only a negative signed operand is converted differently
       return x.v.bits == (holds(c->rel, ln ? -1 : 1) ? 1u : 0u);
     }},
    {"ac", "ac.double_comparison_is_exact",
     "Catapult's ac_fixed #4b: comparisons with double beyond 53 bits (ap: through to_double())",
     [](const ctx& x) {
       const comparison* c = find_comparison(x.op);
       if (c == nullptr || (c->lhs != kD && c->rhs != kD)) return false;
       return x.p.a.w > 53 && to_double_exact_round(x.in.a, x.p.a) == x.in.d;
     }},
    {"ac", "ac.unsigned_complement_widens",
     "Catapult's ac_fixed #6: ~ on an unsigned operand is <W + 1, I + 1, signed>, value -x - 1",
     [](const ctx& x) {
       if (x.op != op_bnot || x.p.a.s) return false;
       const u128 want = ~(x.in.a & mask(x.p.a.w));  // -x - 1, sign-extended
       return x.v.bits == want && x.v.w == x.p.a.w + 1 && x.v.i == x.p.a.i + 1 && x.v.s;
     }},
    {"ac", "ac.to_string_format",
     "Catapult's ac_fixed #12: to_string(AC_DEC) drops the 0 before the point (.5, -.25)",
     [](const ctx& x) {
       if (x.op != op_to_string) return false;
       auto norm = [](std::string t) {  // no 0 before the point, no ".0" after an integer
         const std::size_t z = t.compare(0, 2, "0.") == 0 ? 0 : (t.compare(0, 3, "-0.") == 0 ? 1 : std::string::npos);
         if (z != std::string::npos) t.erase(z, 1);
         if (t.size() >= 2 && t.compare(t.size() - 2, 2, ".0") == 0) t.erase(t.size() - 2);
         return t.empty() || t == "-" ? t + "0" : t;
       };
       if (norm(x.c.text) == norm(x.v.text)) return true;
       // beyond the clone's 128-bit arithmetic it prints the shortest double (as against ap)
       return x.c.text.find('e') != std::string::npos &&
              std::strtod(x.c.text.c_str(), nullptr) == std::strtod(x.v.text.c_str(), nullptr);
     }},
    {"ac", "ac.int_from_double_floors",
     "Catapult's ac_fixed #14: an ac_int from a negative non-integer double floors (ap: toward zero)",
     [](const ctx& x) {
       if ((x.op != op_conv_double && x.op != op_conv_float) || !x.p.a.is_int) return false;
       const double d = x.op == op_conv_float ? static_cast<double>(static_cast<float>(x.in.d)) : x.in.d;
       if (!(d < 0) || std::floor(d) == d || d < -1e30) return false;
       const i128 f = static_cast<i128>(std::floor(d));
       return x.v.bits == convert_trn_wrap(static_cast<u128>(f), 0, x.p.a.w, 0, x.p.a.s);
     }},
    {"ac", "ac.sat_sym_min_compares_exactly",
     "Catapult's ac_fixed #15: a SAT_SYM right operand holding MIN compares exactly (ap, clone: "
     "as MIN + 1 LSB of the left operand)",
     [](const ctx& x) {
       const comparison* c = find_comparison(x.op);
       if (c == nullptr || c->rhs != kA || x.p.a.is_int || !x.p.a.s || x.p.a.o != kSAT_SYM)
         return false;
       if ((x.in.a & mask(x.p.a.w)) != (u128(1) << (x.p.a.w - 1))) return false;  // MIN
       const int f_left = c->lhs == kB ? x.p.b.w - x.p.b.i : 0;
       return f_left > x.p.a.w - x.p.a.i;
     }},
    {"ac", "ac.to_double_rounding_beyond_64_bits",
     "Catapult's ac_fixed #16: to_double() of more than 64 bits can round twice (within 1 ulp)",
     [](const ctx& x) {
       if (x.op != op_to_double || x.p.a.w <= 64) return false;
       double c = 0, v = 0;
       const auto cb = static_cast<std::uint64_t>(x.c.bits), vb = static_cast<std::uint64_t>(x.v.bits);
       std::memcpy(&c, &cb, sizeof c);
       std::memcpy(&v, &vb, sizeof v);
       return std::nextafter(c, v) == v;
     }},
    {"ac", "ac.integer_result_types",
     "Catapult's ac_fixed #10: integer-only expressions have ac_int result types",
     [](const ctx& x) {
       return x.c.kind == 'i' && x.v.kind == 'i' && x.c.bits == x.v.bits && x.c.s == x.v.s;
     }},
};

// ---- Reports --------------------------------------------------------------------------------------
std::string describe_result(const result& r) {
  if (!r.present) return "(none)";
  char buf[64];
  switch (r.kind) {
    case 'b': return r.bits != 0 ? "true" : "false";
    case 's': return "\"" + r.text + "\"";
    case 'd': {
      double d = 0;
      const auto b = static_cast<std::uint64_t>(r.bits);
      std::memcpy(&d, &b, sizeof d);
      std::snprintf(buf, sizeof buf, "%.17g", d);
      return std::string("double ") + buf;
    }
    case 'n': return std::string(r.s ? "int" : "uint") + std::to_string(r.w) + " " + hex(r.bits, r.w);
    default: {
      const type_desc t{r.w, r.i, r.s, r.kind == 'i', 5, 3, 0};
      std::snprintf(buf, sizeof buf, " (%.17g)", to_double_exact_round(r.bits, t));
      return (r.kind == 'i' ? std::string(r.s ? "int<" : "uint<") + std::to_string(r.w) + ">"
                            : std::string(r.s ? "fixed<" : "ufixed<") + std::to_string(r.w) + "," +
                                  std::to_string(r.i) + ">") +
             " " + hex(r.bits, r.w) + buf;
    }
  }
}
void print_reproducer(const char* engine, const pair_desc& p, int op, const inputs& in,
                      const result& c, const result& v) {
  std::printf("UNTAGGED MISMATCH clone vs %s: op %s\n", engine, op_name(op));
  std::printf("  A = %s, a = %s (%.17g)\n", type_name(p.a).c_str(), hex(in.a, p.a.w).c_str(),
              to_double_exact_round(in.a, p.a));
  std::printf("  B = %s, b = %s (%.17g)\n", type_name(p.b).c_str(), hex(in.b, p.b.w).c_str(),
              to_double_exact_round(in.b, p.b));
  std::printf("  n = %d, un = %u, c = %lld, d = %.17g, bit = %d, hi = %d, lo = %d, v = 0x%" PRIx64
              ", bv = %d\n",
              in.n, in.un, in.c, in.d, in.bit, in.hi, in.lo, in.v, in.bv ? 1 : 0);
  std::printf("  clone: %s\n  %s: %s\n", describe_result(c).c_str(), engine,
              describe_result(v).c_str());
}

}  // namespace
}  // namespace voxcast_diff

int main(int argc, char** argv) {
  using namespace voxcast_diff;
  long long records = 150000;
  std::uint64_t seed = 16;
  int max_reports = 20;
  bool keep_stderr = false;
  for (int k = 1; k < argc; ++k) {
    const std::string arg = argv[k];
    if (arg == "--records" && k + 1 < argc) {
      records = std::atoll(argv[++k]);
    } else if (arg == "--seed" && k + 1 < argc) {
      seed = std::strtoull(argv[++k], nullptr, 0);
    } else if (arg == "--keep-stderr") {
      keep_stderr = true;
    } else if (arg == "--max-reports" && k + 1 < argc) {
      max_reports = std::atoi(argv[++k]);
    } else {
      std::fprintf(stderr, "usage: %s [--records N] [--seed S] [--max-reports K] [--keep-stderr]\n",
                   argv[0]);
      return 2;
    }
  }
  // ap's simulation headers print warnings of their own to stderr (e.g. "Bitsize mismach for
  // ap_[u]int |= ap_[u]int" from ap_private.h's wide logic operators); the report is on stdout.
  if (!keep_stderr && std::freopen("/dev/null", "w", stderr) == nullptr) return 2;
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<pair_desc> pairs = describe(all_pairs{});
  const char* const engines[] = {"clone", "ap", "ac"};
  std::map<std::string, std::vector<engine_chunk>> by_engine;
  for (const engine_chunk& c : chunks()) by_engine[c.engine].push_back(c);
  for (const char* e : engines) {
    if (by_engine[e].empty()) {
      std::printf("differential: no %s engine linked\n", e);
      return 2;
    }
  }
  auto eval = [&](const char* engine, int pair, const inputs& in, outputs& out) {
    for (const engine_chunk& c : by_engine[engine]) {
      if (c.eval(pair, in, out)) return true;
    }
    return false;
  };

  generator gen{std::mt19937_64(seed)};
  long long compared[2] = {0, 0}, untagged[2] = {0, 0}, cases = 0;
  std::map<std::string, long long> by_tag;
  std::map<std::string, long long> untagged_by_op;
  int reports = 0;
  const int np = static_cast<int>(pairs.size());
  while (compared[0] < records) {
    const int pi = static_cast<int>(cases % np);
    const pair_desc& p = pairs[static_cast<std::size_t>(pi)];
    ++cases;
    const inputs in = gen.make(p);
    outputs oc, ov[2];
    if (!eval("clone", pi, in, oc)) continue;  // a partial build (not every chunk linked)
    for (int e = 0; e < 2; ++e) {
      if (!eval(engines[e + 1], pi, in, ov[e])) continue;  // ac: no WRAP_SM, no N
      for (int op = 0; op < op_count; ++op) {
        if (op_is_aux(op)) continue;
        const result& c = oc.r[op];
        const result& v = ov[e].r[op];
        if (!c.present || !v.present) continue;
        ++compared[e];
        if (same(c, v)) continue;
        const ctx x{p, op, in, oc, c, v};
        const tag* hit = nullptr;
        for (const tag& t : tags) {
          if (std::strcmp(t.engine, engines[e + 1]) == 0 && t.explains(x)) {
            hit = &t;
            break;
          }
        }
        if (hit != nullptr) {
          ++by_tag[hit->name];
          continue;
        }
        ++untagged[e];
        // The first mismatch of each (engine, operation), up to max_reports in all.
        if (untagged_by_op[std::string(engines[e + 1]) + " " + op_name(op)]++ == 0 &&
            reports++ < max_reports) {
          print_reproducer(engines[e + 1], p, op, in, c, v);
        }
      }
    }
  }
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("differential: seed %" PRIu64 ", %d type pairs, %lld operand cases, %.1f s\n", seed,
              np, cases, secs);
  std::printf("differential: records compared: clone vs ap %lld, clone vs ac %lld\n", compared[0],
              compared[1]);
  for (const tag& t : tags) {
    std::printf("differential:   tagged %-40s %9lld  (%s)\n", t.name, by_tag[t.name], t.doc);
  }
  for (const auto& u : untagged_by_op) {
    std::printf("differential:   UNTAGGED %-36s %9lld\n", u.first.c_str(), u.second);
  }
  std::printf("differential: untagged mismatches: ap %lld, ac %lld\n", untagged[0], untagged[1]);
  if (compared[0] == 0 || compared[1] == 0) {
    std::printf("differential: FAILED: nothing compared\n");
    return 1;
  }
  if (untagged[0] + untagged[1] != 0) {
    std::printf("differential: FAILED\n");
    return 1;
  }
  std::printf("differential: PASSED\n");
  return 0;
}
