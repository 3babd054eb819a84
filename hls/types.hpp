// The one header the voxcast kernels include for their fixed-point and integer types.
//
// Without VOXCAST_VENDOR_TYPES it uses voxcast's own bit-exact clone (hls/fixed_point.hpp);
// with -DVOXCAST_VENDOR_TYPES it maps the same names onto AMD's ap_fixed / ap_ufixed / ap_int /
// ap_uint (<ap_fixed.h>, <ap_int.h> from Vitis HLS or Xilinx/HLS_arbitrary_Precision_Types).
// See docs/fixed-point.md.
//
// Kernels may only use the API both provide (anything else compiles with one and not the
// other, or behaves differently):
//
//   Types      fixed<W, I, Q = TRN, O = WRAP, N = 0>, ufixed<...>, int_t<W>, uint_t<W>
//              q_mode: RND, RND_ZERO, RND_MIN_INF, RND_INF, RND_CONV, TRN, TRN_ZERO
//              o_mode: SAT, SAT_ZERO, SAT_SYM, WRAP, WRAP_SM (signed fixed only)
//              W <= 128 for every type, operator results included (clone limit).
//   Create     default construction (value unspecified: always assign before reading);
//              construction / assignment from fixed, ufixed, int_t, uint_t, C integers,
//              double and float (quantization and overflow of the destination apply).
//   Arithmetic a + b, a - b, a * b, a / b, a & b, a | b, a ^ b where each operand is a
//              fixed/ufixed/int_t/uint_t or a C integer (never double/float: ill-formed in
//              both); a % b between integer types only; -a, ~a, !a; +=, -=, *=, /=, &=, |=,
//              ^= with the same operands; ++/-- (fixed: only when I <= W);
//              a << n, a >> n, <<=, >>= with n an int, unsigned, int_t or uint_t.
//              Result types of fixed expressions are fixed<...>/ufixed<...> in both; result
//              types of integer-only expressions differ (ap_int_base<> vs int_t<>), so never
//              name them: use auto or assign to a declared type.
//   Compare    == != < <= > >= between the operand kinds above, and with double.
//   Convert    x.to_double(), to_float(), to_int(), to_uint(), to_int64(), to_uint64(),
//              to_long(), to_ulong(); static_cast<double / float / int / bool / ...>(x).
//              (The clone has no implicit conversions to C types; ap has them.)
//   Bits       x[i], x.bit(i) (read; write with = bool); x.get_bit(i) on fixed (read);
//              x.range(hi, lo), x.range(), x(hi, lo): read with .to_uint64(), .to_uint(),
//              .to_int(), .to_int64(), .length(); write with = <C integer or int_t/uint_t>
//              or = <another range>. x.setBits(u64), T::bitsToFixed(u64) on fixed.
//   Queries    T::width; on fixed also T::iwidth, T::qmode, T::omode, x.is_neg(),
//              x.is_zero(), x.wl(), x.iwl(); x.length(); x.countLeadingZeros(); x.getNeg()
//              and x.lshift<K>() / x.rshift<K>() on fixed.
//   Print      std::ostream << x (the clone prints the exact decimal value, ap rounds to the
//              stream precision); x.to_string(10).
//
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
