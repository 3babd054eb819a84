// Arithmetic, shifts, comparisons, conversions and bit access of voxcast::hls::fixed / ufixed /
// int_t / uint_t against /work/shared/fixed-point-semantics.md ("section N" below):
//  - result types of every example of section 5 (static_assert);
//  - every worked example of sections 5-12;
//  - small formats swept exhaustively (all pairs of raw patterns) against exact integer
//    arithmetic written here from the specification;
//  - wide formats (W 33..64, results up to 128 bits) sampled with a fixed seed against exact
//    __int128 arithmetic.
#include <gtest/gtest.h>

#include <bit>
#include <charconv>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "hls/fixed_point.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast::hls;

__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;

std::string to_string128(i128 v) {
  if (v == 0) return "0";
  const bool neg = v < 0;
  u128 m = neg ? u128(0) - static_cast<u128>(v) : static_cast<u128>(v);
  std::string s;
  while (m != 0) {
    s.insert(s.begin(), static_cast<char>('0' + static_cast<int>(m % 10)));
    m /= 10;
  }
  return neg ? "-" + s : s;
}

// ---- Exact integer references written from sections 5, 6 and 8 -----------------------

struct format {
  int w;
  int i;
  bool s;
  int f() const { return w - i; }
};

template <class T>
constexpr format format_of() {
  if constexpr (requires { T::iwidth; }) {
    return {T::width, T::iwidth, T::is_signed};
  } else {
    return {T::width, T::width, T::is_signed};
  }
}

i128 shl(i128 v, int n) { return static_cast<i128>(static_cast<u128>(v) << n); }

// Section 8: < via the C rule on the aligned operands.
int reference_compare(format fa, i128 a, format fb, i128 b) {
  const int f = std::max(fa.f(), fb.f());
  const i128 x = shl(a, f - fa.f());
  const i128 y = shl(b, f - fb.f());
  auto exact = [&] { return x < y ? -1 : (x > y ? 1 : 0); };
  if (fa.s == fb.s) return exact();
  const int wa = fa.f() < fb.f() ? fa.w + fb.f() - fa.f() + 1 : fa.w;
  const int wb = fa.f() > fb.f() ? fb.w + fa.f() - fb.f() : fb.w;
  const int ws = fa.s ? wa : wb;
  const int wu = fa.s ? wb : wa;
  if ((ws < 32 && wu < 32) || ws > wu) return exact();
  // Unsigned comparison in max(ws, wu) + 1 bits (ap_private's common width).
  const int m = std::max(ws, wu) + 1;
  const u128 mask = m >= 128 ? ~u128(0) : (u128(1) << m) - 1;
  const u128 ux = static_cast<u128>(x) & mask;
  const u128 uy = static_cast<u128>(y) & mask;
  return ux < uy ? -1 : (ux > uy ? 1 : 0);
}

// Section 8: == compares the signed operand modulo 2^wu in some width combinations.
bool reference_equal(format fa, i128 a, format fb, i128 b) {
  const int f = std::max(fa.f(), fb.f());
  const i128 x = shl(a, f - fa.f());
  const i128 y = shl(b, f - fb.f());
  if (fa.s == fb.s) return x == y;
  const int wa = fa.f() < fb.f() ? fa.w + fb.f() - fa.f() + 1 : fa.w;
  const int wb = fa.f() > fb.f() ? fb.w + fa.f() - fb.f() : fb.w;
  const int ws = fa.s ? wa : wb;
  const int wu = fa.s ? wb : wa;
  if (wu >= 32 && (wu > ws || (wu == ws && wu >= 64))) {
    const u128 mask = wu >= 128 ? ~u128(0) : (u128(1) << wu) - 1;
    return (static_cast<u128>(x) & mask) == (static_cast<u128>(y) & mask);
  }
  return x == y;
}

// ---- "fixed + double" is ill-formed, as with ap_fixed (section 5) ------------------------
template <class A, class B>
concept addable = requires(A a, B b) { a + b; };
template <class A, class B>
concept multipliable = requires(A a, B b) { a * b; };
template <class A, class B>
concept add_assignable = requires(A a, B b) { a += b; };
template <class A, class B>
concept less_comparable = requires(A a, B b) { a < b; };
template <class T, class From>
concept constructible_from = std::is_constructible_v<T, From>;

static_assert(!addable<fixed<8, 4>, double>);
static_assert(!addable<double, fixed<8, 4>>);
static_assert(!addable<fixed<8, 4>, float>);
static_assert(!multipliable<fixed<8, 4>, double>);
static_assert(!multipliable<double, ufixed<8, 4>>);
static_assert(!add_assignable<fixed<8, 4>, double>);
static_assert(!addable<int_t<8>, double>);
static_assert(addable<fixed<8, 4>, int>);
static_assert(addable<fixed<8, 4>, fixed<6, 2>>);
static_assert(add_assignable<fixed<8, 4>, int>);
static_assert(less_comparable<fixed<8, 4>, double>);  // comparisons with double do compile
static_assert(less_comparable<double, fixed<8, 4>>);
static_assert(constructible_from<fixed<8, 4>, double>);
static_assert(constructible_from<fixed<8, 4>, float>);
static_assert(!std::is_convertible_v<fixed<8, 4>, double>);  // explicit only: to_double()
static_assert(std::is_trivially_copyable_v<fixed<8, 4>>);
// Storage is the narrowest C++ integer of W bits or more (docs/fixed-point.md, Representation).
static_assert(sizeof(fixed<8, 4>) == 1 && sizeof(ufixed<9, 1>) == 2 && sizeof(fixed<17, 3>) == 4 &&
              sizeof(uint_t<33>) == 8 && sizeof(fixed<64, 4>) == 8 && sizeof(fixed<100, 4>) == 16);

// ---- Section 5: result types ---------------------------------------------------------------
using A8 = fixed<8, 4>;
using U6 = ufixed<6, 2>;
using N10 = fixed<10, -2>;
using Big = fixed<6, 9>;
template <class T>
T v();  // declval-like, for decltype only

static_assert(std::is_same_v<decltype(v<A8>() + v<U6>()), fixed<9, 5>>);
static_assert(std::is_same_v<decltype(v<A8>() - v<U6>()), fixed<9, 5>>);
static_assert(std::is_same_v<decltype(v<U6>() - v<U6>()), fixed<7, 3>>);  // signed!
static_assert(std::is_same_v<decltype(v<U6>() + v<U6>()), ufixed<7, 3>>);
static_assert(std::is_same_v<decltype(v<A8>() * v<U6>()), fixed<14, 6>>);
static_assert(std::is_same_v<decltype(v<A8>() / v<U6>()), fixed<12, 8>>);
static_assert(std::is_same_v<decltype(v<U6>() / v<A8>()), fixed<11, 7>>);
static_assert(std::is_same_v<decltype(v<A8>() / v<A8>()), fixed<13, 9>>);
static_assert(std::is_same_v<decltype(v<A8>() & v<U6>()), fixed<8, 4>>);
static_assert(std::is_same_v<decltype(v<A8>() | v<U6>()), fixed<8, 4>>);
static_assert(std::is_same_v<decltype(v<A8>() ^ v<U6>()), fixed<8, 4>>);
static_assert(std::is_same_v<decltype(-v<A8>()), fixed<9, 5>>);
static_assert(std::is_same_v<decltype(-v<U6>()), fixed<7, 3>>);
static_assert(std::is_same_v<decltype(~v<U6>()), ufixed<6, 2>>);
static_assert(std::is_same_v<decltype(~v<fixed<8, 4, RND, SAT>>()), fixed<8, 4>>);
static_assert(std::is_same_v<decltype(v<A8>() + v<N10>()), fixed<17, 5>>);
static_assert(std::is_same_v<decltype(v<A8>() / v<N10>()), fixed<21, 17>>);
static_assert(std::is_same_v<decltype(v<A8>() / v<Big>()), fixed<9, 2>>);
static_assert(std::is_same_v<decltype(v<Big>() / v<A8>()), fixed<11, 14>>);
static_assert(std::is_same_v<decltype(v<A8>() + 1), fixed<37, 33>>);
static_assert(std::is_same_v<decltype(1 + v<A8>()), fixed<37, 33>>);
static_assert(std::is_same_v<decltype(v<A8>() * 2), fixed<40, 36>>);
static_assert(std::is_same_v<decltype(v<A8>() / 3), fixed<9, 5>>);
static_assert(std::is_same_v<decltype(v<A8>() + v<int_t<5>>()), fixed<10, 6>>);
// Operand Q/O are ignored: results use the default modes.
static_assert(std::is_same_v<decltype(v<fixed<8, 4, RND, SAT>>() + v<fixed<8, 4, RND, SAT>>()),
                             fixed<9, 5>>);
