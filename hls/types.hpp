// The one header the voxcast kernels include for their fixed-point and integer types.
//
// By default it uses voxcast's own bit-exact clone of ap_fixed (hls/fixed_point.hpp); with
// -DVOXCAST_VENDOR_TYPES it maps the same names onto AMD's ap_fixed / ap_ufixed / ap_int /
// ap_uint (<ap_fixed.h>, <ap_int.h> from Vitis HLS or Xilinx/HLS_arbitrary_Precision_Types), with
// -DVOXCAST_AC_TYPES onto Siemens Catapult's ac_fixed / ac_int (<ac_fixed.h>, <ac_int.h>).
// CMake: VOXCAST_FIXED_TYPES = clone | xilinx | catapult. See docs/fixed-point.md.
// This header is C++14 (Vitis HLS's front end): no inline variables, if constexpr or concepts.
//
// Kernels may only use the API all three provide with the same results (anything else compiles
// with one and not another, or behaves differently: docs/fixed-point.md, "Catapult's ac_fixed"):
//
//   Types      fixed<W, I, Q = TRN, O = WRAP>, ufixed<...>, int_t<W>, uint_t<W>
//              q_mode: RND, RND_ZERO, RND_MIN_INF, RND_INF, RND_CONV, TRN, TRN_ZERO
//              o_mode: SAT, SAT_ZERO, SAT_SYM, WRAP
//              (WRAP_SM and the saturation bits N > 0: clone and ap only; ac has neither.)
//              W <= 128 for every type, operator results included (clone limit).
//   Create     default construction (value unspecified: always assign before reading);
//              construction / assignment from fixed, ufixed, int_t, uint_t, C integers,
//              double and float (quantization and overflow of the destination apply).
//              An int_t / uint_t from a fixed: int_cast<T>(x) (toward zero, then wrap).
//   Arithmetic a + b, a - b, a * b, a / b, a & b, a | b, a ^ b where each operand is a
//              fixed/ufixed/int_t/uint_t or a C integer (never double/float: ill-formed;
//              never a C integer / fixed or int_t: ap sim wraps the quotient);
//              a % b between integer types only; -a, !a; ~a on signed types (on unsigned
//              ones ac widens to a signed W+1-bit result: use only assigned straight into a
//              W-bit unsigned); +=, -=, *=, /=, &=, |=, ^= with the same operands; ++/-- on
//              int_t/uint_t only (on a fixed ap adds 1.0, ac one LSB);
//              a << n, a >> n, <<=, >>= with n an int, unsigned, int_t or uint_t.
//              Result types of fixed expressions are fixed/ufixed-like in all three, of
//              integer-only expressions not (int_t<>, ap_int_base<>, ac_int<>): never name
//              them, use auto or assign to a declared type.
//   Compare    == != < <= > >= between the operand kinds above; between a signed and an
//              unsigned operand only when the signed one cannot be negative or both are
//              narrower than 32 bits (ap applies C's unsigned conversion, ac compares
//              values); with double only when W <= 53.
//   Convert    x.to_double(), to_int(), to_uint(), to_int64(), to_uint64(); to_long(),
//              to_ulong() on int_t/uint_t only (ap_fixed has neither); on a fixed the
//              to_int() family only when x is non-negative or integer-valued (ap truncates
//              toward zero, ac floors). No static_cast of a fixed to a C type (ac_fixed has
//              no conversion operators).
//   Bits       x[i] (read; write with = bool); read_bits(x, hi, lo), write_bits(x, hi, lo,
//              v): bits hi..lo (hi >= lo, at most 64) as / from a std::uint64_t, raw (no
//              quantization or overflow; a signed x re-extends its sign); read_bits(x),
//              write_bits(x, v): all T::width <= 64 bits. No concatenation (a, b): ap
//              concatenates ints, ranges and bits, the clone refuses it at compile time.
//   Queries    T::width, x.length(); fixed_iwidth<T>::value (I of a fixed type). The sign of
//              a fixed: x < 0 (ac_fixed's is_neg() is private). leading_zeros(x): the
//              leading zeros of the W-bit pattern (W for 0; ap countLeadingZeros, ac
//              leading_sign of the unsigned pattern).
//   Print      std::ostream << x.to_double().
//
// Clone and ap only (not ac): x.range(...), x.bit(i), x.get_bit(i), setBits, bitsToFixed,
// is_neg(), is_zero(), wl(), iwl(), countLeadingZeros(), getNeg(), lshift<K>(), rshift<K>(),
// T::iwidth, T::qmode, T::omode, to_float(), to_string(10), implicit/static_cast conversions.
// Clone-only (tests and tools, never kernels): fixed_base, int_base, raw(), from_raw(),
// get_range(), set_range(), set_bit(), nbits, is_signed, max_width, to_string() without radix.
#pragma once

