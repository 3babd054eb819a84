#include "refmodel/precision/presets.hpp"

#include <cmath>

#include "refmodel/error.hpp"
#include "refmodel/precision/preset_profiles.hpp"

namespace voxcast {

PrecisionProfile preset_profile(const std::string& name) {
  if (name == "vizard2") return kVizard2;
  if (name == "balanced") return kBalanced;
  if (name == "precise") return kPrecise;
  std::string list;
  for (const auto& n : preset_names()) list += (list.empty() ? "" : ", ") + n;
  throw Error("unknown precision profile \"" + name + "\" (presets: " + list + ")");
}

std::vector<std::string> preset_names() { return {"vizard2", "balanced", "precise"}; }

const std::vector<ProfileField>& profile_fields() {
  using P = PrecisionProfile;
  static const std::vector<ProfileField> f = {
      {"addr_bits", &P::addr_bits, 1, 12, "voxel index bits per axis (volumes up to 2^addr_bits)"},
      {"pos_frac_bits", &P::pos_frac_bits, 4, 24, "fraction bits of sample positions"},
      {"dir_frac_bits", &P::dir_frac_bits, 8, 24, "fraction bits of ray directions in ray setup"},
      {"rsqrt_seed_bits", &P::rsqrt_seed_bits, 3, 12, "seed-table address bits of the rsqrt unit"},
      {"t_frac_bits", &P::t_frac_bits, 4, 20, "fraction bits of clip parameters (in samples)"},
      {"weight_bits", &P::weight_bits, 1, 10, "interpolation weight bits (6-bit weight addressing)"},
      {"value_bits", &P::value_bits, 1, 16, "voxel value field bits"},
      {"gradient_bits", &P::gradient_bits, 2, 24, "bits per stored gradient component, sign included"},
      {"gradient_frac_bits", &P::gradient_frac_bits, 0, 8, "fraction bits of stored gradients"},
      {"sample_frac_bits", &P::sample_frac_bits, 0, 12, "fraction bits of interpolated samples"},
      {"tf_addr_bits", &P::tf_addr_bits, 1, 16, "classification table address bits"},
      {"color_bits", &P::color_bits, 1, 16, "bits of r, g, b in the classification table"},
      {"alpha_bits", &P::alpha_bits, 1, 24, "bits of the opacity-corrected alpha"},
      {"k_bits", &P::k_bits, 1, 16, "bits of ka, kd, ks"},
      // At most 2^20 entries: 4 x 12 bytes a frame already takes 12 MB on the host.
      {"preint_addr_bits", &P::preint_addr_bits, 1, 10,
       "pre-integration table address bits per segment end (2^(2b) entries)"},
      {"rm_res", &P::rm_res, 1, 256, "reflectance-map cells per cube-face edge"},
      {"rm_frac_bits", &P::rm_frac_bits, 1, 20, "fraction bits of reflectance-map entries"},
      {"rm_int_bits", &P::rm_int_bits, 0, 4, "integer bits of reflectance-map entries"},
      {"rm_bilinear", &P::rm_bilinear, 0, 1,
       "reflectance-map lookup: 0 nearest cell (VIZARD II), 1 bilinear between cell corners"},
      {"rm_weight_bits", &P::rm_weight_bits, 1, 12,
       "fraction bits of the bilinear reflectance-map weights (rm_bilinear = 1)"},
      {"shade_bits", &P::shade_bits, 1, 20, "fraction bits of shaded colours"},
      {"acc_bits", &P::acc_bits, 2, 24, "fraction bits of the colour and opacity accumulators"},
      {"out_bits", &P::out_bits, 1, 16, "bits per output channel"},
  };
  return f;
}

void check_profile_fits(const PrecisionProfile& p, const ref::Volume& v,
                        double max_gradient_component) {
  if (v.bits > p.value_bits)
    throw Error("precision.value_bits = " + std::to_string(p.value_bits) +
                " cannot hold the volume's " + std::to_string(v.bits) + "-bit values (" +
                v.source + ")");
  static const char* const kAxis[3] = {"x", "y", "z"};
  for (int a = 0; a < 3; ++a)
    if (v.dims[a] > (1 << p.addr_bits))
      throw Error("precision.addr_bits = " + std::to_string(p.addr_bits) + " cannot address " +
                  std::to_string(v.dims[a]) + " voxels along " + kAxis[a] + " (at most " +
                  std::to_string(1 << p.addr_bits) + ")");
  // A gradient component, scaled with the values into the value field
  // (docs/pipeline.md §3.4), must fit its signed field with its fraction bits.
  const double limit = std::ldexp(1.0, p.gradient_bits - 1 - p.gradient_frac_bits);
  max_gradient_component = std::ldexp(max_gradient_component, p.value_bits - v.bits);
  if (max_gradient_component >= limit)
    throw Error("precision.gradient_bits = " + std::to_string(p.gradient_bits) + " (with " +
                std::to_string(p.gradient_frac_bits) +
                " fraction bits) cannot hold the volume's gradient component " +
                std::to_string(max_gradient_component) + " (limit " + std::to_string(limit) +
                ")");
}

}  // namespace voxcast
