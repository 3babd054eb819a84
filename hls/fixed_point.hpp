// voxcast::hls fixed-point and arbitrary-width integer types: a bit-exact clone of the C
// simulation behaviour of AMD's ap_fixed / ap_ufixed / ap_int / ap_uint.
//
// The authoritative specification is /work/shared/fixed-point-semantics.md ("semantics" below,
// cited by section); docs/fixed-point.md describes the mapping, the supported subset and the
// places where the clone deliberately differs from ap's simulation bugs. Kernels include
// hls/types.hpp, which selects either this header or the vendor headers.
//
// Representation: a fixed_base<W, I, S, Q, O, N> stores its W-bit pattern V in one int64/uint64
// (W <= 64) or __int128/unsigned __int128 (W <= 128), always in canonical form (sign-extended
// for signed, zero-extended for unsigned), so that raw() is the mathematical integer V and the
// value is V * 2^-(W-I). Quantization and overflow are integer shifts and masks chosen at compile
// time; nothing loops over bits and nothing goes through double except the conversions to and
// from double themselves.
//
// Limits: 1 <= W <= 128 for every type, including the result types of the binary operators
// (a 64 x 64-bit product is 128 bits; a 128-bit operand can only take part in operations whose
// result stays within 128 bits). No heap, no exceptions, no virtual functions.
//
// Language level: C++14, as the vendor front ends read it (UG1399); the header is included by
// synthesizable tops. It compiles unchanged as C++17/20 (the rest of voxcast), with the same
// overloads and results. Where newer features would have been natural:
//  - constraints are std::enable_if_t on the traits ap_type, fixed_type, operands, ...
//    (structs of the same names), so overload resolution sees the same candidates;
//  - compile-time branches that must not be instantiated together (different result types,
//    shift counts that are out of range in the branch not taken) are overloads picked by a tag
//    (bool_c / int_c / a small struct); the others are plain `if`s on constants;
//  - the bits of a double come from __builtin_bit_cast (constexpr in GCC >= 11 and clang >= 9;
//    a front end without it gets memcpy, and conversions from double are then not constant
//    expressions); leading zeros come from __builtin_clzll;
//  - static constexpr data members are defined at namespace scope as well before C++17.
// Printing (to_string, operator<<, <string>, <ostream>) is host-only: absent under __SYNTHESIS__.
#pragma once

#include <cstdint>
#include <type_traits>

#ifndef __SYNTHESIS__
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ostream>
#include <string>
#endif

#if defined(__has_builtin)
#if __has_builtin(__builtin_bit_cast)
#define VOXCAST_HLS_HAS_BIT_CAST 1
#endif
#endif
#ifndef VOXCAST_HLS_HAS_BIT_CAST
#include <cstring>
#endif