#include <cstdint>

#if defined(VOXCAST_VENDOR_TYPES) && defined(VOXCAST_AC_TYPES)
#error "define at most one of VOXCAST_VENDOR_TYPES (Xilinx ap_fixed) and VOXCAST_AC_TYPES (Catapult ac_fixed)"
#endif

#if defined(VOXCAST_VENDOR_TYPES)

#include <ap_fixed.h>
#include <ap_int.h>

namespace voxcast {
namespace hls {

using q_mode = ::ap_q_mode;
using o_mode = ::ap_o_mode;

// Map by name (semantics section 1: same enumerators, same order). Namespace-scope
// constexpr (internal linkage): C++14 has no inline variables.
constexpr q_mode RND = AP_RND;
constexpr q_mode RND_ZERO = AP_RND_ZERO;
constexpr q_mode RND_MIN_INF = AP_RND_MIN_INF;
constexpr q_mode RND_INF = AP_RND_INF;
constexpr q_mode RND_CONV = AP_RND_CONV;
constexpr q_mode TRN = AP_TRN;
constexpr q_mode TRN_ZERO = AP_TRN_ZERO;
constexpr o_mode SAT = AP_SAT;
constexpr o_mode SAT_ZERO = AP_SAT_ZERO;
constexpr o_mode SAT_SYM = AP_SAT_SYM;
constexpr o_mode WRAP = AP_WRAP;
constexpr o_mode WRAP_SM = AP_WRAP_SM;

template <int W, int I, q_mode Q = TRN, o_mode O = WRAP, int N = 0>
using fixed = ::ap_fixed<W, I, Q, O, N>;
template <int W, int I, q_mode Q = TRN, o_mode O = WRAP, int N = 0>
using ufixed = ::ap_ufixed<W, I, Q, O, N>;
template <int W>
using int_t = ::ap_int<W>;
template <int W>
using uint_t = ::ap_uint<W>;

}  // namespace hls
}  // namespace voxcast

#elif defined(VOXCAST_AC_TYPES)

#include <ac_fixed.h>
#include <ac_int.h>