// C integer operands: <w, w> with their signedness (section 5).
static_assert(std::is_same_v<decltype(v<A8>() + 1u), fixed<38, 34>>);  // u32 gets +1 int bit
static_assert(std::is_same_v<decltype(v<U6>() + 1u), ufixed<37, 33>>);
static_assert(std::is_same_v<decltype(v<A8>() + 1LL), fixed<69, 65>>);
static_assert(std::is_same_v<decltype(v<A8>() * static_cast<short>(1)), fixed<24, 20>>);
static_assert(std::is_same_v<decltype(v<A8>() * static_cast<signed char>(1)), fixed<16, 12>>);
static_assert(std::is_same_v<decltype(v<U6>() * true), ufixed<7, 3>>);
// Shifts keep the type including Q/O (section 7).
static_assert(std::is_same_v<decltype(v<fixed<8, 4, RND, SAT>>() << 2), fixed<8, 4, RND, SAT>>);
static_assert(std::is_same_v<decltype(v<U6>() >> v<int_t<4>>()), U6>);
// Section 12: ap_int result widths.
static_assert(std::is_same_v<decltype(v<int_t<8>>() + v<int_t<8>>()), int_t<9>>);
static_assert(std::is_same_v<decltype(v<int_t<8>>() + v<uint_t<8>>()), int_t<10>>);
static_assert(std::is_same_v<decltype(v<uint_t<8>>() - v<uint_t<8>>()), int_t<9>>);
static_assert(std::is_same_v<decltype(v<uint_t<8>>() * v<uint_t<5>>()), uint_t<13>>);
static_assert(std::is_same_v<decltype(v<int_t<8>>() / v<int_t<5>>()), int_t<9>>);
static_assert(std::is_same_v<decltype(v<int_t<8>>() / v<uint_t<5>>()), int_t<8>>);
static_assert(std::is_same_v<decltype(v<int_t<8>>() % v<uint_t<5>>()), int_t<6>>);
static_assert(std::is_same_v<decltype(v<uint_t<8>>() % v<int_t<5>>()), uint_t<5>>);
static_assert(std::is_same_v<decltype(v<int_t<8>>() & v<uint_t<8>>()), int_t<9>>);
static_assert(std::is_same_v<decltype(v<int_t<8>>() + 1), int_t<33>>);
static_assert(std::is_same_v<decltype(-v<uint_t<8>>()), int_t<9>>);
// The 64 x 64-bit product is 128 bits.
static_assert(std::is_same_v<decltype(v<fixed<64, 32>>() * v<fixed<64, 32>>()), fixed<128, 64>>);
static_assert(std::is_same_v<decltype(v<ufixed<64, 0>>() * v<ufixed<64, 0>>()), ufixed<128, 0>>);

// ---- Compile-time evaluation ---------------------------------------------------------------
static_assert(fixed<8, 4>(1.5).to_double() == 1.5);
static_assert((fixed<8, 4>(1.5) * fixed<8, 4>(-2.25)).to_double() == -3.375);
static_assert(fixed<4, 2, RND, SAT>(1.96875).raw() == 7);
static_assert(fixed<8, 4>(-2.5).to_int() == -2);
static_assert(fixed<8, 4>(3) > 2);

TEST(FixedArith, Section5MixedSignednessValues) {
  // ufixed - ufixed is signed; assigning back wraps.
  const ufixed<4, 4> three = 3, five = 5;
  const auto diff = three - five;
  static_assert(std::is_same_v<decltype(diff), const fixed<5, 5>>);
  EXPECT_EQ(diff.to_double(), -2.0);
  const ufixed<4, 4> back = diff;
  EXPECT_EQ(back.to_double(), 14.0);
  // Mixed operands are aligned on the binary point and sign-extended.
  EXPECT_EQ((fixed<8, 4>(-1.5) + ufixed<6, 2>(3.75)).to_double(), 2.25);
  EXPECT_EQ((fixed<8, 4>(-1.5) * ufixed<6, 2>(3.75)).to_double(), -5.625);
  EXPECT_EQ((fixed<8, 4>(-1.5) & ufixed<6, 2>(3.75)).to_double(), 2.5);  // ...1110.1 & 11.11
  EXPECT_EQ((fixed<8, 4>(-1.5) | ufixed<6, 2>(0.25)).to_double(), -1.25);
  EXPECT_EQ((fixed<8, 4>(-1.5) ^ fixed<8, 4>(-1.5)).to_double(), 0.0);
  EXPECT_EQ((fixed<8, 4>(2.5) + 1).to_double(), 3.5);
  EXPECT_EQ((3 - fixed<8, 4>(2.5)).to_double(), 0.5);
  EXPECT_EQ((fixed<8, 4>(2.5) * -2).to_double(), -5.0);
  // -MIN is representable.
  EXPECT_EQ((-fixed<4, 4>(-8)).to_double(), 8.0);
  EXPECT_EQ((fixed<4, 4>(-8).getNeg().to_double()), -8.0);  // same width: wraps
  // ~ is bitwise in the same type.
  EXPECT_EQ((~fixed<8, 4>(1.5)).to_double(), -1.5625);
  EXPECT_EQ((~ufixed<4, 2>(1.5)).to_double(), 2.25);
}

// ---- Section 6: division -------------------------------------------------------------------
TEST(FixedArith, Section6Division) {
  // Truncation toward zero, keeping the dividend's fraction bits.
  EXPECT_EQ((fixed<8, 4>(-1) / fixed<8, 4>(3)).to_double(), -0.3125);  // floor: -0.375
  EXPECT_EQ((fixed<8, 4>(1) / fixed<8, 4>(3)).to_double(), 0.3125);
  EXPECT_EQ((fixed<8, 4>(-1) / fixed<8, 4>(-3)).to_double(), 0.3125);
  EXPECT_EQ((fixed<8, 4>(1) / fixed<8, 4>(-3)).to_double(), -0.3125);
  // The target's rounding cannot recover what the quotient dropped (double quantization)...
  const fixed<8, 4, RND> q = fixed<8, 4>(2) / fixed<8, 4>(3);
  EXPECT_EQ(q.to_double(), 0.625);
  // ...widen the dividend instead.
  const fixed<8, 4, RND> q2 = fixed<16, 4>(2) / fixed<8, 4>(3);
  EXPECT_EQ(q2.to_double(), 0.6875);
  // a / int divides by <32,32>.
  EXPECT_EQ((fixed<8, 4>(7.5) / 2).to_double(), 3.75);
  EXPECT_EQ((fixed<8, 4>(-7.5) / 4).to_double(), -1.875);
  EXPECT_EQ((fixed<8, 4>(-7) / 4).to_double(), -1.75);
  // A fractional divisor shifts the dividend: keeps 4 fraction bits.
  EXPECT_EQ((fixed<8, 4>(1) / fixed<10, -2>(0.0625)).to_double(), 16.0);
  // MIN / -1 LSB: ap sim wraps to -128 (sim artefact); the clone returns the exact +128,
  // which the result type holds.
  const auto m = fixed<8, 8>(-128) / fixed<1, 1>(-1);
  static_assert(std::is_same_v<decltype(m), const fixed<9, 9>>);
  EXPECT_EQ(m.to_double(), 128.0);
  // Compound division quantizes once, with the target's modes.
  fixed<8, 4, RND, SAT> acc = 7;
  acc /= fixed<8, 4>(0.125);  // 56 saturates
  EXPECT_EQ(acc.to_double(), 127.0 / 16);
  // ap_int division and remainder: C semantics.
  EXPECT_EQ((int_t<8>(-7) / int_t<8>(2)).to_int(), -3);
  EXPECT_EQ((int_t<8>(-7) % int_t<8>(2)).to_int(), -1);
  EXPECT_EQ((int_t<8>(7) % int_t<8>(-2)).to_int(), 1);
  EXPECT_EQ((uint_t<8>(200) / int_t<4>(-3)).to_int(), -66);
  EXPECT_EQ((int_t<8>(-128) / int_t<8>(-1)).to_int(), 128);  // int_t<9>
}

