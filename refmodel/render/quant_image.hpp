// An image as the card writes it: integer RGBA channels of `bits` bits
// (docs/pipeline.md §8). The hls engine, the bit-true reference and the cycle
// model all produce one; two are bit-exact iff their pixel vectors are equal.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "refmodel/render/image.hpp"

namespace voxcast::ref {

struct QuantImage {
  int width = 0;
  int height = 0;
  int bits = 8;
  std::vector<std::array<std::uint32_t, 4>> pixels;  // row-major, premultiplied RGBA

  QuantImage() = default;
  QuantImage(int w, int h, int b)
      : width(w), height(h), bits(b),
        pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h),
               std::array<std::uint32_t, 4>{0, 0, 0, 0}) {}
  std::array<std::uint32_t, 4>& at(int x, int y) {
    return pixels[static_cast<std::size_t>(y) * width + x];
  }
  const std::array<std::uint32_t, 4>& at(int x, int y) const {
    return pixels[static_cast<std::size_t>(y) * width + x];
  }
  double full_scale() const { return static_cast<double>((1u << bits) - 1u); }

  // As a float image (channel / full scale), for writing and viewing.
  Image to_image() const {
    Image img(width, height);
    for (std::size_t i = 0; i < pixels.size(); ++i)
      for (int c = 0; c < 4; ++c) img.pixels[i][c] = pixels[i][c] / full_scale();
    return img;
  }
};

}  // namespace voxcast::ref
