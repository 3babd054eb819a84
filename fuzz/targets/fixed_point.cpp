// Fuzz target: hls/fixed_point.hpp, differentially.
//  1. Conversions into 532 target types (10 formats x 7 quantization modes x the
//     overflow modes SAT, SAT_ZERO, SAT_SYM, WRAP with N = 0, 1, 2 and WRAP_SM with
//     N = 0, 1, 2), from any double (every bit pattern: NaN, inf, denormals, huge)
//     and from the raw bits of four wide source types, against `model_bits`, the
//     independent long-double model of /work/shared/fixed-point-semantics.md
//     sections 2, 3 and 9 in tests/common/fixed_point_model.hpp (value
//     arithmetic with floorl/fmodl, not the clone's shifts and masks).
//  2. The widening `+ - *` of six operand types (section 5): result format and
//     exact value, then the result assigned into one target per Q mode.
//  3. The bit-true model's double quantizers (refmodel/bittrue/quantize.hpp:
//     q_trn, q_rnd, u_frac, trunc0_div) against the fixed types the hls kernels
//     use for the same step, inside their documented exactness domain.
// Any disagreement must be exact-zero: one differing bit is a Finding.
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fuzz/targets/targets.hpp"
#include "hls/fixed_point.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "tests/common/fixed_point_model.hpp"

namespace voxcast::fuzz {
namespace {

using namespace voxcast::hls;

// ---- Input bytes --------------------------------------------------------------------------
class Bytes {
 public:
  Bytes(const std::uint8_t* d, std::size_t n) : d_(d), n_(n) {}
  bool empty() const { return pos_ >= n_; }
  std::uint8_t u8() { return pos_ < n_ ? d_[pos_++] : 0; }
  std::uint64_t u64() {
    std::uint64_t v = 0;
    for (int b = 0; b < 8; ++b) v |= std::uint64_t{u8()} << (8 * b);
    return v;
  }
  double f64() {
    const std::uint64_t bits = u64();
    double d;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }

