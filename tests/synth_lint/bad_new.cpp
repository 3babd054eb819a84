// no-dynamic-memory: new and delete in a helper the top calls.
#include "hls/pragma.hpp"

namespace {
int helper(int x) {
  int* p = new int(x);  // expect-lint: no-dynamic-memory
  const int v = *p;
  delete p;  // expect-lint: no-dynamic-memory
  return v;
}
}  // namespace

void lint_top(int x, int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = x)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  *out = helper(x);
}
