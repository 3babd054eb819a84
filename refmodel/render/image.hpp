// A rendered image: premultiplied RGBA in double, row 0 at the top.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec4.hpp>

namespace voxcast::ref {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<glm::dvec4> pixels;  // width*height, row-major, premultiplied (r,g,b,alpha)

  Image() = default;
  Image(int w, int h)
      : width(w), height(h), pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h),
                                     glm::dvec4(0.0)) {}
  glm::dvec4& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const glm::dvec4& at(int x, int y) const {
    return pixels[static_cast<std::size_t>(y) * width + x];
  }
};

}  // namespace voxcast::ref
