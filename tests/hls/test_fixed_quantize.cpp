// Quantization and overflow of voxcast::hls::fixed / ufixed, checked two ways:
//  1. exhaustively for W = 1..6, I = -2..W+2, every Q mode x the O modes SAT, SAT_ZERO,
//     SAT_SYM, WRAP (and WRAP with N = 1, 2, WRAP_SM with N = 0, 1, 2 under TRN and RND),
//     signed and unsigned targets: every raw pattern of a wider signed and a wider unsigned
//     source, C ints and a set of doubles (specials included), against an independent
//     long-double reference written from the tables of /work/shared/fixed-point-semantics.md
//     sections 2, 3 and 9 ("section N" below);
//  2. the worked examples of the specification as explicit assertions.
// The sweep of 1. is fixed_quantize_sweep.hpp, run by test_fixed_quantize_signed.cpp and
// test_fixed_quantize_unsigned.cpp; this file has its integer sources, the reference's own
// check and 2.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "hls/fixed_point.hpp"
#include "tests/hls/fixed_quantize_sweep.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast::hls;
using voxcast::fixed_quantize_sweep::describe;
using voxcast::fixed_quantize_sweep::reference_raw;
using voxcast::fixed_quantize_sweep::target_format;

// Other C integer and ap_int sources into a few targets (each source type is its own
// converting constructor).
template <class T>
void expect_integer_sources() {
  const target_format t{T::width, T::iwidth, T::is_signed, T::qmode, T::omode, T::nbits};
  auto expect = [&](auto value, long double exact) {
    const T got = value;
    EXPECT_EQ(static_cast<std::int64_t>(got.raw()), reference_raw(exact, t))
        << describe(t) << " from " << static_cast<double>(exact);
  };
  for (int k = -200; k <= 200; ++k) {
    expect(static_cast<long long>(k) * 1000, static_cast<long double>(k) * 1000);
    expect(static_cast<short>(k), static_cast<long double>(k));
    expect(static_cast<signed char>(k / 2), static_cast<long double>(k / 2));
    expect(int_t<10>(k), static_cast<long double>(k));
  }
  for (unsigned k = 0; k <= 400; ++k) {
    expect(k, static_cast<long double>(k));
    expect(static_cast<unsigned long long>(k) << 40, std::ldexp(static_cast<long double>(k), 40));
    expect(static_cast<unsigned char>(k), static_cast<long double>(static_cast<unsigned char>(k)));
    expect(uint_t<9>(k), static_cast<long double>(k & 511));
  }
  expect(true, 1.0L);
  expect(false, 0.0L);
  expect(std::numeric_limits<long long>::min(),
         static_cast<long double>(std::numeric_limits<long long>::min()));
  expect(std::numeric_limits<unsigned long long>::max(),
         static_cast<long double>(std::numeric_limits<unsigned long long>::max()));
}
TEST(FixedQuantizeExhaustive, IntegerSources) {
  expect_integer_sources<fixed<6, 3, RND, SAT>>();
  expect_integer_sources<fixed<6, 8, RND_CONV, SAT_SYM>>();
  expect_integer_sources<fixed<5, 7, TRN_ZERO, WRAP>>();
  expect_integer_sources<ufixed<6, 4, RND_INF, SAT>>();
  expect_integer_sources<ufixed<4, 6, RND, WRAP, 2>>();
  expect_integer_sources<fixed<6, 6, TRN, WRAP_SM>>();
  expect_integer_sources<fixed<12, 30, RND_MIN_INF, SAT_ZERO>>();
}

// The reference itself, on the spec's own numbers, so that a wrong reference cannot hide a
// wrong implementation.
TEST(FixedQuantizeReference, AgreesWithSpecExamples) {
  const target_format rnd_sat{4, 2, true, RND, SAT, 0};
  EXPECT_EQ(reference_raw(1.96875L, rnd_sat), 7);  // 1.75
  const target_format rnd_wrap{4, 2, true, RND, WRAP, 0};
  EXPECT_EQ(reference_raw(1.96875L, rnd_wrap), -8);  // -2.0
  const target_format wrap_10_4{10, 4, true, TRN, WRAP, 0};
  EXPECT_EQ(reference_raw(static_cast<long double>(8.99), wrap_10_4), -449);  // -7.015625
  const target_format u_wrap2{4, 4, false, RND, WRAP, 2};
  EXPECT_EQ(reference_raw(-9.0L, u_wrap2), 15);
}

// ---- Worked examples of the specification -------------------------------------------------