namespace voxcast {
namespace hls {

// Semantics section 1: same enumerators, same order as ap_q_mode / ap_o_mode.
enum q_mode { RND, RND_ZERO, RND_MIN_INF, RND_INF, RND_CONV, TRN, TRN_ZERO };
enum o_mode { SAT, SAT_ZERO, SAT_SYM, WRAP, WRAP_SM };

// The widest type (stored or produced by an operator) the clone represents: one __int128.
constexpr int max_width = 128;

template <int W, int I, bool S, q_mode Q = TRN, o_mode O = WRAP, int N = 0>
class fixed_base;
template <int W, bool S>
class int_base;

// ap_fixed<W, I, Q, O, N> / ap_ufixed<...> / ap_int<W> / ap_uint<W>.
template <int W, int I, q_mode Q = TRN, o_mode O = WRAP, int N = 0>
using fixed = fixed_base<W, I, true, Q, O, N>;
template <int W, int I, q_mode Q = TRN, o_mode O = WRAP, int N = 0>
using ufixed = fixed_base<W, I, false, Q, O, N>;
template <int W>
using int_t = int_base<W, true>;
template <int W>
using uint_t = int_base<W, false>;

namespace detail {

__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;

constexpr int imax(int a, int b) { return a > b ? a : b; }
constexpr int imin(int a, int b) { return a < b ? a : b; }

// Compile-time branch tags: overloads taking bool_c<true> / bool_c<false> (or int_c<k>) are the
// branches of a decision known at compile time; only the one taken is instantiated. (Not
// std::integral_constant: a std tag would bring namespace std into argument-dependent lookup,
// where std::equal and std::shift_left would compete with the functions below.)
template <bool B>
struct bool_c {
  static constexpr bool value = B;
};
template <int K>
struct int_c {};

// The enable_if_t of a constrained template:
// `template <class T, enable_if_c<trait<T>::value> = 0>`.
template <bool B>
using enable_if_c = std::enable_if_t<B, int>;

template <class T>
using remove_cvref_t = std::remove_cv_t<std::remove_reference_t<T>>;

// Tag of the internal constructor that stores an already canonical raw value.
struct exact_tag {};

// Working words: unsigned, arithmetic modulo 2^B, reinterpreted as signed where needed.
template <int W>
using word_t = std::conditional_t<(W <= 64), std::uint64_t, u128>;
template <class U>
using sword_t = std::conditional_t<(sizeof(U) == 8), std::int64_t, i128>;
template <class U>
constexpr int word_bits() noexcept {
  return static_cast<int>(sizeof(U) * 8);
}
template <int W, bool S>
using raw_t = std::conditional_t<(W <= 64), std::conditional_t<S, std::int64_t, std::uint64_t>,
                                 std::conditional_t<S, i128, u128>>;
// Storage of V: the narrowest C++ integer of W bits or more. Canonical V fits it, and widening
// it back to raw_t (sign- or zero-extension) gives raw() exactly; arithmetic stays in raw_t.
// The narrow word is what makes a table of fixed-point entries (a classification entry, a
// reflectance-map cell, a voxel bank) as small as its bits: eight 64-bit words per 8-byte
// entry would fill the caches the software engines run from.
template <int B, bool S>
using sized_int_t = std::conditional_t<
    (B == 8), std::conditional_t<S, std::int8_t, std::uint8_t>,
    std::conditional_t<(B == 16), std::conditional_t<S, std::int16_t, std::uint16_t>,
                       std::conditional_t<S, std::int32_t, std::uint32_t>>>;
template <int W, bool S>
using store_t = std::conditional_t<
    (W <= 8), sized_int_t<8, S>,
    std::conditional_t<(W <= 16), sized_int_t<16, S>,
                       std::conditional_t<(W <= 32), sized_int_t<32, S>, raw_t<W, S>>>>;

// Mask of the low n bits (n <= 0 gives 0, n >= word size gives all ones).
template <class U>
constexpr U low_mask(int n) noexcept {
  if (n <= 0) return U(0);
  if (n >= word_bits<U>()) return ~U(0);
  return (U(1) << n) - U(1);
}

// Bit k of the infinite two's-complement extension of (bits, neg).
template <class U>
constexpr bool bit_of(U bits, bool neg, int k) noexcept {
  if (k < 0) return false;
  if (k >= word_bits<U>()) return neg;
  return ((bits >> k) & U(1)) != 0;
}

// x << K for a compile-time K; 0 once K reaches the word size (where C++'s shift is undefined).
template <int K, class U>
constexpr U shift_left(U x, bool_c<true> /* K < word size */) noexcept {
  return static_cast<U>(x << K);
}
template <int K, class U>
constexpr U shift_left(U, bool_c<false> /* K >= word size */) noexcept {
  return U(0);
}
template <int K, class U>
constexpr U shift_left(U x) noexcept {
  return shift_left<K>(x, bool_c<(K < word_bits<U>())>{});
}

// Leading zeros of a whole word (64 resp. 128 for 0).
constexpr int count_leading_zeros(std::uint64_t x) noexcept {
  return x == 0 ? 64 : __builtin_clzll(x);
}
constexpr int count_leading_zeros(u128 x) noexcept {
  const auto hi = static_cast<std::uint64_t>(x >> 64);
  const auto lo = static_cast<std::uint64_t>(x);
  return hi != 0 ? count_leading_zeros(hi) : 64 + count_leading_zeros(lo);
}

// v < 0 for a signed raw value; an unsigned one is never negative (and is not compared).
template <class R>
constexpr bool negative(R v, bool_c<true> /* signed */) noexcept {
  return v < 0;
}
template <class R>
constexpr bool negative(R, bool_c<false> /* unsigned */) noexcept {
  return false;
}

// Canonical form: the low W bits sign-extended (S) or zero-extended (!S) to the whole word.
struct whole_word {};
struct sign_fill {};
struct zero_fill {};
template <int W, class U>
constexpr U extend_as(U x, whole_word) noexcept {
  return x;
}
template <int W, class U>
constexpr U extend_as(U x, sign_fill) noexcept {
  constexpr int B = word_bits<U>();
  return static_cast<U>(static_cast<sword_t<U>>(x << (B - W)) >> (B - W));
}
template <int W, class U>
constexpr U extend_as(U x, zero_fill) noexcept {
  return x & low_mask<U>(W);
}
template <int W, bool S, class U>
constexpr U extend(U x) noexcept {
  using how = std::conditional_t<(W >= word_bits<U>()), whole_word,
                                 std::conditional_t<S, sign_fill, zero_fill>>;
  return extend_as<W>(x, how{});
}

// A value as a word plus its sign: value = neg ? bits - 2^B : bits. A negative value always has
// the top word bit set (it comes from a signed source of at most B bits), a non-negative one
// may use all B bits (an unsigned source of B bits): together they cover B+1-bit integers.
template <class U>
struct wide {
  U bits;
  bool neg;
};

template <class U, bool S, class R>
constexpr wide<U> widen(R raw) noexcept {
  const U bits = static_cast<U>(raw);  // sign-extends signed raws, zero-extends unsigned ones
  if (S) return {bits, static_cast<sword_t<U>>(bits) < 0};
  return {bits, false};
}

// Sets bits [lo, hi] of x to 1 (set) or 0 (!set).
template <class U>
constexpr U assign_bits(U x, int lo, int hi, bool set) noexcept {
  if (hi < lo) return x;
  const U m = low_mask<U>(hi - lo + 1) << lo;
  return set ? (x | m) : (x & ~m);
}

// Semantics sections 2 and 3: converting the exact value (bits, neg) * 2^-fs into the W-bit
// pattern of fixed_base<Wt, It, St, Q, O, N> is one quantization (from the unrounded source's
// floor, first dropped bit, sticky bit and sign) followed by one overflow step on the rounded
// value. The steps are separate functions so that a conversion whose shift is known at compile
// time instantiates only the branch it needs; the double conversion dispatches at run time.

// The rounded value in target LSB units: its low word bits t, its sign, whether it lies above
// MAX or below MIN, and (WRAP_SM, N = 0) bit Wt of the aligned unrounded source.
template <class U>
struct rounded {
  U t;
  bool neg;
  bool ovf;
  bool unf;
  bool ld;
};

template <int Wt, bool St, class U>
struct target_bounds {
  static constexpr U max_t = St ? low_mask<U>(Wt - 1) : low_mask<U>(Wt);  // MAX in LSB units
  static constexpr U min_t = St ? ~max_t : U(0);                           // MIN pattern
};

// Overflow flags of a rounded value that is exact in the word (t, neg).
template <int Wt, bool St, o_mode O, int N, class U>
constexpr void detect_range(rounded<U>& r) noexcept {
  using SU = sword_t<U>;
  using TB = target_bounds<Wt, St, U>;
  if (!(O == WRAP && N == 0)) {  // section 3: plain WRAP never looks
    if (r.neg) {
      r.unf = !St || static_cast<SU>(r.t) < static_cast<SU>(TB::min_t);
    } else {
      r.ovf = r.t > TB::max_t;
    }
  }
}

// d >= 1 source bits drop below the target LSB: section 2.
template <int Wt, bool St, q_mode Q, o_mode O, int N, class U>
constexpr rounded<U> round_down(U bits, bool neg, int d) noexcept {
  static_assert(Q == RND || Q == RND_ZERO || Q == RND_MIN_INF || Q == RND_INF || Q == RND_CONV ||
                    Q == TRN || Q == TRN_ZERO,
                "voxcast::hls: unknown q_mode");
  using SU = sword_t<U>;
  constexpr int B = word_bits<U>();
  rounded<U> r{0, neg, false, false, false};
  bool qb = false;  // first dropped bit
  bool rb = false;  // OR of the dropped bits below qb (sticky)
  if (d > B) {
    r.t = neg ? ~U(0) : U(0);
    qb = neg;
    rb = bits != 0;
  } else {
    r.t = (d == B) ? (neg ? ~U(0) : U(0))
                   : (neg ? static_cast<U>(static_cast<SU>(bits) >> d) : bits >> d);  // floor
    qb = ((bits >> (d - 1)) & U(1)) != 0;
    rb = (bits & low_mask<U>(d - 1)) != 0;
  }
  // The table of section 2; s is the sign of the source.
  bool inc = false;
  if (Q == TRN) {
    inc = false;
  } else if (Q == TRN_ZERO) {
    inc = neg && (qb || rb);
  } else if (Q == RND) {
    inc = qb;
  } else if (Q == RND_ZERO) {
    inc = qb && (neg || rb);
  } else if (Q == RND_MIN_INF) {
    inc = qb && rb;
  } else if (Q == RND_INF) {
    inc = qb && (!neg || rb);
  } else {  // RND_CONV
    inc = qb && ((r.t & U(1)) != 0 || rb);
  }
  if (O == WRAP_SM && N == 0) r.ld = bit_of<U>(r.t, neg, Wt);
  // The carry can move -1 LSB to 0; it never leaves the word because a floor shift by d >= 1
  // halves the magnitude.
  r.t += static_cast<U>(inc);
  r.neg = neg && r.t != 0;
  detect_range<Wt, St, O, N>(r);
  return r;
}

// Same LSB: the value is already exact.
template <int Wt, bool St, o_mode O, int N, class U>
constexpr rounded<U> keep(U bits, bool neg) noexcept {
  rounded<U> r{bits, neg, false, false, false};
  if (O == WRAP_SM && N == 0) r.ld = bit_of<U>(bits, neg, Wt);
  detect_range<Wt, St, O, N>(r);
  return r;
}

// e >= 1: the exact value times 2^e, no quantization. Overflow is decided on the unshifted
// source against the bounds shifted down, so nothing wider than the word is ever formed.
template <int Wt, bool St, o_mode O, int N, class U>
constexpr rounded<U> shift_up(U bits, bool neg, int e) noexcept {
  using SU = sword_t<U>;
  using TB = target_bounds<Wt, St, U>;
  constexpr int B = word_bits<U>();
  rounded<U> r{e >= B ? U(0) : U(bits << e), neg, false, false, false};
  if (!(O == WRAP && N == 0)) {
    if (neg) {
      r.unf = !St || e >= Wt || static_cast<SU>(bits) < (static_cast<SU>(TB::min_t) >> e);
    } else {
      r.ovf = bits > (e >= B ? U(0) : U(TB::max_t >> e));
    }
  }
  if (O == WRAP_SM && N == 0) r.ld = bit_of<U>(bits, neg, Wt - e);
  return r;
}

// Section 3: overflow handling on the rounded value; returns the low word bits (the caller
// extends them to Wt bits). One overload per mode (the tag is the mode).
template <o_mode O>
struct o_mode_c {};

template <int Wt, bool St, int N, class U>
constexpr U handle_overflow(const rounded<U>& r, o_mode_c<SAT>) noexcept {
  using TB = target_bounds<Wt, St, U>;
  return r.ovf ? TB::max_t : (r.unf ? TB::min_t : r.t);
}
template <int Wt, bool St, int N, class U>
constexpr U handle_overflow(const rounded<U>& r, o_mode_c<SAT_ZERO>) noexcept {
  return (r.ovf || r.unf) ? U(0) : r.t;
}
template <int Wt, bool St, int N, class U>
constexpr U handle_overflow(const rounded<U>& r, o_mode_c<SAT_SYM>) noexcept {
  using SU = sword_t<U>;
  using TB = target_bounds<Wt, St, U>;
  // -MAX is built as MIN | 1, as in ap (which makes W = 1 give -1 = MIN). A signed result
  // equal to MIN becomes -MAX too, except for W = 1 where the range is {-1, 0}.
  if (r.ovf) return TB::max_t;
  if (r.unf) return St ? U(TB::min_t | U(1)) : U(0);
  if (St && Wt > 1) {
    if (r.neg && static_cast<SU>(r.t) == static_cast<SU>(TB::min_t)) return TB::min_t | U(1);
  }
  return r.t;
}
template <int Wt, bool St, int N, class U>
constexpr U handle_overflow(const rounded<U>& r, o_mode_c<WRAP>) noexcept {
  if (N == 0) return r.t;
  // N > 0: saturate the top N bits. Unsigned sets them on underflow as well.
  if (!(r.ovf || r.unf)) return r.t;
  if (St) {
    U v = assign_bits<U>(r.t, Wt - 1, Wt - 1, r.neg);
    if (N > 1) v = assign_bits<U>(v, Wt - N, Wt - 2, !r.neg);
    return v;
  }
  return assign_bits<U>(r.t, Wt - N, Wt - 1, true);
}

// WRAP_SM (signed only): the wrapped bits, sign-magnitude style; one overload per N = 0, 1, > 1.
template <int Wt, int N, class U>
constexpr U wrap_sign_magnitude(U v, const rounded<U>& r, bool ro, int_c<0> /* N = 0 */) noexcept {
  if (r.ld != ro) v = assign_bits<U>(~v, Wt - 1, Wt - 1, r.ld);
  return v;
}
template <int Wt, int N, class U>
constexpr U wrap_sign_magnitude(U v, const rounded<U>& r, bool ro, int_c<1> /* N = 1 */) noexcept {
  if (r.neg != ro) v = ~v;
  return assign_bits<U>(v, Wt - 1, Wt - 1, r.neg);
}
template <int Wt, int N, class U>
constexpr U wrap_sign_magnitude(U v, const rounded<U>& r, bool, int_c<2> /* N > 1 */) noexcept {
  if ((((v >> (Wt - N)) & U(1)) != 0) == r.neg) v = ~v;
  v = assign_bits<U>(v, Wt - N, Wt - 2, !r.neg);
  return assign_bits<U>(v, Wt - 1, Wt - 1, r.neg);
}
template <int Wt, bool St, int N, class U>
constexpr U handle_overflow(const rounded<U>& r, o_mode_c<WRAP_SM>) noexcept {
  static_assert(St, "WRAP_SM is signed only");
  if (!(r.ovf || r.unf)) return r.t;
  const U v = r.t;
  const bool ro = ((v >> (Wt - 1)) & U(1)) != 0;
  return wrap_sign_magnitude<Wt, N>(v, r, ro, int_c<(N > 1 ? 2 : N)>{});
}

template <int Wt, bool St, o_mode O, int N, class U>
constexpr U handle_overflow(const rounded<U>& r) noexcept {
  static_assert(O == SAT || O == SAT_ZERO || O == SAT_SYM || O == WRAP || O == WRAP_SM,
                "voxcast::hls: unknown o_mode");
  return handle_overflow<Wt, St, N>(r, o_mode_c<O>{});
}

// Fixed and integer sources: D = source fraction bits - target fraction bits, known at
// compile time; the tag is its sign.
template <int Wt, bool St, q_mode Q, o_mode O, int N, int D, class U>
constexpr rounded<U> rescale(U bits, bool neg, int_c<1> /* D > 0 */) noexcept {
  return round_down<Wt, St, Q, O, N>(bits, neg, D);
}
template <int Wt, bool St, q_mode Q, o_mode O, int N, int D, class U>
constexpr rounded<U> rescale(U bits, bool neg, int_c<0> /* D == 0 */) noexcept {
  return keep<Wt, St, O, N>(bits, neg);
}
template <int Wt, bool St, q_mode Q, o_mode O, int N, int D, class U>
constexpr rounded<U> rescale(U bits, bool neg, int_c<-1> /* D < 0 */) noexcept {
  return shift_up<Wt, St, O, N>(bits, neg, -D);
}
template <int Wt, bool St, q_mode Q, o_mode O, int N, int D, class U>
constexpr U quantize(U bits, bool neg) noexcept {
  static_assert(Wt <= word_bits<U>(), "working word narrower than the target");
  return handle_overflow<Wt, St, O, N>(
      rescale<Wt, St, Q, O, N, D>(bits, neg, int_c<(D > 0 ? 1 : (D == 0 ? 0 : -1))>{}));
}

// Double sources: the shift depends on the exponent.
template <int Wt, bool St, q_mode Q, o_mode O, int N, class U>
constexpr U quantize(U bits, bool neg, int d) noexcept {
  if (d > 0) return handle_overflow<Wt, St, O, N>(round_down<Wt, St, Q, O, N>(bits, neg, d));
  if (d == 0) return handle_overflow<Wt, St, O, N>(keep<Wt, St, O, N>(bits, neg));
  return handle_overflow<Wt, St, O, N>(shift_up<Wt, St, O, N>(bits, neg, -d));
}

// Exact decode of a double (section 9): value = (neg ? -m : m) * 2^-fs with m < 2^53.
// NaN and infinities decode as +-1.mant * 2^1024, which is what makes them saturate / wrap to 0.
struct double_parts {
  std::int64_t m;  // signed mantissa
  int fs;          // fraction bits: value = m * 2^-fs
};
#ifdef VOXCAST_HLS_HAS_BIT_CAST
constexpr std::uint64_t double_bits(double x) noexcept {
  return __builtin_bit_cast(std::uint64_t, x);
}
#define VOXCAST_HLS_DECODE_CONSTEXPR constexpr
#else
inline std::uint64_t double_bits(double x) noexcept {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}
#define VOXCAST_HLS_DECODE_CONSTEXPR
#endif
VOXCAST_HLS_DECODE_CONSTEXPR inline double_parts decode(double x) noexcept {
  const auto b = double_bits(x);
  const bool sign = (b >> 63) != 0;
  const int ex = static_cast<int>((b >> 52) & 0x7ffU);
  std::uint64_t mant = b & ((std::uint64_t{1} << 52) - 1);
  int e = -1074;  // denormals and zero
  if (ex != 0) {
    mant |= std::uint64_t{1} << 52;
    e = ex - 1075;
  }
  const auto m = static_cast<std::int64_t>(mant);
  return {sign ? -m : m, -e};
}
#undef VOXCAST_HLS_DECODE_CONSTEXPR

// x * 2^E for a compile-time E, exact whenever the result is a normal double.
constexpr double pow2(int e) noexcept {
  double r = 1.0;
  for (; e > 0; --e) r *= 2.0;
  for (; e < 0; ++e) r *= 0.5;
  return r;
}
template <int E>
constexpr double scale(double x, bool_c<true> /* 2^E is a normal double */) noexcept {
  constexpr double s = pow2(E);
  return x * s;
}
template <int E>
constexpr double scale(double x, bool_c<false>) noexcept {
  // Outside the normal exponent range (ap returns garbage here, section 9): two exact steps,
  // so the result only rounds (a second time) if it is subnormal.
  constexpr int e1 = E / 2;
  constexpr double s1 = pow2(e1);
  constexpr double s2 = pow2(E - e1);
  return (x * s1) * s2;
}
template <int E>
constexpr double scale(double x) noexcept {
  return scale<E>(x, bool_c<(E >= -1022 && E <= 1023)>{});
}

// Section 9: the integer toward zero of raw * 2^-F, as the low bits of word U (wrapping).
// F <= 0: the value is an integer; its bits move up by -F.
template <class U, int F, bool S, class RU, class R>
constexpr U trunc_toward_zero(R raw, int_c<0> /* F <= 0 */) noexcept {
  return shift_left<-F>(static_cast<U>(raw));
}
template <class U, int F, bool S, class RU, class R>
constexpr U trunc_toward_zero(R, int_c<1> /* F >= raw word size */) noexcept {
  return U(0);  // |value| < 1: a negative value floors to -1 and the carry brings it to 0
}
template <class U, int F, bool S, class RU, class R>
constexpr U trunc_toward_zero(R raw, int_c<2> /* 0 < F < raw word size */) noexcept {
  using RS = sword_t<RU>;
  const RU bits = static_cast<RU>(raw);
  if (S) {
    const RS v = static_cast<RS>(bits);
    RS q = v >> F;                                         // floor
    if (v < 0 && (bits & low_mask<RU>(F)) != 0) q += 1;  // C rounds toward zero
    return static_cast<U>(q);
  }
  return static_cast<U>(bits >> F);
}
template <class U, int F, bool S, class R>
constexpr U trunc_toward_zero(R raw) noexcept {
  using RU = word_t<(sizeof(R) > 8 ? 128 : 64)>;
  return trunc_toward_zero<U, F, S, RU>(
      raw, int_c<(F <= 0 ? 0 : (F >= word_bits<RU>() ? 1 : 2))>{});
}

// ---- Operand traits: every operand of a binary operator is viewed as <w, i, s> --------------
// Section 5: C integers are ap_[u]fixed<w, w> with w = 1/8/16/32/64; ap_[u]int<W> is <W, W>.
template <class T, class Enable = void>
struct operand {
  static constexpr bool valid = false, is_ap = false, is_fixed = false;
};
template <int W, int I, bool S, q_mode Q, o_mode O, int N>
struct operand<fixed_base<W, I, S, Q, O, N>> {
  static constexpr bool valid = true, is_ap = true, is_fixed = true, s = S;
  static constexpr int w = W, i = I;
  static constexpr auto raw(const fixed_base<W, I, S, Q, O, N>& x) noexcept { return x.raw(); }
};
template <int W, bool S>
struct operand<int_base<W, S>> {
  static constexpr bool valid = true, is_ap = true, is_fixed = false, s = S;
  static constexpr int w = W, i = W;
  static constexpr auto raw(const int_base<W, S>& x) noexcept { return x.raw(); }
};
template <class T>
struct operand<T, std::enable_if_t<std::is_integral<T>::value>> {
  static constexpr bool valid = true, is_ap = false, is_fixed = false;
  static constexpr bool s = std::is_signed<T>::value;
  static constexpr int w = std::is_same<T, bool>::value ? 1 : static_cast<int>(sizeof(T) * 8);
  static constexpr int i = w;
  static constexpr T raw(T x) noexcept { return x; }
};

// The constraints of the operators below, as traits (::value).
template <class T>
struct ap_type
    : bool_c<operand<remove_cvref_t<T>>::valid && operand<remove_cvref_t<T>>::is_ap> {};
template <class T>
struct fixed_type : bool_c<ap_type<T>::value && operand<remove_cvref_t<T>>::is_fixed> {};
template <class T>
struct int_type : bool_c<ap_type<T>::value && !operand<remove_cvref_t<T>>::is_fixed> {};
// A binary operator applies when both operands are fixed/int/C-integer and one is ours:
// a double operand never matches, so "a + 0.5" is ill-formed as with ap (section 5).
template <class A, class B>
struct operands : bool_c<operand<remove_cvref_t<A>>::valid && operand<remove_cvref_t<B>>::valid &&
                         (ap_type<A>::value || ap_type<B>::value)> {};
// The right operand of a compound assignment or a shift.
template <class T>
struct shift_operand : bool_c<operand<remove_cvref_t<T>>::valid> {};
template <class T>
struct assign_operand : bool_c<operand<remove_cvref_t<T>>::valid> {};

// Section 5: result types. Integer-only expressions give ap_[u]int (section 12), anything with
// a fixed operand gives ap_[u]fixed with default Q/O.
template <class A, class B>
struct rtype {
  using TA = operand<remove_cvref_t<A>>;
  using TB = operand<remove_cvref_t<B>>;
  static constexpr int w1 = TA::w, i1 = TA::i, f1 = w1 - i1;
  static constexpr int w2 = TB::w, i2 = TB::i, f2 = w2 - i2;
  static constexpr bool s1 = TA::s, s2 = TB::s;
  // An unsigned operand mixed with a signed one gets one extra integer bit.
  static constexpr int ia = i1 + ((s2 && !s1) ? 1 : 0), ib = i2 + ((s1 && !s2) ? 1 : 0);
  static constexpr int fm = imax(f1, f2), im = imax(ia, ib);
  static constexpr bool any_fixed = TA::is_fixed || TB::is_fixed;
  template <int W, int I, bool S>
  using make = std::conditional_t<any_fixed, fixed_base<W, I, S>, int_base<W, S>>;