// ---- Section 7: shifts -------------------------------------------------------------------
TEST(FixedArith, Section7Shifts) {
  fixed<4, 4, TRN, SAT> s = 7;
  s <<= 1;  // no saturation
  EXPECT_EQ(s.to_double(), -2.0);
  const fixed<8, 4> x = 3.25;
  EXPECT_EQ((x << -1).to_double(), (x >> 1).to_double());
  EXPECT_EQ((x >> -2).to_double(), (x << 2).to_double());
  EXPECT_EQ((fixed<8, 4>(-3.25) >> 100).to_double(), -0.0625);
  EXPECT_EQ((fixed<8, 4>(3.25) >> 100).to_double(), 0.0);
  EXPECT_EQ((fixed<8, 4>(3.25) << 8).to_double(), 0.0);
  EXPECT_EQ((fixed<8, 4>(3.25) << 2).to_double(), -3.0);  // bits lost, sign flips
  EXPECT_EQ((fixed<4, 4, TRN, SAT_SYM>(3) << 3).to_double(), -8.0);
  EXPECT_EQ((fixed<8, 4>(-3.25) >> 1).to_double(), -1.625);
  EXPECT_EQ((fixed<8, 4>(-3.25) >> 3).to_double(), -0.4375);  // arithmetic: floor
  EXPECT_EQ((ufixed<8, 4>(13.25) >> 3).to_double(), 1.625);   // logical
  // Shift amounts: unsigned never negative; ap_int/ap_fixed amounts; long long goes through
  // to_int() (low 32 bits).
  EXPECT_EQ((x << 1u).to_double(), 6.5);
  EXPECT_EQ((x << int_t<4>(-1)).to_double(), 1.625);
  EXPECT_EQ((x << uint_t<4>(15)).to_double(), 0.0);
  EXPECT_EQ((x >> fixed<8, 4>(1.9)).to_double(), 1.625);   // to_int(1.9) == 1
  EXPECT_EQ((x >> fixed<8, 4>(-1.9)).to_double(), 6.5);    // to_int(-1.9) == -1
  EXPECT_EQ((x << (1LL << 32)).to_double(), 3.25);         // low 32 bits: 0
  EXPECT_EQ((x << 0xffffffffu).to_double(), 0.0);
  // lshift / rshift reinterpret the bits.
  EXPECT_EQ(x.lshift<2>().to_double(), 13.0);
  static_assert(std::is_same_v<decltype(x.lshift<2>()), fixed<8, 6>>);
  EXPECT_EQ(x.rshift<3>().to_double(), 3.25 / 8);
  // ap_int shifts.
  EXPECT_EQ((int_t<8>(-100) >> 2).to_int(), -25);
  EXPECT_EQ((uint_t<8>(200) << 1).to_int(), 144);
  EXPECT_EQ((int_t<8>(1) << 7).to_int(), -128);
  EXPECT_EQ((int_t<8>(-1) >> 200).to_int(), -1);
}

// ---- Section 8: comparisons --------------------------------------------------------------
TEST(FixedArith, Section8Comparisons) {
  EXPECT_TRUE((fixed<8, 4>(-1) < ufixed<8, 4>(1)));
  EXPECT_FALSE((fixed<40, 20>(-1) < ufixed<40, 20>(1)));  // unsigned compare (ac: true)
  EXPECT_TRUE((fixed<8, 4>(-1) < ufixed<30, 4>(1)));      // aligned 31 vs 30 bits: exact
  EXPECT_FALSE((fixed<8, 4>(-1) < ufixed<30, 29>(1)));    // aligned 8 vs 33 bits: unsigned
  EXPECT_FALSE((fixed<40, 20>(-1) < 0u));                 // unsigned int is <32,32>
  EXPECT_FALSE(int_t<32>(-1) < uint_t<32>(0));
  EXPECT_TRUE(int_t<8>(-1) < uint_t<8>(0));
  EXPECT_TRUE((fixed<40, 20>(-1) > ufixed<40, 20>(1)));
  EXPECT_TRUE((ufixed<40, 20>(1) < fixed<40, 20>(-1)));
  EXPECT_TRUE((ufixed<59, 55>(0) < -17));  // aligned 59 vs 36 bits: unsigned
  EXPECT_FALSE((ufixed<8, 4>(0) < -17));   // both < 32 bits: exact

  EXPECT_TRUE((fixed<20, 1>(-1) == ufixed<31, 31>(2147483647)));  // modulo 2^50
  EXPECT_TRUE((fixed<8, 8>(-1) == ufixed<32, 32>(4294967295u)));
  EXPECT_FALSE((fixed<40, 40>(-1) == ufixed<40, 40>((1LL << 40) - 1)));  // same width < 64
  EXPECT_TRUE((fixed<64, 64>(-1) == ufixed<64, 64>(~0ULL)));
  EXPECT_FALSE((fixed<64, 64>(-1) != ufixed<64, 64>(~0ULL)));
  EXPECT_FALSE((fixed<8, 8>(-1) == ufixed<8, 8>(255)));  // narrow: exact
  // Boundaries of the rules (aligned widths ws, wu).
  EXPECT_TRUE((fixed<31, 31>(-1) < ufixed<31, 31>(0)));    // both < 32: exact
  EXPECT_TRUE((fixed<32, 32>(-1) < ufixed<31, 31>(0)));    // ws > wu: exact
  EXPECT_FALSE((fixed<31, 31>(-1) < ufixed<32, 32>(0)));   // wu >= 32, wu > ws: unsigned
  EXPECT_FALSE((fixed<32, 32>(-1) < ufixed<32, 32>(0)));   // wu == ws: unsigned
  EXPECT_TRUE((fixed<31, 31>(-1) == ufixed<32, 32>(0xffffffffu)));    // wu > ws, wu >= 32
  EXPECT_FALSE((fixed<32, 32>(-1) == ufixed<31, 31>(0x7fffffffu)));   // wu < 32: exact
  EXPECT_FALSE((fixed<32, 32>(-1) == ufixed<32, 32>(0xffffffffu)));   // wu == ws < 64: exact
  EXPECT_FALSE((fixed<63, 63>(-1) == ufixed<63, 63>(~0ULL >> 1)));    // wu == ws < 64: exact
  EXPECT_TRUE((fixed<64, 64>(-1) == ufixed<64, 64>(~0ULL)));          // wu == ws >= 64
  EXPECT_TRUE((fixed<63, 63>(-1) == ufixed<64, 64>(~0ULL)));          // wu > ws
  EXPECT_TRUE((ufixed<64, 64>(~0ULL) == fixed<63, 63>(-1)));          // either order
  // The left operand is widened by one extra bit when it has fewer fraction bits.
  // The left operand is widened with one extra bit when it has fewer fraction bits, so the
  // operand order matters: here ws = 31 + 4 + 1 = 36 > wu = 35 (exact) ...
  EXPECT_TRUE((fixed<31, 31>(-1) < ufixed<35, 31>(0)));
  // ... but swapped, ws = 31 + 4 = 35 == wu (unsigned compare).
  EXPECT_FALSE((ufixed<35, 31>(0) > fixed<31, 31>(-1)));
  EXPECT_TRUE((ufixed<35, 31>(0) < fixed<31, 31>(-1)));

  // Same signedness: exact, whatever the formats.
  EXPECT_TRUE((fixed<8, 4>(1.5) == fixed<12, 2>(1.5)));
  EXPECT_TRUE((fixed<8, 4>(1.5) < fixed<12, 2>(1.5625)));
  EXPECT_TRUE((fixed<4, 8>(-32) < fixed<12, -2>(-0.0625)));
  EXPECT_TRUE((ufixed<64, 64>(~0ULL) > ufixed<64, 0>(0.5)));
  // vs double: through to_double (lossy above 53 bits).
  const fixed<64, 60> y = fixed<64, 60>(std::ldexp(1.0, 58)) + fixed<8, -3>(0.0625);
  EXPECT_TRUE(y == y.to_double());
  EXPECT_TRUE(y.to_double() == y);
  EXPECT_TRUE((fixed<8, 4>(1.5) < 1.6));
  EXPECT_TRUE((1.4 < fixed<8, 4>(1.5)));
  EXPECT_TRUE((fixed<8, 4>(1.5) == 1.5f));
  EXPECT_FALSE((fixed<8, 4>(-1.5) < std::numeric_limits<double>::quiet_NaN()));
  // vs C integers.
  EXPECT_TRUE((fixed<8, 4>(3) == 3));
  EXPECT_TRUE((3 == fixed<8, 4>(3)));
  EXPECT_TRUE((fixed<8, 4>(2.5) > 2));
  EXPECT_TRUE((fixed<8, 4>(2.5) != 2));
  EXPECT_TRUE((fixed<8, 4>(-2.5) <= -2));
}

