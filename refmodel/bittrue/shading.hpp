// The bit-true twins of the classification, reflectance-map, shader and
// compositor units (docs/pipeline.md §4-8), in plain double with the quantizers
// of quantize.hpp: the independent second implementation the hls kernels
// (hls/classification_table.hpp, reflectance_map.hpp, shader.hpp,
// compositor.hpp) must match bit for bit. Values are doubles on their grids
// (value = raw · 2^-F); tables and registers are read from the FrameSetup.
#pragma once

#include <array>
#include <cstdint>
#include <ostream>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/geometry.hpp"
#include "refmodel/precision/profile.hpp"

namespace voxcast::bittrue {

// --- §4 Classification -----------------------------------------------------------------
// addr = SAT(Q_RND(value · 2^(tf_addr_bits - vb), 0), 0, 2^tf_addr_bits - 1).
int bt_class_address(const PrecisionProfile& p, double value);
// The entry at bt_class_address (value: vb.sf, on the sf grid).
const ClassEntry& bt_classify(const FrameSetup& fs, double value);
// §4a: addr = SAT(Q_RND(value · 2^(preint_addr_bits - vb), 0), 0, 2^preint_addr_bits - 1),
// and the pre-integration entry of the segment from `front` to `back`.
int bt_preint_address(const PrecisionProfile& p, double value);
const ClassEntry& bt_classify_segment(const FrameSetup& fs, double front, double back);
// An entry's opacity-corrected alpha as a value (raw · 2^-alpha_bits).
double bt_alpha(const PrecisionProfile& p, const ClassEntry& e);

// --- §5 Reflectance map ----------------------------------------------------------------
struct BtCell {
  bool valid = false;  // false when N = 0 (§5.2)
  // rm_bilinear = 0: the entry face·rm_res² + iv·rm_res + iu (§5.3).
  // rm_bilinear = 1: the cell's lower corner face·(rm_res+1)² + iv·(rm_res+1) + iu (§5.5).
  int index = 0;
  // rm_bilinear = 1: the in-cell position, raw with rm_weight_bits fraction bits
  // (0 .. 2^rm_weight_bits); 0 in nearest mode.
  std::int64_t fu = 0, fv = 0;
};
// The cube-map cell of an interpolated gradient g (index space, on the sf grid),
// world-scaled by the IS registers (dir_frac_bits raw).
BtCell bt_rm_cell(const PrecisionProfile& p, const Raw3& IS, const std::array<double, 3>& g);

struct BtReflect {
  double D = 0.0, S = 0.0;  // rm_int_bits.rm_frac_bits values; 0 without a normal
};
BtReflect bt_reflectance(const FrameSetup& fs, const std::array<double, 3>& g);

// --- §6 Shader ---------------------------------------------------------------------------
// Shaded (or, with shaded = false, unshaded) colour, shade_bits per channel.
std::array<double, 3> bt_shade(const PrecisionProfile& p, const ClassEntry& e, const BtReflect& r,
                               bool shaded);

// --- §7 Compositor -----------------------------------------------------------------------
struct BtAccumulator {
  std::array<double, 3> C{0.0, 0.0, 0.0};  // premultiplied colour, acc_bits
  double A = 0.0;                          // opacity, acc_bits
};
std::ostream& operator<<(std::ostream& os, const BtAccumulator& acc);

// One front-to-back step; returns false (no change) for alpha_c = 0, after which
// the ray loop must not test ERT.
bool bt_composite(const PrecisionProfile& p, BtAccumulator& acc, const std::array<double, 3>& c,
                  double alpha_c);
// A >= Q_RND(threshold, acc_bits), when the frame's ERT register is enabled.
bool bt_ert(const FrameSetup& fs, const BtAccumulator& acc);

// --- §7a Segment opacity (render.partial_segments) ---------------------------------------
// The weights of a ray's first and last samples, in steps (every other sample
// has 1): with d = k_out - k_in and j the pixel's jitter, first = 1 + j (n >= 2)
// or d + j (n = 1), last = frac(d). All 1 without fs.segments or on a miss.
struct BtSegmentWeights {
  double first = 1.0, last = 1.0;
};
BtSegmentWeights bt_segment_weights(const FrameSetup& fs, const BtRay& ray, int px, int py);
// The weight of sample k of a ray of n samples.
double bt_sample_weight(const BtSegmentWeights& w, std::uint64_t k, std::uint64_t n);
// alpha_c (the entry at classification address `addr`) for a segment of weight w:
// alpha_c when w = 1, else U(1 - 2^-y, ab), y = Q_RND(w·tau2[addr], ab + g), 2^-y from
// the ROM's lerp and a shift (§7a.3-7.5).
double bt_segment_alpha(const FrameSetup& fs, int addr, double alpha_c, double w);

// MIP: the running maximum (M starts at 0) and the pixel (grey, grey, grey, 1) with
// grey = SAT(Q_RND(M·RM, acc_bits), 0, 1).
inline double bt_mip_max(double M, double value) { return value > M ? value : M; }
BtAccumulator bt_mip_pixel(const FrameSetup& fs, double M);

// --- §8 Output ---------------------------------------------------------------------------
// Q_RND(x · (2^out_bits - 1), 0) of one channel in [0, 1].
std::uint32_t bt_output_channel(const PrecisionProfile& p, double x);
// (r, g, b, alpha) of a finished ray; a miss is bt_output of a fresh accumulator.
std::array<std::uint32_t, 4> bt_output(const PrecisionProfile& p, const BtAccumulator& acc);

}  // namespace voxcast::bittrue
