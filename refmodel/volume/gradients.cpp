#include "refmodel/volume/gradients.hpp"

#include <algorithm>
#include <thread>

#include "refmodel/error.hpp"
#include "refmodel/parallel.hpp"

namespace voxcast::ref {
namespace {

struct ClampedGrid {
  const Volume& v;
  float operator()(int x, int y, int z) const {
    x = std::clamp(x, 0, v.dims[0] - 1);
    y = std::clamp(y, 0, v.dims[1] - 1);
    z = std::clamp(z, 0, v.dims[2] - 1);
    return static_cast<float>(v.at(x, y, z));
  }
};

glm::vec3 central_difference(const ClampedGrid& f, int x, int y, int z) {
  return {0.5f * (f(x + 1, y, z) - f(x - 1, y, z)), 0.5f * (f(x, y + 1, z) - f(x, y - 1, z)),
          0.5f * (f(x, y, z + 1) - f(x, y, z - 1))};
}

// Sobel: derivative taps [-1 0 1] along the axis, smoothing taps [1 2 1] on the
// two others; the weights sum to 32 on a unit ramp, hence the division.
glm::vec3 sobel(const ClampedGrid& f, int x, int y, int z) {
  static constexpr float kSmooth[3] = {1.0f, 2.0f, 1.0f};
  glm::vec3 g{0.0f};
  for (int b = -1; b <= 1; ++b)
    for (int a = -1; a <= 1; ++a) {
      const float w = kSmooth[a + 1] * kSmooth[b + 1];
      g.x += w * (f(x + 1, y + a, z + b) - f(x - 1, y + a, z + b));
      g.y += w * (f(x + a, y + 1, z + b) - f(x + a, y - 1, z + b));
      g.z += w * (f(x + a, y + b, z + 1) - f(x + a, y + b, z - 1));
    }
  return g / 32.0f;
}

}  // namespace

GradientField compute_gradients(const Volume& v, GradientOperator op) {
  GradientField field;
  field.g.resize(v.voxel_count());
  const ClampedGrid f{v};
  parallel_for(v.dims[2], [&](int z) {
    for (int y = 0; y < v.dims[1]; ++y)
      for (int x = 0; x < v.dims[0]; ++x)
        field.g[v.index(x, y, z)] =
            op == GradientOperator::Central ? central_difference(f, x, y, z) : sobel(f, x, y, z);
  });
  return field;
}

GradientOperator parse_gradient_operator(const std::string& name) {
  if (name == "central") return GradientOperator::Central;
  if (name == "sobel") return GradientOperator::Sobel;
  throw Error("unknown gradient operator \"" + name + "\" (expected \"central\" or \"sobel\")");
}

const char* to_string(GradientOperator op) {
  return op == GradientOperator::Central ? "central" : "sobel";
}

}  // namespace voxcast::ref
