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

#else

#include "hls/fixed_point.hpp"

#endif
