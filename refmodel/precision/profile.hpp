// The precision profile: every bit width and table size of the fixed-point
// VIZARD II pipeline, in one plain struct.
//
// The struct is runtime data (the bit-true reference, the resource model,
// reports). The hls kernels take a profile as a type with the same members as
// static constexpr ints (`template <class P>`, P::value_bits; the presets are
// refmodel/precision/profile_traits.hpp, ProfileTraits<V> turns a constexpr
// value into one), so the design and its checks read one set of numbers. The datapath each width belongs to is specified in
// docs/pipeline.md; widths are named after the unit that owns them.
#pragma once

namespace voxcast {

struct PrecisionProfile {
  // --- Geometry processor: ray setup and stepping (docs/pipeline.md §1-2) ---
  int addr_bits = 9;          // voxel index bits per axis: volumes up to 2^addr_bits per axis
  int pos_frac_bits = 16;     // fraction bits of a sample position (index space)
  int dir_frac_bits = 20;     // fraction bits of ray directions and step vectors
  int rsqrt_seed_bits = 6;    // address bits of the reciprocal-square-root seed table
  int t_frac_bits = 12;       // fraction bits of clip parameters, in samples
  // --- Interpolation processor (§3) ---
  int weight_bits = 6;        // the papers' "6-bit weight addressing"
  int value_bits = 8;         // voxel value field of the voxel word
  int gradient_bits = 8;      // per gradient component in the voxel word, sign included
  int gradient_frac_bits = 0; // fraction bits of stored gradient components
  int sample_frac_bits = 4;   // fraction bits kept of an interpolated value / gradient
  // --- Classification table (§4) ---
  int tf_addr_bits = 8;       // table entries = 2^tf_addr_bits over the value range
  int color_bits = 8;         // r, g, b (unsigned fractions of 1)
  int alpha_bits = 8;         // opacity-corrected alpha (unsigned fraction of 1)
  int k_bits = 8;             // ka, kd, ks (unsigned fractions of 1)
  // --- Pre-integration table (render.classification = "preintegrated") ---
  int preint_addr_bits = 8;   // per sample of a segment: 2^(2 preint_addr_bits) entries
                              // addressed by (front, back) value (Engel et al. 2001: 256 x 256)
  // --- Reflectance map and shader (§5-6) ---
  int rm_res = 16;            // cells along each edge of a cube-map face (6*rm_res^2 cells)
  int rm_frac_bits = 8;       // fraction bits of a reflectance-map entry
  int rm_int_bits = 0;        // integer bits of an entry (>0 when light intensities sum past 1)
  int rm_bilinear = 0;        // 0: the nearest cell's entry (VIZARD II); 1: bilinear between the
                              // entries at the cell's four corners, 6*(rm_res+1)^2 per table (§5.5)
  int rm_weight_bits = 6;     // fraction bits of the in-cell position, the bilinear weights
                              // (used only when rm_bilinear = 1)
  int shade_bits = 8;         // fraction bits of a shaded colour channel
  // --- Compositor and output (§7-8) ---
  int acc_bits = 12;          // fraction bits of the accumulated colour and opacity
  int out_bits = 8;           // bits per output channel

  friend constexpr bool operator==(const PrecisionProfile&, const PrecisionProfile&) = default;
};

}  // namespace voxcast
