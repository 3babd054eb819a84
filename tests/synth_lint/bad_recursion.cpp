// no-recursion: two functions calling each other (a cycle, not a self call).
#include "hls/pragma.hpp"

namespace {
int odd(int n);
int even(int n) { return n == 0 ? 1 : odd(n - 1); }  // expect-lint: no-recursion
int odd(int n) { return n == 0 ? 0 : even(n - 1); }  // expect-lint: no-recursion
}  // namespace

void lint_top(int n, int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = n)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  *out = even(n);
}
