// One engine of the differential test: the operations of tests/differential/differential.hpp on
// hls/types.hpp's mapping selected by the compile definitions (none: the clone;
// VOXCAST_VENDOR_TYPES: Xilinx ap_fixed; VOXCAST_AC_TYPES: Catapult ac_fixed), for the pairs of
// pairs.hpp whose index is VOXCAST_DIFF_CHUNK modulo VOXCAST_DIFF_CHUNKS. The same source for
// every engine: only the kernels' common API (hls/types.hpp's list, its bridges included), plus
// reading and writing raw patterns, the result types' W/I/signedness, and range() (clone and ap).
//
// One mapping per translation unit, as in the kernels' builds: voxcast::hls names the engine's
// types here and the clone's in another object of the same program; this file defines nothing
// in voxcast::hls and keeps its own code in a namespace of its engine and chunk.
#include <cmath>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>

#include "hls/types.hpp"
#include "tests/differential/differential.hpp"
#include "tests/differential/pairs.hpp"

#if defined(VOXCAST_AC_TYPES)
#define VOXCAST_DIFF_ENGINE ac
#define VOXCAST_DIFF_ENGINE_NAME "ac"
#elif defined(VOXCAST_VENDOR_TYPES)
#define VOXCAST_DIFF_ENGINE ap
#define VOXCAST_DIFF_ENGINE_NAME "ap"
#else
#define VOXCAST_DIFF_ENGINE clone
#define VOXCAST_DIFF_ENGINE_NAME "clone"
#endif
#ifndef VOXCAST_DIFF_CHUNK
#define VOXCAST_DIFF_CHUNK 0
#define VOXCAST_DIFF_CHUNKS 1
#endif
#define VOXCAST_DIFF_CAT2(a, b, c) a##_##b##_##c
#define VOXCAST_DIFF_CAT(a, b, c) VOXCAST_DIFF_CAT2(a, b, c)
#define VOXCAST_DIFF_NS VOXCAST_DIFF_CAT(engine, VOXCAST_DIFF_ENGINE, VOXCAST_DIFF_CHUNK)

