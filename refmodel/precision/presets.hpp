// Named precision presets and the checks that a profile can hold a scene.
#pragma once

#include <string>
#include <vector>

#include "refmodel/precision/profile.hpp"
#include "refmodel/volume/volume.hpp"

namespace voxcast {

// "vizard2": as close to the VIZARD II card as the paper allows (32-bit voxel
// word = 8-bit value + 3 x 8-bit gradient; classification entry in two 32-bit
// SRAM words, 256 entries = 2 KB; reflectance maps of 3 KB).
// "balanced": the default; the accuracy target of docs/accuracy.md.
// "precise": wide everywhere, for judging the others.
PrecisionProfile preset_profile(const std::string& name);  // throws voxcast::Error if unknown
std::vector<std::string> preset_names();

// One named field of the profile, for [precision] overrides, sweeps and reports.
struct ProfileField {
  const char* name;
  int PrecisionProfile::*member;
  int min, max;     // the range the kernels support
  const char* doc;  // one line: what it is (docs/scenes.md lists them)
};
const std::vector<ProfileField>& profile_fields();

// Throws voxcast::Error naming the width that cannot hold a value of the scene
// ("precision.value_bits = 8 cannot hold the volume's 12-bit values").
void check_profile_fits(const PrecisionProfile& p, const ref::Volume& volume,
                        double max_gradient_component);

// Widths of derived quantities (docs/pipeline.md), shared by hls and bit-true.
constexpr int voxel_word_bits(const PrecisionProfile& p) {
  return p.value_bits + 3 * p.gradient_bits;
}
constexpr int tf_entry_bits(const PrecisionProfile& p) {
  return 3 * p.color_bits + p.alpha_bits + 3 * p.k_bits;
}
// Entries per reflectance-map table: one per cell (nearest) or per cell
// corner (bilinear), docs/pipeline.md §5.
constexpr int rm_entries(const PrecisionProfile& p) {
  const int n = p.rm_bilinear ? p.rm_res + 1 : p.rm_res;
  return 6 * n * n;
}

}  // namespace voxcast
