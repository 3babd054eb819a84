// no-virtual: a virtual function of a class the top uses, and its call.
#include "hls/pragma.hpp"

namespace {
struct Unit {
  virtual int step(int x) const { return x + 1; }  // expect-lint: no-virtual
  virtual ~Unit() = default;  // expect-lint: no-virtual
};
int run(const Unit& u, int x) { return u.step(x); }  // expect-lint: no-virtual
}  // namespace

void lint_top(int x, int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = x)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  const Unit u;
  *out = run(u, x);
}
