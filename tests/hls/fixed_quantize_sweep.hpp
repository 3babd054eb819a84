// The exhaustive quantization and overflow sweep of voxcast::hls::fixed / ufixed, shared by
// test_fixed_quantize_signed.cpp and test_fixed_quantize_unsigned.cpp (what it checks is
// described at the top of test_fixed_quantize.cpp). Thousands of target types are instantiated
// here, so the sweep is split by signedness into two translation units that compile in
// parallel (docs/building.md).
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "hls/fixed_point.hpp"
#include "tests/common/fixed_point_model.hpp"

namespace voxcast::fixed_quantize_sweep {

using namespace voxcast::hls;

// ---- Independent reference (tests/common/fixed_point_model.hpp) ---------------------------
// Works on the exact value in long double (64-bit mantissa: every value below is exact) with
// floorl / fmodl, not with the integer shifts and masks of the implementation; shared with the
// fixed-point fuzz target (fuzz/targets/fixed_point.cpp).

using target_format = voxcast::fixed_model::Format;
using voxcast::fixed_model::describe;

// The canonical raw integer (sign-extended for signed targets) that converting the exact value
// x into format t must give. Signed source: of the section 3 rules only SAT_SYM's "exact MIN
// becomes -MAX" asks, and only a signed source reaches a negative MIN.
inline std::int64_t reference_raw(long double x, const target_format& t) {
  return voxcast::fixed_model::model_raw(x, true, t);
}

// Section 9: a double is decoded as sign, exponent and mantissa; NaN and inf decode as
// +-1.mant * 2^1024.
inline long double exact_value_of(double d) { return voxcast::fixed_model::model_value(d); }

// ---- Sweep machinery ------------------------------------------------------------------------
// Compile time is the constraint (thousands of target types): each target instantiates only a
// few one-line conversion functions, stored as pointers; the loops, the reference and the
// reporting are ordinary functions.

using raw_conversion = std::int64_t (*)(std::int64_t);
using double_conversion = std::int64_t (*)(double);

struct source_format {
  int w = 0;
  int i = 0;
  bool s = false;
  raw_conversion convert = nullptr;  // raw pattern of the source -> raw of the target
};

struct target_case {
  target_format t;
  source_format sources[2];
  raw_conversion from_int;  // C int -> target, nullptr if not swept
  double_conversion from_double;
};

template <class T, class Src>
std::int64_t convert_fixed(std::int64_t raw) {
  const T t = Src::from_raw(static_cast<typename Src::raw_type>(raw));
  return static_cast<std::int64_t>(t.raw());
}
template <class T>
std::int64_t convert_int(std::int64_t v) {
  const T t = static_cast<int>(v);
  return static_cast<std::int64_t>(t.raw());
}
template <class T>
std::int64_t convert_double(double d) {
  const T t = d;
  return static_cast<std::int64_t>(t.raw());
}

template <class Src>
constexpr source_format describe_source(raw_conversion f) {
  return {Src::width, Src::iwidth, Src::is_signed, f};
}

// Sources: every pattern of a signed <W+4, I+2> (2 dropped bits, 4x the range) and doubles
// (run-time shift amounts, ties, specials) for every target. The sweep is bounded by compile
// time (every target x source pair is its own instantiated conversion), so the sources whose
// behaviour does not depend on Q are swept with the quantization modes that matter to them:
// an unsigned <W+5, I+1> (4 dropped bits: sticky; top bit set without being negative) with
// TRN, RND and TRN_ZERO (which must act as TRN for an unsigned source), and C ints (an exact
// left shift, or a rounding one when I > W) with TRN and RND.
template <int W, int I, bool S, q_mode Q, o_mode O, int N>
constexpr target_case make_case() {
  using T = fixed_base<W, I, S, Q, O, N>;
  using A = fixed<W + 4, I + 2>;
  using B = ufixed<W + 5, I + 1>;
  constexpr bool with_b = Q == TRN || Q == RND || Q == TRN_ZERO;
  constexpr bool with_int = Q == TRN || Q == RND;
  return {{W, I, S, Q, O, N},
          {describe_source<A>(&convert_fixed<T, A>),
           with_b ? describe_source<B>(&convert_fixed<T, B>) : source_format{}},
          with_int ? &convert_int<T> : nullptr,
          &convert_double<T>};
}

// All four overflow modes of the brief with every Q; the saturation-bit variants (WRAP with
// N = 1, 2 and the signed-only WRAP_SM with N = 0, 1, 2) with a truncating and a rounding Q,
// which is what their rules depend on (the sign and the rounding carry).
template <int W, int I, bool S, q_mode Q>
constexpr auto cases_for_q_mode() {
  constexpr std::array basic = {make_case<W, I, S, Q, SAT, 0>(), make_case<W, I, S, Q, SAT_ZERO, 0>(),
                                make_case<W, I, S, Q, SAT_SYM, 0>(), make_case<W, I, S, Q, WRAP, 0>()};
  if constexpr (Q != TRN && Q != RND) {
    return basic;
  } else if constexpr (!S) {
    constexpr int n2 = W >= 2 ? 2 : 1;  // N <= W
    return std::array{basic[0], basic[1], basic[2], basic[3], make_case<W, I, S, Q, WRAP, 1>(),
                      make_case<W, I, S, Q, WRAP, n2>()};
  } else {
    constexpr int n2 = W >= 2 ? 2 : 1;
    return std::array{basic[0],
                      basic[1],
                      basic[2],
                      basic[3],
                      make_case<W, I, S, Q, WRAP, 1>(),
                      make_case<W, I, S, Q, WRAP, n2>(),
                      make_case<W, I, S, Q, WRAP_SM, 0>(),
                      make_case<W, I, S, Q, WRAP_SM, 1>(),
                      make_case<W, I, S, Q, WRAP_SM, n2>()};
  }
}

template <int W, int I, bool S>
void append_cases(std::vector<target_case>& cases) {
  static constexpr auto rnd = cases_for_q_mode<W, I, S, RND>();
  static constexpr auto rnd_zero = cases_for_q_mode<W, I, S, RND_ZERO>();
  static constexpr auto rnd_min_inf = cases_for_q_mode<W, I, S, RND_MIN_INF>();
  static constexpr auto rnd_inf = cases_for_q_mode<W, I, S, RND_INF>();
  static constexpr auto rnd_conv = cases_for_q_mode<W, I, S, RND_CONV>();
  static constexpr auto trn = cases_for_q_mode<W, I, S, TRN>();
  static constexpr auto trn_zero = cases_for_q_mode<W, I, S, TRN_ZERO>();
  for (const auto* table : {rnd.data(), rnd_zero.data(), rnd_min_inf.data(), rnd_inf.data(),
                            rnd_conv.data(), trn_zero.data()}) {
    cases.insert(cases.end(), table, table + 4);
  }
  cases.insert(cases.end(), rnd.begin() + 4, rnd.end());
  cases.insert(cases.end(), trn.begin(), trn.end());
}

// I from -2 to W + 2.
template <int W, bool S>
std::vector<target_case> cases_for_width() {
  std::vector<target_case> cases;
  [&]<int... K>(std::integer_sequence<int, K...>) {
    (append_cases<W, K - 2, S>(cases), ...);
  }(std::make_integer_sequence<int, W + 5>{});
  return cases;
}

struct sweep_stats {
  std::uint64_t comparisons = 0;
  std::uint64_t failures = 0;
};

inline const std::vector<double>& special_doubles() {
  static const std::vector<double> values = [] {
    const double inf = std::numeric_limits<double>::infinity();
    const double nan = std::numeric_limits<double>::quiet_NaN();
    std::vector<double> v = {0.0,
                             -0.0,
                             inf,
                             -inf,
                             nan,
                             -nan,
                             std::numeric_limits<double>::max(),
                             -std::numeric_limits<double>::max(),
                             std::numeric_limits<double>::min(),
                             -std::numeric_limits<double>::min(),
                             std::numeric_limits<double>::denorm_min(),
                             -std::numeric_limits<double>::denorm_min(),
                             1e300,
                             -1e300,
                             1e-300,
                             -1e-300,
                             0.1,
                             -0.1,
                             1.3,
                             -1.3,
                             8.99,
                             -8.99};
    for (int e = -70; e <= 70; ++e) {
      v.push_back(std::ldexp(1.0, e));
      v.push_back(-std::ldexp(1.0, e));
      v.push_back(std::ldexp(1.0 + 0x1.0p-52, e));   // just above a power of two
      v.push_back(-std::ldexp(2.0 - 0x1.0p-52, e));  // just below one, negative
    }
    std::mt19937_64 rng(0x5eedf1c5);
    std::uniform_real_distribution<double> dist(-600.0, 600.0);
    for (int k = 0; k < 200; ++k) v.push_back(dist(rng));
    return v;
  }();
  return values;
}

inline void run_case(const target_case& c, sweep_stats& st) {
  // Every raw pattern of both fixed sources.
  for (const source_format& src : c.sources) {
    if (src.convert == nullptr) continue;
    const std::int64_t lo = src.s ? -(std::int64_t{1} << (src.w - 1)) : 0;
    const std::int64_t hi =
        src.s ? (std::int64_t{1} << (src.w - 1)) - 1 : (std::int64_t{1} << src.w) - 1;
    for (std::int64_t raw = lo; raw <= hi; ++raw) {
      const long double exact = std::ldexp(static_cast<long double>(raw), src.i - src.w);
      const std::int64_t want = reference_raw(exact, c.t);
      const std::int64_t got = src.convert(raw);
      ++st.comparisons;
      if (got != want && ++st.failures <= 20) {
        ADD_FAILURE() << describe(c.t) << " from " << (src.s ? "fixed<" : "ufixed<") << src.w
                      << "," << src.i << "> raw " << raw << ": raw " << got << ", reference "
                      << want;
      }
    }
  }
  // C ints.
  if (c.from_int != nullptr) {
    for (int k = -300; k <= 300; ++k) {
      const std::int64_t want = reference_raw(static_cast<long double>(k), c.t);
      const std::int64_t got = c.from_int(k);
      ++st.comparisons;
      if (got != want && ++st.failures <= 20) {
        ADD_FAILURE() << describe(c.t) << " from int " << k << ": raw " << got
                      << ", reference " << want;
      }
    }
  }
  // Doubles: every multiple of q/8 over four times the range (ties, stickies, carries and
  // overflow), plus the specials.
  auto check_double = [&](double d) {
    const std::int64_t want = reference_raw(exact_value_of(d), c.t);
    const std::int64_t got = c.from_double(d);
    ++st.comparisons;
    if (got != want && ++st.failures <= 20) {
      ADD_FAILURE() << describe(c.t) << " from double " << std::hexfloat << d << std::defaultfloat
                    << ": raw " << got << ", reference " << want;
    }
  };
  const double q8 = std::ldexp(1.0, c.t.i - c.t.w - 3);
  const int span = 16 << c.t.w;
  for (int k = -span; k <= span; ++k) check_double(k * q8);
  for (const double d : special_doubles()) check_double(d);
}

template <int W, bool S>
void run_sweep() {
  const std::vector<target_case> cases = cases_for_width<W, S>();
  sweep_stats st;
  for (const target_case& c : cases) run_case(c, st);
  EXPECT_EQ(st.failures, 0U) << "of " << st.comparisons << " comparisons";
  EXPECT_GT(st.comparisons, 0U);
  ::testing::Test::RecordProperty("target_types", std::to_string(cases.size()));
  ::testing::Test::RecordProperty("comparisons", std::to_string(st.comparisons));
  std::printf("[   INFO   ] %s W=%d: %zu target types, %llu conversions compared\n",
              S ? "signed" : "unsigned", W, cases.size(),
              static_cast<unsigned long long>(st.comparisons));
}

}  // namespace voxcast::fixed_quantize_sweep
