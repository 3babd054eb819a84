// A translation unit that does not compile: the checker must fail (exit 2),
// never pass what it could not read.
#include "hls/pragma.hpp"

void lint_top(int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  *out = undeclared_helper(1);
}
