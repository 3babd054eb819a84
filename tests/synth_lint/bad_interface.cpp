// interface-pragma: the top's own body must name every parameter and
// `return`; pragmas in a sub-function (as Vitis ignores them) do not count.
#include "hls/pragma.hpp"

namespace {
void kernel(const int* in, int n, int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = in)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  *out = in[0] + n;
}
}  // namespace

void lint_top(  // expect-lint: interface-pragma (no port = return)
    const int* in,  // expect-lint: interface-pragma
    int n, int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = n)
  kernel(in, n, out);
}