 private:
  const std::uint8_t* d_;
  std::size_t n_;
  std::size_t pos_ = 0;
};

// ---- The model (tests/common/fixed_point_model.hpp, shared with the exhaustive sweep) ------
using Fmt = fixed_model::Format;
using fixed_model::describe;
using fixed_model::ld;
using fixed_model::low_mask;
using fixed_model::model_bits;
using fixed_model::model_value;

template <class T>
std::uint64_t bits_of(const T& x) {
  return static_cast<std::uint64_t>(x.raw()) & low_mask(T::width);
}
template <class T>
ld value_of(const T& x) {
  return std::ldexp(static_cast<ld>(x.raw()), T::iwidth - T::width);
}
template <class T>
Fmt fmt_of() {
  return {T::width, T::iwidth, T::is_signed, T::qmode, T::omode, T::nbits};
}

std::string hex(std::uint64_t v) {
  std::ostringstream os;
  os << "0x" << std::hex << v;
  return os.str();
}

// `from` describes the input; it is only called (strings built) on a mismatch.
template <class Describe>
void expect_bits(std::uint64_t got, std::uint64_t want, const Fmt& t, Describe from) {
  if (got != want)
    throw Finding(describe(t) + " from " + from() + ": bits " + hex(got) + ", model " + hex(want));
}

std::string double_text(double d) {
  std::ostringstream os;
  os.precision(17);
  os << d << " (" << std::hexfloat << d << ")";
  return os.str();
}

// ---- 1. Conversions ---------------------------------------------------------------------
// Wide sources (<= 64 bits: exact in long double) whose raw bits come from the input.
using Src0 = fixed<64, 20>;
using Src1 = ufixed<64, 40>;
using Src2 = fixed<40, -6>;
using Src3 = ufixed<20, 30>;
constexpr int kSources = 4;

struct Target {
  Fmt fmt;
  std::uint64_t (*from_double)(double);
  std::array<std::uint64_t (*)(std::uint64_t), kSources> from_source;
};

template <class T, class Src>
std::uint64_t convert_source(std::uint64_t raw) {
  return bits_of(T(Src::bitsToFixed(raw)));
}
template <class T>
std::uint64_t convert_double(double d) {
  return bits_of(T(d));
}

template <class T>
Target make_target() {
  return {fmt_of<T>(),
          &convert_double<T>,
          {&convert_source<T, Src0>, &convert_source<T, Src1>, &convert_source<T, Src2>,
           &convert_source<T, Src3>}};
}

template <int W, int I, bool S, q_mode Q>
void add_overflow_modes(std::vector<Target>& out) {
  out.push_back(make_target<fixed_base<W, I, S, Q, SAT, 0>>());
  out.push_back(make_target<fixed_base<W, I, S, Q, SAT_ZERO, 0>>());
  out.push_back(make_target<fixed_base<W, I, S, Q, SAT_SYM, 0>>());
  out.push_back(make_target<fixed_base<W, I, S, Q, WRAP, 0>>());
  out.push_back(make_target<fixed_base<W, I, S, Q, WRAP, 1>>());
  if constexpr (W >= 2) out.push_back(make_target<fixed_base<W, I, S, Q, WRAP, 2>>());
  if constexpr (S) {
    out.push_back(make_target<fixed_base<W, I, S, Q, WRAP_SM, 0>>());
    out.push_back(make_target<fixed_base<W, I, S, Q, WRAP_SM, 1>>());
    if constexpr (W >= 2) out.push_back(make_target<fixed_base<W, I, S, Q, WRAP_SM, 2>>());
  }
}

template <int W, int I, bool S>
void add_format(std::vector<Target>& out) {
  add_overflow_modes<W, I, S, RND>(out);
  add_overflow_modes<W, I, S, RND_ZERO>(out);
  add_overflow_modes<W, I, S, RND_MIN_INF>(out);
  add_overflow_modes<W, I, S, RND_INF>(out);
  add_overflow_modes<W, I, S, RND_CONV>(out);
  add_overflow_modes<W, I, S, TRN>(out);
  add_overflow_modes<W, I, S, TRN_ZERO>(out);
}

const std::vector<Target>& targets() {
  static const std::vector<Target> all = [] {
    std::vector<Target> t;
    // W = 1 (signed {-1, 0}), I < 0, I = 0, I > W, 33..64 bits, signed and unsigned.
    add_format<1, 1, true>(t);
    add_format<5, -3, true>(t);
    add_format<8, 4, false>(t);
    add_format<12, 0, false>(t);
    add_format<16, 20, true>(t);
    add_format<24, 8, true>(t);
    add_format<33, 1, false>(t);
    add_format<48, 30, true>(t);
    add_format<64, 64, false>(t);
    add_format<64, 10, true>(t);
    return t;
  }();
  return all;
}

template <class Src>
void check_from_source(const Target& t, int index, std::uint64_t raw) {
  const Src s = Src::bitsToFixed(raw);
  const std::uint64_t want = model_bits(value_of(s), Src::is_signed, t.fmt);
  const std::uint64_t got = t.from_source[static_cast<std::size_t>(index)](raw);
  expect_bits(got, want, t.fmt, [&] { return describe(fmt_of<Src>()) + " raw " + hex(bits_of(s)); });
}

void conversion_case(Bytes& in) {
  const auto& all = targets();
  const std::size_t pick = std::size_t{in.u8()} | (std::size_t{in.u8()} << 8);
  const Target& t = all[pick % all.size()];
  const auto kind = static_cast<std::uint8_t>(in.u8() % (kSources + 1));
  if (kind == kSources) {
    const double d = in.f64();
    expect_bits(t.from_double(d), model_bits(model_value(d), true, t.fmt), t.fmt,
                [&] { return "double " + double_text(d); });
    return;
  }
  const std::uint64_t raw = in.u64();
  switch (kind) {
    case 0: check_from_source<Src0>(t, 0, raw); break;
    case 1: check_from_source<Src1>(t, 1, raw); break;
    case 2: check_from_source<Src2>(t, 2, raw); break;
    default: check_from_source<Src3>(t, 3, raw); break;
  }
}

// ---- 2. Widening + - * (section 5) ---------------------------------------------------------
using Op0 = fixed<8, 4>;
using Op1 = ufixed<6, 2>;
using Op2 = fixed<10, -2>;
using Op3 = fixed<20, 12>;
using Op4 = ufixed<31, 31>;
using Op5 = fixed<32, 1>;

// The section 5 result format of a OP b.
Fmt result_format(char op, const Fmt& a, const Fmt& b) {
  const int fa = a.w - a.i, fb = b.w - b.i;
  if (op == '*') return {a.w + b.w, a.i + b.i, a.s || b.s, TRN, WRAP, 0};
  const int ia = a.i + (b.s && !a.s ? 1 : 0), ib = b.i + (a.s && !b.s ? 1 : 0);
  const int i = std::max(ia, ib) + 1;
  return {i + std::max(fa, fb), i, op == '-' || a.s || b.s, TRN, WRAP, 0};
}

// One assignment target per Q mode, each with a different overflow mode.
template <class R>
std::array<std::uint64_t, 7> assign_all(const R& r) {
  return {bits_of(fixed<12, 5, RND, SAT>(r)),        bits_of(fixed<12, 5, RND_ZERO, SAT_SYM>(r)),
          bits_of(fixed<12, 5, RND_MIN_INF, WRAP, 2>(r)), bits_of(ufixed<12, 5, RND_INF, SAT>(r)),
          bits_of(fixed<12, 5, RND_CONV, WRAP_SM>(r)), bits_of(ufixed<12, 5, TRN, WRAP, 1>(r)),
          bits_of(fixed<12, 5, TRN_ZERO, SAT_ZERO>(r))};
}
const std::array<Fmt, 7> kAssignFormats{{{12, 5, true, RND, SAT, 0},
                                         {12, 5, true, RND_ZERO, SAT_SYM, 0},
                                         {12, 5, true, RND_MIN_INF, WRAP, 2},
                                         {12, 5, false, RND_INF, SAT, 0},
                                         {12, 5, true, RND_CONV, WRAP_SM, 0},
                                         {12, 5, false, TRN, WRAP, 1},
                                         {12, 5, true, TRN_ZERO, SAT_ZERO, 0}}};

template <class R, class Describe>
void check_result(char op, const Fmt& fa, const Fmt& fb, ld exact, const R& r, Describe what) {
  const Fmt want = result_format(op, fa, fb);
  const Fmt got = fmt_of<R>();
  if (got.w != want.w || got.i != want.i || got.s != want.s)
    throw Finding(what() + ": result type " + describe(got) + ", section 5 says " + describe(want));
  if (value_of(r) != exact)
    throw Finding(what() + ": result raw " + hex(bits_of(r)) + " is not the exact value");
  const auto assigned = assign_all(r);
  for (std::size_t k = 0; k < assigned.size(); ++k)
    expect_bits(assigned[k], model_bits(exact, R::is_signed, kAssignFormats[k]), kAssignFormats[k],
                [&] { return what() + " = " + describe(got) + " raw " + hex(bits_of(r)); });
}

template <class A, class B>
void arith_pair(Bytes& in) {
  const A a = A::bitsToFixed(in.u64());
  const B b = B::bitsToFixed(in.u64());
  const ld va = value_of(a), vb = value_of(b);
  const Fmt fa = fmt_of<A>(), fb = fmt_of<B>();
  const auto with = [&](const char* op) {
    return [&, op] {
      return std::string(op) + " with a = " + describe(fa) + " raw " + hex(bits_of(a)) +
             ", b = " + describe(fb) + " raw " + hex(bits_of(b));
    };
  };
  check_result('+', fa, fb, va + vb, a + b, with("a + b"));
  check_result('-', fa, fb, va - vb, a - b, with("a - b"));
  check_result('*', fa, fb, va * vb, a * b, with("a * b"));
}

template <class A>
void arith_with(Bytes& in, int b) {
  switch (b) {
    case 0: arith_pair<A, Op0>(in); break;
    case 1: arith_pair<A, Op1>(in); break;
    case 2: arith_pair<A, Op2>(in); break;
    case 3: arith_pair<A, Op3>(in); break;
    case 4: arith_pair<A, Op4>(in); break;
    default: arith_pair<A, Op5>(in); break;
  }
}

void arithmetic_case(Bytes& in) {
  const int a = in.u8() % 6, b = in.u8() % 6;
  switch (a) {
    case 0: arith_with<Op0>(in, b); break;
    case 1: arith_with<Op1>(in, b); break;
    case 2: arith_with<Op2>(in, b); break;
    case 3: arith_with<Op3>(in, b); break;
    case 4: arith_with<Op4>(in, b); break;
    default: arith_with<Op5>(in, b); break;
  }
}

// ---- 3. The bit-true model's double quantizers -------------------------------------------
template <class Describe>
void expect_same(double got, double want, Describe what) {
  if (std::memcmp(&got, &want, sizeof got) != 0 && !(got == 0 && want == 0))
    throw Finding(what() + ": fixed gives " + double_text(got) + ", bittrue " + double_text(want));
}

template <int F>
void bittrue_quantizers(double x) {
  // quantize.hpp's exactness domain: finite x with |x * 2^F| < 2^52.
  if (!std::isfinite(x) || std::fabs(std::ldexp(x, F)) >= 0x1p52) return;
  const auto at = [x](const char* fn) {
    return [x, fn] { return std::string(fn) + " x = " + double_text(x) + ", F = " + std::to_string(F); };
  };
  // A wide enough target never overflows, so only the quantization mode acts.
  expect_same(fixed<62, 62 - F, TRN, SAT>(x).to_double(), bittrue::q_trn(x, F), at("q_trn"));
  expect_same(fixed<62, 62 - F, RND, SAT>(x).to_double(), bittrue::q_rnd(x, F), at("q_rnd"));
  expect_same(ufixed<F, 0, RND, SAT>(x).to_double(), bittrue::u_frac(x, F), at("u_frac"));
}

void bittrue_case(Bytes& in) {
  const double x = in.f64();
  switch (in.u8() % 4) {
    case 0: bittrue_quantizers<6>(x); break;
    case 1: bittrue_quantizers<10>(x); break;
    case 2: bittrue_quantizers<16>(x); break;
    default: {
      // trunc0_div against ap's `/` (section 6): the dividend's fraction bits, toward zero.
      const auto a = fixed<16, 8>::bitsToFixed(in.u64());
      const auto b = fixed<12, 4>::bitsToFixed(in.u64());
      if (b.raw() == 0) return;  // division by zero is undefined (section 6)
      expect_same((a / b).to_double(), bittrue::trunc0_div(a.to_double(), 8, b.to_double(), 8, 8),
                  [&] {
                    return "trunc0_div a = " + double_text(a.to_double()) +
                           ", b = " + double_text(b.to_double());
                  });
    }
  }
}

}  // namespace

void fixed_point(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  while (!in.empty()) {
    switch (in.u8() % 3) {
      case 0: conversion_case(in); break;
      case 1: arithmetic_case(in); break;
      default: bittrue_case(in); break;
    }
  }
}

}  // namespace voxcast::fuzz
