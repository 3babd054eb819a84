// Bricked layout: the grid is cut into bricks of bx x by x bz words (powers of
// two; 8 x 8 x 8 = 512 words = one row of the MT4LSDT864A), each brick stored
// contiguously (x fastest inside), bricks in x-fastest order. A ray crossing
// a brick in any direction stays in one row for about 8 word steps (16 voxels
// in y and z, 8 in x), instead of streaming only along x.
//
// Swizzled ("bricked-swizzled"): the bank of every word is rotated by
// (brick y + brick z) of the first brick of its row group, mod the banks.
// With bricks of one row and a brick count along x that the banks divide
// (8 x 8 x 8 words at 256^3), the next brick along y or z is then in the
// next bank, as the next brick along x always is, so look-ahead activation
// can open it while the current one streams (docs/performance.md §7); the
// plain layout puts it in the same bank. The rotation depends on the row
// only, so the mapping stays injective for any grid (permutation-based
// interleaving, Zhang, Zhu and Zhang, MICRO 2000).
#pragma once

#include <array>
#include <cstdint>

#include "rtl_model/layout/address_mapping.hpp"

namespace voxcast::rtl::layout {

class BrickedMapping final : public AddressMapping {
 public:
  // Throws voxcast::Error unless every brick edge is a power of two.
  BrickedMapping(const WordGrid& grid, const sdram::Geometry& geometry,
                 std::array<std::uint32_t, 3> brick, bool swizzle = false);
  std::string_view name() const override { return swizzle_ ? "bricked-swizzled" : "bricked"; }
  // Inline (below): the address generator maps four words per sample, and
  // the pipeline calls it on this final class, without the virtual call.
  std::uint64_t index(const WordCoord& c) const override;

 private:
  // The bank of the unswizzled index `i` rotated.
  std::uint64_t swizzled(std::uint64_t i) const;

  // Everything index() needs that depends only on the grid, the bricks and
  // the geometry, computed once: it runs for four words per sample.
  std::array<std::uint32_t, 3> shift_{};  // log2 of the brick edges
  std::array<std::uint32_t, 3> bricks_{};  // bricks per axis (rounded up)
  std::array<std::uint32_t, 3> edge_mask_{};  // brick edge - 1: a word's offset in its brick
  std::uint32_t inner_z_shift_ = 0;           // shift_[0] + shift_[1]
  std::uint32_t brick_bits_ = 0;              // log2 of the words in a brick
  int column_bits_ = 0;                       // log2 of the columns
  std::uint64_t bank_mask_ = 0;               // banks - 1
  std::uint64_t row_offset_mask_ = 0;         // the column and bank bits of an index
  // The swizzle's divisions by bricks_[0] and bricks_[0] * bricks_[1] as
  // shifts when those are powers of two (every 2^n volume); 0: divide.
  int shift_x_ = 0, shift_xy_ = 0;
  bool pow2_ = false;
  bool swizzle_ = false;
};

inline std::uint64_t BrickedMapping::index(const WordCoord& c) const {
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

inline std::uint64_t BrickedMapping::swizzled(std::uint64_t i) const {
  // Rotate the bank field by (y + z) of the brick that starts the row group.
  const std::uint64_t first = (i & ~row_offset_mask_) >> brick_bits_;
  const std::uint64_t by =
      pow2_ ? (first >> shift_x_) & (bricks_[1] - 1u) : (first / bricks_[0]) % bricks_[1];
  const std::uint64_t bz =
      pow2_ ? first >> shift_xy_ : first / (std::uint64_t{bricks_[0]} * bricks_[1]);
  const std::uint64_t bank = (((i >> column_bits_) & bank_mask_) + by + bz) & bank_mask_;
  return (i & ~(bank_mask_ << column_bits_)) | (bank << column_bits_);
}

}  // namespace voxcast::rtl::layout
