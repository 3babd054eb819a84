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

}  // namespace voxcast::rtl::layout
