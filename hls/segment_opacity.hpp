// Segment opacity unit (render.partial_segments, issue 19 part 2): the opacity
// of a classified sample for the length of the ray segment it stands for, when
// that length is not one step. A ray's samples start at its entry with a whole
// number of steps, so without it the sample count, and the image, jump when a
// ray's length crosses a multiple of the step; with it the first and the last
// sample weigh by their fractional segments and the opacity along the ray is
// 1 - (1 - alpha)^(L/step) for any length L. The datapath is
// docs/pipeline.md §7a; its float twin is ref::segment_weight +
// ref::opacity_correct at the fractional step, its bit-true twin
// bittrue::bt_segment_weights + bt_segment_alpha (refmodel/bittrue/shading.hpp).
//
// Layout of this header:
//   1. SegmentOpacityParams<P>: every width and type of the unit, derived from P.
//   2. The synthesizable unit: the tables (SegmentOpacityTables), the ray's
//      segment weights (§7a.1, from the ray set-up), the weight of sample k,
//      and segment_opacity (§7a.2-7.5): alpha_w = U(1 - 2^-(w·tau2), ab).
//   3. host:: — loading the tables from the raw integers the driver computes
//      (bittrue::make_segment_tables). Not synthesized.
#pragma once

#include <cstdint>

#include "hls/classification_table.hpp"
#include "hls/geometry_processor.hpp"
#include "hls/pragma.hpp"
#include "hls/types.hpp"
#include "hls/widths.hpp"

#if VOXCAST_HLS_HOST_CODE
#include <vector>

#include "refmodel/bittrue/frame_setup.hpp"
#endif

namespace voxcast {
namespace hls {

// ---- 1. Parameters ------------------------------------------------------------------------
// ab = alpha_bits, tf = t_frac_bits, r = rom_index_bits; hls/widths.hpp derives each width.
template <class P>
struct SegmentOpacityParams {
  static constexpr int ab = P::alpha_bits;
  static constexpr int tf = P::t_frac_bits;
  static constexpr int frac_bits = widths::segment_frac_bits(profile_fields<P>());  // ab + g
  static constexpr int entries = widths::class_entries(profile_fields<P>());  // tau2 per address
  static constexpr int rom_index_bits = widths::segment_rom_index_bits(profile_fields<P>());
  static constexpr int rom_entries = widths::segment_rom_entries(profile_fields<P>());
  static constexpr int max_shift = widths::segment_max_shift(profile_fields<P>());

  // §7a.1 a sample's weight w in [0, 2), tf fraction bits.
  using weight_t = ufixed<widths::segment_weight_bits(profile_fields<P>()),
                          widths::segment_weight_int_bits>;
  // §7a.2 tau2 = -log2(1 - alpha_c), ab + g fraction bits.
  using tau_t = ufixed<widths::segment_tau_bits(profile_fields<P>()),
                       widths::segment_tau_int_bits(profile_fields<P>())>;
  // §7a.3 y = Q_RND(w·tau2, ab + g).
  using y_t = ufixed<widths::segment_y_bits(profile_fields<P>()),
                     widths::segment_y_int_bits(profile_fields<P>()), RND>;
  // §7a.4 ROM entries 2^-(i·2^-r) in [1/2, 1], the lerp position in a cell, and
  // m = Q_RND(lerp, ab + g).
  using rom_t = ufixed<widths::segment_mant_bits(profile_fields<P>()), 1>;
  using lerp_frac_t = ufixed<widths::segment_lerp_frac_bits(profile_fields<P>()), 0>;
  using mant_t = ufixed<widths::segment_mant_bits(profile_fields<P>()), 1, RND>;
  // §7a.5 the shift count, v = m·2^-s (exact) and 1 - v.
  using shift_t = uint_t<widths::segment_shift_bits(profile_fields<P>())>;
  using scaled_t = ufixed<widths::segment_scaled_bits(profile_fields<P>()), 1>;
  // U(1 - v, ab): one rounding, then the saturation at 1 - 2^-ab.
  using alpha_round_t = ufixed<ab, 0, RND, SAT>;
  using alpha_t = typename ClassificationParams<P>::alpha_t;
  using k_t = typename GeometryParams<P>::k_t;