// Section 8 as ap_fixed_base.h's OP_CMP_AF computes it: the right operand, when it has fewer
// fraction bits, is widened to <W2 + F - F2, I2> with its OWN modes; a signed SAT_SYM one
// holding MIN becomes -MAX = MIN + 1 LSB of the left operand there (issue 16; results of
// the vendor's own header, tests/differential checks them against it).
TEST(FixedArith, Section8SatSymRightOperandHoldingMin) {
  using B1 = fixed<1, 1, TRN, SAT_SYM>;
  const B1 b = -5;  // -1: for W = 1 an ordinary assignment reaches MIN
  EXPECT_EQ(b.raw(), -1);
  const fixed<8, 4> a = -1.0;
  EXPECT_FALSE(a == b);  // b compares as -0.9375
  EXPECT_TRUE(a != b);
  EXPECT_TRUE(a < b);
  EXPECT_TRUE(a <= b);
  EXPECT_FALSE(a > b);
  EXPECT_FALSE(a >= b);
  EXPECT_TRUE((fixed<8, 4>(-0.9375) == b));
  EXPECT_FALSE((fixed<8, 4>(-0.9375) < b));
  EXPECT_TRUE((fixed<8, 4>(-0.875) > b));
  // Swapped, b is the left operand and is widened with an extra integer bit: exact.
  EXPECT_TRUE(b == a);
  EXPECT_FALSE((b == fixed<8, 4>(-0.9375)));
  EXPECT_TRUE((b < fixed<8, 4>(-0.9375)));
  // Same fraction bits (no widening): exact.
  EXPECT_TRUE((fixed<4, 4>(-1) == b));
  // W > 1: MIN reached by a shift; every other value compares exactly.
  using S4 = fixed<4, 4, TRN, SAT_SYM>;
  const S4 m = S4(3) << 3;  // -8 = MIN
  EXPECT_EQ(m.raw(), -8);
  EXPECT_FALSE((fixed<8, 6>(-8) == m));  // m compares as -8 + 0.25
  EXPECT_TRUE((fixed<8, 6>(-7.75) == m));
  EXPECT_TRUE((fixed<8, 6>(-8) < m));
  EXPECT_TRUE((fixed<8, 6>(-7) == S4(-7)));
  // The other overflow modes keep MIN.
  EXPECT_TRUE((fixed<8, 6>(-8) == fixed<4, 4, TRN, SAT>::from_raw(-8)));
  EXPECT_TRUE((fixed<8, 6>(-8) == fixed<4, 4, TRN, SAT_ZERO>::from_raw(-8)));
  EXPECT_TRUE((fixed<8, 6>(-8) == fixed<4, 4, TRN, WRAP, 2>::from_raw(-8)));
  EXPECT_TRUE((fixed<8, 6>(-8) == fixed<4, 4, TRN, WRAP_SM>::from_raw(-8)));
  // A C integer or int_t on the left has F = 0: a right operand with I > W qualifies.
  using S2 = fixed<2, 4, TRN, SAT_SYM>;  // LSB 4: {-8, -4, 0, 4}
  const S2 m2 = S2::from_raw(-2);        // -8 = MIN
  EXPECT_FALSE(-8 == m2);                // m2 compares as -7
  EXPECT_TRUE(-7 == m2);
  EXPECT_TRUE(-8 < m2);
  EXPECT_TRUE((int_t<6>(-7) == m2));
  EXPECT_TRUE((m2 == -8));  // m2 on the left: exact
  // An unsigned left operand with the modular == (aligned wu = 41 > ws = 5 + 35 = 40): MIN + 1
  // LSB modulo 2^41.
  EXPECT_TRUE((ufixed<41, 5>::from_raw((std::uint64_t{1} << 41) - (std::uint64_t{1} << 39) + 1) ==
               fixed<5, 4, TRN, SAT_SYM>::from_raw(-16)));
  EXPECT_FALSE((ufixed<41, 5>::from_raw((std::uint64_t{1} << 41) - (std::uint64_t{1} << 39)) ==
                fixed<5, 4, TRN, SAT_SYM>::from_raw(-16)));
  // A signed 1-bit left operand: -0.125 equals MIN + 1 LSB = -0.25 + 0.125.
  EXPECT_TRUE((fixed<1, -2>(-0.125) == fixed<1, -1, TRN, SAT_SYM>(-0.25)));
  EXPECT_FALSE((fixed<1, -2>(-0.125) < fixed<1, -1, TRN, SAT_SYM>(-0.25)));
}

// Concatenation: ap's (a, b) on ints, ranges and bits. The clone refuses it (a deleted
// operator,) where ap concatenates; the ctest cases fixed_point_concat_* compile it.
template <class A, class B>
constexpr bool comma_compiles = requires(A a, B b) { (a, b); };
TEST(FixedArith, ConcatenationDoesNotCompile) {
  using R = decltype(std::declval<fixed<8, 4>&>().range(7, 0));
  using CR = decltype(std::declval<const fixed<8, 4>&>().range(7, 0));
  using IR = decltype(std::declval<uint_t<8>&>().range(3, 0));
  using BR = decltype(std::declval<fixed<8, 4>&>()[1]);
  static_assert(!comma_compiles<R, R>);
  static_assert(!comma_compiles<CR, R>);
  static_assert(!comma_compiles<IR, CR>);
  static_assert(!comma_compiles<BR, BR>);
  static_assert(!comma_compiles<BR, R>);
  static_assert(!comma_compiles<uint_t<8>, int_t<4>>);
  static_assert(!comma_compiles<uint_t<8>&, int>);
  static_assert(!comma_compiles<unsigned, int_t<4>>);
  static_assert(!comma_compiles<R, bool>);
  // Not concatenation in ap either (the built-in comma): these compile in both.
  static_assert(comma_compiles<fixed<8, 4>, fixed<8, 4>>);
  static_assert(comma_compiles<fixed<8, 4>, int_t<4>>);
  static_assert(comma_compiles<int, fixed<8, 4>>);
  static_assert(comma_compiles<R, fixed<8, 4>>);
  SUCCEED();
}

// Section 8, modular ==: the signed operand's aligned pattern modulo 2^wu must equal the
// unsigned one, including the low bits that alignment fills with zeros.
TEST(FixedArith, Section8ModularEqualityPartners) {
  // du > 0: the unsigned operand moves up by 19 bits (aligned 22 vs 50 bits).
  using S = fixed<22, 3>;
  using U = ufixed<31, 31>;
  std::mt19937_64 rng(0x5e8);
  for (int k = 0; k < 2000; ++k) {
    const std::int64_t hi = -static_cast<std::int64_t>(rng() % 4) - 1;  // -1 .. -4
    const S s = S::from_raw(hi * (std::int64_t{1} << 19));                 // -1.0 .. -4.0
    const U partner = U::from_raw(((std::uint64_t{1} << 31) + static_cast<std::uint64_t>(hi)) &
                                  0x7fffffffU);
    EXPECT_TRUE(s == partner) << s << " " << partner;
    EXPECT_FALSE(s != partner);
    const S off = S::from_raw(hi * (std::int64_t{1} << 19) + 1 +
                              static_cast<std::int64_t>(rng() % 1000));
    EXPECT_FALSE(off == partner) << off << " " << partner;
    EXPECT_EQ(off == partner, reference_equal({22, 3, true}, off.raw(), {31, 31, false},
                                              partner.raw()));
  }
  // ds > 0: the signed operand moves up by 20 bits (aligned 29 vs 40 bits).
  EXPECT_TRUE((fixed<8, 8>(-1) == ufixed<40, 20>(1048575)));
  EXPECT_TRUE((fixed<8, 8>(-2) == ufixed<40, 20>(1048574)));
  EXPECT_FALSE((fixed<8, 8>(-1) == ufixed<40, 20>::from_raw((std::uint64_t{1048575} << 20) + 1)));
  EXPECT_FALSE((fixed<8, 8>(-1) == ufixed<40, 20>(1048574)));
  EXPECT_TRUE((ufixed<40, 20>(1048575) == fixed<8, 8>(-1)));
}

