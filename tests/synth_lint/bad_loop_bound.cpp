// static-loop-bound: loops bounded by run-time values without a
// LOOP_TRIPCOUNT pragma of their own (the inner loop's pragma does not count
// for the outer loop); the loops with a constant bound or their own pragma
// pass.
#include "hls/pragma.hpp"

namespace {
constexpr int kLanes = 4;
template <int N>
int fill(int* a) {
  int s = 0;
  for (int i = 0; i < N; ++i) s += a[i];  // template parameter bound: fine
  for (int i = 0; i < kLanes; ++i) s += a[i];  // constexpr bound: fine
  return s;
}
int rows(const int* a, int h, int w) {
  int s = 0;
  for (int y = 0; y < h; ++y) {  // expect-lint: static-loop-bound
    for (int x = 0; x < w; ++x) {
      VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT max = 64)
      s += a[y * w + x];
    }
  }
  int k = h;
  while (k > 0) --k;  // expect-lint: static-loop-bound
  for (int i = h; i < 8; ++i) s += i;  // expect-lint: static-loop-bound
  return s;
}
}  // namespace

void lint_top(int* a, int h, int w, int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = a)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = h)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = w)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  *out = fill<8>(a) + rows(a, h, w);
}
