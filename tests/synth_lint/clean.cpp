// A design the checker passes: templates and their instantiations, a lambda
// handed to a template, operators and constructors of a small value class,
// loops bounded by a template parameter, a constexpr variable and a static
// constexpr member or carrying LOOP_TRIPCOUNT, std::array, voxcast's fixed
// point (exempt: it stands in for the vendor's ap_fixed), host-only set-up
// code in double, constexpr set-up evaluated by the compiler.
#include <array>
#include <cstdint>
#include <vector>

#include "hls/fixed_point.hpp"
#include "hls/pragma.hpp"

#ifndef __SYNTHESIS__
namespace host {
inline std::vector<double> setup_table(int n) { return std::vector<double>(n, 0.5); }
}  // namespace host
#endif

namespace {
struct Acc {
  static constexpr int kTaps = 3;
  std::int32_t v = 0;
  Acc& operator+=(std::int32_t x) {
    v += x;
    return *this;
  }
};

constexpr int kLanes = 4;
constexpr int lanes_squared() { return kLanes * kLanes; }

template <int N, class F>
std::int32_t reduce(const std::array<std::int32_t, N>& a, F f) {
  Acc acc;
  for (int i = 0; i < N; ++i) acc += f(a[i]);
  for (int t = 0; t < Acc::kTaps; ++t) acc += t;
  return acc.v;
}
}  // namespace

void lint_top(const std::int32_t* in, int n, std::int32_t* out) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = in)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = n)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  constexpr int kSquares = lanes_squared();
  std::array<std::int32_t, kLanes> a{};
  for (int i = 0; i < kLanes; ++i) a[i] = in[i];
  const std::int32_t k = 3;
  std::int32_t s = reduce<kLanes>(a, [k](std::int32_t x) { return k * x; });
  for (int i = 0; i < n; ++i) {
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT max = 1024)
    s += in[i];
  }
  voxcast::hls::fixed<16, 8> f = 0;
  f += voxcast::hls::fixed<16, 8>(s);
  *out = static_cast<std::int32_t>(f.to_int()) + kSquares;
}