// ---- Section 9: conversions out ----------------------------------------------------------
TEST(FixedArith, Section9ConversionsOut) {
  EXPECT_EQ((fixed<8, 4>(-2.5).to_int()), -2);  // toward zero (ac floors to -3)
  EXPECT_EQ((fixed<8, 4>(-7.5).to_int()), -7);
  EXPECT_EQ((fixed<8, 4>(7.9375).to_int()), 7);
  EXPECT_EQ((fixed<8, 4>(-8).to_int()), -8);
  EXPECT_EQ((fixed<8, 4>(-0.0625).to_int()), 0);
  // I <= 0: the clone returns the correct 0 (ap sim: -1 for I == 0, garbage for I < 0).
  EXPECT_EQ((fixed<8, 0>(-0.25).to_int()), 0);
  EXPECT_EQ((fixed<12, -2>(0.1).to_int()), 0);
  EXPECT_EQ((fixed<12, -2>(-0.1).to_int()), 0);
  // I > W and wrap to the C type's width.
  EXPECT_EQ((fixed<4, 8>(-128).to_int()), -128);
  EXPECT_EQ((fixed<8, 40>(std::ldexp(1.0, 35)).to_int()), 0);  // 2^35 wraps in 32 bits
  EXPECT_EQ((fixed<8, 40>(std::ldexp(1.0, 35)).to_int64()), std::int64_t{1} << 35);
  EXPECT_EQ((fixed<8, 4>(-1).to_uint()), 0xffffffffu);
  EXPECT_EQ((fixed<8, 4>(-1).to_uint64()), ~0ULL);
  EXPECT_EQ((fixed<70, 70>::from_raw(static_cast<fixed<70, 70>::raw_type>(-3)).to_int64()), -3);
  EXPECT_EQ(static_cast<int>(fixed<8, 4>(-2.5)), -2);
  EXPECT_EQ(static_cast<double>(fixed<8, 4>(-2.5)), -2.5);
  EXPECT_TRUE(static_cast<bool>(fixed<8, 4>(0.0625)));
  EXPECT_FALSE(static_cast<bool>(fixed<8, 4>(0)));
  EXPECT_TRUE((!fixed<8, 4>(0)));
  // ap_int from fixed and double: toward zero, then wrap.
  EXPECT_EQ(int_t<8>(fixed<8, 4>(-2.5)).to_int(), -2);
  EXPECT_EQ(int_t<4>(fixed<8, 8>(100)).to_int(), 4);
  EXPECT_EQ(int_t<8>(-2.7).to_int(), -2);
  EXPECT_EQ(int_t<8>(300.5).to_int(), 44);
  EXPECT_EQ(int_t<8>(-0.3).to_int(), 0);  // ap sim: +1 (bug), the clone: 0
  EXPECT_EQ(uint_t<8>(-1).to_int(), 255);

  // to_double: round to nearest even above 53 bits.
  EXPECT_EQ((fixed<10, 4>(8.99).to_double()), -7.015625);
  const auto big = fixed<64, 64>::from_raw((std::int64_t{1} << 62) + (1 << 9) + 1);
  EXPECT_EQ(big.to_double(), std::ldexp(1.0, 62) + std::ldexp(1.0, 10));  // above the tie
  const auto tie = fixed<64, 64>::from_raw((std::int64_t{1} << 62) + (1 << 9));
  EXPECT_EQ(tie.to_double(), std::ldexp(1.0, 62));  // tie to even
  EXPECT_EQ((fixed<64, 0>::from_raw(std::numeric_limits<std::int64_t>::min()).to_double()), -0.5);
  EXPECT_TRUE(std::isinf(fixed<8, 1100>::from_raw(1).to_double()));  // ap: garbage
  EXPECT_EQ((fixed<8, -1070>::from_raw(64).to_double()), std::ldexp(1.0, -1072));  // subnormal
  EXPECT_EQ((fixed<8, 4>(1.5).to_float()), 1.5f);
  EXPECT_EQ((fixed<64, 64>::from_raw((std::int64_t{1} << 40) + (1 << 16) + 1).to_float()),
            std::ldexp(1.0f, 40) + std::ldexp(1.0f, 17));  // single rounding
  // Single rounding: through double, 2^40 + 2^16 + 2^-20 would become the tie 2^40 + 2^16
  // and then round to even (2^40).
  const auto nearly_tie =
      fixed<64, 44>::from_raw((((std::int64_t{1} << 40) + (std::int64_t{1} << 16)) << 20) + 1);
  EXPECT_EQ(nearly_tie.to_float(), std::ldexp(1.0f, 40) + std::ldexp(1.0f, 17));
}

// Section 9 table: double specials into <8,4> for each overflow mode (also swept in
// test_fixed_quantize.cpp); here for a wide and an unsigned target.
TEST(FixedArith, Section9SpecialsWideAndUnsigned) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  using W = fixed<64, 20>;
  EXPECT_EQ(W(nan).raw(), 0);
  EXPECT_EQ(W(-inf).raw(), 0);
  EXPECT_EQ((fixed<64, 20, TRN, SAT>(inf).raw()), std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ((fixed<64, 20, TRN, SAT>(-nan).raw()), std::numeric_limits<std::int64_t>::min());
  EXPECT_EQ((fixed<64, 20, TRN, SAT_SYM>(-inf).raw()),
            std::numeric_limits<std::int64_t>::min() + 1);
  EXPECT_EQ((fixed<100, 20, TRN, SAT>(inf).to_double()), std::ldexp(1.0, 19));
  EXPECT_EQ((ufixed<8, 4, TRN, SAT>(nan).to_double()), 15.9375);
  EXPECT_EQ((ufixed<8, 4, TRN, SAT>(-nan).to_double()), 0.0);
  EXPECT_EQ((ufixed<8, 4, TRN, SAT>(-inf).to_double()), 0.0);
  EXPECT_EQ((ufixed<8, 4>(-std::numeric_limits<double>::denorm_min()).to_double()), 15.9375);
}

// ---- Section 10: bit and range access ----------------------------------------------------
TEST(FixedArith, Section10BitsAndRanges) {
  fixed<8, 4> b = -2.75;
  EXPECT_EQ(b.range().to_uint64(), 0xd4U);
  EXPECT_EQ(b.range(3, 0).to_uint64(), 4U);
  EXPECT_EQ(b.range(0, 3).to_uint64(), 2U);  // reversed
  EXPECT_EQ(b(7, 4).to_uint64(), 0xdU);
  EXPECT_TRUE(b[7]);
  EXPECT_FALSE(b[0]);
  EXPECT_TRUE(b.bit(2));
  EXPECT_TRUE(b.get_bit(-2));  // weight 2^-2
  EXPECT_TRUE(b.is_neg());
  b[7] = false;  // raw write, no Q/O
  EXPECT_EQ(b.to_double(), 5.25);
  b.range(3, 0) = 0xf;
  EXPECT_EQ(b.to_double(), 5.9375);
  b.range(7, 4) = 0x8;
  EXPECT_EQ(b.to_double(), -7.0625);
  b.range(0, 3) = 0x1;  // reversed write: bit 3 := 1, bits 2..0 := 0
  EXPECT_EQ(b.range(3, 0).to_uint64(), 8U);
  b.range() = b.range(3, 0);  // range to range: 8 into all W bits
  EXPECT_EQ(b.raw(), 8);
  b.setBits(0xff);
  EXPECT_EQ(b.to_double(), -0.0625);
  EXPECT_EQ((fixed<8, 4>::bitsToFixed(0x18).to_double()), 1.5);
  EXPECT_EQ((fixed<8, 4>::from_raw(0x1d4).raw()), -44);  // keeps the low W bits
  EXPECT_EQ((ufixed<8, 4>::from_raw(0x1d4).raw()), 0xd4U);
  const ufixed<8, 4> u = 13.25;
  EXPECT_EQ(u.range(7, 2).to_uint(), 53U);
  EXPECT_EQ(u.countLeadingZeros(), 0);
  EXPECT_EQ((ufixed<8, 4>(0.25).countLeadingZeros()), 5);
  EXPECT_EQ((fixed<100, 4>::from_raw(1).countLeadingZeros()), 99);
  EXPECT_TRUE((fixed<8, 4>(0).is_zero()));
  EXPECT_FALSE((ufixed<8, 4>(1).is_neg()));
  int_t<12> i = -1;
  EXPECT_EQ(i.range(11, 4).to_uint64(), 0xffU);
  i.range(11, 8) = 0;
  EXPECT_EQ(i.to_int(), 255);
  i[11] = 1;
  EXPECT_EQ(i.to_int(), 255 - 2048);
  // Wide raw access.
  auto w = fixed<128, 64>::from_raw(0);
  w.range(127, 64) = 0x8000000000000000ULL;
  EXPECT_TRUE(w.is_neg());
  EXPECT_EQ(w.range(127, 64).to_uint64(), 0x8000000000000000ULL);
  EXPECT_EQ(w.to_double(), -std::ldexp(1.0, 63));
}

