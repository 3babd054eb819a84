// The widths of the VIZARD II datapath as functions of the precision profile:
// the one place they are derived. Every unit's Params struct (hls/*.hpp) builds
// its types from these functions, and the resource report (cosim/hardware/report.cpp)
// sizes its operators with the same calls, so the design and its estimate
// cannot disagree about a width (tests/report/test_report.cpp checks every
// operator width of the report against the kernels' types).
//
// A function takes the profile as one literal value, ProfileFields, which both
// forms of a profile convert to:
//   hls::profile_fields<P>()   a traits type P (P::value_bits, C++14, compile time:
//                              the kernels' template parameter);
//   hls::profile_fields(p)     a PrecisionProfile value (the C++20 side: report,
//                              tests; host code only).
// The field list is VOXCAST_PRECISION_PROFILE_FIELDS (profile_traits.hpp).
//
// Each width is stated with the value range that sets it (docs/pipeline.md,
// "Notation": every product and sum between rounding points is exact in the
// operator's widened result type). A fixed-point format's integer bits are
// given next to its width (*_int_bits) where they are not the profile's own.
//
// This header is C++14 (the synthesized tops include it).
#pragma once

#include "hls/pragma.hpp"
#include "refmodel/precision/profile_traits.hpp"

#if VOXCAST_HLS_HOST_CODE
#include "refmodel/precision/profile.hpp"
#endif

