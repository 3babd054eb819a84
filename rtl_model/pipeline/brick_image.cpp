#include "rtl_model/pipeline/brick_image.hpp"

#include <string>

#include "refmodel/error.hpp"

namespace voxcast::rtl::pipeline {

namespace {
std::string voxel(const std::array<int, 3>& v) {
  return "(" + std::to_string(v[0]) + ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) +
         ")";
}
}  // namespace

BrickImage::BrickImage(const layout::BurstLayout& layout, const std::array<int, 3>& dims) {
  const std::array<int, 3>& b = layout.brick();
  std::array<int, 3> v{};
  for (v[2] = 0; v[2] < dims[2]; v[2] += b[2])
    for (v[1] = 0; v[1] < dims[1]; v[1] += b[1])
      for (v[0] = 0; v[0] < dims[0]; v[0] += b[0]) {
        const layout::BurstAddress a = layout.burst_of(v);
        auto& bricks = origin_[static_cast<std::size_t>(a.channel)];
        if (a.index >= bricks.size())
          bricks.resize(a.index + 1, {kUnwritten, kUnwritten, kUnwritten});
        std::array<int, 3>& o = bricks[a.index];
        if (o[0] != kUnwritten)
          throw Error("DDR4 card: the burst layout " + layout.name() + " puts the bricks at " +
                      voxel(o) + " and " + voxel(v) + " in one burst (channel " +
                      std::to_string(a.channel) + ", index " + std::to_string(a.index) + ")");
        o = v;
      }
}

const std::array<int, 3>& BrickImage::origin(int channel, std::uint64_t index) const {
  const auto& bricks = origin_[static_cast<std::size_t>(channel)];
  if (index >= bricks.size() || bricks[index][0] == kUnwritten)
    throw Error("DDR4 card: channel " + std::to_string(channel) + " burst " +
                std::to_string(index) + " holds no brick of the volume");
  return bricks[index];
}

}  // namespace voxcast::rtl::pipeline