// Section 1: ranges of unusual formats.
TEST(FixedSpecExamples, Section1Ranges) {
  using a = fixed<4, -2>;  // multiples of 1/64 in [-1/8, 7/64]
  EXPECT_EQ((fixed<4, -2, TRN, SAT>(1.0).to_double()), 7.0 / 64);
  EXPECT_EQ((fixed<4, -2, TRN, SAT>(-1.0).to_double()), -1.0 / 8);
  EXPECT_EQ(a::from_raw(1).to_double(), 1.0 / 64);
  using b = fixed<4, 8>;  // multiples of 16 in [-128, 112]
  EXPECT_EQ((fixed<4, 8, TRN, SAT>(1000).to_double()), 112.0);
  EXPECT_EQ((fixed<4, 8, TRN, SAT>(-1000).to_double()), -128.0);
  EXPECT_EQ(b::from_raw(1).to_double(), 16.0);
  EXPECT_EQ(b(37.0).to_double(), 32.0);
  EXPECT_EQ((fixed<8, 4>::width), 8);
  EXPECT_EQ((fixed<8, 4>::iwidth), 4);
  EXPECT_EQ((fixed<8, 4, RND, SAT>::qmode), RND);
  EXPECT_EQ((fixed<8, 4, RND, SAT>::omode), SAT);
  // Same enumerator order as ap_q_mode / ap_o_mode.
  static_assert(RND == 0 && RND_ZERO == 1 && RND_MIN_INF == 2 && RND_INF == 3 && RND_CONV == 4 &&
                TRN == 5 && TRN_ZERO == 6);
  static_assert(SAT == 0 && SAT_ZERO == 1 && SAT_SYM == 2 && WRAP == 3 && WRAP_SM == 4);
}

// Section 2: target ap_fixed<3,2,Q,AP_SAT> (q = 0.5), columns in q_mode order.
template <q_mode Q>
double to_q3(double x) {
  return fixed<3, 2, Q, SAT>(x).to_double();
}
TEST(FixedSpecExamples, Section2QuantizationTable) {
  struct row {
    double x;
    double expect[7];  // RND, RND_ZERO, RND_MIN_INF, RND_INF, RND_CONV, TRN, TRN_ZERO
  };
  const row rows[] = {
      {1.25, {1.5, 1.0, 1.0, 1.5, 1.0, 1.0, 1.0}},
      {-1.25, {-1.0, -1.0, -1.5, -1.5, -1.0, -1.5, -1.0}},
      {0.75, {1.0, 0.5, 0.5, 1.0, 1.0, 0.5, 0.5}},
      {-0.75, {-0.5, -0.5, -1.0, -1.0, -1.0, -1.0, -0.5}},
      {1.3, {1.5, 1.5, 1.5, 1.5, 1.5, 1.0, 1.0}},
      {-1.3, {-1.5, -1.5, -1.5, -1.5, -1.5, -1.5, -1.0}},
  };
  for (const row& r : rows) {
    SCOPED_TRACE(r.x);
    EXPECT_EQ(to_q3<RND>(r.x), r.expect[0]);
    EXPECT_EQ(to_q3<RND_ZERO>(r.x), r.expect[1]);
    EXPECT_EQ(to_q3<RND_MIN_INF>(r.x), r.expect[2]);
    EXPECT_EQ(to_q3<RND_INF>(r.x), r.expect[3]);
    EXPECT_EQ(to_q3<RND_CONV>(r.x), r.expect[4]);
    EXPECT_EQ(to_q3<TRN>(r.x), r.expect[5]);
    EXPECT_EQ(to_q3<TRN_ZERO>(r.x), r.expect[6]);
  }
  // UG1399's examples.
  EXPECT_EQ((fixed<3, 2, RND, SAT>(1.25).to_double()), 1.5);
  EXPECT_EQ((fixed<3, 2, RND, SAT>(-1.25).to_double()), -1.0);
  EXPECT_EQ((fixed<3, 2, RND_ZERO, SAT>(1.25).to_double()), 1.0);
  EXPECT_EQ((fixed<3, 2, RND_ZERO, SAT>(-1.25).to_double()), -1.0);
  EXPECT_EQ((fixed<3, 2, RND_MIN_INF, SAT>(-1.25).to_double()), -1.5);
  // The rounding carry overflows, then O applies.
  EXPECT_EQ((fixed<4, 2, RND, SAT>(1.96875)), 1.75);
  EXPECT_EQ((fixed<4, 2, RND, WRAP>(1.96875)), -2.0);
  // Ties use the sign of the source: the same tie from a fixed source.
  EXPECT_EQ((fixed<3, 2, RND_ZERO, SAT>(fixed<8, 4>(-0.75)).to_double()), -0.5);
  EXPECT_EQ((fixed<3, 2, RND_INF, SAT>(fixed<8, 4>(-0.75)).to_double()), -1.0);
  // TRN_ZERO from an unsigned source is TRN (both floor a non-negative value).
  EXPECT_EQ((ufixed<3, 2, TRN_ZERO>(ufixed<8, 4>(1.75)).to_double()), 1.5);
}