  using plus = make<im + 1 + fm, im + 1, s1 || s2>;
  using minus = make<im + 1 + fm, im + 1, true>;  // ufixed - ufixed is signed
  using mult = make<w1 + w2, i1 + i2, s1 || s2>;
  using div = make<w1 + imax(f2, 0) + (s2 ? 1 : 0), i1 + f2 + (s2 ? 1 : 0), s1 || s2>;
  using logic = make<im + fm, im, s1 || s2>;
  // Section 12: ap_int % keeps the dividend's sign.
  using mod = int_base<imin(w1, w2 + ((!s2 && s1) ? 1 : 0)), s1>;
};

template <class T>
constexpr auto raw_of(const T& x) noexcept {
  return operand<remove_cvref_t<T>>::raw(x);
}

// The operand's pattern, sign/zero-extended to word U and moved up by Shift bits.
template <class U, int Shift, class T>
constexpr U aligned(const T& x) noexcept {
  return shift_left<Shift>(static_cast<U>(raw_of(x)));
}

// Results of the operators below are exact in their result type (section 5), so the word
// pattern is already the canonical one and is stored as is.
template <class R, class U>
constexpr R make_exact(U pattern) noexcept {
  return R(exact_tag{}, static_cast<typename R::raw_type>(pattern));
}

// Sections 4-6: the binary operators are exact in their widened result type (division
// truncates toward zero); no quantization or overflow handling happens here. binary<Op>
// picks the overload of Op's group (the groups have different result types).
enum class op { add, sub, mul, div, band, bor, bxor, mod };
struct additive {};
struct multiplicative {};
struct bitwise {};
struct divisive {};
template <op Op>
using op_group = std::conditional_t<
    Op == op::add || Op == op::sub, additive,
    std::conditional_t<Op == op::mul, multiplicative,
                       std::conditional_t<Op == op::band || Op == op::bor || Op == op::bxor,
                                          bitwise, divisive>>>;

template <op Op, class A, class B>
constexpr auto binary(const A& a, const B& b, additive) noexcept {
  using RT = rtype<A, B>;
  using R = std::conditional_t<Op == op::add, typename RT::plus, typename RT::minus>;
  using U = word_t<R::width>;
  const U x = aligned<U, RT::fm - RT::f1>(a);
  const U y = aligned<U, RT::fm - RT::f2>(b);
  return make_exact<R>(Op == op::add ? U(x + y) : U(x - y));
}
template <op Op, class A, class B>
constexpr auto binary(const A& a, const B& b, multiplicative) noexcept {
  using R = typename rtype<A, B>::mult;
  using U = word_t<R::width>;
  return make_exact<R>(U(static_cast<U>(raw_of(a)) * static_cast<U>(raw_of(b))));
}
template <op Op, class A, class B>
constexpr auto binary(const A& a, const B& b, bitwise) noexcept {
  using RT = rtype<A, B>;
  using R = typename RT::logic;
  using U = word_t<R::width>;
  const U x = aligned<U, RT::fm - RT::f1>(a);
  const U y = aligned<U, RT::fm - RT::f2>(b);
  const U z = Op == op::band ? U(x & y) : (Op == op::bor ? U(x | y) : U(x ^ y));
  return R::from_raw(static_cast<typename R::raw_type>(extend<R::width, R::is_signed>(z)));
}
template <op Op, class A, class B>
constexpr auto binary(const A& a, const B& b, divisive) noexcept {
  // Section 6: (a.V << max(F2, 0)) / b.V, C integer division (toward zero). Computed on
  // magnitudes, so MIN / -1 LSB gives the mathematically correct value (ap sim wraps).
  using RT = rtype<A, B>;
  using R = std::conditional_t<Op == op::div, typename RT::div, typename RT::mod>;
  using U = word_t<imax(imax(RT::w1, RT::w2), R::width) + 1>;
  constexpr int sh = Op == op::div ? imax(RT::f2, 0) : 0;
  const wide<U> n = widen<U, RT::s1>(raw_of(a));
  const wide<U> dv = widen<U, RT::s2>(raw_of(b));
  const U nm = (n.neg ? U(U(0) - n.bits) : n.bits) << sh;
  const U dm = dv.neg ? U(U(0) - dv.bits) : dv.bits;
  if (Op == op::div) {
    const U q = nm / dm;
    return make_exact<R>((n.neg != dv.neg) ? U(U(0) - q) : q);
  }
  const U rm = nm % dm;
  return R::from_raw(static_cast<typename R::raw_type>(
      extend<R::width, R::is_signed>(n.neg ? U(U(0) - rm) : rm)));
}
template <op Op, class A, class B>
constexpr auto binary(const A& a, const B& b) noexcept {
  return binary<Op>(a, b, op_group<Op>{});
}

// ---- Comparisons (section 8) ----------------------------------------------------------------

// Compares floor(x / 2^d) (and the dropped remainder) with y; x and y have the same sign.
template <class U>
constexpr int cmp_shifted(wide<U> x, int d, wide<U> y) noexcept {
  using SU = sword_t<U>;
  U fx = x.bits;
  bool rem = false;
  if (d >= word_bits<U>()) {
    fx = x.neg ? ~U(0) : U(0);
    rem = x.bits != 0;
  } else if (d > 0) {
    fx = x.neg ? static_cast<U>(static_cast<SU>(x.bits) >> d) : x.bits >> d;
    rem = (x.bits & low_mask<U>(d)) != 0;
  }
  if (fx != y.bits) {
    const bool less = x.neg ? static_cast<SU>(fx) < static_cast<SU>(y.bits) : fx < y.bits;
    return less ? -1 : 1;
  }
  return rem ? 1 : 0;
}

// Exact three-way comparison of x * 2^-fx and y * 2^-fy.
template <class U>
constexpr int cmp_exact(wide<U> x, int fx, wide<U> y, int fy) noexcept {
  if (x.neg != y.neg) return x.neg ? -1 : 1;
  return fx >= fy ? cmp_shifted(x, fx - fy, y) : -cmp_shifted(y, fy - fx, x);
}

template <class A, class B>
struct cmp_rule {
  using RT = rtype<A, B>;
  // Section 8: the operand with fewer fraction bits is widened; the left one gets an extra bit.
  static constexpr int wa = RT::f1 < RT::f2 ? RT::w1 + RT::f2 - RT::f1 + 1 : RT::w1;
  static constexpr int wb = RT::f1 > RT::f2 ? RT::w2 + RT::f1 - RT::f2 : RT::w2;
  static constexpr bool mixed = RT::s1 != RT::s2;
  static constexpr int ws = RT::s1 ? wa : wb;
  static constexpr int wu = RT::s1 ? wb : wa;
  // < <= > >=: C's usual arithmetic conversions make the comparison unsigned.
  static constexpr bool rel_unsigned = mixed && !(ws < 32 && wu < 32) && wu >= ws;
  // == !=: the signed operand is compared modulo 2^wu.
  static constexpr bool eq_modular = mixed && wu >= 32 && (wu > ws || (wu == ws && wu >= 64));
  using U = word_t<imax(RT::w1, RT::w2)>;
};

// Both operands aligned to the finer LSB fit one signed 64-bit word when their exact
// difference does (the width of a - b): then the exact comparison is one comparison of the
// aligned patterns, as a - b would compute it (section 5), without the general path's sign and
// remainder cases. Not for the unsigned rules of mixed signedness (rel_unsigned, eq_modular).
template <class A, class B>
struct cmp_in_word : bool_c<(rtype<A, B>::im + 1 + rtype<A, B>::fm <= 64)> {};
template <class A, class B>
constexpr std::int64_t aligned_word(const A& a) noexcept {
  using RT = rtype<A, B>;
  return static_cast<std::int64_t>(aligned<std::uint64_t, RT::fm - RT::f1>(a));
}
template <class A, class B>
constexpr std::int64_t aligned_word_right(const B& b) noexcept {
  using RT = rtype<A, B>;
  return static_cast<std::int64_t>(aligned<std::uint64_t, RT::fm - RT::f2>(b));
}

template <class A, class B>
constexpr int compare_as_is(const A& a, const B& b, bool_c<true> /* in one word */) noexcept {
  const std::int64_t x = aligned_word<A, B>(a);
  const std::int64_t y = aligned_word_right<A, B>(b);
  return (x > y) - (x < y);
}
template <class A, class B>
constexpr int compare_as_is(const A& a, const B& b, bool_c<false>) noexcept {
  using C = cmp_rule<A, B>;
  using U = typename C::U;
  const wide<U> x = widen<U, C::RT::s1>(raw_of(a));
  const wide<U> y = widen<U, C::RT::s2>(raw_of(b));
  if (C::rel_unsigned) {
    // Converted to unsigned, a negative signed operand exceeds every unsigned value.
    if (x.neg) return 1;
    if (y.neg) return -1;
  }
  return cmp_exact(x, C::RT::f1, y, C::RT::f2);
}
template <class A, class B>
struct cmp_fast : bool_c<!cmp_rule<A, B>::rel_unsigned && cmp_in_word<A, B>::value> {};
template <class A, class B>
constexpr int compare_as_is(const A& a, const B& b) noexcept {
  return compare_as_is(a, b, cmp_fast<A, B>{});
}

// (s mod 2^wu) == u on the aligned patterns, for a negative signed s (section 8). The signed
// pattern moves up by ds (u fixed), or the unsigned one moves up by du (s fixed); the tag
// says which, and whether the shift leaves the 128-bit word.
template <int Ds, int Du, int WuAligned>
constexpr bool modular_equal(i128, u128 u, int_c<0> /* du == 0, ds >= wu */) noexcept {
  return u == 0;
}
template <int Ds, int Du, int WuAligned>
constexpr bool modular_equal(i128 s, u128 u, int_c<1> /* du == 0, ds < wu */) noexcept {
  const auto sp = static_cast<u128>(s);
  constexpr int k = WuAligned - Ds;
  return (u & low_mask<u128>(Ds)) == 0 && (u >> Ds) == (sp & low_mask<u128>(k));
}
template <int Ds, int Du, int WuAligned>
constexpr bool modular_equal(i128, u128, int_c<2> /* du >= 128 */) noexcept {
  return false;  // a negative s has a non-zero bit below 2^128
}
template <int Ds, int Du, int WuAligned>
constexpr bool modular_equal(i128 s, u128 u, int_c<3> /* 0 < du < 128 */) noexcept {
  const auto sp = static_cast<u128>(s);
  constexpr int k = WuAligned - Du;
  if ((sp & low_mask<u128>(Du)) != 0) return false;
  const auto hi = static_cast<u128>(s >> Du);
  if (k > 128) return false;  // bit 128 of a negative pattern is 1, u has only 128 bits
  return (hi & low_mask<u128>(k)) == u;
}
template <int Ws, int Fs, int Wu, int Fu, int WuAligned>
constexpr bool modular_equal(i128 s, u128 u) noexcept {
  constexpr int f = imax(Fs, Fu);
  constexpr int ds = f - Fs;  // the signed pattern moves up by ds (u fixed), or
  constexpr int du = f - Fu;  // the unsigned one moves up by du (s fixed)
  return modular_equal<ds, du, WuAligned>(
      s, u, int_c<(du == 0 ? (ds >= WuAligned ? 0 : 1) : (du >= 128 ? 2 : 3))>{});
}

// == on the exact values; == with the modular rule when the signed operand (a for
// bool_c<true>, b for bool_c<false>) is negative.
template <class A, class B>
constexpr bool equal_exact(const A& a, const B& b, bool_c<true> /* in one word */) noexcept {
  return aligned_word<A, B>(a) == aligned_word_right<A, B>(b);
}
template <class A, class B>
constexpr bool equal_exact(const A& a, const B& b, bool_c<false>) noexcept {
  using C = cmp_rule<A, B>;
  using RT = typename C::RT;
  using U = typename C::U;
  return cmp_exact(widen<U, RT::s1>(raw_of(a)), RT::f1, widen<U, RT::s2>(raw_of(b)), RT::f2) ==
         0;
}
template <class A, class B>
constexpr bool equal_exact(const A& a, const B& b) noexcept {
  return equal_exact(a, b, cmp_in_word<A, B>{});
}
template <class A, class B>
constexpr bool equal_modular(const A& a, const B& b,
                             bool_c<true> /* a is the signed one */) noexcept {
  using C = cmp_rule<A, B>;
  using RT = typename C::RT;
  const auto ra = raw_of(a);
  const auto rb = raw_of(b);
  if (static_cast<i128>(ra) < 0) {
    return modular_equal<RT::w1, RT::f1, RT::w2, RT::f2, C::wu>(static_cast<i128>(ra),
                                                                static_cast<u128>(rb));
  }
  return equal_exact(a, b);
}
template <class A, class B>
constexpr bool equal_modular(const A& a, const B& b,
                             bool_c<false> /* b is the signed one */) noexcept {
  using C = cmp_rule<A, B>;
  using RT = typename C::RT;
  const auto ra = raw_of(a);
  const auto rb = raw_of(b);
  if (static_cast<i128>(rb) < 0) {
    return modular_equal<RT::w2, RT::f2, RT::w1, RT::f1, C::wu>(static_cast<i128>(rb),
                                                                static_cast<u128>(ra));
  }
  return equal_exact(a, b);
}
template <class A, class B>
constexpr bool equal(const A& a, const B& b, bool_c<false> /* not eq_modular */) noexcept {
  return equal_exact(a, b);
}
template <class A, class B>
constexpr bool equal(const A& a, const B& b, bool_c<true> /* eq_modular */) noexcept {
  return equal_modular(a, b, bool_c<rtype<A, B>::s1>{});
}
template <class A, class B>
constexpr bool equal_as_is(const A& a, const B& b) noexcept {
  return equal(a, b, bool_c<cmp_rule<A, B>::eq_modular>{});
}

// ap's comparison widens the operand with fewer fraction bits before comparing the patterns
// (ap_fixed_base.h, OP_CMP_AF): the left one to <W + F2 - F + 1, I + 1> and the right one to
// <W2 + F - F2, I2>, each a conversion with the operand's OWN Q/O/N. The left one gains an
// integer bit, so nothing happens to it. The right one keeps I2 and gains only fraction bits:
// that conversion never quantizes and never leaves the range, and ap's operator= enters its
// overflow path only for a signed SAT_SYM destination (I - S < I2 - S2 + (S2 && SAT_SYM)),
// where "the result is MIN" counts as underflow and gives -MAX = MIN | 1 LSB of the widened
// type. So exactly one case changes a value: a signed SAT_SYM right operand with fewer
// fraction bits than the left one (a C integer or int_t on the left has F = 0, so a right
// operand with I2 > W2 qualifies), holding MIN, is compared as MIN + 2^-F (F: the left
// operand's fraction bits). The other modes (SAT, SAT_ZERO, WRAP with any N, WRAP_SM) and
// unsigned operands keep the value. A SAT_SYM variable holds MIN after shifts, bit writes,
// from_raw, and, for W2 = 1 (range {-1, 0}), after any assignment of a negative value.
template <class A, class B>
struct sat_sym_right : bool_c<false> {};
template <class A, int W2, int I2, q_mode Q2, int N2>
struct sat_sym_right<A, fixed_base<W2, I2, true, Q2, SAT_SYM, N2>>
    : bool_c<(operand<A>::w - operand<A>::i > W2 - I2)> {};

template <int W2, class R>
constexpr bool holds_min(R raw) noexcept {
  using U = word_t<W2>;
  return raw < 0 && (static_cast<U>(raw) & low_mask<U>(W2 - 1)) == 0;
}
// The left operand with its lowest bit cleared, and whether that bit was set.
template <class T>
constexpr bool lsb_set(const T& a, bool_c<true> /* C integer */) noexcept {
  return (a & 1) != 0;
}
template <class T>
constexpr bool lsb_set(const T& a, bool_c<false> /* fixed or int */) noexcept {
  return (a.raw() & 1) != 0;
}
// A signed 1-bit operand's -1 without its lowest bit is -2 (one LSB = 2^(I-1)), which needs a
// second bit; both operands are then signed and compared exactly, so the wider type changes
// nothing else. Everything else keeps its type (an odd pattern minus 1 stays in range).
template <class T>
struct even_type {
  using type = T;
};
template <int I, q_mode Q, o_mode O, int N>
struct even_type<fixed_base<1, I, true, Q, O, N>> {
  using type = fixed_base<2, I + 1, true>;
};
template <>
struct even_type<int_base<1, true>> {
  using type = int_base<2, true>;
};
template <class T>
constexpr T clear_lsb(const T& a, bool_c<true> /* C integer */) noexcept {
  return static_cast<T>(a - (a & 1));
}
template <class T>
constexpr typename even_type<T>::type clear_lsb(const T& a,
                                                bool_c<false> /* fixed or int */) noexcept {
  using R = typename even_type<T>::type;
  return R::from_raw(static_cast<typename R::raw_type>(a.raw() - (a.raw() & 1)));
}
// a == MIN + 2^-F for the widened b = MIN: MIN aligned to a's LSB has a zero lowest bit, so
// a must have its lowest bit set and equal MIN without it (exactly or modulo 2^wu, whichever
// rule applies to these types: the widths are those of the widened operand either way).
template <class A, class B>
constexpr bool equal_to_min_plus_lsb(const A& a, const B& b) noexcept {
  using is_c = bool_c<std::is_integral<A>::value>;
  return lsb_set(a, is_c{}) && equal_as_is(clear_lsb(a, is_c{}), b);
}

template <class A, class B>
constexpr int compare(const A& a, const B& b, bool_c<false>) noexcept {
  return compare_as_is(a, b);
}
template <class A, class B>
constexpr int compare(const A& a, const B& b, bool_c<true> /* sat_sym_right */) noexcept {
  if (!holds_min<B::width>(b.raw())) return compare_as_is(a, b);
  // b counts as MIN + 1 LSB of a: a <= MIN means a < b; above MIN, a == b or a > b.
  if (compare_as_is(a, b) <= 0) return -1;
  return equal_to_min_plus_lsb(a, b) ? 0 : 1;
}
template <class A, class B>
constexpr int compare(const A& a, const B& b) noexcept {
  return compare(a, b, bool_c<sat_sym_right<A, B>::value>{});
}
// a < b, a <= b, a > b, a >= b. Where compare() would compare the two aligned words
// (compare_as_is's one-word path, no SAT_SYM right operand), the relation is that one
// comparison of the words: the same result as compare(a, b) OP 0, without the three-way
// value, which the compiler does not fold back into a single compare (it was 9 % of the hls
// engine's instructions).
struct rel_lt {
  template <class T>
  constexpr bool operator()(T x, T y) const noexcept {
    return x < y;
  }
};
struct rel_le {
  template <class T>
  constexpr bool operator()(T x, T y) const noexcept {
    return x <= y;
  }
};
struct rel_gt {
  template <class T>
  constexpr bool operator()(T x, T y) const noexcept {
    return x > y;
  }
};
struct rel_ge {
  template <class T>
  constexpr bool operator()(T x, T y) const noexcept {
    return x >= y;
  }
};
template <class A, class B>
struct rel_in_word : bool_c<cmp_fast<A, B>::value && !sat_sym_right<A, B>::value> {};
template <class Rel, class A, class B>
constexpr bool relation(const A& a, const B& b, bool_c<true> /* one word */) noexcept {
  return Rel{}(aligned_word<A, B>(a), aligned_word_right<A, B>(b));
}
template <class Rel, class A, class B>
constexpr bool relation(const A& a, const B& b, bool_c<false>) noexcept {
  return Rel{}(compare(a, b), 0);
}
template <class Rel, class A, class B>
constexpr bool relation(const A& a, const B& b) noexcept {
  return relation<Rel>(a, b, rel_in_word<A, B>{});
}

template <class A, class B>
constexpr bool equal_sym(const A& a, const B& b, bool_c<false>) noexcept {
  return equal_as_is(a, b);
}
template <class A, class B>
constexpr bool equal_sym(const A& a, const B& b, bool_c<true> /* sat_sym_right */) noexcept {
  if (!holds_min<B::width>(b.raw())) return equal_as_is(a, b);
  return equal_to_min_plus_lsb(a, b);
}
template <class A, class B>
constexpr bool equal(const A& a, const B& b) noexcept {
  return equal_sym(a, b, bool_c<sat_sym_right<A, B>::value>{});
}

// Section 7: shift amounts. Signed C integers and ap_int go through to_int() (low 32 bits,
// negative reverses the direction), unsigned ones through to_uint(); an ap_fixed amount is
// truncated toward zero first.
template <class T>
constexpr std::int64_t shift_amount(const T& n, bool_c<true> /* C integer */) noexcept {
  if (std::is_signed<T>::value) return static_cast<std::int32_t>(static_cast<std::uint32_t>(n));
  return static_cast<std::uint32_t>(n);
}
template <class T>
constexpr std::int64_t shift_amount(const T& n, bool_c<false> /* fixed or int */) noexcept {
  if (operand<T>::s) return n.to_int();
  return n.to_uint();
}
template <class T>
constexpr std::int64_t shift_amount(const T& n) noexcept {
  return shift_amount(n, bool_c<std::is_integral<T>::value>{});
}

#ifndef __SYNTHESIS__
// Decimal text of an unsigned 128-bit integer.
inline std::string u128_to_string(u128 x) {
  char buf[48];
  int pos = 48;
  do {
    buf[--pos] = static_cast<char>('0' + static_cast<int>(x % 10));
    x /= 10;
  } while (x != 0);
  return std::string(buf + pos, buf + 48);
}

// The shortest decimal text that reads back as d, as std::to_chars(first, last, d) (C++17)
// writes it: the fewest significant digits that round-trip, the closest such number to d, in
// fixed or scientific notation, whichever is shorter (fixed on a tie).
//
// The correctly rounded p-digit number (printf "%.*e") is the closest one; if it does not read
// back as d, the only p-digit number that can is its neighbour on the other side of d.
inline bool reads_back(const std::string& digits, int exp10, double mag) {
  const std::string text =
      digits + "e" + std::to_string(exp10 - static_cast<int>(digits.size()) + 1);
  return std::strtod(text.c_str(), nullptr) == mag;
}
// digits * 10^(exp10 - n + 1) one unit in the last place up (up) or down (!up), same length.
inline void step_last_digit(std::string& digits, int& exp10, bool up) {
  const std::size_t n = digits.size();
  if (up) {
    std::size_t i = n;
    while (i > 0 && digits[i - 1] == '9') digits[--i] = '0';
    if (i == 0) {  // 99..9 + 1 = 10..0: one more decade
      digits = "1" + std::string(n - 1, '0');
      ++exp10;
    } else {
      ++digits[i - 1];
    }
  } else if (digits == "1" + std::string(n - 1, '0')) {  // 10..0 - 1 = 99..9 a decade lower
    digits = std::string(n, '9');
    --exp10;
  } else {
    std::size_t i = n;
    while (digits[i - 1] == '0') digits[--i] = '9';
    --digits[i - 1];
  }
}
inline std::string double_to_string(double d) {
  const std::string sign = std::signbit(d) ? "-" : "";
  if (std::isnan(d)) return sign + "nan";
  if (std::isinf(d)) return sign + "inf";
  if (d == 0) return sign + "0";
  const double mag = std::fabs(d);
  // Significant digits d1 d2 ... dn and the exponent: mag ~ d1.d2...dn * 10^exp10.
  std::string digits;
  int exp10 = 0;
  for (int p = 0; p <= 16; ++p) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*e", p, mag);
    const std::string text = buf;  // d[.ddd]e+XX
    const std::size_t e = text.find('e');
    digits = text.substr(0, 1) + (p > 0 ? text.substr(2, e - 2) : std::string());
    exp10 = std::atoi(text.c_str() + e + 1);
    if (reads_back(digits, exp10, mag)) break;
    const bool below = std::strtod(buf, nullptr) < mag;
    step_last_digit(digits, exp10, below);
    if (reads_back(digits, exp10, mag)) break;
  }
  while (digits.size() > 1 && digits.back() == '0') digits.pop_back();
  const int n = static_cast<int>(digits.size());
  // Scientific: d1[.d2...dn]e+XX (at least two exponent digits).
  const int ax = exp10 < 0 ? -exp10 : exp10;
  const std::string sci = digits.substr(0, 1) + (n > 1 ? "." + digits.substr(1) : "") + "e" +
                          (exp10 < 0 ? "-" : "+") + (ax < 10 ? "0" : "") + std::to_string(ax);
  // Fixed: the digits with the point placed. An integer is printed exactly (all its digits
  // rather than the shortest ones padded with zeros: as long, and closer to d).
  std::string fix;
  if (exp10 < 0) {
    fix = "0." + std::string(static_cast<std::size_t>(-exp10 - 1), '0') + digits;
  } else if (n <= exp10 + 1) {
    char ibuf[320];  // the largest double has 309 digits
    std::snprintf(ibuf, sizeof ibuf, "%.0f", mag);
    fix = ibuf;
  } else {
    fix = digits.substr(0, static_cast<std::size_t>(exp10 + 1)) + "." +
          digits.substr(static_cast<std::size_t>(exp10 + 1));
  }
  return sign + (sci.size() < fix.size() ? sci : fix);
}

// Exact decimal text of raw * 2^-F when it fits the 128-bit arithmetic, else the double.
// The tag is the case of F: an integer beyond 128 bits, an integer, a fraction, too fine.
template <int F>
std::string fixed_to_string(const std::string& sign, u128 mag, double approx,
                            int_c<0> /* F <= -128 */) {
  if (mag != 0) return double_to_string(approx);
  return sign + u128_to_string(mag);
}
template <int F>
std::string fixed_to_string(const std::string& sign, u128 mag, double approx,
                            int_c<1> /* -128 < F <= 0 */) {
  if (mag != 0 && (mag >> (127 + F)) != 0) return double_to_string(approx);
  return sign + u128_to_string(mag << -F);
}
template <int F>
std::string fixed_to_string(const std::string& sign, u128 mag, double,
                            int_c<2> /* 0 < F <= 124 */) {
  std::string s = sign + u128_to_string(mag >> F);
  u128 frac = mag & low_mask<u128>(F);
  if (frac != 0) s += '.';
  while (frac != 0) {
    frac *= 10;
    s += static_cast<char>('0' + static_cast<int>(frac >> F));
    frac &= low_mask<u128>(F);
  }
  return s;
}
template <int F>
std::string fixed_to_string(const std::string&, u128, double approx, int_c<3> /* F > 124 */) {
  return double_to_string(approx);
}
template <int F, bool S, class R>
std::string fixed_to_string(R raw, double approx) {
  const wide<u128> v = widen<u128, S>(raw);
  const u128 mag = v.neg ? u128(0) - v.bits : v.bits;
  const std::string sign = v.neg ? "-" : "";
  return fixed_to_string<F>(sign, mag, approx,
                            int_c<(F <= -128 ? 0 : (F <= 0 ? 1 : (F <= 124 ? 2 : 3)))>{});
}
#endif  // __SYNTHESIS__

// Proxies for x[i] and x.range(hi, lo) (section 10): raw bit access, no Q/O on writes.
template <class Owner>
class bit_ref {
 public:
  constexpr bit_ref(Owner* owner, int index) noexcept : owner_(owner), index_(index) {}
  constexpr bit_ref(const bit_ref&) noexcept = default;
  constexpr operator bool() const noexcept { return static_cast<const Owner&>(*owner_)[index_]; }
  constexpr bool to_bool() const noexcept { return static_cast<bool>(*this); }
  constexpr bit_ref& operator=(bool b) noexcept {
    owner_->set_bit(index_, b);
    return *this;
  }
  constexpr bit_ref& operator=(const bit_ref& other) noexcept {
    return *this = static_cast<bool>(other);
  }

