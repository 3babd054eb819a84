// The voxel grid as every engine sees it.
//
// Voxel values are stored as unsigned integers of `bits` bits (the hardware's
// voxel word holds an unsigned value field, VIZARD II section 2.2); the data's
// physical unit (Hounsfield units for CT, scanner intensity for MRI) is
//   physical = slope * stored + intercept.
// Loaders choose the smallest `bits` that holds the data's range exactly, so bit
// widths follow from the data, and transfer functions are written in physical
// units and converted with to_stored().
//
// Coordinates: voxel centres sit at integer indices (x, y, z), x fastest in
// memory. `spacing` is the physical voxel size in millimetres.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

namespace voxcast::ref {

struct Volume {
  std::array<int, 3> dims{0, 0, 0};       // voxels along x, y, z (each >= 1)
  glm::dvec3 spacing{1.0, 1.0, 1.0};      // mm per voxel along x, y, z (each > 0)
  int bits = 8;                           // stored value width, 1..16
  double slope = 1.0;                     // physical = slope * stored + intercept
  double intercept = 0.0;
  std::vector<std::uint16_t> data;        // dims[0]*dims[1]*dims[2] values, x fastest
  std::string source;                     // where it came from, for messages and reports

  std::size_t voxel_count() const {
    return static_cast<std::size_t>(dims[0]) * static_cast<std::size_t>(dims[1]) *
           static_cast<std::size_t>(dims[2]);
  }
  std::size_t index(int x, int y, int z) const {
    return (static_cast<std::size_t>(z) * static_cast<std::size_t>(dims[1]) +
            static_cast<std::size_t>(y)) * static_cast<std::size_t>(dims[0]) +
           static_cast<std::size_t>(x);
  }
  std::uint16_t at(int x, int y, int z) const { return data[index(x, y, z)]; }
  std::uint32_t max_stored() const { return (1u << bits) - 1u; }
  double to_physical(double stored) const { return slope * stored + intercept; }
  double to_stored(double physical) const { return (physical - intercept) / slope; }
};

// Throws voxcast::Error naming `what` if the volume breaks an invariant above
// (zero or negative dims, data size not matching dims, values wider than bits,
// non-positive or non-finite spacing, zero slope).
void validate(const Volume& v, const std::string& what);

// Smallest bit width (>= 1) that holds every value in [0, max_value].
int bits_for(std::uint32_t max_value);

}  // namespace voxcast::ref
