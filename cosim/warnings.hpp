// Warnings about a scene the fixed-point design renders, but not as the float
// reference does: an input that is valid, yet falls below what the profile's
// widths can represent, so a material vanishes from every fixed-point image.
// Unlike the errors of check_fixed_point (a width that cannot hold a value at
// all), the render proceeds; the command prints each warning as one line on
// stderr, "voxcast: warning: ...".
#pragma once

#include <string>
#include <vector>

#include "refmodel/scene/scene.hpp"
#include "refmodel/volume/volume.hpp"

namespace voxcast::cosim {

// One line per transfer-function control point whose material vanishes:
//  - its opacity-corrected alpha (docs/pipeline.md §4.2: U(1 - (1 - alpha)^step,
//    alpha_bits) with step = 1/render.oversampling) rounds to 0 although alpha > 0:
//      classification.points[2] alpha 0.001 vanishes at oversampling 16: its step
//      opacity 6.3e-05 is below half an LSB of precision.alpha_bits = 8 (0.00195)
//  - binary interpolation: the values it classifies (from its value up to the next
//    point's) meet the volume's data range but hold no classification-table entry
//    (§4.2: entry i sits at i·2^(value_bits - tf_addr_bits) in the value field), so
//    every such sample reads a neighbouring point's entry:
//      classification.points[1] value 65535 vanishes: no classification-table entry
//      lies between it and the data's largest value 65535 (precision.tf_addr_bits =
//      14: entries every 4 stored values, the last at 65532)
// Empty for a MIP scene (no classification in the datapath). Reads the scene's
// profile (scene.precision), its points, its oversampling, and the volume's
// stored-value range and scaling.
std::vector<std::string> fixed_point_warnings(const ref::Scene& scene, const ref::Volume& volume);

}  // namespace voxcast::cosim