 private:
  Owner* owner_;
  int index_;
};

// The reads of x.range(hi, lo), shared by range_ref<T> and the read-only range_ref<const T>.
template <class Owner>
class range_reader {
 public:
  constexpr range_reader(Owner* owner, int hi, int lo) noexcept
      : owner_(owner), hi_(hi), lo_(lo) {}

  // Read as an unsigned integer of length() bits (hi < lo reads the bits reversed).
  constexpr u128 raw_bits() const noexcept { return owner_->get_range(hi_, lo_); }
  constexpr std::uint64_t to_uint64() const noexcept {
    return static_cast<std::uint64_t>(raw_bits());
  }
  constexpr std::int64_t to_int64() const noexcept {
    return static_cast<std::int64_t>(to_uint64());
  }
  constexpr unsigned to_uint() const noexcept { return static_cast<unsigned>(to_uint64()); }
  constexpr int to_int() const noexcept { return static_cast<int>(to_uint()); }
  constexpr int length() const noexcept { return (hi_ >= lo_ ? hi_ - lo_ : lo_ - hi_) + 1; }
  constexpr bool operator==(std::uint64_t v) const noexcept { return raw_bits() == v; }

 protected:
  Owner* owner_;
  int hi_;
  int lo_;
};

template <class Owner>
class range_ref : public range_reader<Owner> {
 public:
  constexpr range_ref(Owner* owner, int hi, int lo) noexcept
      : range_reader<Owner>(owner, hi, lo) {}
  constexpr range_ref(const range_ref&) noexcept = default;

