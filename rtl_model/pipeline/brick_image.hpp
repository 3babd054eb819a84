// What the four DDR4 channels hold (docs/sdram.md §10): for every burst a
// BurstLayout places, the brick of the volume whose voxels it carries. The
// DDR4 card reads a returning burst's voxels through this image, by the
// burst's (channel, index) alone, so a layout that put two bricks in one
// burst, or a sample that asked for the wrong burst, shows as a wrong pixel
// (or, for two bricks in one burst, as this constructor's error).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "rtl_model/layout/burst_layout.hpp"

namespace voxcast::rtl::pipeline {

class BrickImage {
 public:
  // Lays out every brick of a volume of `dims`. Throws voxcast::Error naming
  // the layout and both bricks if two bricks land in one burst.
  BrickImage(const layout::BurstLayout& layout, const std::array<int, 3>& dims);

  // The lowest voxel of the brick in burst `index` of `channel`. Throws
  // voxcast::Error for a burst the layout never wrote.
  const std::array<int, 3>& origin(int channel, std::uint64_t index) const;

 private:
  static constexpr int kUnwritten = -1;
  std::array<std::vector<std::array<int, 3>>, layout::kBurstChannels> origin_;
};

}  // namespace voxcast::rtl::pipeline
