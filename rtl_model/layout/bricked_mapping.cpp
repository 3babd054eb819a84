#include "rtl_model/layout/bricked_mapping.hpp"

#include <bit>
#include <string>

#include "refmodel/error.hpp"

namespace voxcast::rtl::layout {

BrickedMapping::BrickedMapping(const WordGrid& grid, const sdram::Geometry& geometry,
                               std::array<std::uint32_t, 3> brick, bool swizzle)
    : AddressMapping(grid, geometry), swizzle_(swizzle) {
  const std::uint32_t n[3] = {grid.nx, grid.ny2, grid.nz2};
  std::uint64_t space = 1;
  for (std::size_t k = 0; k < 3; ++k) {
    if (!std::has_single_bit(brick[k]))
      throw Error("address mapping 'bricked': brick edge " + std::to_string(brick[k]) +
                  " is not a power of two");
    shift_[k] = static_cast<std::uint32_t>(std::countr_zero(brick[k]));
    bricks_[k] = (n[k] + brick[k] - 1u) >> shift_[k];
    space *= std::uint64_t{bricks_[k]} << shift_[k];
  }
  check_fits(name(), space, geometry);
  pow2_ = std::has_single_bit(bricks_[0]) && std::has_single_bit(bricks_[1]);
  shift_x_ = std::countr_zero(bricks_[0]);
  shift_xy_ = shift_x_ + std::countr_zero(bricks_[1]);
}

std::uint64_t BrickedMapping::index(const WordCoord& c) const {
  const std::uint32_t v[3] = {c.x, c.y2, c.z2};
  std::uint64_t brick = 0, inner = 0;
  // Step 1: the brick's number, x fastest; step 2: the word inside it, x fastest.
  for (int k = 2; k >= 0; --k) {
    const auto i = static_cast<std::size_t>(k);
    brick = brick * bricks_[i] + (v[i] >> shift_[i]);
    inner = (inner << shift_[i]) | (v[i] & ((1u << shift_[i]) - 1u));
  }
  const std::uint32_t brick_bits = shift_[0] + shift_[1] + shift_[2];
  const std::uint64_t i = (brick << brick_bits) | inner;
  if (!swizzle_) return i;
  // Rotate the bank field by (y + z) of the brick that starts the row group.
  const sdram::Geometry& g = geometry();
  const int cb = std::countr_zero(g.columns);
  const int bb = std::countr_zero(g.banks);
  const std::uint64_t row = i >> (cb + bb);
  const std::uint64_t first = (row << (cb + bb)) >> brick_bits;
  const std::uint64_t by = pow2_ ? (first >> shift_x_) & (bricks_[1] - 1u)
                                 : (first / bricks_[0]) % bricks_[1];
  const std::uint64_t bz =
      pow2_ ? first >> shift_xy_ : first / (std::uint64_t{bricks_[0]} * bricks_[1]);
  const std::uint64_t mask = g.banks - 1u;
  const std::uint64_t bank = (((i >> cb) & mask) + by + bz) & mask;
  return (i & ~(mask << cb)) | (bank << cb);
}

}  // namespace voxcast::rtl::layout