  // Writes the low length() bits of v (raw, no quantization or overflow handling).
  constexpr range_ref& operator=(std::uint64_t v) noexcept {
    this->owner_->set_range(this->hi_, this->lo_, u128(v));
    return *this;
  }
  template <int W2, bool S2>
  constexpr range_ref& operator=(const int_base<W2, S2>& v) noexcept {
    this->owner_->set_range(this->hi_, this->lo_, static_cast<u128>(v.raw()));
    return *this;
  }
  template <class O2>
  constexpr range_ref& operator=(const range_ref<O2>& v) noexcept {
    this->owner_->set_range(this->hi_, this->lo_, v.raw_bits());
    return *this;
  }
  constexpr range_ref& operator=(const range_ref& v) noexcept {
    this->owner_->set_range(this->hi_, this->lo_, v.raw_bits());
    return *this;
  }
};

// x.range(hi, lo) of a const x: read only, no assignment at all.
template <class Owner>
class range_ref<const Owner> : public range_reader<const Owner> {
 public:
  constexpr range_ref(const Owner* owner, int hi, int lo) noexcept
      : range_reader<const Owner>(owner, hi, lo) {}
  constexpr range_ref(const range_ref&) noexcept = default;
  range_ref& operator=(const range_ref&) = delete;
};

// Shared raw-bit helpers of fixed_base and int_base (W-bit canonical storage in word U).
template <int W, bool S, class U>
constexpr u128 read_range(U v, int hi, int lo) noexcept {
  if (hi < lo) {
    // Section 10: hi < lo returns the bits reversed.
    u128 r = 0;
    for (int i = hi; i <= lo; ++i) r = (r << 1) | u128((v >> i) & U(1));
    return r;
  }
  return u128((v >> lo) & low_mask<U>(hi - lo + 1));
}
template <int W, bool S, class U>
constexpr U write_range(U v, int hi, int lo, u128 x) noexcept {
  if (hi < lo) {
    for (int i = hi; i <= lo; ++i) {
      v = assign_bits<U>(v, i, i, ((x >> (lo - i)) & 1) != 0);
    }
    return extend<W, S>(v);
  }
  const U m = low_mask<U>(hi - lo + 1) << lo;
  return extend<W, S>(U((v & ~m) | ((static_cast<U>(x) << lo) & m)));
}

}  // namespace detail

// =============================================================================================
// fixed_base: ap_fixed_base<W, I, S, Q, O, N>. Use the aliases fixed<> / ufixed<>.
// =============================================================================================
template <int W, int I, bool S, q_mode Q, o_mode O, int N>
class fixed_base {
  static_assert(W >= 1, "voxcast::hls::fixed: W must be at least 1");
  static_assert(W <= max_width,
                "voxcast::hls::fixed: W exceeds 128 bits, the widest type the clone supports "
                "(stored or produced by an operator, e.g. a 64 x 64-bit product); narrow the "
                "operands before this operation");
  static_assert(S || O != WRAP_SM,
                "voxcast::hls::ufixed: WRAP_SM is signed only (ap_ufixed calls exit(1))");
  static_assert(N >= 0 && N <= W, "voxcast::hls::fixed: saturation bits N must be in [0, W]");