// ---- Sections 11, 12: other operators and ap_int -------------------------------------------
TEST(FixedArith, Section11And12IntegerTypes) {
  int_t<8> a = 127;
  ++a;
  EXPECT_EQ(a.to_int(), -128);  // wraps
  a--;
  EXPECT_EQ(a.to_int(), 127);
  uint_t<4> u = 0;
  --u;
  EXPECT_EQ(u.to_int(), 15);
  int_t<8> c = 100;
  c += 100;
  EXPECT_EQ(c.to_int(), -56);
  c *= int_t<8>(-2);
  EXPECT_EQ(c.to_int(), 112);
  c %= 5;
  EXPECT_EQ(c.to_int(), 2);
  c -= 5;
  EXPECT_EQ(c.to_int(), -3);
  c ^= 1;
  EXPECT_EQ(c.to_int(), -4);
  c >>= 1;
  EXPECT_EQ(c.to_int(), -2);
  EXPECT_EQ((int_t<8>(-3) + uint_t<8>(200)).to_int(), 197);
  EXPECT_EQ((uint_t<8>(3) - uint_t<8>(5)).to_int(), -2);
  EXPECT_EQ((int_t<8>(-3) * 1000).to_int(), -3000);
  EXPECT_EQ((~uint_t<4>(5)).to_int(), 10);
  EXPECT_EQ((-int_t<8>(-128)).to_int(), 128);
  EXPECT_EQ(int_t<8>(int_t<16>(0x1234)).to_int(), 0x34);
  EXPECT_EQ(int_t<70>(-5).to_int64(), -5);
  EXPECT_EQ(uint_t<70>(-5).to_uint64(), ~0ULL - 4);
  EXPECT_EQ(uint_t<64>(~0ULL).to_double(), 18446744073709551616.0);
  // A fixed takes an ap_int as <W, W>.
  EXPECT_EQ((fixed<8, 4, RND, SAT>(int_t<12>(-100))).to_double(), -8.0);
}

// ---- Printing ------------------------------------------------------------------------------
TEST(FixedArith, Printing) {
  EXPECT_EQ((fixed<8, 4>(-2.75).to_string()), "-2.75");
  EXPECT_EQ((fixed<10, 4>(8.99).to_string()), "-7.015625");
  EXPECT_EQ((fixed<4, 8>(32).to_string()), "32");  // ap prints 0 here (I > W bug)
  EXPECT_EQ((fixed<8, -2>::from_raw(-1).to_string()), "-0.0009765625");
  EXPECT_EQ((ufixed<64, 64>(~0ULL).to_string()), "18446744073709551615");
  EXPECT_EQ((fixed<128, 0>::from_raw(0).to_string()), "0");
  EXPECT_EQ(int_t<8>(-128).to_string(), "-128");
  EXPECT_EQ((fixed<8, 4>(-2.75).to_string(2)), "0b11010100");
  EXPECT_EQ((ufixed<12, 4>::from_raw(0xabc).to_string(16)), "0xabc");
  std::ostringstream os;
  os << fixed<8, 4>(1.5) << " " << int_t<8>(-3);
  EXPECT_EQ(os.str(), "1.5 -3");
}

// A value beyond the 128-bit decimal arithmetic prints as its double, in the shortest text
// that reads back (std::to_chars; the C++14 header writes it with snprintf / strtod).
std::string to_chars_text(double d) {
  char buf[400];
  const auto res = std::to_chars(buf, buf + sizeof(buf), d);
  return std::string(buf, res.ptr);
}
TEST(FixedArith, PrintingBeyond128BitsIsTheShortestDouble) {
  std::mt19937_64 rng(20240601);
  std::uint64_t mismatches = 0;
  const auto expect_text = [&](const std::string& got, double d) {
    if (got != to_chars_text(d) && ++mismatches <= 10) {
      ADD_FAILURE() << std::hexfloat << d << ": " << got << " != " << to_chars_text(d);
    }
  };
  for (int k = 0; k < 2000; ++k) {
    const auto r = static_cast<std::int64_t>(rng() >> (rng() % 64));
    const auto fine = fixed<64, -100>::from_raw(r);     // F = 164 > 124: the double
    const auto huge = fixed<64, 300>::from_raw(~r);     // integers beyond 2^128
    const auto tiny = ufixed<20, -1060>::from_raw(static_cast<std::uint64_t>(r));  // subnormal
    expect_text(fine.to_string(), fine.to_double());
    expect_text(huge.to_string(), huge.to_double());
    expect_text(tiny.to_string(), tiny.to_double());
  }
  EXPECT_EQ((fixed<64, 1100>::from_raw(1LL << 62).to_string()), "inf");
  EXPECT_EQ((fixed<8, 300>::from_raw(0).to_string()), "0");
  EXPECT_EQ((fixed<8, -200>::from_raw(-1).to_string()), "-2.4308653429145085e-63");
  EXPECT_EQ((fixed<8, 200>::from_raw(1).to_string()), "6.277101735386681e+57");
  EXPECT_EQ((fixed<8, 120>::from_raw(3).to_string()), "15576890575604482885591488987660288");
  // Every bit pattern class of a double (the helper itself).
  for (int k = 0; k < 20000; ++k) {
    const double d = std::bit_cast<double>(rng());
    expect_text(detail::double_to_string(d), d);
  }
  for (int e = -1074; e <= 1023; ++e) {
    const double p = std::ldexp(1.0, e);
    for (const double d : {p, -p, std::nextafter(p, 0.0), std::nextafter(p, INFINITY), 3 * p}) {
      expect_text(detail::double_to_string(d), d);
    }
  }
  for (int e = -320; e <= 300; ++e) {
    for (int m = 1; m < 10; ++m) {
      const double d = m * std::pow(10.0, e);
      expect_text(detail::double_to_string(d), d);
      expect_text(detail::double_to_string(std::nextafter(d, 0.0)), std::nextafter(d, 0.0));
    }
  }
  EXPECT_EQ(mismatches, 0u);
}

// ---- Exhaustive small formats: all pairs of raw patterns ----------------------------------

struct pair_stats {
  std::uint64_t comparisons = 0;
  std::uint64_t failures = 0;
};

void expect_raw(pair_stats& st, const char* op, i128 a, i128 b, i128 got, i128 want) {
  ++st.comparisons;
  if (got != want && ++st.failures <= 20) {
    ADD_FAILURE() << "a=" << to_string128(a) << " " << op << " b=" << to_string128(b)
                  << ": raw " << to_string128(got) << ", want " << to_string128(want);
  }
}

// Checks every operator for one pair of operand values.
template <class A, class B>
void check_pair(const A& a, const B& b, pair_stats& st) {
  constexpr format fa = format_of<A>();
  constexpr format fb = format_of<B>();
  const i128 ra = static_cast<i128>(a.raw());
  const i128 rb = static_cast<i128>(b.raw());
  const int f = std::max(fa.f(), fb.f());
  const i128 x = shl(ra, f - fa.f());
  const i128 y = shl(rb, f - fb.f());
  // Section 5: + - & | ^ on the aligned operands are exact; * is the exact raw product.
  expect_raw(st, "+", ra, rb, static_cast<i128>((a + b).raw()), x + y);
  expect_raw(st, "-", ra, rb, static_cast<i128>((a - b).raw()), x - y);
  expect_raw(st, "*", ra, rb, static_cast<i128>((a * b).raw()), ra * rb);
  expect_raw(st, "&", ra, rb, static_cast<i128>((a & b).raw()), x & y);
  expect_raw(st, "|", ra, rb, static_cast<i128>((a | b).raw()), x | y);
  expect_raw(st, "^", ra, rb, static_cast<i128>((a ^ b).raw()), x ^ y);
  // Section 6: (a.V << max(F2, 0)) / b.V, truncated toward zero (C division).
  if (rb != 0) {
    expect_raw(st, "/", ra, rb, static_cast<i128>((a / b).raw()),
               shl(ra, std::max(fb.f(), 0)) / rb);
  }
  // Section 8.
  const int c = reference_compare(fa, ra, fb, rb);
  const bool eq = reference_equal(fa, ra, fb, rb);
  expect_raw(st, "<", ra, rb, a < b, c < 0);
  expect_raw(st, "<=", ra, rb, a <= b, c <= 0);
  expect_raw(st, ">", ra, rb, a > b, c > 0);
  expect_raw(st, ">=", ra, rb, a >= b, c >= 0);
  expect_raw(st, "==", ra, rb, a == b, eq);
  expect_raw(st, "!=", ra, rb, a != b, !eq);
}

