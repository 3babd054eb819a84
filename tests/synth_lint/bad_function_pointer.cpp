// no-function-pointer: a function's address taken, calls through a function
// pointer and a member function pointer. The lambda handed to a template is
// fine (its call operator is called directly).
#include "hls/pragma.hpp"

namespace {
int twice(int x) { return 2 * x; }
struct Scale {
  int k;
  int apply(int x) const { return k * x; }
};
template <class F>
int with(F f, int x) { return f(x); }
int through_pointer(int x) {
  int (*fp)(int) = twice;  // expect-lint: no-function-pointer
  return fp(x);            // expect-lint: no-function-pointer
}
int through_member_pointer(int x) {
  const Scale s{3};
  int (Scale::*mp)(int) const = &Scale::apply;  // expect-lint: no-function-pointer
  return (s.*mp)(x);                            // expect-lint: no-function-pointer
}
}  // namespace

void lint_top(int x, int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = x)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  *out = through_pointer(x) + through_member_pointer(x) + with([](int v) { return v + 1; }, x);
}
