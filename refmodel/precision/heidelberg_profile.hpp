// The widths of VIRIM's fixed-point datapath (rotator and slice processor),
// one plain struct like the ray caster's PrecisionProfile; like it, the
// kernels in hls/virim/ take it as a traits type (VirimTraits,
// HeidelbergTraits<V>: refmodel/precision/profile_traits.hpp, preset_profiles.hpp). Each width is
// specified in docs/heidelberg.md §7.
#pragma once

namespace voxcast {

struct HeidelbergProfile {
  // --- Geometry processor (§7.1) ---
  int addr_bits = 9;         // data cube index bits per axis (cube up to 2^addr_bits)
  int view_bits = 9;         // view cube index bits per axis (W, D, H up to 2^view_bits)
  int coord_frac_bits = 16;  // fraction bits of the matrix, plane scales and positions
  // --- Memory, LUT and interpolation processor (§7.2-7.3) ---
  int value_bits = 16;       // gray values in the RAM units, addressing the LUT
  int weight_bits = 6;       // weight-ROM address bits per coordinate (VIRIM: 64x64x64)
  int weight_frac_bits = 14; // fraction bits of a ROM weight (the 8 sum to exactly 1)
  // --- The rotator-to-DSP bus word (§7.4): 16 + 16 + 16 = 48 bits in VIRIM ---
  int density_bits = 16;     // density, an unsigned fraction of 1
  int gradient_bits = 16;    // Sobel x and y: signed, all fraction, in (-1/2, 1/2)
  // --- Slice processor (§7.5) ---
  int light_frac_bits = 16;  // transmittances, light, deposited energy, accumulator
  int cos_frac_bits = 14;    // Phong cosines and the surface probability
  int user_weight_bits = 8;  // fraction bits of the four user weights
  int out_bits = 8;          // output gray level

  friend constexpr bool operator==(const HeidelbergProfile&, const HeidelbergProfile&) = default;
};

// VIRIM as published: 6-bit weight addressing, a 48-bit bus word.
inline constexpr HeidelbergProfile kVirimProfile{};

}  // namespace voxcast