namespace voxcast {
namespace hls {

using q_mode = ::ac_q_mode;
using o_mode = ::ac_o_mode;

// Map by meaning: ac's enumerators have other names and another order (AC_TRN is 0, AP_RND
// is 0). ac has no WRAP_SM and no saturation-bit count N (below).
constexpr q_mode RND = AC_RND;
constexpr q_mode RND_ZERO = AC_RND_ZERO;
constexpr q_mode RND_MIN_INF = AC_RND_MIN_INF;
constexpr q_mode RND_INF = AC_RND_INF;
constexpr q_mode RND_CONV = AC_RND_CONV;
constexpr q_mode TRN = AC_TRN;
constexpr q_mode TRN_ZERO = AC_TRN_ZERO;
constexpr o_mode SAT = AC_SAT;
constexpr o_mode SAT_ZERO = AC_SAT_ZERO;
constexpr o_mode SAT_SYM = AC_SAT_SYM;
constexpr o_mode WRAP = AC_WRAP;

namespace ac_detail {
// ap's N (saturation bits of WRAP) has no ac counterpart: only N = 0 maps.
template <o_mode O, int N>
struct o_mode_of {
  static_assert(N == 0, "voxcast::hls::fixed/ufixed with N != 0 (WRAP with saturation bits): "
                        "Catapult's ac_fixed has no N; kernels must use N = 0");
  static constexpr o_mode value = O;
};
}  // namespace ac_detail

template <int W, int I, q_mode Q = TRN, o_mode O = WRAP, int N = 0>
using fixed = ::ac_fixed<W, I, true, Q, ac_detail::o_mode_of<O, N>::value>;
template <int W, int I, q_mode Q = TRN, o_mode O = WRAP, int N = 0>
using ufixed = ::ac_fixed<W, I, false, Q, ac_detail::o_mode_of<O, N>::value>;
template <int W>
using int_t = ::ac_int<W, true>;
template <int W>
using uint_t = ::ac_int<W, false>;

// Bit fields (ac has slc<W>(lsb) / set_slc(lsb, ac_int) instead of ap's range(hi, lo)). The
// pattern of a value is its W bits as an ac_int<W, false>; fields are read and written there.
namespace ac_detail {
template <int W, bool S>
inline ::ac_int<W, false> pattern(const ::ac_int<W, S>& x) {
  return x;
}
template <int W, int I, bool S, q_mode Q, o_mode O>
inline ::ac_int<W, false> pattern(const ::ac_fixed<W, I, S, Q, O>& x) {
  return x.template slc<W>(0);
}
template <int W, bool S>
inline void set_pattern(::ac_int<W, S>& x, const ::ac_int<W, false>& p) {
  x.set_slc(0, p);
}
template <int W, int I, bool S, q_mode Q, o_mode O>
inline void set_pattern(::ac_fixed<W, I, S, Q, O>& x, const ::ac_int<W, false>& p) {
  x.set_slc(0, p);  // raw: no quantization, no overflow handling; re-extends the sign
}
inline std::uint64_t low_mask(int n) {
  return n >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1;
}
}  // namespace ac_detail

template <class T>
inline std::uint64_t read_bits(const T& x, int hi, int lo) {
  return ac_detail::pattern(x).template slc<64>(lo).to_uint64() & ac_detail::low_mask(hi - lo + 1);
}
template <class T>
inline void write_bits(T& x, int hi, int lo, std::uint64_t v) {
  auto p = ac_detail::pattern(x);
  using P = decltype(p);
  const P mask = P(ac_detail::low_mask(hi - lo + 1)) << lo;
  p = (p & mask.bit_complement()) | ((P(v) << lo) & mask);
  ac_detail::set_pattern(x, p);
}

// int_t / uint_t from a fixed: ap's int_t<W>(x) truncates toward zero, then wraps to W bits;
// ac_int has no constructor from ac_fixed (and to_ac_int() floors).
template <class T, int W, int I, bool S, q_mode Q, o_mode O>
inline T int_cast(const ::ac_fixed<W, I, S, Q, O>& x) {
  constexpr int IW = I > 1 ? I : 1;
  const ::ac_fixed<IW, IW, S, AC_TRN_ZERO, AC_WRAP> t = x;  // toward zero: no overflow
  return T(t.template slc<IW>(0));
}
template <class T, int W, bool S>
inline T int_cast(const ::ac_int<W, S>& x) {
  return T(x);
}

// The integer bits I of a fixed type (ac_fixed calls it i_width, ap_fixed iwidth).
template <class T>
struct fixed_iwidth {
  static constexpr int value = T::i_width;
};

// Leading zeros of x's W-bit pattern (W for 0): ac's leading_sign() of the unsigned pattern.
template <class T>
inline int leading_zeros(const T& x) {
  return ac_detail::pattern(x).leading_sign().to_int();
}

}  // namespace hls
}  // namespace voxcast

#else

#include "hls/fixed_point.hpp"

#endif

#if !defined(VOXCAST_AC_TYPES)
// The clone and ap: bit fields are range(hi, lo) proxies.
namespace voxcast {
namespace hls {
template <class T>
inline std::uint64_t read_bits(const T& x, int hi, int lo) {
  return x.range(hi, lo).to_uint64();
}
template <class T>
inline void write_bits(T& x, int hi, int lo, std::uint64_t v) {
  x.range(hi, lo) = v;
}
template <class T, class F>
inline T int_cast(const F& x) {
  return T(x);
}
template <class T>
struct fixed_iwidth {
  static constexpr int value = T::iwidth;
};
// Leading zeros of x's W-bit pattern (W for 0; W <= 64): countLeadingZeros(), which ap
// declares non-const (hence the copy).
template <class T>
inline int leading_zeros(const T& x) {
  T t = x;
  return t.countLeadingZeros();
}
}  // namespace hls
}  // namespace voxcast
#endif

// The whole pattern of x (T::width <= 64 bits) as an unsigned integer, and written from one.
namespace voxcast {
namespace hls {
template <class T>
inline std::uint64_t read_bits(const T& x) {
  static_assert(T::width <= 64, "read_bits(x): x has more than 64 bits");
  return read_bits(x, T::width - 1, 0);
}
template <class T>
inline void write_bits(T& x, std::uint64_t v) {
  static_assert(T::width <= 64, "write_bits(x, v): x has more than 64 bits");
  write_bits(x, T::width - 1, 0, v);
}
}  // namespace hls
}  // namespace voxcast
