// Bricked layout: the grid is cut into bricks of bx x by x bz words (powers of
// two; 8 x 8 x 8 = 512 words = one row of the MT4LSDT864A), each brick stored
// contiguously (x fastest inside), bricks in x-fastest order. A ray crossing
// a brick in any direction stays in one row for about 8 word steps (16 voxels
// in y and z, 8 in x), instead of streaming only along x.
#pragma once

#include <array>
#include <cstdint>

#include "rtl_model/layout/address_mapping.hpp"

namespace voxcast::rtl::layout {

class BrickedMapping final : public AddressMapping {
 public:
  // Throws voxcast::Error unless every brick edge is a power of two.
  BrickedMapping(const WordGrid& grid, const sdram::Geometry& geometry,
                 std::array<std::uint32_t, 3> brick);
  std::string_view name() const override { return "bricked"; }
  std::uint64_t index(const WordCoord& c) const override;

 private:
  std::array<std::uint32_t, 3> shift_{};  // log2 of the brick edges
  std::array<std::uint32_t, 3> bricks_{};  // bricks per axis (rounded up)
};

}  // namespace voxcast::rtl::layout
