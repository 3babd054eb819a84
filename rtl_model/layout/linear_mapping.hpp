// Linear layout: the word index is x + nx (y2 + ny2 z2), x fastest. With the
// 256^3 volume a row of 512 words holds two lines of x, and a z2 slice
// (32,768 words) is 64 rows, so successive slices fall into the same bank:
// rays along x stream, rays along z change rows every second sample.
#pragma once

#include "rtl_model/layout/address_mapping.hpp"

namespace voxcast::rtl::layout {

class LinearMapping final : public AddressMapping {
 public:
  LinearMapping(const WordGrid& grid, const sdram::Geometry& geometry);
  std::string_view name() const override { return "linear"; }
  std::uint64_t index(const WordCoord& c) const override { return grid().linear(c); }
};

}  // namespace voxcast::rtl::layout