namespace voxcast {
namespace hls {

// The profile's fields (PrecisionProfile's, in its order) as a C++14 literal aggregate.
struct ProfileFields {
#define VOXCAST_FIELD_DECLARATION(name) int name;
  VOXCAST_PRECISION_PROFILE_FIELDS(VOXCAST_FIELD_DECLARATION)
#undef VOXCAST_FIELD_DECLARATION
};

// The fields of a traits type (P::addr_bits ... as static constexpr ints).
template <class P>
constexpr ProfileFields profile_fields() {
#define VOXCAST_FIELD_OF_TRAITS(name) P::name,
  return ProfileFields{VOXCAST_PRECISION_PROFILE_FIELDS(VOXCAST_FIELD_OF_TRAITS)};
#undef VOXCAST_FIELD_OF_TRAITS
}

#if VOXCAST_HLS_HOST_CODE
// The fields of a profile value.
constexpr ProfileFields profile_fields(const PrecisionProfile& v) {
#define VOXCAST_FIELD_OF_VALUE(name) v.name,
  return ProfileFields{VOXCAST_PRECISION_PROFILE_FIELDS(VOXCAST_FIELD_OF_VALUE)};
#undef VOXCAST_FIELD_OF_VALUE
}
#endif

namespace widths {

// Bits of an unsigned integer that holds every value 0..n (n >= 0; at least 1):
// C++20's std::bit_width, as a C++14 constant expression. Widths of types only,
// evaluated at compile time (so its loop needs no label or trip count).
constexpr int bits_for(long long n) {
  int b = 1;
  while (b < 63 && (n >> b) > 0) ++b;
  return b;
}

// ---- Geometry processor: registers, ray set-up, stepping (docs/pipeline.md §0-2) -----------
// a = addr_bits, pf = pos_frac_bits, df = dir_frac_bits, tf = t_frac_bits, sb = rsqrt_seed_bits.

// Pixel coordinates: render.width/height <= 8192 (scene_toml.cpp), so px < 2^13.
constexpr int pixel_bits = 13;
// §0 A, B, C, U and the pixel direction d: |d| < 2 (host-checked at the four
// corner pixels; d·d is convex in the pixel), df fraction bits.
constexpr int dir_int_bits = 2;
constexpr int dir_bits(const ProfileFields& p) { return p.dir_frac_bits + dir_int_bits; }
// §0 E, O, P, R and the ray origin o: within ±2^(a+3) per axis (host-checked):
// a + 3 magnitude bits + sign.
constexpr int origin_int_bits(const ProfileFields& p) { return p.addr_bits + 4; }
constexpr int origin_bits(const ProfileFields& p) { return origin_int_bits(p) + p.pos_frac_bits; }
// §0 K = step/world_scale <= 4 (step <= 4, world_scale >= 1), unsigned.
constexpr int kreg_int_bits = 3;
constexpr int kreg_bits(const ProfileFields& p) { return p.dir_frac_bits + kreg_int_bits; }
// §0 LO, HI in [0, 2^a), signed so that compares with positions are same-sign.
constexpr int box_bits(const ProfileFields& p) { return p.addr_bits + 1; }
// A voxel index and LAST = dim - 1 (< 2^a); dims <= 2^a.
constexpr int coord_bits(const ProfileFields& p) { return p.addr_bits; }
constexpr int dim_bits(const ProfileFields& p) { return p.addr_bits + 1; }
// §3.3 HX = ceil(dx/2) <= 2^(a-1) words per bank row, HXY = HX·ceil(dy/2) <= 2^(2a-2).
constexpr int half_bits(const ProfileFields& p) { return p.addr_bits; }
constexpr int slice_bits(const ProfileFields& p) { return 2 * p.addr_bits; }
// §3.3 bank word address: each bank holds ceil(dx/2)·ceil(dy/2)·ceil(dz/2) <= 2^(3a-3) words.
constexpr int word_addr_bits(const ProfileFields& p) {
  return 3 * (p.addr_bits - 1) > 0 ? 3 * (p.addr_bits - 1) : 1;
}

// §1.2 the rsqrt unit. The seed ROM has 2^sb entries.
constexpr int rsqrt_seed_entries(const ProfileFields& p) { return 1 << p.rsqrt_seed_bits; }
// n2 = d·d < 4, exact (2df fraction bits); n2·4^e < 1 (e >= -1: 2df + 2 fraction bits).
constexpr int n2_int_bits = 2;
constexpr int n2_bits(const ProfileFields& p) { return 2 * p.dir_frac_bits + n2_int_bits; }
constexpr int n2_norm_bits(const ProfileFields& p) { return 2 * p.dir_frac_bits + 2 + n2_int_bits; }
// d' = d·2^e, |d'| < 1 (df + 1 fraction bits), signed.
constexpr int dnorm_int_bits = 2;
constexpr int dnorm_bits(const ProfileFields& p) { return p.dir_frac_bits + 1 + dnorm_int_bits; }
// m = Q_RND(n2·4^e, df) in [1/4, 1].
constexpr int m_int_bits = 1;
constexpr int m_bits(const ProfileFields& p) { return p.dir_frac_bits + m_int_bits; }
// Seed entries and y: 1/sqrt(m) in (1, 2] (a few LSBs above 2 after rounding).
constexpr int y_int_bits = 2;
constexpr int y_bits(const ProfileFields& p) { return p.dir_frac_bits + y_int_bits; }
// Q_RND(y·y) and Q_RND(m·t): below 4.1 < 8.
constexpr int sq_int_bits = 3;
constexpr int sq_bits(const ProfileFields& p) { return p.dir_frac_bits + sq_int_bits; }
// y·(3 - t) (2df + 6 bits, 6 integer) with one more fraction bit, so that halving is exact.
constexpr int halving_int_bits = 6;
constexpr int halving_bits(const ProfileFields& p) {
  return 2 * p.dir_frac_bits + 1 + halving_int_bits;
}
// u: |u| <= 1 + a few LSBs, signed.
constexpr int unit_int_bits = 2;
constexpr int unit_bits(const ProfileFields& p) { return p.dir_frac_bits + unit_int_bits; }

// §1.3 s = Q_RND(u·K, pf): |s| <= |u|·K < 4.1, signed.
constexpr int step_int_bits = 4;
constexpr int step_bits(const ProfileFields& p) { return p.pos_frac_bits + step_int_bits; }
// §1.5 Q_TRN(LO - o, tf): |LO - o| < 2^a + 2^(a+3) < 2^(a+4), signed.
constexpr int clip_int_bits(const ProfileFields& p) { return p.addr_bits + 5; }
constexpr int clip_num_bits(const ProfileFields& p) { return clip_int_bits(p) + p.t_frac_bits; }
// §1.5 k = (LO - o)/s in ap's quotient type (semantics §5-6): the numerator's
// width plus the divisor's fraction bits plus its sign bit (checked against
// decltype(num_t() / step_t()) in GeometryParams).
constexpr int clip_quotient_bits(const ProfileFields& p) {
  return clip_num_bits(p) + p.pos_frac_bits + 1;
}
// §1.6 Q_RND(k_in·s, pf): on a hit |k_in·s[a]| <= max(|LO - o|, |HI - o|) < 2^(a+4).
constexpr int kstep_bits(const ProfileFields& p) { return clip_int_bits(p) + p.pos_frac_bits; }
// §1.6, §2 sample positions: within [LO, HI] up to a fraction of a voxel, LO, HI < 2^a.
constexpr int pos_int_bits(const ProfileFields& p) { return p.addr_bits + 2; }
constexpr int pos_bits(const ProfileFields& p) { return pos_int_bits(p) + p.pos_frac_bits; }
// §1.6 the sample count n <= 2^(a+pf): a + pf + 1 bits.
constexpr int count_bits(const ProfileFields& p) { return p.addr_bits + p.pos_frac_bits + 1; }

// ---- Address generator and interpolation processor (§3) ------------------------------------
// vb = value_bits, gb = gradient_bits, gfb = gradient_frac_bits, wb = weight_bits,
// sf = sample_frac_bits.

// §3.4 a stored gradient component: gb bits, gb - gfb integer bits (sign included).
constexpr int grad_int_bits(const ProfileFields& p) {
  return p.gradient_bits - p.gradient_frac_bits;
}
// §3.5 an interpolated one: rounding to sf < gfb bits can carry the largest
// stored value 2^(gb-1-gfb) - 2^-gfb up to 2^(gb-1-gfb), one integer bit more.
constexpr int sample_grad_int_bits(const ProfileFields& p) {
  return grad_int_bits(p) + (p.sample_frac_bits < p.gradient_frac_bits ? 1 : 0);
}
// §3.4 the packed voxel word: value and three gradient components.
constexpr int voxel_word_bits(const ProfileFields& p) { return p.value_bits + 3 * p.gradient_bits; }
// §3.1 p clamped into [LO, HI] ⊂ [0, 2^a), unsigned, a integer bits.
constexpr int cpos_bits(const ProfileFields& p) { return p.addr_bits + p.pos_frac_bits; }
// §3.2 f = p - i0 in [0, 1], and its weight fq = Q_RND(f, wb) in [0, 1].
constexpr int cell_frac_bits(const ProfileFields& p) { return p.pos_frac_bits + 1; }
constexpr int lerp_weight_bits(const ProfileFields& p) { return p.weight_bits + 1; }
// §3.5 exact lerp results after `axes` of the three axes: a convex combination
// stays in the range of the stored field, with wb more fraction bits per axis
// (integer bits: vb for the value, grad_int_bits for a gradient component).
constexpr int value_lerp_bits(const ProfileFields& p, int axes) {
  return p.value_bits + axes * p.weight_bits;
}
constexpr int grad_lerp_bits(const ProfileFields& p, int axes) {
  return p.gradient_bits + axes * p.weight_bits;
}
// §3.5 the sample: value vb.sf unsigned, gradient sample_grad_int_bits.sf signed.
constexpr int sample_value_bits(const ProfileFields& p) {
  return p.value_bits + p.sample_frac_bits;
}
constexpr int sample_grad_bits(const ProfileFields& p) {
  return sample_grad_int_bits(p) + p.sample_frac_bits;
}

// ---- Classification table (§4) --------------------------------------------------------------
constexpr int class_entries(const ProfileFields& p) { return 1 << p.tf_addr_bits; }
// §4.1 the address before its clamp: Q_RND can carry to 2^tf_addr_bits.
constexpr int class_addr_round_bits(const ProfileFields& p) { return p.tf_addr_bits + 1; }
// §4.2 one entry's payload: r, g, b, alpha, ka, kd, ks (the vizard2 SRAM words
// add 8 reserved bits, §4.3).
constexpr int class_entry_bits(const ProfileFields& p) {
  return 3 * p.color_bits + p.alpha_bits + 3 * p.k_bits;
}

// ---- Pre-integration table (§4a) -------------------------------------------------------------
// One entry per (front, back) address pair; the entry is a classification entry (§4.2).
constexpr int preint_entries(const ProfileFields& p) { return 1 << (2 * p.preint_addr_bits); }

// ---- Reflectance map (§5) -------------------------------------------------------------------
constexpr bool rm_bilinear(const ProfileFields& p) { return p.rm_bilinear != 0; }
// Cells of the cube map, entries per face row and per table: nearest mode (VIZARD II)
// one entry per cell; §5.5 bilinear reads the entries at the cells' corners, (rm_res + 1)^2
// per face.
constexpr int rm_cells(const ProfileFields& p) { return 6 * p.rm_res * p.rm_res; }
constexpr int rm_side(const ProfileFields& p) { return rm_bilinear(p) ? p.rm_res + 1 : p.rm_res; }
constexpr int rm_entries(const ProfileFields& p) { return 6 * rm_side(p) * rm_side(p); }
// §5.5 each table banked four ways by corner parity: 6·h² words per bank, h = ceil((rm_res+1)/2).
constexpr int rm_bank_entries(const ProfileFields& p) {
  return 6 * ((p.rm_res + 2) / 2) * ((p.rm_res + 2) / 2);
}
// Fraction bits of the in-cell position (0 in nearest mode: the division gives the cell).
constexpr int rm_pos_frac_bits(const ProfileFields& p) {
  return rm_bilinear(p) ? p.rm_weight_bits : 0;
}
// §5.1 IS[a] = Q_RND(1/world_scale[a], df) <= 1, unsigned, one integer bit.
constexpr int rm_scale_bits(const ProfileFields& p) { return p.dir_frac_bits + 1; }
// §5.1 N = -gw needs one integer bit more than the sample gradient; |N| fits unsigned
// in the gradient's own format; N[a] + |N[m]| in [0, 2 |N[m]|] in N's width.
constexpr int rm_normal_int_bits(const ProfileFields& p) { return sample_grad_int_bits(p) + 1; }
constexpr int rm_normal_bits(const ProfileFields& p) {
  return rm_normal_int_bits(p) + p.sample_frac_bits;
}
constexpr int rm_magnitude_bits(const ProfileFields& p) { return sample_grad_bits(p); }
// §5.3 (§5.5) the integer division on raw values (units of 2^-sf): numerator
// (N[a] + |N[m]|)·res·2^wb, denominator 2|N[m]|; the quotient t = floor(position
// in cells · 2^wb) lies in [0, res·2^wb].
constexpr int rm_res_bits(const ProfileFields& p) { return bits_for(p.rm_res); }
constexpr int rm_den_bits(const ProfileFields& p) {
  return sample_grad_int_bits(p) + 1 + p.sample_frac_bits;
}
constexpr int rm_num_bits(const ProfileFields& p) {
  return rm_den_bits(p) + rm_res_bits(p) + rm_pos_frac_bits(p);
}
constexpr int rm_pos_bits(const ProfileFields& p) {
  return bits_for(static_cast<long long>(p.rm_res) << rm_pos_frac_bits(p));
}
// The cell iu, iv (< rm_res) and the table index (< rm_entries).
constexpr int rm_cell_bits(const ProfileFields& p) { return bits_for(p.rm_res - 1); }
constexpr int rm_index_bits(const ProfileFields& p) { return bits_for(rm_entries(p) - 1); }
// §5.5 the in-cell position f in [0, 1] (1 only at the clamped last cell).
constexpr int rm_blend_weight_bits(const ProfileFields& p) { return rm_pos_frac_bits(p) + 1; }
// §5.4 a table entry, rm_int_bits.rm_frac_bits unsigned, and §5.5's exact blend after
// `axes` lerps (wb more fraction bits per lerp, the entries' range).
constexpr int rm_entry_bits(const ProfileFields& p) { return p.rm_int_bits + p.rm_frac_bits; }
constexpr int rm_lerp_bits(const ProfileFields& p, int axes) {
  return rm_entry_bits(p) + axes * rm_pos_frac_bits(p);
}

// ---- Shader (§6) ----------------------------------------------------------------------------
// ka + kd·D + ks·S < 1 + 2·2^rm_int_bits (ka, kd, ks < 1; D, S < 2^rm_int_bits):
// rm_int_bits + 2 integer bits hold it, and its rounding, without saturation.
constexpr int intensity_int_bits(const ProfileFields& p) { return p.rm_int_bits + 2; }
// The exact sum has k_bits + rm_frac_bits fraction bits.
constexpr int intensity_sum_bits(const ProfileFields& p) {
  return intensity_int_bits(p) + p.k_bits + p.rm_frac_bits;
}
// I = Q_RND(·, shade_bits).
constexpr int intensity_bits(const ProfileFields& p) {
  return p.shade_bits + intensity_int_bits(p);
}
// colour · I, the widest product of the unit.
constexpr int shade_product_bits(const ProfileFields& p) {
  return p.color_bits + p.shade_bits + intensity_int_bits(p);
}

// ---- Compositor and output (§7-8) -----------------------------------------------------------
// C[3], A and the weights w: acc_bits fraction bits, one integer bit, in [0, 1].
constexpr int acc_word_bits(const ProfileFields& p) { return p.acc_bits + 1; }
// MIP: the RM register Q_RND(1/max_stored, df) <= 1, and Q_RND(M·RM, acc_bits)
// before its clamp to 1 (M·RM < 2^vb as RM <= 1).
constexpr int mip_scale_bits(const ProfileFields& p) { return p.dir_frac_bits + 1; }
constexpr int grey_int_bits(const ProfileFields& p) { return p.value_bits + 1; }
constexpr int grey_bits(const ProfileFields& p) { return p.acc_bits + grey_int_bits(p); }
// §8 the largest output value.
constexpr unsigned out_max(const ProfileFields& p) { return (1u << p.out_bits) - 1u; }

// ---- Segment opacity (§7a, render.partial_segments) -----------------------------------------
// ab = alpha_bits, tf = t_frac_bits, g = segment_guard_bits.
// Guard bits beyond alpha_bits of the unit's intermediate roundings (the optical
// depth tau2, y = w·tau2, the 2^-x ROM entries and their lerp): each rounding
// then errs by at most 2^-(ab+g+1), and the unit's error against
// 1 - (1 - alpha_c)^w stays below 2^-(ab+1) + (3 ln2 + 3)·2^-(ab+g+1), 0.82
// alpha LSB for g = 3 (docs/pipeline.md §7a.6, tests/hls/test_segment_opacity.cpp).
constexpr int segment_guard_bits = 3;
// §7a.1 a sample's segment weight w in [0, 2): tf fraction bits (k_in, k_out and
// the jitter are on that grid), one integer bit.
constexpr int segment_weight_int_bits = 1;
constexpr int segment_weight_bits(const ProfileFields& p) {
  return p.t_frac_bits + segment_weight_int_bits;
}
// §7a.2 tau2 = -log2(1 - alpha_c) in [0, ab] (alpha_c <= 1 - 2^-ab), ab + g fraction bits.
constexpr int segment_frac_bits(const ProfileFields& p) { return p.alpha_bits + segment_guard_bits; }
constexpr int segment_tau_int_bits(const ProfileFields& p) { return bits_for(p.alpha_bits); }
constexpr int segment_tau_bits(const ProfileFields& p) {
  return segment_tau_int_bits(p) + segment_frac_bits(p);
}
// §7a.3 the product w·tau2 (exact) and y = Q_RND(w·tau2, ab + g), both in [0, 2ab).
constexpr int segment_product_bits(const ProfileFields& p) {
  return segment_weight_bits(p) + segment_tau_bits(p);
}
constexpr int segment_y_int_bits(const ProfileFields& p) { return bits_for(2 * p.alpha_bits); }
constexpr int segment_y_bits(const ProfileFields& p) {
  return segment_y_int_bits(p) + segment_frac_bits(p);
}
// §7a.4 the ROM of 2^-x at x = i·2^-r, i = 0 .. 2^r (2^r + 1 entries, in [1/2, 1]:
// one integer bit, ab + g fraction bits). Linear interpolation of 2^-x over a
// cell of 2^-r errs by at most (ln 2)^2/8 · 4^-r = 2^-(4.06 + 2r), below 2^-(ab+g+1)
// when 2r >= ab + g - 3: r = ceil((ab + g - 3)/2).
constexpr int segment_rom_index_bits(const ProfileFields& p) {
  return (p.alpha_bits + segment_guard_bits - 2) / 2;
}
constexpr int segment_rom_entries(const ProfileFields& p) {
  return (1 << segment_rom_index_bits(p)) + 1;
}
constexpr int segment_mant_bits(const ProfileFields& p) { return segment_frac_bits(p) + 1; }
// The lerp's position inside a cell: the fraction bits of y below the top r.
constexpr int segment_lerp_frac_bits(const ProfileFields& p) {
  return segment_frac_bits(p) - segment_rom_index_bits(p);
}
// §7a.5 the shift 2^-floor(y) clamped at ab + 2 (beyond it 2^-y < 2^-(ab+2) and
// U(1 - 2^-y, ab) saturates either way), and m·2^-s exact.
constexpr int segment_max_shift(const ProfileFields& p) { return p.alpha_bits + 2; }
constexpr int segment_shift_bits(const ProfileFields& p) { return bits_for(segment_max_shift(p)); }
constexpr int segment_scaled_bits(const ProfileFields& p) {
  return segment_mant_bits(p) + segment_max_shift(p);
}

// ---- Space leaping (docs/leaping.md) --------------------------------------------------------
// The leap's binary search has leap_bits stages and finds runs of up to 2^leap_bits
// samples; a longer run is split into several leaps, each exact, so this bounds the
// hardware, not the result: 1024 samples cover an 8^3 block's diagonal at 16x
// oversampling (8·sqrt(3)·16 = 222) with room for anisotropic spacing.
constexpr int max_leap_bits = 10;
constexpr int leap_bits(const ProfileFields& p) {
  return count_bits(p) < max_leap_bits ? count_bits(p) : max_leap_bits;
}
// Prefix counts of the classification entries with alpha != 0, in [0, 2^tf_addr_bits].
constexpr int prefix_count_bits(const ProfileFields& p) { return p.tf_addr_bits + 1; }
// Block coordinates i0 >> lb < 2^a; bx + by·BX + bz·BXY before the range check.
constexpr int block_coord_bits(const ProfileFields& p) { return p.addr_bits; }
constexpr int block_addr_wide_bits(const ProfileFields& p) { return 3 * p.addr_bits + 1; }
// A step and a position plus up to 2^leap_bits steps: |s| < 4.1, so 3 + leap_bits
// magnitude bits for the step.
constexpr int leap_step_int_bits(const ProfileFields& p) { return step_int_bits + leap_bits(p); }
constexpr int leap_step_bits(const ProfileFields& p) {
  return p.pos_frac_bits + leap_step_int_bits(p);
}
constexpr int leap_pos_int_bits(const ProfileFields& p) { return p.addr_bits + 6 + leap_bits(p); }
constexpr int leap_pos_bits(const ProfileFields& p) {
  return p.pos_frac_bits + leap_pos_int_bits(p);
}

}  // namespace widths
}  // namespace hls
}  // namespace voxcast
