// VIRIM's interpolation processor (virim-1994.txt, "Rotator Board": "the eight
// values from the RAM are mapped onto density values using a freely modifiable
// LUT ... using eight density values and eight weights the interpolation
// processor interpolates the density values"; docs/heidelberg.md §7.3). The
// weights come from the ROM at the geometry processor's address; the 8 of an
// entry sum to exactly 1, so the convex sum never exceeds the largest density.
#pragma once

#include <cstdint>

#include "hls/pragma.hpp"
#include "hls/virim/params.hpp"

namespace voxcast {
namespace hls {
namespace virim {

template <class HP>
struct InterpolationTables {
  using V = VirimParams<HP>;
  typename V::density_t lut[V::lut_entries];      // gray value -> density
  typename V::weight_t rom[V::rom_entries][8];    // address (qz qy qx) -> 8 weights
};

template <class HP>
typename VirimParams<HP>::density_t interpolation_processor(const InterpolationTables<HP>& t,
                                                           const uint_t<3 * HP::weight_bits>& addr,
                                                           const std::uint16_t value[8],
                                                           const bool valid[8]) {
  using V = VirimParams<HP>;
  // Each product is exact; the sum of 8 has wf + db fraction bits and stays below 1.
  ufixed<V::wf + V::db + 4, 4> sum = 0;
  [[gnu::unused]] mac_loop : for (int c = 0; c < 8; ++c) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const typename V::density_t rho = valid[c] ? t.lut[value[c]] : typename V::density_t(0);
    sum += t.rom[addr.to_uint64()][c] * rho;
  }
  const typename V::density_t out = sum;  // TRN to db bits
  return out;
}

}  // namespace virim
}  // namespace hls
}  // namespace voxcast
