// no-dynamic-memory: the C allocator, called from a template instantiation.
#include <cstdlib>

#include "hls/pragma.hpp"

namespace {
template <int N>
int sum() {
  int* p = static_cast<int*>(std::malloc(N * sizeof(int)));  // expect-lint: no-dynamic-memory
  int s = 0;
  for (int i = 0; i < N; ++i) s += p[i] = i;
  std::free(p);  // expect-lint: no-dynamic-memory
  return s;
}
}  // namespace

void lint_top(int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  *out = sum<4>();
}