template <class A, class B>
void sweep_pairs() {
  pair_stats st;
  const std::int64_t alo = A::is_signed ? -(std::int64_t{1} << (A::width - 1)) : 0;
  const std::int64_t ahi = A::is_signed ? (std::int64_t{1} << (A::width - 1)) : (std::int64_t{1} << A::width);
  const std::int64_t blo = B::is_signed ? -(std::int64_t{1} << (B::width - 1)) : 0;
  const std::int64_t bhi = B::is_signed ? (std::int64_t{1} << (B::width - 1)) : (std::int64_t{1} << B::width);
  for (std::int64_t ra = alo; ra < ahi; ++ra) {
    const A a = A::from_raw(static_cast<typename A::raw_type>(ra));
    for (std::int64_t rb = blo; rb < bhi; ++rb) {
      check_pair(a, B::from_raw(static_cast<typename B::raw_type>(rb)), st);
    }
  }
  EXPECT_EQ(st.failures, 0U) << "of " << st.comparisons;
  std::printf("[   INFO   ] %llu operator results compared\n",
              static_cast<unsigned long long>(st.comparisons));
}

TEST(FixedArithExhaustive, SignedSigned) {
  sweep_pairs<fixed<6, 3>, fixed<5, 1>>();
  sweep_pairs<fixed<5, -1>, fixed<6, 7>>();
}
TEST(FixedArithExhaustive, SignedUnsigned) {
  sweep_pairs<fixed<6, 3>, ufixed<5, 1>>();
  sweep_pairs<ufixed<5, 4>, fixed<6, -2>>();
  sweep_pairs<ufixed<6, 2>, ufixed<5, 5>>();
}
TEST(FixedArithExhaustive, Integers) {
  sweep_pairs<int_t<6>, uint_t<5>>();
  sweep_pairs<uint_t<6>, int_t<6>>();
  sweep_pairs<fixed<6, 2>, int_t<5>>();
}

// ---- Shifts, exhaustively on small formats ------------------------------------------------
template <class T>
void sweep_shifts() {
  const std::int64_t lo = T::is_signed ? -(std::int64_t{1} << (T::width - 1)) : 0;
  const std::int64_t hi = T::is_signed ? (std::int64_t{1} << (T::width - 1)) : (std::int64_t{1} << T::width);
  const std::int64_t mask = (std::int64_t{1} << T::width) - 1;
  auto canon = [](std::int64_t p) {
    p &= (std::int64_t{1} << T::width) - 1;
    if (T::is_signed && (p >> (T::width - 1)) != 0) p -= std::int64_t{1} << T::width;
    return p;
  };
  for (std::int64_t r = lo; r < hi; ++r) {
    const T x = T::from_raw(static_cast<typename T::raw_type>(r));
    for (int n = -2 * T::width; n <= 2 * T::width; ++n) {
      // Section 7: raw W-bit pattern; >> is floor (sign fill) or logical; >= W: 0 / fill.
      const int left = n;  // x << n
      std::int64_t want_l = 0;
      if (left >= 0) {
        want_l = left >= T::width ? 0 : canon((r << left) & mask);
      } else {
        want_l = -left >= T::width ? (r < 0 ? -1 : 0) : (r >> -left);
      }
      ASSERT_EQ(static_cast<std::int64_t>((x << n).raw()), want_l) << r << " << " << n;
      ASSERT_EQ(static_cast<std::int64_t>((x >> -n).raw()), want_l) << r << " >> " << -n;
      T y = x;
      y <<= n;
      ASSERT_EQ(static_cast<std::int64_t>(y.raw()), want_l);
    }
  }
}

TEST(FixedArithExhaustive, Shifts) {
  sweep_shifts<fixed<6, 3, RND, SAT>>();
  sweep_shifts<ufixed<5, -1>>();
  sweep_shifts<fixed<1, 1>>();
  sweep_shifts<int_t<7>>();
  sweep_shifts<uint_t<6>>();
}

// ---- Wide formats: random operands against exact __int128 arithmetic --------------------

// Independent wide reference of sections 2-3 on __int128 (for sources that fit it).
i128 reference_convert(i128 v, int fs, format t, q_mode q, o_mode o) {
  const int d = fs - t.f();
  i128 r = 0;
  if (d > 0) {
    const i128 fl = d >= 127 ? (v < 0 ? -1 : 0) : (v >> d);
    const i128 rem = v - shl(fl, d);  // 0 <= rem < 2^d
    const i128 half = d - 1 >= 127 ? std::numeric_limits<std::int64_t>::max() : shl(1, d - 1);
    const bool qb = rem >= half;
    const bool sticky = qb ? rem > half : rem > 0;
    const bool s = v < 0;
    bool inc = false;
    switch (q) {
      case TRN: inc = false; break;
      case TRN_ZERO: inc = s && (qb || sticky); break;
      case RND: inc = qb; break;
      case RND_ZERO: inc = qb && (s || sticky); break;
      case RND_MIN_INF: inc = qb && sticky; break;
      case RND_INF: inc = qb && (!s || sticky); break;
      case RND_CONV: inc = qb && ((fl & 1) != 0 || sticky); break;
    }
    r = fl + (inc ? 1 : 0);
  } else {
    r = shl(v, -d);
  }
  const i128 max_v = t.s ? shl(1, t.w - 1) - 1 : shl(1, t.w) - 1;
  const i128 min_v = t.s ? -shl(1, t.w - 1) : 0;
  const i128 two_w = shl(1, t.w);
  i128 low = r % two_w;
  if (low < 0) low += two_w;
  if (t.s && low > max_v) low -= two_w;
  if (o == WRAP) return low;
  if (o == SAT) return r > max_v ? max_v : (r < min_v ? min_v : low);
  if (o == SAT_ZERO) return (r > max_v || r < min_v) ? 0 : low;
  // SAT_SYM
  if (r > max_v) return max_v;
  if (r < min_v || (t.s && t.w > 1 && r == min_v)) return t.s ? min_v + 1 : 0;
  return low;
}

template <class T>
T random_value(std::mt19937_64& rng) {
  // A mix of full-range patterns and small values around 0, MIN and MAX.
  const std::uint64_t pick = rng() % 8;
  const std::uint64_t lo = rng();
  const std::uint64_t hi = rng();
  using R = typename T::raw_type;
  if (pick == 0) return T::from_raw(static_cast<R>(static_cast<std::int64_t>(lo % 7) - 3));
  if (pick == 1) return T::from_raw(static_cast<R>(static_cast<R>(-1) << (T::width - 1)) + static_cast<R>(lo % 3));
  if (pick == 2) return T::from_raw(static_cast<R>(~(static_cast<R>(-1) << (T::width - 1))) - static_cast<R>(lo % 3));
  if constexpr (T::width > 64) {
    return T::from_raw(static_cast<R>((static_cast<u128>(hi) << 64) | lo));
  } else {
    return T::from_raw(static_cast<R>(lo));
  }
}

// Correctly rounded (nearest even) double of v * 2^-f, written out bit by bit.
double reference_to_double(i128 v, int f) {
  if (v == 0) return 0.0;
  const bool neg = v < 0;
  u128 m = neg ? u128(0) - static_cast<u128>(v) : static_cast<u128>(v);
  int top = 127;
  while (((m >> top) & 1) == 0) --top;
  int e = top - f;  // value = 1.xxx * 2^e
  if (top > 52) {
    const int drop = top - 52;
    const u128 kept = m >> drop;
    const u128 rest = m & ((u128(1) << drop) - 1);
    const u128 half = u128(1) << (drop - 1);
    u128 r = kept;
    if (rest > half || (rest == half && (kept & 1) != 0)) ++r;
    if ((r >> 53) != 0) {
      r >>= 1;
      ++e;
    }
    m = r;
  } else {
    m <<= (52 - top);
  }
  const double d = std::ldexp(static_cast<double>(static_cast<std::uint64_t>(m)), e - 52);
  return neg ? -d : d;
}

