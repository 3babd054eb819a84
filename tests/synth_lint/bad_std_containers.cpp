// no-std-containers: a std::vector variable, a std::string parameter, a
// std::function member; std::array is allowed (fixed size, like a C array).
#include <array>
#include <functional>
#include <string>
#include <vector>

#include "hls/pragma.hpp"

namespace {
struct Holder {
  std::function<int(int)> f;  // expect-lint: no-std-containers
  int get() const { return 1; }
};
int length(const std::string& s) { return static_cast<int>(s.size()); }  // expect-lint: no-std-containers
int total(int x) {
  std::vector<int> v(4, x);  // expect-lint: no-std-containers
  const std::array<int, 4> a{{1, 2, 3, 4}};
  return v[0] + a[3];  // expect-lint: no-std-containers
}
}  // namespace

void lint_top(int x, int* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = x)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  const Holder h{};
  *out = total(x) + length("ab") + h.get();  // expect-lint: no-std-containers
}
