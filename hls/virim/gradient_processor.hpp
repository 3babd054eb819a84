// VIRIM's gradient processor and the rotator-to-DSP bus word (virim-1994.txt,
// "Rotator Board": "the gradient processor applies the Sobel operator for x and
// y direction"; "48 bit wide unidirectional rotator-DSP bus"; docs/heidelberg.md
// §7.4). Sobel/8 on three density rows of one constant-z plane (y - 1, y,
// y + 1), neighbours outside the view cube read 0; the result is floored to
// gb fraction bits (it lies in (-1/2, 1/2): no overflow).
#pragma once

#include "hls/pragma.hpp"
#include "hls/virim/params.hpp"

namespace voxcast {
namespace hls {
namespace virim {

template <class HP>
struct BusWord {
  typename VirimParams<HP>::density_t density;
  typename VirimParams<HP>::grad_t gx, gy;
};

// Bus layout: density in [db-1:0], gx in [db+gb-1:db], gy in [db+2gb-1:db+gb].
template <class HP>
typename VirimParams<HP>::bus_t pack_bus_word(const BusWord<HP>& w) {
  using V = VirimParams<HP>;
  typename V::bus_t b = 0;
  write_bits(b, V::db - 1, 0, read_bits(w.density, V::db - 1, 0));
  write_bits(b, V::db + V::gb - 1, V::db, read_bits(w.gx, V::gb - 1, 0));
  write_bits(b, V::db + 2 * V::gb - 1, V::db + V::gb, read_bits(w.gy, V::gb - 1, 0));
  return b;
}

template <class HP>
BusWord<HP> unpack_bus_word(const typename VirimParams<HP>::bus_t& b) {
  using V = VirimParams<HP>;
  BusWord<HP> w;
  write_bits(w.density, V::db - 1, 0, read_bits(b, V::db - 1, 0));
  write_bits(w.gx, V::gb - 1, 0, read_bits(b, V::db + V::gb - 1, V::db));
  write_bits(w.gy, V::gb - 1, 0, read_bits(b, V::db + 2 * V::gb - 1, V::db + V::gb));
  return w;
}

// The bus word of voxel x of row `row`; `above` (y - 1) and `below` (y + 1)
// are null at the view cube's first and last row.
template <class HP>
BusWord<HP> gradient_processor(const typename VirimParams<HP>::density_t* above,
                               const typename VirimParams<HP>::density_t* row,
                               const typename VirimParams<HP>::density_t* below, int x, int W) {
  using V = VirimParams<HP>;
  using d_t = typename V::density_t;
  const d_t* rows[3] = {above, row, below};
  // Sums of +-1, +-2 times densities < 1: |.| < 4, exact at db fraction bits.
  fixed<V::db + 4, 4> sx = 0, sy = 0;
  [[gnu::unused]] sobel_loop : for (int d = 0; d < 3; ++d) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const int w = d == 1 ? 2 : 1;
    const d_t* r = rows[d];
    const d_t right = (r && x + 1 < W) ? r[x + 1] : d_t(0);
    const d_t left = (r && x >= 1) ? r[x - 1] : d_t(0);
    const int xi = x + d - 1;
    const bool in = xi >= 0 && xi < W;
    const d_t up = (below && in) ? below[xi] : d_t(0);
    const d_t down = (above && in) ? above[xi] : d_t(0);
    sx += (right - left) * w;
    sy += (up - down) * w;
  }
  BusWord<HP> out;
  out.density = row[x];
  // /8 exactly (3 more fraction bits), then floored to gb fraction bits.
  const fixed<V::db + 7, 4> wx = sx, wy = sy;
  out.gx = wx >> 3;
  out.gy = wy >> 3;
  return out;
}

}  // namespace virim
}  // namespace hls
}  // namespace voxcast
