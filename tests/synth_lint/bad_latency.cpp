// latency-pragma: an HLS LATENCY pragma names the unit's declared depth, a
// namespace-scope integer constant, for min and max alike; a number typed in
// the pragma, two different names, a name that is no such constant, or a
// LATENCY in an inlined function (Vitis ignores its pragmas) is a finding.
#include "hls/pragma.hpp"

namespace {
constexpr int add_depth = 1;
constexpr int mul_depth = 3;
int variable = 2;

int add(int a, int b) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = add_depth max = add_depth)
  return a + b;
}
int mul(int a, int b) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = 3 max = 3)  // expect-lint: latency-pragma
  return a * b;
}
int mac(int a, int b, int c) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = add_depth max = mul_depth)  // expect-lint: latency-pragma
  return add(mul(a, b), c);
}
int sub(int a, int b) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY max = add_depth)  // expect-lint: latency-pragma
  return a - b;
}
int neg(int a) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = variable max = variable)  // expect-lint: latency-pragma
  return -a;
}
int twice(int a) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = add_depth max = add_depth)  // expect-lint: latency-pragma
  return a + a;
}
int thrice(int a) {
  VOXCAST_HLS_PRAGMA(HLS INLINE off)
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = mul_depth max = mul_depth)
  return 3 * a;
}
}  // namespace

void lint_top(int a, int b, int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = a)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = b)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  *out = mac(a, b, 1) + sub(a, b) + neg(a) + twice(b) + thrice(a);
}