namespace voxcast_diff {
namespace VOXCAST_DIFF_NS {

namespace H = voxcast::hls;

// ---- Modes by meaning (hls/types.hpp's constants) ---------------------------------------------
constexpr H::q_mode q_of(int q) {
  return q == kRND         ? H::RND
         : q == kRND_ZERO  ? H::RND_ZERO
         : q == kRND_MIN_INF ? H::RND_MIN_INF
         : q == kRND_INF   ? H::RND_INF
         : q == kRND_CONV  ? H::RND_CONV
         : q == kTRN       ? H::TRN
                           : H::TRN_ZERO;
}
#if defined(VOXCAST_AC_TYPES)
constexpr bool has_wrap_sm = false;
constexpr H::o_mode o_of(int o) {
  return o == kSAT ? H::SAT : o == kSAT_ZERO ? H::SAT_ZERO : o == kSAT_SYM ? H::SAT_SYM : H::WRAP;
}
#else
constexpr bool has_wrap_sm = true;
constexpr H::o_mode o_of(int o) {
  return o == kSAT        ? H::SAT
         : o == kSAT_ZERO ? H::SAT_ZERO
         : o == kSAT_SYM  ? H::SAT_SYM
         : o == kWRAP     ? H::WRAP
                          : H::WRAP_SM;
}
#endif

// Whether this engine has the descriptor's type (ac: no WRAP_SM, no N).
template <class D>
constexpr bool supported() {
  return has_wrap_sm || (D::O != kWRAP_SM && D::N == 0);
}

template <class D, bool IsInt = D::is_int, bool S = D::S>
struct type_of;
template <class D>
struct type_of<D, false, true> {
  using type = H::fixed<D::W, D::I, q_of(D::Q), o_of(D::O), D::N>;
};
template <class D>
struct type_of<D, false, false> {
  using type = H::ufixed<D::W, D::I, q_of(D::Q), o_of(D::O), D::N>;
};
template <class D>
struct type_of<D, true, true> {
  using type = H::int_t<D::W>;
};
template <class D>
struct type_of<D, true, false> {
  using type = H::uint_t<D::W>;
};
template <class D>
using type_t = typename type_of<D>::type;

// ---- Raw patterns in and out, result types (engine-specific) ----------------------------------
inline u128 extend(u128 bits, int w, bool s) {
  if (w >= 128) return bits;
  const u128 mask = (u128(1) << w) - 1;
  bits &= mask;
  if (s && ((bits >> (w - 1)) & 1) != 0) bits |= ~mask;
  return bits;
}
inline result value_of(char kind, u128 bits, int w, int i, bool s) {
  result r;
  r.present = true;
  r.kind = kind;
  r.bits = extend(bits, w, s);
  r.w = w;
  r.i = i;
  r.s = s;
  return r;
}

#if defined(VOXCAST_AC_TYPES)
template <int W, bool S>
u128 int_bits(const ac_int<W, S>& x) {
  const u128 lo = static_cast<std::uint64_t>(x.to_uint64());
  if (W <= 64) return lo;
  const ac_int<W, S> hi = x >> 64;
  return (static_cast<u128>(static_cast<std::uint64_t>(hi.to_uint64())) << 64) | lo;
}
template <int W, bool S>
result cap(const ac_int<W, S>& x) {
  return value_of('i', int_bits(x), W, W, S);
}
template <int W, int I, bool S, ac_q_mode Q, ac_o_mode O>
result cap(const ac_fixed<W, I, S, Q, O>& x) {
  return value_of('f', int_bits(x.template slc<W>(0)), W, I, S);
}
template <int W>
ac_int<W, false> pattern(u128 bits) {
  ac_int<W, false> p = static_cast<std::uint64_t>(bits >> 64);
  p <<= 64;
  p |= ac_int<W, false>(static_cast<std::uint64_t>(bits));
  return p;
}
template <class T>
T make(u128 bits) {
  T x = 0;
  x.set_slc(0, pattern<T::width>(bits));
  return x;
}
#elif defined(VOXCAST_VENDOR_TYPES)
template <int W, bool S>
u128 int_bits(const ap_int_base<W, S>& x) {
  ap_int_base<W, false> u;
  u.V = x.V;
  const u128 lo = static_cast<std::uint64_t>(u.to_uint64());
  if (W <= 64) return lo;
  const ap_int_base<W, false> hi = u >> 64;
  return (static_cast<u128>(static_cast<std::uint64_t>(hi.to_uint64())) << 64) | lo;
}
template <int W, bool S>
result cap(const ap_int_base<W, S>& x) {
  return value_of('i', int_bits(x), W, W, S);
}
template <int W, int I, bool S, ap_q_mode Q, ap_o_mode O, int N>
result cap(const ap_fixed_base<W, I, S, Q, O, N>& x) {
  ap_int_base<W, S> p;
  p.V = x.V;
  return value_of('f', int_bits(p), W, I, S);
}
template <int W>
ap_int_base<W, false> pattern(u128 bits) {
  ap_int_base<W, false> p = static_cast<unsigned long long>(bits >> 64);
  p <<= 64;
  p |= ap_int_base<W, false>(static_cast<unsigned long long>(bits));
  return p;
}
template <class T>
T make(u128 bits) {
  T x = 0;
  x.V = pattern<T::width>(bits).V;
  return x;
}
#else
template <int W, bool S>
result cap(const H::int_base<W, S>& x) {
  return value_of('i', static_cast<u128>(x.raw()), W, W, S);
}
template <int W, int I, bool S, H::q_mode Q, H::o_mode O, int N>
result cap(const H::fixed_base<W, I, S, Q, O, N>& x) {
  return value_of('f', static_cast<u128>(x.raw()), W, I, S);
}
template <class T>
T make(u128 bits) {
  return T::from_raw(static_cast<typename T::raw_type>(bits));
}
#endif

// C scalars.
inline result cap(bool b) { return value_of('b', b ? 1 : 0, 1, 1, false); }
template <class T, std::enable_if_t<std::is_integral<T>::value, int> = 0>
result cap(T x) {
  constexpr int w = static_cast<int>(sizeof(T) * 8);
  return value_of('n', static_cast<u128>(x), w, w, std::is_signed<T>::value);
}
inline result cap(const std::string& t) {
  result r = value_of('s', 0, 1, 1, false);
  r.text = t;
  return r;
}
inline result cap(double d) {
  std::uint64_t b = 0;
  std::memcpy(&b, &d, sizeof b);
  return value_of('d', b, 64, 64, false);
}

// ---- Result widths (semantics section 5): the clone's limit is 128 bits -----------------------
template <class A, class B>
struct widths {
  static constexpr int f1 = A::W - A::I, f2 = B::W - B::I;
  static constexpr int ia = A::I + ((B::S && !A::S) ? 1 : 0);
  static constexpr int ib = B::I + ((A::S && !B::S) ? 1 : 0);
  static constexpr int fm = f1 > f2 ? f1 : f2, im = ia > ib ? ia : ib;
  static constexpr bool add = im + 1 + fm <= 128;
  static constexpr bool mul = A::W + B::W <= 128;
  static constexpr bool div = A::W + (f2 > 0 ? f2 : 0) + (B::S ? 1 : 0) <= 128;
  static constexpr bool logic = im + fm <= 128;
  // -(a / b): one bit more than the quotient
  static constexpr bool neg_div = A::W + (f2 > 0 ? f2 : 0) + (B::S ? 1 : 0) + 1 <= 128;
};
using c_int = in<32, true>;
using c_uint = in<32, false>;

template <class T>
using is_fixed_type = std::integral_constant<bool, !std::is_integral<T>::value>;

// An integer type from any operand: int_cast for a fixed source (ac_int has no constructor from
// ac_fixed, hls/types.hpp), a plain conversion otherwise.
template <class T, class DS, class S>
T to_type(const S& x, std::true_type /* T is an integer type */) {
  if constexpr (DS::is_int) {
    return T(x);
  } else {
    return H::int_cast<T>(x);
  }
}
template <class T, class DS, class S>
T to_type(const S& x, std::false_type) {
  return T(x);
}
template <class DT, class DS, class S>
type_t<DT> convert(const S& x) {
  return to_type<type_t<DT>, DS>(x, std::integral_constant<bool, DT::is_int>{});
}

// ---- The operations of one pair ----------------------------------------------------------------
template <class P>
void eval_pair(const inputs& in, outputs& out) {
  using DA = typename P::A;
  using DB = typename P::B;
  using A = type_t<DA>;
  using B = type_t<DB>;
  using WD = widths<DA, DB>;
  using WC = widths<DA, c_int>;
  using CW = widths<c_int, DA>;
  constexpr bool full = P::kind == kFull;
  constexpr bool ints = DA::is_int && DB::is_int;
  constexpr bool a_int = DA::is_int;
  const A a = make<A>(in.a);
  const B b = make<B>(in.b);
  const int ci = static_cast<int>(in.c);
  const unsigned cu = static_cast<unsigned>(in.c);
  auto put = [&](int o, const auto& v) { out.r[o] = cap(v); };

  // Binary operators (exact in their result types), with the operand types and with an int.
  if constexpr (full) {
    if constexpr (WD::add) {
      put(op_add, a + b);
      put(op_sub, a - b);
    }
    if constexpr (WD::mul) put(op_mul, a * b);
    if constexpr (WD::div) {
      if (in.b != 0) put(op_div, a / b);
    }
    if constexpr (WD::logic) {
      put(op_band, a & b);
      put(op_bor, a | b);
      put(op_bxor, a ^ b);
    }
    if constexpr (ints) {
      if (in.b != 0) put(op_mod, a % b);
    }
    if constexpr (WC::add) {
      put(op_add_c, a + ci);
      put(op_c_sub, ci - a);
    }
    if constexpr (WC::mul) put(op_mul_c, a * ci);
    if constexpr (WC::div) {
      if (ci != 0) put(op_div_c, a / ci);
    }
    if constexpr (CW::div) {
      if (in.a != 0) put(op_c_div, ci / a);
    }
    if constexpr (WC::logic) put(op_band_c, a & ci);
  }

  // Compound assignments: the exact result, then one conversion into A (A's modes). An integer
  // type takes integer operands only (int_t += fixed does not compile with the clone).
  if constexpr (!(a_int && !DB::is_int)) {
    if constexpr (WD::add) {
      A t = a;
      t += b;
      put(op_add_assign, t);
      t = a;
      t -= b;
      put(op_sub_assign, t);
    }
    if constexpr (WD::mul) {
      A t = a;
      t *= b;
      put(op_mul_assign, t);
    }
    if constexpr (full && WD::div) {
      if (in.b != 0) {
        A t = a;
        t /= b;
        put(op_div_assign, t);
      }
    }
    if constexpr (full && WD::logic) {
      A t = a;
      t &= b;
      put(op_and_assign, t);
      t = a;
      t |= b;
      put(op_or_assign, t);
      t = a;
      t ^= b;
      put(op_xor_assign, t);
    }
    if constexpr (full && ints) {
      if (in.b != 0) {
        A t = a;
        t %= b;
        put(op_mod_assign, t);
      }
    }
  }
  if constexpr (WC::add) {
    A t = a;
    t += ci;
    put(op_add_assign_c, t);
  }
  if constexpr (full && WC::mul) {
    A t = a;
    t *= ci;
    put(op_mul_assign_c, t);
  }

  // Comparisons, both operand orders (ap widens the right operand with its own modes: the
  // mode pairs keep the orders with A on the right).
  put(op_eq, a == b);
  put(op_lt, a < b);
  put(op_eq_ba, b == a);
  put(op_lt_ba, b < a);
  put(op_le_ba, b <= a);
  put(op_gt_ba, b > a);
  put(op_c_eq, ci == a);
  put(op_c_lt, ci < a);
  put(op_u_eq, cu == a);
  if constexpr (full) {
    put(op_ne, a != b);
    put(op_le, a <= b);
    put(op_gt, a > b);
    put(op_ge, a >= b);
    put(op_ne_ba, b != a);
    put(op_ge_ba, b >= a);
    put(op_eq_c, a == ci);
    put(op_lt_c, a < ci);
    put(op_gt_c, a > ci);
    put(op_c_ge, ci >= a);
    put(op_eq_u, a == cu);
    put(op_lt_u, a < cu);
    put(op_u_lt, cu < a);
  }
  // ac_int has no comparison with double (ambiguous): ac compares fixed types only.
#if defined(VOXCAST_AC_TYPES)
  constexpr bool double_compare = full && !a_int;
#else
  constexpr bool double_compare = full;
#endif
  if constexpr (double_compare) {
    put(op_eq_d, a == in.d);
    put(op_ne_d, a != in.d);
    put(op_lt_d, a < in.d);
    put(op_le_d, a <= in.d);
    put(op_gt_d, a > in.d);
    put(op_ge_d, a >= in.d);
    put(op_d_lt, in.d < a);
    put(op_d_eq, in.d == a);
  }

  // Conversions into A (A's modes) from B, C integers, double and float; and into B.
  put(op_conv_b, convert<DA, DB>(b));
  if constexpr (full) put(op_conv_a_to_b, convert<DB, DA>(a));
  put(op_conv_int, A(ci));
  put(op_conv_uint, A(cu));
  put(op_conv_ll, A(static_cast<long long>(in.c)));
  put(op_conv_ull, A(static_cast<unsigned long long>(in.c)));
  if constexpr (full) {
    put(op_conv_short, A(static_cast<short>(in.c)));
    put(op_conv_bool, A((in.c & 1) != 0));
  }
  put(op_conv_double, A(in.d));
  // Finite values only (a double beyond the float range would be an infinity here).
  if (std::isfinite(static_cast<float>(in.d))) put(op_conv_float, A(static_cast<float>(in.d)));
  {
    A t = 0;
    if constexpr (a_int && !DB::is_int) {
      t = H::int_cast<A>(b);
    } else {
      t = b;
    }
    put(op_assign_b, t);
  }
  if constexpr (full) {
    put(op_int_cast_s12, H::int_cast<H::int_t<12>>(a));
    put(op_int_cast_u16, H::int_cast<H::uint_t<16>>(a));
    put(op_int_cast_s64, H::int_cast<H::int_t<64>>(a));
    put(op_int_cast_u70, H::int_cast<H::uint_t<70>>(a));
    put(op_int_cast_s128, H::int_cast<H::int_t<128>>(a));
  }

  // Unary operators.
  if constexpr (full && DA::W < 128) put(op_neg, -a);
  if constexpr (full) {
    put(op_lnot, !a);
    put(op_bnot, ~a);
  }
  if constexpr (full) {
    const A t = ~a;
    put(op_bnot_assigned, t);
  }
  // ++/-- add fixed<W - I + 1, 1, false>(1): not for I > W (clone and ap), and within 128 bits.
  if constexpr (DA::I <= DA::W && widths<DA, fx<DA::W - DA::I + 1, 1, false>>::add) {
    A t = a;
    ++t;
    put(op_pre_inc, t);
    t = a;
    --t;
    put(op_pre_dec, t);
    t = a;
    const A old = t++;
    put(op_post_inc, t);
    put(op_post_inc_value, old);
    t = a;
    t--;
    put(op_post_dec, t);
  }

  // Shifts: int, unsigned, int_t and uint_t amounts; same type, raw (no Q/O: full pairs only).
  if constexpr (full) {
  put(op_shl_int, a << in.n);
  put(op_shr_int, a >> in.n);
  put(op_shl_uint, a << in.un);
  put(op_shr_uint, a >> in.un);
  put(op_shl_ap_int, a << H::int_t<8>(in.n));
  put(op_shr_ap_uint, a >> H::uint_t<5>(in.un));
  {
    A t = a;
    t <<= in.n;
    put(op_shl_assign, t);
    t = a;
    t >>= in.n;
    put(op_shr_assign, t);
  }
  }

  if constexpr (full) {
    // Conversions out.
    put(op_to_double, a.to_double());
#if defined(VOXCAST_AC_TYPES)
    // ac_fixed's to_int() & co. cast an ac_int<I>, which has no C conversion above 64 bits.
    constexpr bool to_c = DA::I <= 64;
#else
    constexpr bool to_c = true;
#endif
    if constexpr (to_c) {
      put(op_to_int, a.to_int());
      put(op_to_uint, a.to_uint());
      put(op_to_int64, static_cast<long long>(a.to_int64()));
      put(op_to_uint64, static_cast<unsigned long long>(a.to_uint64()));
    }
    if constexpr (DA::is_int) {  // ap_fixed has neither
      put(op_to_long, a.to_long());
      put(op_to_ulong, a.to_ulong());
    }

    // Bits: x[i], the bit-field bridges, queries.
    put(op_bit_read, static_cast<bool>(a[in.bit]));
    {
      A t = a;
      t[in.bit] = in.bv;
      put(op_bit_write, t);
      t = a;
      H::write_bits(t, in.hi, in.lo, in.v);
      put(op_write_bits, t);
    }
    put(op_read_bits, static_cast<unsigned long long>(H::read_bits(a, in.hi, in.lo)));
    if constexpr (DA::W <= 64) {
      put(op_read_bits_all, static_cast<unsigned long long>(H::read_bits(a)));
      A t = a;
      H::write_bits(t, in.v);
      put(op_write_bits_all, t);
      put(op_leading_zeros, H::leading_zeros(a));  // normalize_direction's priority encoder
    }
    put(op_length, a.length());
    put(op_width, static_cast<int>(A::width));
    if constexpr (!DA::is_int) put(op_iwidth, static_cast<int>(H::fixed_iwidth<A>::value));
    // Printing: not in the common subset (print to_double()); compared for the record.
#if defined(VOXCAST_AC_TYPES)
    put(op_to_string, a.to_string(AC_DEC));
#else
    put(op_to_string, a.to_string(10));
#endif
#if !defined(VOXCAST_AC_TYPES)
    // range(): clone and ap only.
    put(op_range_read, static_cast<unsigned long long>(a.range(in.hi, in.lo).to_uint64()));
    {
      A t = a;
      t.range(in.hi, in.lo) = static_cast<unsigned long long>(in.v);
      put(op_range_write, t);
    }
    put(op_range_reversed, static_cast<unsigned long long>(a.range(in.lo, in.hi).to_uint64()));
#endif
  }

  // Auxiliary values for the tags (never compared).
  if constexpr (!DA::is_int && widths<DA, fx<1, DA::I - DA::W + 1, false>>::add) {
    using L = H::ufixed<1, DA::I - DA::W + 1>;  // 1 LSB of A
    const L lsb = make<L>(1);
    A t = a;
    t += lsb;
    put(op_AUX_a_plus_lsb, t);
    t = a;
    t -= lsb;
    put(op_AUX_a_minus_lsb, t);
  }
  if constexpr (full && WD::neg_div) {
    if (in.b != 0) {
      put(op_AUX_neg_quotient, -(a / b));
      if constexpr (!a_int) put(op_AUX_neg_quotient_in_a, A(-(a / b)));
    }
  }
}

// ---- The chunk's table ----------------------------------------------------------------------
template <class P, int K>
bool eval_if(const inputs& in, outputs& out) {
  if constexpr (K % VOXCAST_DIFF_CHUNKS == VOXCAST_DIFF_CHUNK && supported<typename P::A>() &&
                supported<typename P::B>()) {
    eval_pair<P>(in, out);
    return true;
  } else {
    return false;
  }
}
template <class... P, std::size_t... K>
bool eval_index(int pair, const inputs& in, outputs& out, list<P...>, std::index_sequence<K...>) {
  using fn = bool (*)(const inputs&, outputs&);
  static constexpr fn table[] = {&eval_if<P, static_cast<int>(K)>...};
  return table[pair](in, out);
}
bool eval(int pair, const inputs& in, outputs& out) {
  if (pair % VOXCAST_DIFF_CHUNKS != VOXCAST_DIFF_CHUNK) return false;
  return eval_index(pair, in, out, all_pairs{}, std::make_index_sequence<pair_count>{});
}

}  // namespace VOXCAST_DIFF_NS

namespace {
[[maybe_unused]] const bool registered = register_chunk(
    {VOXCAST_DIFF_ENGINE_NAME, VOXCAST_DIFF_CHUNK, &VOXCAST_DIFF_NS::eval});
}  // namespace

}  // namespace voxcast_diff