// Section 3: ap_fixed<4,4,AP_RND,O,N> (range -8..7) and ap_ufixed<4,4,AP_RND,O,N>.
template <o_mode O, int N = 0>
double s4(int x) {
  const double from_int = fixed<4, 4, RND, O, N>(x).to_double();
  EXPECT_EQ(from_int, (fixed<4, 4, RND, O, N>(static_cast<double>(x)).to_double())) << x;
  return from_int;
}
template <o_mode O, int N = 0>
double u4(int x) {
  const double from_int = ufixed<4, 4, RND, O, N>(x).to_double();
  EXPECT_EQ(from_int, (ufixed<4, 4, RND, O, N>(static_cast<double>(x)).to_double())) << x;
  return from_int;
}
TEST(FixedSpecExamples, Section3OverflowTable) {
  struct row {
    int x;
    double expect[13];
  };
  // SAT, SAT_ZERO, SAT_SYM, WRAP, WRAP N=1, WRAP N=2, WRAP_SM, WRAP_SM N=1, WRAP_SM N=2,
  // u SAT, u SAT_SYM, u WRAP, u WRAP N=2
  const row rows[] = {
      {19, {7, 0, 7, 3, 3, 7, -4, 3, 4, 15, 15, 3, 15}},
      {-19, {-8, 0, -7, -3, -3, -7, 2, -3, -6, 0, 0, 13, 13}},
      {8, {7, 0, 7, -8, 0, 4, 7, 7, 7, 8, 8, 8, 8}},
      {-9, {-8, 0, -7, 7, -1, -5, -8, -8, -8, 0, 0, 7, 15}},
  };
  for (const row& r : rows) {
    SCOPED_TRACE(r.x);
    EXPECT_EQ(s4<SAT>(r.x), r.expect[0]);
    EXPECT_EQ(s4<SAT_ZERO>(r.x), r.expect[1]);
    EXPECT_EQ(s4<SAT_SYM>(r.x), r.expect[2]);
    EXPECT_EQ(s4<WRAP>(r.x), r.expect[3]);
    EXPECT_EQ((s4<WRAP, 1>(r.x)), r.expect[4]);
    EXPECT_EQ((s4<WRAP, 2>(r.x)), r.expect[5]);
    EXPECT_EQ(s4<WRAP_SM>(r.x), r.expect[6]);
    EXPECT_EQ((s4<WRAP_SM, 1>(r.x)), r.expect[7]);
    EXPECT_EQ((s4<WRAP_SM, 2>(r.x)), r.expect[8]);
    EXPECT_EQ(u4<SAT>(r.x), r.expect[9]);
    EXPECT_EQ(u4<SAT_SYM>(r.x), r.expect[10]);
    EXPECT_EQ(u4<WRAP>(r.x), r.expect[11]);
    EXPECT_EQ((u4<WRAP, 2>(r.x)), r.expect[12]);
  }
  EXPECT_EQ((ufixed<4, 4, RND, WRAP, 2>(-9).to_double()), 15.0);
  // SAT_SYM: an exact MIN becomes -MAX; W = 1 keeps -1.
  EXPECT_EQ((fixed<4, 4, TRN, SAT_SYM>(-8).to_double()), -7.0);
  EXPECT_EQ((fixed<1, 1, TRN, SAT_SYM>(-1).to_double()), -1.0);
  EXPECT_EQ((fixed<1, 1, TRN, SAT_SYM>(-5).to_double()), -1.0);  // ap: MIN | 1 == MIN
  // ... also from another fixed type holding MIN, but a same-type copy is a bit copy.
  const fixed<4, 4> min4 = -8;
  EXPECT_EQ((fixed<4, 4, TRN, SAT_SYM>(min4).to_double()), -7.0);
  const auto sym_min = fixed<4, 4, TRN, SAT_SYM>(3) << 3;  // shifts bypass overflow
  const fixed<4, 4, TRN, SAT_SYM> copy = sym_min;
  EXPECT_EQ(copy.to_double(), -8.0);
}

