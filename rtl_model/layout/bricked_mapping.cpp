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
  for (std::size_t k = 0; k < 3; ++k) edge_mask_[k] = (1u << shift_[k]) - 1u;
  inner_z_shift_ = shift_[0] + shift_[1];
  brick_bits_ = shift_[0] + shift_[1] + shift_[2];
  column_bits_ = std::countr_zero(geometry.columns);
  bank_mask_ = geometry.banks - 1u;
  row_offset_mask_ = (std::uint64_t{1} << (column_bits_ + std::countr_zero(geometry.banks))) - 1u;
  pow2_ = std::has_single_bit(bricks_[0]) && std::has_single_bit(bricks_[1]);
  shift_x_ = std::countr_zero(bricks_[0]);
  shift_xy_ = shift_x_ + std::countr_zero(bricks_[1]);
}

std::uint64_t BrickedMapping::index(const WordCoord& c) const {
  // Step 1: the brick's number, x fastest; step 2: the word inside it, x fastest.
  const std::uint64_t brick =
      (std::uint64_t{c.z2 >> shift_[2]} * bricks_[1] + (c.y2 >> shift_[1])) * bricks_[0] +
      (c.x >> shift_[0]);
  const std::uint64_t inner = (std::uint64_t{c.z2 & edge_mask_[2]} << inner_z_shift_) |
                              (std::uint64_t{c.y2 & edge_mask_[1]} << shift_[0]) |
                              (c.x & edge_mask_[0]);
  const std::uint64_t i = (brick << brick_bits_) | inner;
  return swizzle_ ? swizzled(i) : i;
}

std::uint64_t BrickedMapping::swizzled(std::uint64_t i) const {
  // Rotate the bank field by (y + z) of the brick that starts the row group.
  const std::uint64_t first = (i & ~row_offset_mask_) >> brick_bits_;
  const std::uint64_t by = pow2_ ? (first >> shift_x_) & (bricks_[1] - 1u)
                                 : (first / bricks_[0]) % bricks_[1];
  const std::uint64_t bz =
      pow2_ ? first >> shift_xy_ : first / (std::uint64_t{bricks_[0]} * bricks_[1]);
  const std::uint64_t bank = (((i >> column_bits_) & bank_mask_) + by + bz) & bank_mask_;
  return (i & ~(bank_mask_ << column_bits_)) | (bank << column_bits_);
}

}  // namespace voxcast::rtl::layout
