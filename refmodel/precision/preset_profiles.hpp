// The presets of presets.cpp as constexpr values, for the hls kernels' template
// parameter (`template <PrecisionProfile P>`), which needs a compile-time
// profile. They mirror preset_profile(name) field for field; a test checks
// that kVizard2 == preset_profile("vizard2") and so on.
#pragma once

#include "refmodel/precision/profile.hpp"

namespace voxcast {

inline constexpr PrecisionProfile kVizard2{};  // the struct's defaults are the vizard2 card

inline constexpr PrecisionProfile kBalanced = [] {
  PrecisionProfile p;
  p.addr_bits = 10;
  p.pos_frac_bits = 18;
  p.dir_frac_bits = 22;
  p.rsqrt_seed_bits = 8;
  p.t_frac_bits = 14;
  p.weight_bits = 8;
  p.value_bits = 12;
  p.gradient_bits = 16;
  p.gradient_frac_bits = 3;
  p.sample_frac_bits = 8;
  p.tf_addr_bits = 12;
  p.color_bits = 12;
  p.alpha_bits = 16;
  p.k_bits = 12;
  p.rm_res = 32;
  p.rm_frac_bits = 12;
  p.rm_int_bits = 2;
  p.rm_bilinear = 1;  // §5.5, 6·33² entries per table: as accurate as nearest at rm_res 256
  p.rm_weight_bits = 8;
  p.shade_bits = 12;
  p.acc_bits = 16;
  p.out_bits = 8;
  return p;
}();

inline constexpr PrecisionProfile kPrecise = [] {
  PrecisionProfile p;
  p.addr_bits = 10;
  p.pos_frac_bits = 22;
  p.dir_frac_bits = 24;
  p.rsqrt_seed_bits = 10;
  p.t_frac_bits = 16;
  p.weight_bits = 10;
  p.value_bits = 16;
  p.gradient_bits = 20;
  p.gradient_frac_bits = 3;
  p.sample_frac_bits = 10;
  p.tf_addr_bits = 14;
  p.color_bits = 16;
  p.alpha_bits = 20;
  p.k_bits = 16;
  p.rm_res = 64;
  p.rm_frac_bits = 16;
  p.rm_int_bits = 2;
  p.rm_bilinear = 1;  // §5.5, 6·65² entries per table: finer grids no longer change the image
  p.rm_weight_bits = 10;
  p.shade_bits = 16;
  p.acc_bits = 20;
  p.out_bits = 8;
  return p;
}();

}  // namespace voxcast