// Section 4: quantization on conversion only; one per statement; named intermediates round
// again.
TEST(FixedSpecExamples, Section4WhenQuantizationApplies) {
  // WRAP of 8.99 into <10,4>: floor to 8.984375 = raw 575, wraps to 575 - 1024 = -449.
  EXPECT_EQ((fixed<10, 4>(8.99).to_double()), -7.015625);
  EXPECT_EQ((fixed<10, 4>(8.99)).raw(), -449);

  using T = fixed<6, 3, RND>;  // LSB 1/8
  const fixed<8, 4> a = 1.4375, b = 1.4375, c = 0.0625;
  const T once = a * b + c;  // 2.12890625 -> 2.125
  const T p = a * b;         // 2.06640625 -> 2.125
  const T twice = p + c;     // 2.1875 -> 2.25 (tie rounds up)
  EXPECT_EQ(once.to_double(), 2.125);
  EXPECT_EQ(twice.to_double(), 2.25);
  // Compound assignment computes the exact result and quantizes once.
  T acc = 1.0;
  acc += fixed<8, 4>(0.1875);  // 1.1875 -> 1.25 (RND)
  EXPECT_EQ(acc.to_double(), 1.25);
  // Binary operators are exact: no Q/O of the operands applies.
  const fixed<4, 4, TRN, SAT> s7 = 7;
  const auto sum = s7 + s7;
  static_assert(std::is_same_v<decltype(sum), const fixed<5, 5>>);
  EXPECT_EQ(sum.to_double(), 14.0);
}

// Section 9: double -> fixed, specials.
template <o_mode O>
void expect_specials() {
  using T = fixed<8, 4, TRN, O>;
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double max = 127.0 / 16, min = -8.0, nmax = -127.0 / 16;
  const bool wrap = O == WRAP;
  const bool zero = O == SAT_ZERO;
  EXPECT_EQ(T(nan).to_double(), wrap || zero ? 0.0 : max);
  EXPECT_EQ(T(-nan).to_double(), wrap || zero ? 0.0 : (O == SAT_SYM ? nmax : min));
  EXPECT_EQ(T(inf).to_double(), wrap || zero ? 0.0 : max);
  EXPECT_EQ(T(-inf).to_double(), wrap || zero ? 0.0 : (O == SAT_SYM ? nmax : min));
  const double huge = std::ldexp(1.0, 4 + 53);  // abs(d) >= 2^(I+53): every kept bit is 0
  EXPECT_EQ(T(huge).to_double(), wrap || zero ? 0.0 : max);
  EXPECT_EQ(T(-huge).to_double(), wrap || zero ? 0.0 : (O == SAT_SYM ? nmax : min));
  EXPECT_EQ(T(-std::numeric_limits<double>::denorm_min()).to_double(), -1.0 / 16);
  EXPECT_EQ(T(-0.0).raw(), 0);
}
TEST(FixedSpecExamples, Section9DoubleSpecials) {
  expect_specials<WRAP>();
  expect_specials<SAT>();
  expect_specials<SAT_SYM>();
  expect_specials<SAT_ZERO>();
  // Single rounding from double: 1.3 is just below 1.3, RND into <8,4> gives 1.3125.
  EXPECT_EQ((fixed<8, 4, RND>(1.3).to_double()), 1.3125);
  // float goes through double exactly.
  EXPECT_EQ((fixed<16, 4, RND>(0.1f).to_double()), (fixed<16, 4, RND>(static_cast<double>(0.1f)).to_double()));
}

// Section 11: ++/-- add 1.0 with the type's Q/O.
template <class T>
concept incrementable = requires(T x) {
  ++x;
  x++;
  --x;
  x--;
};
TEST(FixedSpecExamples, Section11IncrementAddsOne) {
  fixed<8, 4> p = 1.5;
  ++p;
  EXPECT_EQ(p.to_double(), 2.5);
  const fixed<8, 4> old = p++;
  EXPECT_EQ(old.to_double(), 2.5);
  EXPECT_EQ(p.to_double(), 3.5);
  --p;
  p--;
  EXPECT_EQ(p.to_double(), 1.5);
  fixed<4, 4, TRN, SAT> s = 7;
  ++s;
  EXPECT_EQ(s.to_double(), 7.0);  // saturates
  fixed<4, 4> w = 7;
  ++w;
  EXPECT_EQ(w.to_double(), -8.0);  // wraps
  // I <= 0: 1.0 is out of range; with I == 0 it wraps to the same value.
  fixed<6, 0> z = 0.25;
  ++z;  // 1.25 wraps modulo 1.0
  EXPECT_EQ(z.to_double(), 0.25);
  fixed<6, -1> zm = 0.125;
  --zm;  // -0.875 wraps modulo 0.5
  EXPECT_EQ(zm.to_double(), 0.125);
  fixed<6, 0, TRN, SAT> zs = 0.25;
  ++zs;
  EXPECT_EQ(zs.to_double(), 31.0 / 64);
  // ++ is ill-formed for I > W.
  static_assert(incrementable<fixed<8, 4>>);
  static_assert(incrementable<fixed<8, 8>>);
  static_assert(!incrementable<fixed<4, 8>>);
}

}  // namespace