  using word = detail::word_t<W>;

 public:
  using raw_type = detail::raw_t<W, S>;
  using store_type = detail::store_t<W, S>;
  static constexpr int width = W;
  static constexpr int iwidth = I;
  static constexpr q_mode qmode = Q;
  static constexpr o_mode omode = O;
  static constexpr int nbits = N;
  static constexpr bool is_signed = S;

  // ---- Construction: every conversion into a different type quantizes and handles overflow
  // with this type's Q/O/N (section 4); copies of the same type are bit copies.
  // Default construction zero-initialises (ap leaves V uninitialised): deterministic
  // simulation; code must not rely on either.
  constexpr fixed_base() noexcept = default;

  template <int W2, int I2, bool S2, q_mode Q2, o_mode O2, int N2>
  constexpr fixed_base(const fixed_base<W2, I2, S2, Q2, O2, N2>& x) noexcept
      : v_(narrow_raw(convert<W2 - I2, S2, W2>(x.raw()))) {}

  template <int W2, bool S2>
  constexpr fixed_base(const int_base<W2, S2>& x) noexcept
      : v_(narrow_raw(convert<0, S2, W2>(x.raw()))) {}

  template <class T, detail::enable_if_c<std::is_integral<T>::value> = 0>
  constexpr fixed_base(T x) noexcept
      : v_(narrow_raw(convert<0, detail::operand<T>::s, detail::operand<T>::w>(x))) {}

  // Section 9: exact decode, one quantization and one overflow step; NaN/inf per its table.
  constexpr fixed_base(double d) noexcept : v_(narrow_raw(from_double(d))) {}
  constexpr fixed_base(float f) noexcept : v_(narrow_raw(from_double(static_cast<double>(f)))) {}
  // Internal (the operators of this header): v is already sign/zero-extended from W bits.
  constexpr fixed_base(detail::exact_tag, raw_type v) noexcept : v_(narrow_raw(v)) {}

  // ---- Raw bits. from_raw keeps the low W bits of its argument (two's complement) and
  // reinterprets them; raw() returns V sign-extended (signed) or zero-extended (unsigned).
  static constexpr fixed_base from_raw(raw_type bits) noexcept {
    fixed_base r;
    r.v_ = narrow_raw(static_cast<raw_type>(detail::extend<W, S>(static_cast<word>(bits))));
    return r;
  }
  constexpr raw_type raw() const noexcept { return v_; }
  // ap names (section 10): bitsToFixed / setBits take the low W bits of a 64-bit pattern.
  static constexpr fixed_base bitsToFixed(std::uint64_t bits) noexcept {
    return from_raw(static_cast<raw_type>(bits));
  }
  constexpr fixed_base& setBits(std::uint64_t bits) noexcept {
    v_ = from_raw(static_cast<raw_type>(bits)).v_;
    return *this;
  }

  // ---- Conversions out (section 9) ---------------------------------------------------------
  // Round to nearest even (exact when the value fits 53 bits).
  constexpr double to_double() const noexcept {
    return detail::scale<I - W>(static_cast<double>(raw()));
  }
  constexpr float to_float() const noexcept {
    return static_cast<float>(detail::scale<I - W>(static_cast<double>(static_cast<float>(raw()))));
  }
  // Toward zero, then the low bits (wrap). For I <= 0 this returns the mathematically correct
  // 0; ap sim returns -1 (I == 0, negative non-integer) or stack garbage (I < 0).
  constexpr int to_int() const noexcept {
    return static_cast<int>(static_cast<std::uint32_t>(trunc64()));
  }
  constexpr unsigned to_uint() const noexcept { return static_cast<std::uint32_t>(trunc64()); }
  constexpr std::int64_t to_int64() const noexcept { return static_cast<std::int64_t>(trunc64()); }
  constexpr std::uint64_t to_uint64() const noexcept { return trunc64(); }
  constexpr long to_long() const noexcept { return static_cast<long>(to_int64()); }
  constexpr unsigned long to_ulong() const noexcept {
    return static_cast<unsigned long>(to_uint64());
  }
  constexpr char to_char() const noexcept { return static_cast<char>(to_int()); }
  constexpr bool to_bool() const noexcept { return raw() != 0; }

  // Explicit only: ap converts implicitly, which is what makes "a + 0.5" ambiguous there; here
  // the conversions are explicit so that "a + 0.5" is equally ill-formed.
  template <class T, detail::enable_if_c<std::is_arithmetic<T>::value> = 0>
  constexpr explicit operator T() const noexcept {
    if (std::is_same<T, bool>::value) return static_cast<T>(raw() != 0);
    if (std::is_same<T, float>::value) return static_cast<T>(to_float());
    if (std::is_floating_point<T>::value) return static_cast<T>(to_double());
    if (std::is_signed<T>::value) return static_cast<T>(to_int64());
    return static_cast<T>(to_uint64());
  }

  // ---- Queries ---------------------------------------------------------------------------
  constexpr bool is_neg() const noexcept { return detail::negative(raw(), detail::bool_c<S>{}); }
  constexpr bool is_zero() const noexcept { return raw() == 0; }
  constexpr bool operator!() const noexcept { return raw() == 0; }
  constexpr int wl() const noexcept { return W; }
  constexpr int iwl() const noexcept { return I; }
  constexpr int length() const noexcept { return W; }
  constexpr int n_bits() const noexcept { return N; }
  constexpr int countLeadingZeros() const noexcept {
    const word u = static_cast<word>(raw()) & detail::low_mask<word>(W);
    return detail::count_leading_zeros(u) - (detail::word_bits<word>() - W);
  }

  // ---- Bit and range access (section 10): raw bits, no Q/O --------------------------------
  constexpr bool operator[](int i) const noexcept {
    return ((static_cast<word>(raw()) >> i) & 1) != 0;
  }
  constexpr detail::bit_ref<fixed_base> operator[](int i) noexcept { return {this, i}; }
  constexpr bool bit(int i) const noexcept { return (*this)[i]; }
  constexpr detail::bit_ref<fixed_base> bit(int i) noexcept { return {this, i}; }
  // Bit of weight 2^i, i in [I - W, I - 1].
  constexpr bool get_bit(int i) const noexcept { return (*this)[i + W - I]; }
  constexpr void set_bit(int i, bool b) noexcept {
    v_ = narrow_raw(static_cast<raw_type>(
        detail::extend<W, S>(detail::assign_bits<word>(static_cast<word>(raw()), i, i, b))));
  }
  constexpr detail::range_ref<fixed_base> range(int hi, int lo) noexcept { return {this, hi, lo}; }
  constexpr detail::range_ref<const fixed_base> range(int hi, int lo) const noexcept {
    return {this, hi, lo};
  }
  constexpr detail::range_ref<fixed_base> range() noexcept { return {this, W - 1, 0}; }
  constexpr detail::range_ref<const fixed_base> range() const noexcept { return {this, W - 1, 0}; }
  constexpr detail::range_ref<fixed_base> operator()(int hi, int lo) noexcept {
    return {this, hi, lo};
  }
  constexpr detail::range_ref<const fixed_base> operator()(int hi, int lo) const noexcept {
    return {this, hi, lo};
  }
  constexpr detail::u128 get_range(int hi, int lo) const noexcept {
    return detail::read_range<W, S>(static_cast<word>(raw()), hi, lo);
  }
  constexpr void set_range(int hi, int lo, detail::u128 x) noexcept {
    v_ = narrow_raw(
        static_cast<raw_type>(detail::write_range<W, S>(static_cast<word>(raw()), hi, lo, x)));
  }

  // ---- Unary operators (section 11) -------------------------------------------------------
  constexpr fixed_base operator+() const noexcept { return *this; }
  // Exact in <W+1, I+1, signed>, so -MIN is representable.
  constexpr fixed_base<W + 1, I + 1, true> operator-() const noexcept {
    using U = detail::word_t<W + 1>;
    return detail::make_exact<fixed_base<W + 1, I + 1, true>>(U(U(0) - static_cast<U>(raw())));
  }
  // Negation in the same width (wraps), as ap's getNeg().
  constexpr fixed_base<W, I, true, Q, O, N> getNeg() const noexcept {
    using R = fixed_base<W, I, true, Q, O, N>;
    return R::from_raw(static_cast<typename R::raw_type>(word(word(0) - static_cast<word>(raw()))));
  }
  // Bitwise NOT in the same type with default Q/O (ap: ap_fixed_base<W, I, S>).
  constexpr fixed_base<W, I, S> operator~() const noexcept {
    using R = fixed_base<W, I, S>;
    return R::from_raw(static_cast<typename R::raw_type>(~static_cast<word>(raw())));
  }

  // Section 11: ++/-- add 1.0 (not one LSB) through +=, so they quantize and handle overflow
  // with this type's modes; ill-formed for I > W, as in ap (templates only so that the
  // condition can remove them: I2 is always I).
  template <int I2 = I, detail::enable_if_c<(I2 <= W)> = 0>
  constexpr fixed_base& operator++() noexcept {
    return *this += fixed_base<W - I + 1, 1, false>(1);
  }
  template <int I2 = I, detail::enable_if_c<(I2 <= W)> = 0>
  constexpr fixed_base& operator--() noexcept {
    return *this -= fixed_base<W - I + 1, 1, false>(1);
  }
  template <int I2 = I, detail::enable_if_c<(I2 <= W)> = 0>
  constexpr fixed_base operator++(int) noexcept {
    const fixed_base r = *this;
    ++*this;
    return r;
  }
  template <int I2 = I, detail::enable_if_c<(I2 <= W)> = 0>
  constexpr fixed_base operator--(int) noexcept {
    const fixed_base r = *this;
    --*this;
    return r;
  }

