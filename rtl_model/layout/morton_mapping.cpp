#include "rtl_model/layout/morton_mapping.hpp"

#include <bit>

namespace voxcast::rtl::layout {

MortonMapping::MortonMapping(const WordGrid& grid, const sdram::Geometry& geometry)
    : AddressMapping(grid, geometry) {
  const std::uint32_t n[3] = {grid.nx, grid.ny2, grid.nz2};
  int bits[3];
  for (int k = 0; k < 3; ++k)
    bits[k] = n[k] <= 1u ? 0 : static_cast<int>(std::bit_width(n[k] - 1u));
  // Interleave position of bit b of axis k: x, y2, z2 in turn, skipping an
  // axis whose bits are used up.
  std::vector<int> position[3];
  int next = 0;
  for (int b = 0; b < 32; ++b)
    for (int k = 0; k < 3; ++k)
      if (b < bits[k]) position[k].push_back(next++);
  check_fits(name(), std::uint64_t{1} << next, geometry);
  for (int k = 0; k < 3; ++k) {
    auto& table = spread_[k];
    table.resize(n[k]);
    for (std::uint32_t v = 0; v < n[k]; ++v) {
      std::uint64_t s = 0;
      for (int b = 0; b < bits[k]; ++b)
        if ((v >> b) & 1u) s |= std::uint64_t{1} << position[k][static_cast<std::size_t>(b)];
      table[v] = s;
    }
  }
}

std::uint64_t MortonMapping::index(const WordCoord& c) const {
  return spread_[0][c.x] | spread_[1][c.y2] | spread_[2][c.z2];
}

}  // namespace voxcast::rtl::layout
