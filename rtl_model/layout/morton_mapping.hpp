// Morton (Z-order) layout: the bits of x, y2 and z2 interleaved (x lowest),
// each axis padded to a power of two; an axis that runs out of bits drops out
// of the interleave, so the index space is 2^(bx + by + bz) words. Any
// aligned 8 x 8 x 8-word cube is one row of 512 words.
#pragma once

#include <cstdint>
#include <vector>

#include "rtl_model/layout/address_mapping.hpp"

namespace voxcast::rtl::layout {

class MortonMapping final : public AddressMapping {
 public:
  MortonMapping(const WordGrid& grid, const sdram::Geometry& geometry);
  std::string_view name() const override { return "morton"; }
  std::uint64_t index(const WordCoord& c) const override;

 private:
  // Per axis, each coordinate's bits spread to their interleaved positions;
  // the index is the OR of the three (the hardware's wiring, as tables).
  std::vector<std::uint64_t> spread_[3];
};

}  // namespace voxcast::rtl::layout
