// The operation-level differential test of the fixed-point types (issue 16, docs/fixed-point.md,
// "Differential test"): shared declarations of the driver (main.cpp) and the engines
// (engine.cpp, compiled once per engine and chunk).
//
// An engine is hls/types.hpp's mapping of voxcast::hls::fixed / ufixed / int_t / uint_t: the
// clone (hls/fixed_point.hpp), Xilinx's ap_fixed (-DVOXCAST_VENDOR_TYPES) or Catapult's ac_fixed
// (-DVOXCAST_AC_TYPES). engine.cpp is written once against the kernels' common API (the list at
// the top of hls/types.hpp, bridges included) and compiled once per mapping, so every engine
// runs the same source, as the kernels do. This header names no engine type: it holds the
// compile-time list of operand type pairs, the operations, the inputs and the results.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>

namespace voxcast_diff {

__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;

// ---- Operand types as descriptors (engine-free) ----------------------------------------------
// Q and O are indices in ap's order (hls/types.hpp: RND, RND_ZERO, RND_MIN_INF, RND_INF,
// RND_CONV, TRN, TRN_ZERO; SAT, SAT_ZERO, SAT_SYM, WRAP, WRAP_SM); each engine maps them by
// meaning onto its own enumerators.
enum : int { kRND, kRND_ZERO, kRND_MIN_INF, kRND_INF, kRND_CONV, kTRN, kTRN_ZERO };
enum : int { kSAT, kSAT_ZERO, kSAT_SYM, kWRAP, kWRAP_SM };

template <int W_, int I_, bool S_, int Q_ = kTRN, int O_ = kWRAP, int N_ = 0>
struct fx {
  static constexpr int W = W_, I = I_, Q = Q_, O = O_, N = N_;
  static constexpr bool S = S_, is_int = false;
};
template <int W_, bool S_>
struct in {
  static constexpr int W = W_, I = W_, Q = kTRN, O = kWRAP, N = 0;
  static constexpr bool S = S_, is_int = true;
};

// What a pair runs: kFull every operation (operators, comparisons, conversions, bits, ...);
// kModes the operations whose result depends on A's quantization / overflow modes
// (conversions into A, compound assignments, ++/--, shifts, comparisons with A on either side).
enum pair_kind : int { kFull, kModes };
template <class A_, class B_, int K_ = kFull>
struct pr {
  using A = A_;
  using B = B_;
  static constexpr int kind = K_;
};
template <class... P>
struct list {};

struct type_desc {
  int w, i;
  bool s, is_int;
  int q, o, n;
};
template <class D>
constexpr type_desc desc_of() {
  return {D::W, D::I, D::S, D::is_int, D::Q, D::O, D::N};
}
struct pair_desc {
  type_desc a, b;
  int kind;
};
std::string type_name(const type_desc& t);

// ---- Operations ------------------------------------------------------------------------------
// One record per operation and engine pair (clone vs ap, clone vs ac). AUX_ entries are
// computed by every engine but never compared: the tags' predicates use the clone's.
#define VOXCAST_DIFF_OPS(X)                                                                     \
  X(add) X(sub) X(mul) X(div) X(band) X(bor) X(bxor) X(mod)                                     \
  X(add_c) X(c_sub) X(mul_c) X(div_c) X(c_div) X(band_c)                                        \
  X(add_assign) X(sub_assign) X(mul_assign) X(div_assign) X(and_assign) X(or_assign)           \
  X(xor_assign) X(mod_assign) X(add_assign_c) X(mul_assign_c)                                   \
  X(eq) X(ne) X(lt) X(le) X(gt) X(ge) X(eq_ba) X(ne_ba) X(lt_ba) X(le_ba) X(gt_ba) X(ge_ba)    \
  X(eq_c) X(lt_c) X(gt_c) X(c_eq) X(c_lt) X(c_ge) X(eq_u) X(lt_u) X(u_lt) X(u_eq)              \
  X(eq_d) X(ne_d) X(lt_d) X(le_d) X(gt_d) X(ge_d) X(d_lt) X(d_eq)                              \
  X(conv_b) X(conv_a_to_b) X(conv_int) X(conv_uint) X(conv_ll) X(conv_ull) X(conv_short)       \
  X(conv_bool) X(conv_double) X(conv_float) X(assign_b)                                         \
  X(int_cast_s12) X(int_cast_u16) X(int_cast_s64) X(int_cast_u70) X(int_cast_s128)             \
  X(neg) X(lnot) X(bnot) X(bnot_assigned) X(pre_inc) X(pre_dec) X(post_inc)                    \
  X(post_inc_value) X(post_dec)                                                                 \
  X(shl_int) X(shr_int) X(shl_uint) X(shr_uint) X(shl_ap_int) X(shr_ap_uint) X(shl_assign)     \
  X(shr_assign)                                                                                 \
  X(to_double) X(to_int) X(to_uint) X(to_int64) X(to_uint64) X(to_long) X(to_ulong)            \
  X(bit_read) X(bit_write) X(read_bits) X(write_bits) X(read_bits_all) X(write_bits_all)       \
  X(leading_zeros)                                                                              \
  X(length) X(width) X(iwidth)                                                                  \
  X(range_read) X(range_write) X(range_reversed) X(to_string)                                  \
  X(AUX_a_plus_lsb) X(AUX_a_minus_lsb) X(AUX_neg_quotient) X(AUX_neg_quotient_in_a)

enum op : int {
#define X(name) op_##name,
  VOXCAST_DIFF_OPS(X)
#undef X
      op_count
};
const char* op_name(int o);
inline bool op_is_aux(int o) { return std::strncmp(op_name(o), "AUX_", 4) == 0; }

// ---- Inputs and results ----------------------------------------------------------------------
struct inputs {
  u128 a = 0, b = 0;           // raw W-bit patterns of the operands (low bits)
  int n = 0;                   // signed shift amount
  unsigned un = 0;             // unsigned shift amount
  long long c = 0;             // a C integer operand (used as int, unsigned, long long, short)
  double d = 0;                // a double operand
  int bit = 0;                 // a bit index < W of A
  int hi = 0, lo = 0;          // a bit field of A (hi >= lo, at most 64 bits)
  std::uint64_t v = 0;         // a value to write
  bool bv = false;             // a bit to write
};

// kind: 'f' fixed, 'i' integer type (int_t / ap_int_base / ac_int), 'b' bool, 'n' C integer,
// 'd' double, 's' text. bits: the value's pattern sign- or zero-extended to 128 bits (C
// integers: the value as such, double: its IEEE bits). w, i, s: the result type (fixed and
// integer types).
struct result {
  bool present = false;
  char kind = 0;
  u128 bits = 0;
  int w = 0, i = 0;
  bool s = false;
  std::string text;
};
struct outputs {
  result r[op_count];
};
inline bool same(const result& x, const result& y) {
  return x.kind == y.kind && x.bits == y.bits && x.w == y.w && x.i == y.i && x.s == y.s &&
         x.text == y.text;
}
inline bool same_value(const result& x, const result& y) { return x.bits == y.bits; }

// One engine (one mapping, one chunk of the pair list): eval(pair index, inputs, outputs).
using eval_fn = bool (*)(int pair, const inputs&, outputs&);
struct engine_chunk {
  const char* engine;  // "clone", "ap", "ac"
  int chunk;
  eval_fn eval;  // false: the pair is not in this chunk
};
// Each engine object registers its chunk during static initialization (main.cpp owns the list).
bool register_chunk(const engine_chunk& c);

}  // namespace voxcast_diff