  static_assert(widths::segment_product_bits(profile_fields<P>()) <= 64,
                "w x tau2 exceeds 64 bits");
  static_assert(widths::segment_scaled_bits(profile_fields<P>()) <= 64,
                "m x 2^-s exceeds 64 bits");
  static_assert(rom_index_bits >= 1 && rom_index_bits < frac_bits, "ROM index out of range");
};

// Pipeline depth (clocks; see hls/geometry_processor.hpp, "Pipeline depths").
// The optical-depth table is read in the classification table's clock, at the
// same address (§4.1), so it adds none; then §7a.3 the product w·tau2 and its
// rounding 1, §7a.4 the ROM read (two adjacent entries, one dual-port read) 1,
// §7a.4-7.5 the lerp, the shift and U(1 - v) 1. It runs beside the reflectance
// map and the shader (4 clocks), whose colour the compositor waits for: in a
// shaded frame it adds no clock. In an unshaded frame (shading 1 clock) the
// cycle model's shading stage takes max(1, this) when the frame has the unit
// (rtl::pipeline::elaborate_latencies). Inlined (HLS INLINE): no LATENCY pragma.
constexpr int segment_opacity_depth = 3;

// ---- 2. The unit ----------------------------------------------------------------------------

// The unit's tables, loaded with the classification table (§7a.2) and once
// (the ROM, §7a.4); `enabled` is the frame's render.partial_segments register
// (never set in a MIP frame).
template <class P>
struct SegmentOpacityTables {
  using S = SegmentOpacityParams<P>;
  bool enabled = false;
  typename S::tau_t tau[S::entries];
  typename S::rom_t rom[S::rom_entries];
};

// §7a.1: the weights of a ray's first and last samples (every other sample has 1).
template <class P>
struct SegmentWeights {
  typename SegmentOpacityParams<P>::weight_t first, last;
};

// §7a.1 from the ray set-up: with d = k_out - k_in (exact, tf bits) and j the
// pixel's jitter (the entry is k_in0 = k_in - j), the first sample stands for
// [k_in0, min(k_in + 1, k_out)]: 1 + j when n >= 2, d + j when it is the only
// sample; the last (n >= 2) for [k_in + n - 1, k_out]: frac(d). Weights of 1
// when the frame's register is off or the ray misses.
template <class P>
SegmentWeights<P> segment_weights(const SegmentOpacityTables<P>& t, const RaySetup<P>& ray,
                                  const typename GeometryParams<P>::k_t& jitter) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using S = SegmentOpacityParams<P>;
  using weight_t = typename S::weight_t;
  SegmentWeights<P> w;
  w.first = 1;
  w.last = 1;
  if (!t.enabled || !ray.hit) return w;
  const typename S::k_t d = ray.k_out - ray.k_in;  // exact: 0 <= d < k_out
  weight_t frac = 0;  // the bits of d below the binary point
  write_bits(frac, S::tf - 1, 0, read_bits(d, S::tf - 1, 0));
  weight_t j = 0;
  write_bits(j, S::tf - 1, 0, read_bits(jitter, S::tf - 1, 0));
  const weight_t one = 1;
  if (ray.n == 1) {
    w.first = frac + j;  // d < 1 here, so d = frac(d); d + j < 2
  } else {
    w.first = one + j;
    w.last = frac;
  }
  return w;
}

// The weight of sample k of a ray of n samples.
template <class P>
VOXCAST_HLS_HOST_INLINE typename SegmentOpacityParams<P>::weight_t sample_weight(
    const SegmentWeights<P>& w, std::uint64_t k, std::uint64_t n) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  typename SegmentOpacityParams<P>::weight_t one = 1;
  if (k == 0) return w.first;
  if (k + 1 == n) return w.last;
  return one;
}

// §7a.2-7.5: the opacity alpha_c of classification address `addr` for a
// segment of weight w: alpha_c itself when w = 1 (bit for bit the table's),
// else U(1 - 2^-y, ab) with y = Q_RND(w·tau2[addr], ab + g) and
// 2^-y = 2^-min(floor(y), ab+2) · lerp of the ROM at frac(y).
template <class P>
VOXCAST_HLS_HOST_INLINE typename ClassificationParams<P>::alpha_t segment_opacity(
    const SegmentOpacityTables<P>& t, const typename ClassificationParams<P>::addr_t& addr,
    const typename ClassificationParams<P>::alpha_t& alpha_c,
    const typename SegmentOpacityParams<P>::weight_t& w) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using S = SegmentOpacityParams<P>;
  if (w == 1) return alpha_c;
  // §7a.3 the optical depth of the segment (the product exact, one rounding).
  const typename S::y_t y = w * t.tau[addr.to_uint()];
  // §7a.4 2^-frac(y): the top r fraction bits address the ROM, the rest interpolate.
  const unsigned i = static_cast<unsigned>(
      read_bits(y, S::frac_bits - 1, S::frac_bits - S::rom_index_bits));
  typename S::lerp_frac_t u;
  write_bits(u, S::frac_bits - S::rom_index_bits - 1, 0,
             read_bits(y, S::frac_bits - S::rom_index_bits - 1, 0));
  const typename S::rom_t e0 = t.rom[i];
  const typename S::rom_t e1 = t.rom[i + 1];
  const typename S::rom_t drop = e0 - e1;  // exact: the ROM decreases
  const typename S::mant_t m = e0 - drop * u;  // Q_RND(·, ab + g), in [1/2, 1]
  // §7a.5 2^-floor(y), the shift clamped at ab + 2; 1 - v and U(·, ab).
  const std::uint64_t fl = read_bits(y, S::y_t::width - 1, S::frac_bits);
  const typename S::shift_t s =
      fl > static_cast<std::uint64_t>(S::max_shift) ? static_cast<std::uint64_t>(S::max_shift) : fl;
  typename S::scaled_t v = m;
  v >>= s;  // exact: scaled_t has max_shift more fraction bits than m
  const typename S::scaled_t one = 1;
  const typename S::scaled_t complement = one - v;  // exact: v <= 1
  const typename S::alpha_round_t a = complement;  // U(·, ab)
  return a;
}

// ---- 3. Host side (not synthesized) -------------------------------------------------------
#if VOXCAST_HLS_HOST_CODE
namespace host {

// Loads the tables from the driver's raw integers (bittrue::make_segment_tables);
// false (tables unchanged) if a size does not match the profile.
template <class P>
bool load_segment_tables(SegmentOpacityTables<P>& t, const bittrue::SegmentTables& raw) {
  using S = SegmentOpacityParams<P>;
  if (raw.tau.size() != static_cast<std::size_t>(S::entries) ||
      raw.rom.size() != static_cast<std::size_t>(S::rom_entries))
    return false;
  [[gnu::unused]] load_tau_loop : for (int i = 0; i < S::entries; ++i)
    write_bits(t.tau[i], static_cast<std::uint64_t>(raw.tau[static_cast<std::size_t>(i)]));
  [[gnu::unused]] load_rom_loop : for (int i = 0; i < S::rom_entries; ++i)
    write_bits(t.rom[i], static_cast<std::uint64_t>(raw.rom[static_cast<std::size_t>(i)]));
  t.enabled = true;
  return true;
}

}  // namespace host
#endif
}  // namespace hls
}  // namespace voxcast
