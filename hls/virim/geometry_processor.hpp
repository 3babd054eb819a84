// VIRIM's geometry processor (virim-1994.txt, "Rotator Board": "calculates the
// addresses of the voxels to be interpolated using the rotation matrix, the
// matrix for the perspective, and the zooming factor"; docs/heidelberg.md §7.1).
// For output voxel (i, j, k) of the view cube: p = base + M u with
// u = ((i - cx) s_j, j - cy, (k - cz) s_j), exact until one TRN to cf bits.
#pragma once

#include "hls/pragma.hpp"
#include "hls/virim/params.hpp"

namespace voxcast {
namespace hls {
namespace virim {

template <class HP>
struct GeometryRegisters {
  using V = VirimParams<HP>;
  typename V::matrix_t M[3][3];              // R^T / zoom
  typename V::pos_t base[3];                 // c - R^T t
  typename V::offset_t cx, cy, cz;           // (W-1)/2, (D-1)/2, (H-1)/2
  typename V::scale_t scale[V::max_view];    // per-plane perspective factor s_j
  int W, D, H;
};

// The position rounded to the ROM's grid (RND to wb fraction bits: the
// nearest of the 2^wb mask offsets; a fraction that rounds up to 1 carries
// into the integer part, the paper's "distance = 1 handled separately"), its
// integer part (the 2x2x2 neighbourhood's lower corner) and the ROM address.
template <class HP>
struct Address {
  typename VirimParams<HP>::coord_t x0[3];
  uint_t<HP::weight_bits> q[3];
};

template <class HP>
void data_position(const GeometryRegisters<HP>& g, int i, int j, int k,
                   typename VirimParams<HP>::pos_t p[3]) {
  using V = VirimParams<HP>;
  const typename V::view_t vi = i, vj = j, vk = k;
  const typename V::offset_t ox = vi - g.cx, oy = vj - g.cy, oz = vk - g.cz;
  const typename V::scale_t s = g.scale[j];
  const auto ux = ox * s;
  const auto uz = oz * s;
  [[gnu::unused]] position_loop : for (int r = 0; r < 3; ++r) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    p[r] = g.base[r] + g.M[r][0] * ux + g.M[r][1] * oy + g.M[r][2] * uz;
  }
}

template <class HP>
Address<HP> geometry_processor(const GeometryRegisters<HP>& g, int i, int j, int k) {
  using V = VirimParams<HP>;
  typename V::pos_t p[3];
  data_position<HP>(g, i, j, k, p);
  Address<HP> a;
  [[gnu::unused]] address_loop : for (int r = 0; r < 3; ++r) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const typename V::rom_pos_t pr = p[r];
    const typename V::floor_t fl = pr;
    const ufixed<V::wb, 0> f = pr - fl;
    a.x0[r] = fl.to_int();
    a.q[r] = read_bits(f, V::wb - 1, 0);
  }
  return a;
}

}  // namespace virim
}  // namespace hls
}  // namespace voxcast
