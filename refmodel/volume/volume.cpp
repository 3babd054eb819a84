#include "refmodel/volume/volume.hpp"

#include <cmath>

#include "refmodel/error.hpp"

namespace voxcast::ref {

int bits_for(std::uint32_t max_value) {
  int bits = 1;
  while (bits < 32 && (max_value >> bits) != 0) ++bits;
  return bits;
}

void validate(const Volume& v, const std::string& what) {
  static const char* const kAxis[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a) {
    if (v.dims[a] < 1)
      throw Error(what + ": dimension " + kAxis[a] + " is " + std::to_string(v.dims[a]) +
                  " (must be >= 1)");
    if (!std::isfinite(v.spacing[a]) || v.spacing[a] <= 0.0)
      throw Error(what + ": spacing along " + kAxis[a] + " is " + std::to_string(v.spacing[a]) +
                  " (must be a finite number > 0)");
  }
  if (v.bits < 1 || v.bits > 16)
    throw Error(what + ": voxel width " + std::to_string(v.bits) + " bits is outside 1..16");
  if (v.data.size() != v.voxel_count())
    throw Error(what + ": holds " + std::to_string(v.data.size()) + " voxels but its dims " +
                std::to_string(v.dims[0]) + "x" + std::to_string(v.dims[1]) + "x" +
                std::to_string(v.dims[2]) + " need " + std::to_string(v.voxel_count()));
  if (!std::isfinite(v.slope) || v.slope == 0.0 || !std::isfinite(v.intercept))
    throw Error(what + ": value scaling slope " + std::to_string(v.slope) + ", intercept " +
                std::to_string(v.intercept) + " is not usable (slope must be finite and non-zero)");
  const std::uint32_t limit = v.max_stored();
  for (std::size_t i = 0; i < v.data.size(); ++i)
    if (v.data[i] > limit)
      throw Error(what + ": voxel " + std::to_string(i) + " holds " + std::to_string(v.data[i]) +
                  ", wider than the declared " + std::to_string(v.bits) + " bits");
}

}  // namespace voxcast::ref
