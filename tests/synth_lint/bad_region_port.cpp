// sample-loop-ports (--region region --port in --port out): the region may
// reach external memory only through the ports the top passes it as they are.
// Passing another pointer parameter, a local that aliases one, a value read
// through one, or using a mutable global inside the region is a finding; the
// on-chip local and the scalar are fine.
#include "hls/pragma.hpp"

namespace {
int table[16];            // mutable: memory outside the region's arguments
constexpr int kScale = 3;  // a constant: fine

void stage(const int* port, const int& cfg, int* out) {
  for (int i = 0; i < 16; ++i) out[i] = port[i] * kScale + cfg + table[i];  // expect-lint: sample-loop-ports
}

void region(const int* port, const int* other, int* out, int n, const int& cfg,
            const int (&on_chip)[4]) {
  stage(port, cfg, out);
  out[0] += other[0] + n + on_chip[0];
}
}  // namespace

void lint_top(const int* in, const int* frame, int* out, int n) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = in)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = frame)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = n)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  int state[4] = {0, 1, 2, 3};
  const int* alias = frame;
  region(in,
         frame,  // expect-lint: sample-loop-ports
         out, n,
         frame[0],  // expect-lint: sample-loop-ports
         state);
  region(in,
         alias,  // expect-lint: sample-loop-ports
         out,
         n, state[1], state);
  region(in + 1,  // expect-lint: sample-loop-ports (pointer arithmetic on a port)
         in, out, n, n, state);
}