template <class A, class B>
void random_pairs(std::uint64_t seed, int count) {
  std::mt19937_64 rng(seed);
  constexpr format fa = format_of<A>();
  constexpr format fb = format_of<B>();
  pair_stats st;
  for (int k = 0; k < count; ++k) {
    const A a = random_value<A>(rng);
    const B b = random_value<B>(rng);
    const i128 ra = static_cast<i128>(a.raw());
    const i128 rb = static_cast<i128>(b.raw());
    const int f = std::max(fa.f(), fb.f());
    const i128 x = shl(ra, f - fa.f());
    const i128 y = shl(rb, f - fb.f());
    expect_raw(st, "+", ra, rb, static_cast<i128>((a + b).raw()), x + y);
    expect_raw(st, "-", ra, rb, static_cast<i128>((a - b).raw()), x - y);
    const auto p = a * b;
    if constexpr (!decltype(p)::is_signed && decltype(p)::width == 128) {
      expect_raw(st, "*", ra, rb, static_cast<i128>(p.raw() >> 64),
                 static_cast<i128>((static_cast<u128>(ra) * static_cast<u128>(rb)) >> 64));
      // The low word of the unsigned product (as i128, ra * rb overflows: UB).
      expect_raw(st, "*lo", ra, rb, static_cast<i128>(static_cast<std::uint64_t>(p.raw())),
                 static_cast<i128>(static_cast<std::uint64_t>(
                     static_cast<u128>(ra) * static_cast<u128>(rb))));
    } else {
      expect_raw(st, "*", ra, rb, static_cast<i128>(p.raw()), ra * rb);
    }
    if (rb != 0) {
      expect_raw(st, "/", ra, rb, static_cast<i128>((a / b).raw()),
                 shl(ra, std::max(fb.f(), 0)) / rb);
    }
    expect_raw(st, "<", ra, rb, a < b, reference_compare(fa, ra, fb, rb) < 0);
    expect_raw(st, ">=", ra, rb, a >= b, reference_compare(fa, ra, fb, rb) >= 0);
    expect_raw(st, "==", ra, rb, a == b, reference_equal(fa, ra, fb, rb));
    // Also equal operands (the random ones almost never are).
    expect_raw(st, "==self", ra, ra, a == a, true);
    // Conversions out.
    expect_raw(st, "to_int64", ra, 0, a.to_int64(),
               static_cast<std::int64_t>(static_cast<std::uint64_t>(
                   static_cast<u128>(fa.f() >= 0 ? ra / shl(1, fa.f()) : shl(ra, -fa.f())))));
    ++st.comparisons;
    if (a.to_double() != reference_to_double(ra, fa.f()) && ++st.failures <= 20) {
      ADD_FAILURE() << "to_double of raw " << to_string128(ra);
    }
  }
  EXPECT_EQ(st.failures, 0U) << "of " << st.comparisons;
}

TEST(FixedArithRandom, WideOperators) {
  random_pairs<fixed<40, 20>, fixed<48, 10>>(1, 20000);
  random_pairs<fixed<64, 32>, fixed<64, 60>>(2, 20000);
  random_pairs<ufixed<64, 20>, ufixed<64, 64>>(3, 20000);
  random_pairs<fixed<33, 33>, ufixed<64, 30>>(4, 20000);
  random_pairs<ufixed<50, -5>, fixed<37, 45>>(5, 20000);
  random_pairs<fixed<64, 64>, fixed<64, 64>>(6, 20000);
  random_pairs<ufixed<64, 64>, fixed<64, 64>>(7, 20000);
  random_pairs<ufixed<40, 20>, fixed<40, 20>>(8, 20000);
  random_pairs<int_t<64>, uint_t<64>>(9, 20000);
  random_pairs<uint_t<33>, int_t<40>>(10, 20000);
}

// Conversions between wide formats and from double, every Q with every O.
template <class T, class Src>
void random_conversions(std::mt19937_64& rng, int count, pair_stats& st) {
  constexpr format ft = format_of<T>();
  constexpr format fs = format_of<Src>();
  for (int k = 0; k < count; ++k) {
    const Src s = random_value<Src>(rng);
    const T t = s;
    expect_raw(st, "convert", static_cast<i128>(s.raw()), 0, static_cast<i128>(t.raw()),
               reference_convert(static_cast<i128>(s.raw()), fs.f(), ft, T::qmode, T::omode));
  }
  for (int k = 0; k < count; ++k) {
    // Doubles spread over the target's range and beyond.
    const double d = std::ldexp(std::uniform_real_distribution<double>(-1.0, 1.0)(rng),
                                static_cast<int>(rng() % static_cast<std::uint64_t>(ft.w + 8)) +
                                    ft.i - ft.w);
    int e = 0;
    const double mant = std::frexp(d, &e);
    const auto m = static_cast<std::int64_t>(std::ldexp(mant, 53));  // exact
    const T t = d;
    expect_raw(st, "from double", m, e, static_cast<i128>(t.raw()),
               reference_convert(m, 53 - e, ft, T::qmode, T::omode));
  }
}

template <int W, int I, bool S, q_mode Q>
void random_conversions_all_o(std::mt19937_64& rng, pair_stats& st) {
  random_conversions<fixed_base<W, I, S, Q, WRAP>, fixed<64, 32>>(rng, 2000, st);
  random_conversions<fixed_base<W, I, S, Q, SAT>, ufixed<64, 40>>(rng, 2000, st);
  random_conversions<fixed_base<W, I, S, Q, SAT_ZERO>, fixed<100, 60>>(rng, 2000, st);
  random_conversions<fixed_base<W, I, S, Q, SAT_SYM>, fixed<64, 32>>(rng, 2000, st);
  random_conversions<fixed_base<W, I, S, Q, SAT_SYM>, fixed<100, 60>>(rng, 2000, st);
}

template <int W, int I, bool S>
void random_conversions_all_q(std::mt19937_64& rng, pair_stats& st) {
  random_conversions_all_o<W, I, S, RND>(rng, st);
  random_conversions_all_o<W, I, S, RND_ZERO>(rng, st);
  random_conversions_all_o<W, I, S, RND_MIN_INF>(rng, st);
  random_conversions_all_o<W, I, S, RND_INF>(rng, st);
  random_conversions_all_o<W, I, S, RND_CONV>(rng, st);
  random_conversions_all_o<W, I, S, TRN>(rng, st);
  random_conversions_all_o<W, I, S, TRN_ZERO>(rng, st);
}

TEST(FixedArithRandom, WideConversions) {
  std::mt19937_64 rng(0xf17ed);
  pair_stats st;
  random_conversions_all_q<40, 20, true>(rng, st);
  random_conversions_all_q<64, 30, true>(rng, st);
  random_conversions_all_q<64, 50, false>(rng, st);
  random_conversions_all_q<33, 0, true>(rng, st);
  random_conversions_all_q<48, 60, false>(rng, st);
  EXPECT_EQ(st.failures, 0U) << "of " << st.comparisons;
  std::printf("[   INFO   ] %llu wide conversions compared\n",
              static_cast<unsigned long long>(st.comparisons));
}

// The widest types: 128-bit products and their conversions.
TEST(FixedArithRandom, Products128) {
  std::mt19937_64 rng(0x128);
  pair_stats st;
  for (int k = 0; k < 20000; ++k) {
    const auto a = random_value<fixed<64, 32>>(rng);
    const auto b = random_value<fixed<64, 10>>(rng);
    const auto p = a * b;  // fixed<128, 42>
    const i128 want = static_cast<i128>(a.raw()) * static_cast<i128>(b.raw());
    expect_raw(st, "*", a.raw(), b.raw(), p.raw(), want);
    const fixed<40, 20, RND_CONV, SAT> n = p;
    expect_raw(st, "narrow", a.raw(), b.raw(), n.raw(),
               reference_convert(want, 86, {40, 20, true}, RND_CONV, SAT));
    const fixed<64, 42, RND, WRAP> m = p;
    expect_raw(st, "narrow64", a.raw(), b.raw(), m.raw(),
               reference_convert(want, 86, {64, 42, true}, RND, WRAP));
    ++st.comparisons;
    if (p.to_double() != reference_to_double(want, 86) && ++st.failures <= 20) {
      ADD_FAILURE() << "to_double of " << to_string128(want);
    }
    expect_raw(st, "cmp", a.raw(), b.raw(), p < a, reference_compare({128, 42, true}, want, {64, 32, true}, a.raw()) < 0);
  }
  EXPECT_EQ(st.failures, 0U) << "of " << st.comparisons;
}

}  // namespace
