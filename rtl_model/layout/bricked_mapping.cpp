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

}  // namespace voxcast::rtl::layout