  // ---- Compound assignment (section 4): full-precision result, then ONE conversion -------
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value> = 0>
  constexpr fixed_base& operator+=(const B& b) noexcept {
    return *this = detail::binary<detail::op::add>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value> = 0>
  constexpr fixed_base& operator-=(const B& b) noexcept {
    return *this = detail::binary<detail::op::sub>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value> = 0>
  constexpr fixed_base& operator*=(const B& b) noexcept {
    return *this = detail::binary<detail::op::mul>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value> = 0>
  constexpr fixed_base& operator/=(const B& b) noexcept {
    return *this = detail::binary<detail::op::div>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value> = 0>
  constexpr fixed_base& operator&=(const B& b) noexcept {
    return *this = detail::binary<detail::op::band>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value> = 0>
  constexpr fixed_base& operator|=(const B& b) noexcept {
    return *this = detail::binary<detail::op::bor>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value> = 0>
  constexpr fixed_base& operator^=(const B& b) noexcept {
    return *this = detail::binary<detail::op::bxor>(*this, b);
  }

  // ---- Shifts (section 7): same type including Q/O, raw pattern, no quantization or
  // overflow handling; negative signed amounts reverse; amounts >= W give 0 / sign fill.
  template <class T, detail::enable_if_c<detail::shift_operand<T>::value> = 0>
  constexpr fixed_base operator<<(const T& n) const noexcept {
    return shl(detail::shift_amount(n));
  }
  template <class T, detail::enable_if_c<detail::shift_operand<T>::value> = 0>
  constexpr fixed_base operator>>(const T& n) const noexcept {
    return shr(detail::shift_amount(n));
  }
  template <class T, detail::enable_if_c<detail::shift_operand<T>::value> = 0>
  constexpr fixed_base& operator<<=(const T& n) noexcept {
    return *this = shl(detail::shift_amount(n));
  }
  template <class T, detail::enable_if_c<detail::shift_operand<T>::value> = 0>
  constexpr fixed_base& operator>>=(const T& n) noexcept {
    return *this = shr(detail::shift_amount(n));
  }
  // Reinterpret the same bits with the binary point moved (exact, no bits lost).
  template <int K>
  constexpr fixed_base<W, I + K, S> lshift() const noexcept {
    return fixed_base<W, I + K, S>::from_raw(raw());
  }
  template <int K>
  constexpr fixed_base<W, I - K, S> rshift() const noexcept {
    return fixed_base<W, I - K, S>::from_raw(raw());
  }

#ifndef __SYNTHESIS__
  // ---- Printing (host only): exact decimal (ap's to_string() defaults to radix 2; use
  // to_string(10) in code that must compile with both). Radix 2 and 16 print the raw W-bit
  // pattern.
  std::string to_string(int radix = 10) const {
    if (radix == 2 || radix == 16) return raw_pattern_string(radix);
    return detail::fixed_to_string<W - I, S>(raw(), to_double());
  }
#endif

 private:
  template <int Fs, bool Ss, int Ws, class R>
  static constexpr raw_type convert(R raw) noexcept {
    using U = detail::word_t<detail::imax(W, Ws)>;
    const detail::wide<U> src = detail::widen<U, Ss>(raw);
    return store(detail::quantize<W, S, Q, O, N, Fs - (W - I)>(src.bits, src.neg));
  }
  static constexpr raw_type from_double(double d) noexcept {
    const detail::double_parts p = detail::decode(d);
    using U = detail::word_t<W>;  // the 54-bit signed mantissa fits either word
    const detail::wide<U> src = detail::widen<U, true>(p.m);
    return store(detail::quantize<W, S, Q, O, N>(src.bits, src.neg, p.fs - (W - I)));
  }
  template <class U>
  static constexpr raw_type store(U pattern) noexcept {
    return static_cast<raw_type>(detail::extend<W, S>(static_cast<word>(pattern)));
  }
  constexpr std::uint64_t trunc64() const noexcept {
    return detail::trunc_toward_zero<std::uint64_t, W - I, S>(raw());
  }
  constexpr fixed_base shl(std::int64_t n) const noexcept {
    if (n < 0) return shr(-n);
    if (n >= W) return from_raw(0);
    return from_raw(static_cast<raw_type>(static_cast<word>(raw()) << n));
  }
  constexpr fixed_base shr(std::int64_t n) const noexcept {
    if (n < 0) return shl(-n);
    if (n >= W) return from_raw(is_neg() ? static_cast<raw_type>(~word(0)) : raw_type(0));
    return from_raw(static_cast<raw_type>(raw() >> n));
  }
#ifndef __SYNTHESIS__
  std::string raw_pattern_string(int radix) const {
    const int step = radix == 2 ? 1 : 4;
    const word u = static_cast<word>(raw()) & detail::low_mask<word>(W);
    std::string s = radix == 2 ? "0b" : "0x";
    for (int pos = ((W - 1) / step) * step; pos >= 0; pos -= step) {
      s += "0123456789abcdef"[static_cast<int>((u >> pos) & word(radix - 1))];
    }
    return s;
  }
#endif

  // raw_type -> storage: exact, since every stored V is canonical in W bits (detail::store_t).
  static constexpr store_type narrow_raw(raw_type v) noexcept { return static_cast<store_type>(v); }

  store_type v_ = 0;
};

// =============================================================================================
// int_base: ap_int_base<W, S>. Use int_t<W> / uint_t<W>. Integer arithmetic like
// fixed<W, W> without Q/O: every conversion into it wraps (section 12).
// =============================================================================================
template <int W, bool S>
class int_base {
  static_assert(W >= 1, "voxcast::hls::int_t: W must be at least 1");
  static_assert(W <= max_width,
                "voxcast::hls::int_t: W exceeds 128 bits, the widest type the clone supports "
                "(stored or produced by an operator); narrow the operands first");

  using word = detail::word_t<W>;

 public:
  using raw_type = detail::raw_t<W, S>;
  using store_type = detail::store_t<W, S>;
  static constexpr int width = W;
  static constexpr bool is_signed = S;

  // Zero-initialised (ap: uninitialised).
  constexpr int_base() noexcept = default;
  template <int W2, bool S2>
  constexpr int_base(const int_base<W2, S2>& x) noexcept : v_(narrow_raw(store(x.raw()))) {}
  template <class T, detail::enable_if_c<std::is_integral<T>::value> = 0>
  constexpr int_base(T x) noexcept : v_(narrow_raw(store(x))) {}
  // Conversions from fixed and double truncate toward zero, then wrap (section 9).
  template <int W2, int I2, bool S2, q_mode Q2, o_mode O2, int N2>
  constexpr int_base(const fixed_base<W2, I2, S2, Q2, O2, N2>& x) noexcept
      : v_(narrow_raw(store(detail::trunc_toward_zero<word, W2 - I2, S2>(x.raw())))) {}
  // ap sim gives +1 for d in (-0.5, 0) (section 9 bug); the clone returns the correct 0.
  constexpr int_base(double d) noexcept : v_(narrow_raw(from_double(d))) {}
  constexpr int_base(float f) noexcept : v_(narrow_raw(from_double(static_cast<double>(f)))) {}
  // Internal (the operators of this header): v is already sign/zero-extended from W bits.
  constexpr int_base(detail::exact_tag, raw_type v) noexcept : v_(narrow_raw(v)) {}

  static constexpr int_base from_raw(raw_type bits) noexcept {
    int_base r;
    r.v_ = narrow_raw(store(bits));
    return r;
  }
  constexpr raw_type raw() const noexcept { return v_; }

  constexpr double to_double() const noexcept { return static_cast<double>(raw()); }
  constexpr float to_float() const noexcept { return static_cast<float>(raw()); }
  constexpr int to_int() const noexcept {
    return static_cast<int>(static_cast<std::uint32_t>(raw()));
  }
  constexpr unsigned to_uint() const noexcept { return static_cast<std::uint32_t>(raw()); }
  constexpr std::int64_t to_int64() const noexcept {
    return static_cast<std::int64_t>(static_cast<std::uint64_t>(raw()));
  }
  constexpr std::uint64_t to_uint64() const noexcept { return static_cast<std::uint64_t>(raw()); }
  constexpr long to_long() const noexcept { return static_cast<long>(to_int64()); }
  constexpr unsigned long to_ulong() const noexcept {
    return static_cast<unsigned long>(to_uint64());
  }
  constexpr char to_char() const noexcept { return static_cast<char>(to_int()); }
  constexpr bool to_bool() const noexcept { return raw() != 0; }
  template <class T, detail::enable_if_c<std::is_arithmetic<T>::value> = 0>
  constexpr explicit operator T() const noexcept {
    if (std::is_same<T, bool>::value) return static_cast<T>(raw() != 0);
    if (std::is_floating_point<T>::value) return static_cast<T>(raw());
    return static_cast<T>(to_uint64());
  }

  constexpr bool is_neg() const noexcept { return detail::negative(raw(), detail::bool_c<S>{}); }
  constexpr bool is_zero() const noexcept { return raw() == 0; }
  constexpr bool operator!() const noexcept { return raw() == 0; }
  constexpr int length() const noexcept { return W; }
  constexpr int countLeadingZeros() const noexcept {
    return fixed_base<W, W, S>::from_raw(raw()).countLeadingZeros();
  }

  constexpr bool operator[](int i) const noexcept {
    return ((static_cast<word>(raw()) >> i) & 1) != 0;
  }
  constexpr detail::bit_ref<int_base> operator[](int i) noexcept { return {this, i}; }
  constexpr bool bit(int i) const noexcept { return (*this)[i]; }
  constexpr detail::bit_ref<int_base> bit(int i) noexcept { return {this, i}; }
  constexpr void set_bit(int i, bool b) noexcept {
    v_ = narrow_raw(static_cast<raw_type>(
        detail::extend<W, S>(detail::assign_bits<word>(static_cast<word>(raw()), i, i, b))));
  }
  constexpr detail::range_ref<int_base> range(int hi, int lo) noexcept { return {this, hi, lo}; }
  constexpr detail::range_ref<const int_base> range(int hi, int lo) const noexcept {
    return {this, hi, lo};
  }
  constexpr detail::range_ref<int_base> range() noexcept { return {this, W - 1, 0}; }
  constexpr detail::range_ref<const int_base> range() const noexcept { return {this, W - 1, 0}; }
  constexpr detail::range_ref<int_base> operator()(int hi, int lo) noexcept {
    return {this, hi, lo};
  }
  constexpr detail::range_ref<const int_base> operator()(int hi, int lo) const noexcept {
    return {this, hi, lo};
  }
  constexpr detail::u128 get_range(int hi, int lo) const noexcept {
    return detail::read_range<W, S>(static_cast<word>(raw()), hi, lo);
  }
  constexpr void set_range(int hi, int lo, detail::u128 x) noexcept {
    v_ = narrow_raw(
        static_cast<raw_type>(detail::write_range<W, S>(static_cast<word>(raw()), hi, lo, x)));
  }

  constexpr int_base operator+() const noexcept { return *this; }
  // ap computes -x as ap_int_base<1, false>(0) - x: W + 1 bits, but 3 for a signed 1-bit x
  // (the unsigned 0 takes an extra bit next to a signed operand).
  static constexpr int neg_width = (S && W == 1) ? 3 : W + 1;
  constexpr int_base<neg_width, true> operator-() const noexcept {
    using U = detail::word_t<neg_width>;
    return detail::make_exact<int_base<neg_width, true>>(U(U(0) - static_cast<U>(raw())));
  }
  constexpr int_base operator~() const noexcept {
    return from_raw(static_cast<raw_type>(~static_cast<word>(raw())));
  }
  constexpr int_base& operator++() noexcept { return *this += 1; }
  constexpr int_base& operator--() noexcept { return *this -= 1; }
  constexpr int_base operator++(int) noexcept {
    const int_base r = *this;
    ++*this;
    return r;
  }
  constexpr int_base operator--(int) noexcept {
    const int_base r = *this;
    --*this;
    return r;
  }

  // Compound assignment with integer operands: full-width result, then wrap.
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value &&
                                         !detail::fixed_type<B>::value> = 0>
  constexpr int_base& operator+=(const B& b) noexcept {
    return *this = detail::binary<detail::op::add>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value &&
                                         !detail::fixed_type<B>::value> = 0>
  constexpr int_base& operator-=(const B& b) noexcept {
    return *this = detail::binary<detail::op::sub>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value &&
                                         !detail::fixed_type<B>::value> = 0>
  constexpr int_base& operator*=(const B& b) noexcept {
    return *this = detail::binary<detail::op::mul>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value &&
                                         !detail::fixed_type<B>::value> = 0>
  constexpr int_base& operator/=(const B& b) noexcept {
    return *this = detail::binary<detail::op::div>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value &&
                                         !detail::fixed_type<B>::value> = 0>
  constexpr int_base& operator%=(const B& b) noexcept {
    return *this = detail::binary<detail::op::mod>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value &&
                                         !detail::fixed_type<B>::value> = 0>
  constexpr int_base& operator&=(const B& b) noexcept {
    return *this = detail::binary<detail::op::band>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value &&
                                         !detail::fixed_type<B>::value> = 0>
  constexpr int_base& operator|=(const B& b) noexcept {
    return *this = detail::binary<detail::op::bor>(*this, b);
  }
  template <class B, detail::enable_if_c<detail::assign_operand<B>::value &&
                                         !detail::fixed_type<B>::value> = 0>
  constexpr int_base& operator^=(const B& b) noexcept {
    return *this = detail::binary<detail::op::bxor>(*this, b);
  }

  template <class T, detail::enable_if_c<detail::shift_operand<T>::value> = 0>
  constexpr int_base operator<<(const T& n) const noexcept {
    return shl(detail::shift_amount(n));
  }
  template <class T, detail::enable_if_c<detail::shift_operand<T>::value> = 0>
  constexpr int_base operator>>(const T& n) const noexcept {
    return shr(detail::shift_amount(n));
  }
  template <class T, detail::enable_if_c<detail::shift_operand<T>::value> = 0>
  constexpr int_base& operator<<=(const T& n) noexcept {
    return *this = shl(detail::shift_amount(n));
  }
  template <class T, detail::enable_if_c<detail::shift_operand<T>::value> = 0>
  constexpr int_base& operator>>=(const T& n) noexcept {
    return *this = shr(detail::shift_amount(n));
  }

#ifndef __SYNTHESIS__
  // Printing (host only), as fixed_base::to_string.
  std::string to_string(int radix = 10) const {
    if (radix == 2 || radix == 16) return fixed_base<W, W, S>::from_raw(raw()).to_string(radix);
    return detail::fixed_to_string<0, S>(raw(), to_double());
  }
#endif

 private:
  template <class T>
  static constexpr raw_type store(T x) noexcept {
    return static_cast<raw_type>(detail::extend<W, S>(static_cast<word>(x)));
  }
  static constexpr raw_type from_double(double d) noexcept {
    // Toward zero on the magnitude, then wrap.
    const detail::double_parts p = detail::decode(d);
    const bool neg = p.m < 0;
    const auto mag = static_cast<detail::u128>(neg ? -p.m : p.m);
    detail::u128 t = 0;
    if (p.fs <= 0) {
      t = -p.fs >= 128 ? detail::u128(0) : mag << -p.fs;
    } else {
      t = p.fs >= 128 ? detail::u128(0) : mag >> p.fs;
    }
    return store(neg ? detail::u128(detail::u128(0) - t) : t);
  }
  constexpr int_base shl(std::int64_t n) const noexcept {
    if (n < 0) return shr(-n);
    if (n >= W) return from_raw(0);
    return from_raw(static_cast<raw_type>(static_cast<word>(raw()) << n));
  }
  constexpr int_base shr(std::int64_t n) const noexcept {
    if (n < 0) return shl(-n);
    if (n >= W) return from_raw(is_neg() ? static_cast<raw_type>(~word(0)) : raw_type(0));
    return from_raw(static_cast<raw_type>(raw() >> n));
  }

  // raw_type -> storage: exact, since every stored V is canonical in W bits (detail::store_t).
  static constexpr store_type narrow_raw(raw_type v) noexcept { return static_cast<store_type>(v); }

  store_type v_ = 0;
};

// =============================================================================================
// Binary operators (sections 5, 6, 12): exact in the widened result type.
// =============================================================================================
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr auto operator+(const A& a, const B& b) noexcept {
  return detail::binary<detail::op::add>(a, b);
}
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr auto operator-(const A& a, const B& b) noexcept {
  return detail::binary<detail::op::sub>(a, b);
}
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr auto operator*(const A& a, const B& b) noexcept {
  return detail::binary<detail::op::mul>(a, b);
}
// Division by zero is undefined (ap and ac simulation crash with SIGFPE).
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr auto operator/(const A& a, const B& b) noexcept {
  return detail::binary<detail::op::div>(a, b);
}
template <class A, class B,
          detail::enable_if_c<detail::operands<A, B>::value && !detail::fixed_type<A>::value &&
                              !detail::fixed_type<B>::value> = 0>
constexpr auto operator%(const A& a, const B& b) noexcept {
  return detail::binary<detail::op::mod>(a, b);
}
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr auto operator&(const A& a, const B& b) noexcept {
  return detail::binary<detail::op::band>(a, b);
}
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr auto operator|(const A& a, const B& b) noexcept {
  return detail::binary<detail::op::bor>(a, b);
}
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr auto operator^(const A& a, const B& b) noexcept {
  return detail::binary<detail::op::bxor>(a, b);
}

// ---- Concatenation: not supported, and refused at compile time. ap overloads the comma
// operator as bit concatenation on ap_int_base, range and bit references (ap_range_ref,
// af_range_ref, ap_bit_ref, af_bit_ref) and C integers next to one of them
// (ap_int_base.h, ap_int_ref.h, ap_fixed_ref.h): (a.range(7, 0), b.range(7, 0)) is a 16-bit
// value there. Without an overload C++ would take the built-in comma and silently yield the
// right operand, so every pair ap concatenates selects this deleted overload instead. Pairs
// ap does not concatenate either (two fixed values, a fixed and an integer) keep the
// built-in comma in both.
namespace detail {
template <class T>
struct concat_part : bool_c<false> {};
template <int W, bool S>
struct concat_part<int_base<W, S>> : bool_c<true> {};
template <class Owner>
struct concat_part<range_ref<Owner>> : bool_c<true> {};
template <class Owner>
struct concat_part<bit_ref<Owner>> : bool_c<true> {};
template <class A, class B>
struct concatenation
    : bool_c<(concat_part<A>::value || concat_part<B>::value) &&
             (concat_part<A>::value || std::is_integral<A>::value) &&
             (concat_part<B>::value || std::is_integral<B>::value)> {};
}  // namespace detail
template <class A, class B,
          detail::enable_if_c<detail::concatenation<detail::remove_cvref_t<A>,
                                                    detail::remove_cvref_t<B>>::value> = 0>
void operator,(A&&, B&&) = delete;  // concatenation (ap's (a, b)) is not supported

// ---- Comparisons (section 8): exact for equal signedness; mixed signedness follows ap's
// C-conversion rules. Comparisons with double go through to_double().
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr bool operator==(const A& a, const B& b) noexcept {
  return detail::equal(a, b);
}
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr bool operator!=(const A& a, const B& b) noexcept {
  return !detail::equal(a, b);
}
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr bool operator<(const A& a, const B& b) noexcept {
  return detail::relation<detail::rel_lt>(a, b);
}
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr bool operator<=(const A& a, const B& b) noexcept {
  return detail::relation<detail::rel_le>(a, b);
}
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr bool operator>(const A& a, const B& b) noexcept {
  return detail::relation<detail::rel_gt>(a, b);
}
template <class A, class B, detail::enable_if_c<detail::operands<A, B>::value> = 0>
constexpr bool operator>=(const A& a, const B& b) noexcept {
  return detail::relation<detail::rel_ge>(a, b);
}

template <class A, detail::enable_if_c<detail::ap_type<A>::value> = 0>
constexpr bool operator==(const A& a, double d) noexcept {
  return a.to_double() == d;
}
template <class A, detail::enable_if_c<detail::ap_type<A>::value> = 0>
constexpr bool operator!=(const A& a, double d) noexcept {
  return a.to_double() != d;
}
template <class A, detail::enable_if_c<detail::ap_type<A>::value> = 0>
constexpr bool operator<(const A& a, double d) noexcept {
  return a.to_double() < d;
}
template <class A, detail::enable_if_c<detail::ap_type<A>::value> = 0>
constexpr bool operator<=(const A& a, double d) noexcept {
  return a.to_double() <= d;
}
template <class A, detail::enable_if_c<detail::ap_type<A>::value> = 0>
constexpr bool operator>(const A& a, double d) noexcept {
  return a.to_double() > d;
}
template <class A, detail::enable_if_c<detail::ap_type<A>::value> = 0>
constexpr bool operator>=(const A& a, double d) noexcept {
  return a.to_double() >= d;
}
template <class A, detail::enable_if_c<detail::ap_type<A>::value> = 0>
constexpr bool operator==(double d, const A& a) noexcept {
  return d == a.to_double();
}
template <class A, detail::enable_if_c<detail::ap_type<A>::value> = 0>
constexpr bool operator!=(double d, const A& a) noexcept {
  return d != a.to_double();
}
template <class A, detail::enable_if_c<detail::ap_type<A>::value> = 0>
constexpr bool operator<(double d, const A& a) noexcept {
  return d < a.to_double();
}
template <class A, detail::enable_if_c<detail::ap_type<A>::value> = 0>
constexpr bool operator<=(double d, const A& a) noexcept {
  return d <= a.to_double();
}
template <class A, detail::enable_if_c<detail::ap_type<A>::value> = 0>
constexpr bool operator>(double d, const A& a) noexcept {
  return d > a.to_double();
}
template <class A, detail::enable_if_c<detail::ap_type<A>::value> = 0>
constexpr bool operator>=(double d, const A& a) noexcept {
  return d >= a.to_double();
}

#ifndef __SYNTHESIS__
// ---- Printing (host only): exact decimal value.
template <int W, int I, bool S, q_mode Q, o_mode O, int N>
std::ostream& operator<<(std::ostream& os, const fixed_base<W, I, S, Q, O, N>& x) {
  return os << x.to_string();
}
template <int W, bool S>
std::ostream& operator<<(std::ostream& os, const int_base<W, S>& x) {
  return os << x.to_string();
}
#endif

#if __cplusplus < 201703L
// Before C++17 a static constexpr data member that is odr-used (bound to a reference, as by
// std::min or a test macro) needs a definition at namespace scope; from C++17 on the members
// are inline and these would be redundant (deprecated).
template <int W, int I, bool S, q_mode Q, o_mode O, int N>
constexpr int fixed_base<W, I, S, Q, O, N>::width;
template <int W, int I, bool S, q_mode Q, o_mode O, int N>
constexpr int fixed_base<W, I, S, Q, O, N>::iwidth;
template <int W, int I, bool S, q_mode Q, o_mode O, int N>
constexpr q_mode fixed_base<W, I, S, Q, O, N>::qmode;
template <int W, int I, bool S, q_mode Q, o_mode O, int N>
constexpr o_mode fixed_base<W, I, S, Q, O, N>::omode;
template <int W, int I, bool S, q_mode Q, o_mode O, int N>
constexpr int fixed_base<W, I, S, Q, O, N>::nbits;
template <int W, int I, bool S, q_mode Q, o_mode O, int N>
constexpr bool fixed_base<W, I, S, Q, O, N>::is_signed;
template <int W, bool S>
constexpr int int_base<W, S>::width;
template <int W, bool S>
constexpr int int_base<W, S>::neg_width;
template <int W, bool S>
constexpr bool int_base<W, S>::is_signed;
#endif

}  // namespace hls
}  // namespace voxcast
