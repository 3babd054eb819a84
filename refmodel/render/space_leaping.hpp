// Beyond the papers (docs/leaping.md): the two options VIZARD II's authors list
// as future work, shared by every engine so they cannot disagree.
//
//   Space leaping. The volume's cells are grouped into blocks of B^3 cells
//   (B = render.leap_block). A sample belongs to the block of its cell's base
//   voxel i0 (the interpolation's lower neighbour, after clamping); the block
//   records the minimum and maximum of the voxel values its cells read, i.e.
//   voxels [bB, bB + B] per axis (the one-voxel apron). A trilinear sample is a
//   convex combination of its eight voxels, so its value lies in [min, max];
//   if the transfer function is transparent over that whole range the sample
//   contributes nothing and is skipped without reading the voxel memory.
//
//   Jittered ray starts. Each ray's first sample moves a deterministic
//   per-pixel fraction of a step along the ray: an integer hash of the pixel
//   coordinates (a few shifts, xors and two multiplications, which hardware
//   computes in the ray set-up), quantized to the t_frac_bits of the ray
//   parameter. It trades the slicing artefacts of a fixed sampling grid for
//   noise.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "refmodel/render/jitter.hpp"
#include "refmodel/volume/volume.hpp"

namespace voxcast::ref {

// The base voxel of a clamped coordinate c along an axis of n voxels: the
// interpolation's i0 = min(floor(c), n - 2), 0 on a one-voxel axis (the same
// in ref::interpolate, bittrue::bt_corners and hls::address_generator).
inline int cell_base(double c, int n) {
  if (n == 1) return 0;
  const int f = static_cast<int>(c);  // c >= 0: truncation is floor
  return f < n - 2 ? f : n - 2;
}

// The min-max block structure of a volume, computed once when the volume is
// loaded (the host's upload step). Values are the stored ones.
struct MinMaxBlocks {
  int block_log2 = 3;
  std::array<int, 3> dims{};    // voxels
  std::array<int, 3> blocks{};  // blocks per axis: (max(n - 2, 0) >> log2) + 1
  std::vector<std::uint16_t> vmin, vmax;  // x fastest

  std::size_t index(int bx, int by, int bz) const {
    return static_cast<std::size_t>(bx) +
           static_cast<std::size_t>(blocks[0]) *
               (static_cast<std::size_t>(by) +
                static_cast<std::size_t>(blocks[1]) * static_cast<std::size_t>(bz));
  }
  std::size_t count() const { return vmin.size(); }
};

// Builds the blocks of `volume` for edge 2^block_log2 cells (block_log2 in 2..6).
MinMaxBlocks make_min_max_blocks(const Volume& volume, int block_log2);

// log2 of render.leap_block (a power of two 4..64, checked by the scene reader).
int leap_block_log2(int leap_block);

}  // namespace voxcast::ref
