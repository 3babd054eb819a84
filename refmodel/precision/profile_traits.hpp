// The precision profiles as types: what the hls kernels take as their template
// parameter. A kernel is `template <class P>` and reads `P::value_bits` as a
// `static constexpr int`, the way AMD's Vitis Libraries L1 pass their FFT and
// solver traits: C++14, which the vendor HLS front ends read (UG1399,
// "Migrating from Vivado HLS to Vitis HLS"). A synthesized design fixes its
// widths, so a profile is a type, one instantiation of the whole pipeline.
//
// The presets' numbers live here and only here. The C++20 side of the project
// reads them as PrecisionProfile values (refmodel/precision/preset_profiles.hpp:
// kVizard2 = profile_value<Vizard2Traits>() and so on), and turns any other
// constexpr PrecisionProfile into a traits type with ProfileTraits<V>. Each
// member is the PrecisionProfile field of the same name (refmodel/precision/
// profile.hpp says what each width is; docs/pipeline.md where it is used).
//
// This header is C++14 (the synthesizable tops include it): no inline
// variables, no nested namespace definitions.
#pragma once

// Every field of PrecisionProfile (refmodel/precision/profile.hpp), in declaration
// order: X(name) once each. The traits types below have exactly these members;
// preset_profiles.hpp converts between the two forms with it, and hls/widths.hpp
// builds its C++14 value of a profile (hls::ProfileFields) from it.
#define VOXCAST_PRECISION_PROFILE_FIELDS(X)                                                      \
  X(addr_bits) X(pos_frac_bits) X(dir_frac_bits) X(rsqrt_seed_bits) X(t_frac_bits)               \
  X(weight_bits) X(value_bits) X(gradient_bits) X(gradient_frac_bits) X(sample_frac_bits)        \
  X(tf_addr_bits) X(color_bits) X(alpha_bits) X(k_bits) X(preint_addr_bits) X(rm_res)          \
  X(rm_frac_bits) X(rm_int_bits) X(rm_bilinear) X(rm_weight_bits) X(shade_bits) X(acc_bits)      \
  X(out_bits)
#define VOXCAST_HEIDELBERG_PROFILE_FIELDS(X)                                                     \
  X(addr_bits) X(view_bits) X(coord_frac_bits) X(value_bits) X(weight_bits)                      \
  X(weight_frac_bits) X(density_bits) X(gradient_bits) X(light_frac_bits) X(cos_frac_bits)       \
  X(user_weight_bits) X(out_bits)

namespace voxcast {

// The VIZARD II card as published (PrecisionProfile's defaults): 9-bit voxel
// addresses, 6-bit weight addressing, 8-bit voxels and gradients, a 256-entry
// classification table of 8-bit fields, 16x16 reflectance-map faces.
struct Vizard2Traits {
  static constexpr int addr_bits = 9;
  static constexpr int pos_frac_bits = 16;
  static constexpr int dir_frac_bits = 20;
  static constexpr int rsqrt_seed_bits = 6;
  static constexpr int t_frac_bits = 12;
  static constexpr int weight_bits = 6;
  static constexpr int value_bits = 8;
  static constexpr int gradient_bits = 8;
  static constexpr int gradient_frac_bits = 0;
  static constexpr int sample_frac_bits = 4;
  static constexpr int tf_addr_bits = 8;
  static constexpr int color_bits = 8;
  static constexpr int alpha_bits = 8;
  static constexpr int k_bits = 8;
  static constexpr int preint_addr_bits = 8;
  static constexpr int rm_res = 16;
  static constexpr int rm_frac_bits = 8;
  static constexpr int rm_int_bits = 0;
  static constexpr int rm_bilinear = 0;
  static constexpr int rm_weight_bits = 6;
  static constexpr int shade_bits = 8;
  static constexpr int acc_bits = 12;
  static constexpr int out_bits = 8;
};

// Wider than the card in every field: 10-bit addresses, 12-bit values, 16-bit
// gradients, a 4096-entry table, a bilinear 32x32 reflectance map
// (docs/accuracy.md measures what each preset buys).
struct BalancedTraits {
  static constexpr int addr_bits = 10;
  static constexpr int pos_frac_bits = 18;
  static constexpr int dir_frac_bits = 22;
  static constexpr int rsqrt_seed_bits = 8;
  static constexpr int t_frac_bits = 14;
  static constexpr int weight_bits = 8;
  static constexpr int value_bits = 12;
  static constexpr int gradient_bits = 16;
  static constexpr int gradient_frac_bits = 3;
  static constexpr int sample_frac_bits = 8;
  static constexpr int tf_addr_bits = 12;
  static constexpr int color_bits = 12;
  static constexpr int alpha_bits = 16;
  static constexpr int k_bits = 12;
  static constexpr int preint_addr_bits = 8;
  static constexpr int rm_res = 32;
  static constexpr int rm_frac_bits = 12;
  static constexpr int rm_int_bits = 2;
  static constexpr int rm_bilinear = 1;  // §5.5, 6·33² entries per table: as accurate as
                                         // nearest at rm_res 256
  static constexpr int rm_weight_bits = 8;
  static constexpr int shade_bits = 12;
  static constexpr int acc_bits = 16;
  static constexpr int out_bits = 8;
};

// 16-bit values, 20-bit gradients, a 16384-entry table, a bilinear 64x64
// reflectance map and wide intermediates.
struct PreciseTraits {
  static constexpr int addr_bits = 10;
  static constexpr int pos_frac_bits = 22;
  static constexpr int dir_frac_bits = 24;
  static constexpr int rsqrt_seed_bits = 10;
  static constexpr int t_frac_bits = 16;
  static constexpr int weight_bits = 10;
  static constexpr int value_bits = 16;
  static constexpr int gradient_bits = 20;
  static constexpr int gradient_frac_bits = 3;
  static constexpr int sample_frac_bits = 10;
  static constexpr int tf_addr_bits = 14;
  static constexpr int color_bits = 16;
  static constexpr int alpha_bits = 20;
  static constexpr int k_bits = 16;
  static constexpr int preint_addr_bits = 8;
  static constexpr int rm_res = 64;
  static constexpr int rm_frac_bits = 16;
  static constexpr int rm_int_bits = 2;
  static constexpr int rm_bilinear = 1;  // §5.5, 6·65² entries per table: finer grids no
                                         // longer change the image
  static constexpr int rm_weight_bits = 10;
  static constexpr int shade_bits = 16;
  static constexpr int acc_bits = 20;
  static constexpr int out_bits = 8;
};

// VIRIM as published (HeidelbergProfile's defaults, refmodel/precision/
// heidelberg_profile.hpp): 6-bit weight addressing, a 48-bit bus word
// (docs/heidelberg.md §7).
struct VirimTraits {
  static constexpr int addr_bits = 9;
  static constexpr int view_bits = 9;
  static constexpr int coord_frac_bits = 16;
  static constexpr int value_bits = 16;
  static constexpr int weight_bits = 6;
  static constexpr int weight_frac_bits = 14;
  static constexpr int density_bits = 16;
  static constexpr int gradient_bits = 16;
  static constexpr int light_frac_bits = 16;
  static constexpr int cos_frac_bits = 14;
  static constexpr int user_weight_bits = 8;
  static constexpr int out_bits = 8;
};

}  // namespace voxcast
