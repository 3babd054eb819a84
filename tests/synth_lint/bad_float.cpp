// no-float-datapath: floating-point arithmetic in a reachable function. The
// host-only set-up code in double (namespace host, #ifndef __SYNTHESIS__) is
// not in the synthesis compile and not a finding.
#include "hls/pragma.hpp"

#ifndef __SYNTHESIS__
namespace host {
inline double gain_table(int i) { return 0.5 * i; }
}  // namespace host
#endif

namespace {
int scale(int x) {
  const float g = 0.75f;  // expect-lint: no-float-datapath
  return static_cast<int>(g * x);  // expect-lint: no-float-datapath
}
}  // namespace

void lint_top(int x, int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = x)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  *out = scale(x);
}
