// no-exceptions: try, catch and throw in a reachable function.
#include "hls/pragma.hpp"

namespace {
int checked(int x) {
  try {  // expect-lint: no-exceptions
    if (x < 0) throw x;  // expect-lint: no-exceptions
  } catch (int) {
    return 0;
  }
  return x;
}
}  // namespace

void lint_top(int x, int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = x)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  *out = checked(x);
}
