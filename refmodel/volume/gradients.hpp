// Per-voxel gradients: computed once when the volume loads and then treated as a
// voxel property, interpolated like the value (VIZARD II section 2.1: "gradients
// are considered to be a voxel property", which is why its voxel word carries
// gradient fields next to the value).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "refmodel/volume/volume.hpp"

namespace voxcast::ref {

enum class GradientOperator {
  Central,  // (v[i+1] - v[i-1]) / 2 per axis
  Sobel,    // 3x3x3 Sobel: [-1 0 1] derivative, [1 2 1] smoothing on the other axes, / 32
};

// Gradients in stored-value units per voxel index step (index space, not world
// space: the shading stage divides by the normalised spacing). Indices beyond
// the border are clamped, so the border gradient is the one-sided difference
// halved. All values are exact in float: central differences of integers are
// half-integers, Sobel sums are integers / 32.
struct GradientField {
  std::vector<glm::vec3> g;  // one per voxel, same order as Volume::data
  const glm::vec3& at(std::size_t index) const { return g[index]; }
};

GradientField compute_gradients(const Volume& v, GradientOperator op);

GradientOperator parse_gradient_operator(const std::string& name);  // "central" | "sobel"
const char* to_string(GradientOperator op);

}  // namespace voxcast::ref
