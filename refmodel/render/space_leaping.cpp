#include "refmodel/render/space_leaping.hpp"

#include <algorithm>
#include <string>

#include "refmodel/error.hpp"

namespace voxcast::ref {

int leap_block_log2(int leap_block) {
  for (int lb = 2; lb <= 6; ++lb)
    if (leap_block == 1 << lb) return lb;
  throw Error("render.leap_block = " + std::to_string(leap_block) +
              " must be a power of two in 4..64");
}

MinMaxBlocks make_min_max_blocks(const Volume& volume, int block_log2) {
  if (block_log2 < 2 || block_log2 > 6)
    throw Error("space leaping: block edge 2^" + std::to_string(block_log2) + " is outside 4..64");
  MinMaxBlocks b;
  b.block_log2 = block_log2;
  b.dims = volume.dims;
  for (std::size_t k = 0; k < 3; ++k) b.blocks[k] = (std::max(volume.dims[k] - 2, 0) >> block_log2) + 1;
  const std::size_t n = static_cast<std::size_t>(b.blocks[0]) * static_cast<std::size_t>(b.blocks[1]) *
                        static_cast<std::size_t>(b.blocks[2]);
  b.vmin.assign(n, 0xffff);
  b.vmax.assign(n, 0);
  // Voxel x is read by the cells of block x >> lb and, when it starts a block
  // (x = bB, the apron of block b - 1), by block b - 1 too. Along an axis the
  // last cell n - 2 reads voxel n - 1, which the rule gives to block
  // (n - 1) >> lb only if that block exists: clamp to the last block.
  const auto range = [&](int x, std::size_t k, int& lo, int& hi) {
    const int last = b.blocks[k] - 1;
    hi = std::min(x >> block_log2, last);
    lo = (x & ((1 << block_log2) - 1)) == 0 && x > 0 ? std::min((x >> block_log2) - 1, last) : hi;
  };
  for (int z = 0; z < volume.dims[2]; ++z) {
    int z0, z1;
    range(z, 2, z0, z1);
    for (int y = 0; y < volume.dims[1]; ++y) {
      int y0, y1;
      range(y, 1, y0, y1);
      for (int x = 0; x < volume.dims[0]; ++x) {
        int x0, x1;
        range(x, 0, x0, x1);
        const std::uint16_t v = volume.at(x, y, z);
        for (int bz = z0; bz <= z1; ++bz)
          for (int by = y0; by <= y1; ++by)
            for (int bx = x0; bx <= x1; ++bx) {
              const std::size_t i = b.index(bx, by, bz);
              b.vmin[i] = std::min(b.vmin[i], v);
              b.vmax[i] = std::max(b.vmax[i], v);
            }
      }
    }
  }
  return b;
}

}  // namespace voxcast::ref
