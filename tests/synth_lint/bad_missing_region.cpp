// sample-loop-ports: a top that does not call the --region function is a
// finding (a renamed region must not make the check pass by finding nothing).
#include "hls/pragma.hpp"

namespace {
void renamed_region(const int* port, int* out) { out[0] = port[0]; }
}  // namespace

void lint_top(  // expect-lint: sample-loop-ports
    const int* in, int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = in)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  renamed_region(in, out);
}
