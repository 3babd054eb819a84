// Address generator and interpolation processor, VIZARD II section 2.1-2.2
// ("the sample value is computed by trilinear interpolation ... in a similar
// fashion, the gradient at sample location is computed"; the voxel memory is
// 8-way interleaved so the eight neighbours are read in one access, and the
// weights use 6-bit weight addressing). The datapath is docs/pipeline.md §3; its
// float twin is ref::interpolate, its bit-true twin bittrue::bt_interpolate
// (refmodel/bittrue/interpolation.hpp).
//
// Layout of this header:
//   1. InterpolationParams<P>: every width and type of the unit, derived from P.
//   2. VoxelWordFx<P> (§3.4) and the bank views: PackedBanks<P> (the top level's
//      8 arrays of packed words) and host::BitTrueBanks<P> (8 pointers into
//      bittrue::VoxelMemory, for simulation).
//   3. The synthesizable unit: address_generator (§3.1-3.3), gather,
//      interpolation_processor (§3.5), interpolate (both), and march_ray: the
//      per-sample loop (stepping §2 + interpolation) with PIPELINE II=1.
#pragma once

#include <cstdint>

#include "hls/geometry_processor.hpp"
#include "hls/pragma.hpp"
#include "hls/types.hpp"
#include "hls/widths.hpp"

#if VOXCAST_HLS_HOST_CODE
#include "refmodel/bittrue/frame_setup.hpp"
#endif

namespace voxcast {
namespace hls {

// ---- 1. Parameters ------------------------------------------------------------------------
// vb = value_bits, gb = gradient_bits, gfb = gradient_frac_bits, wb =
// weight_bits, sf = sample_frac_bits; a, pf as in GeometryParams. The widths are
// hls/widths.hpp's functions of the profile.
template <class P>
struct InterpolationParams {
  using G = GeometryParams<P>;
  static constexpr int a = P::addr_bits;
  static constexpr int pf = P::pos_frac_bits;
  static constexpr int vb = P::value_bits;
  static constexpr int gb = P::gradient_bits;
  static constexpr int gfb = P::gradient_frac_bits;
  static constexpr int wb = P::weight_bits;
  static constexpr int sf = P::sample_frac_bits;
  static constexpr int banks = 8;
  // Integer bits (sign included) of a stored gradient component and of an interpolated one.
  static constexpr int grad_int_bits = widths::grad_int_bits(profile_fields<P>());
  static constexpr int sample_grad_int_bits = widths::sample_grad_int_bits(profile_fields<P>());
  static constexpr int word_bits = widths::voxel_word_bits(profile_fields<P>());  // §3.4

  // Value x weight products stay exact and within 64 bits (the clone's fast path).
  static_assert(widths::grad_lerp_bits(profile_fields<P>(), 3) + 2 <= 64,
                "gradient lerp products exceed 64 bits");

  using word_addr_t = typename G::word_addr_t;
  using voxel_value_t = uint_t<vb>;               // §3.4 value field
  using voxel_grad_t = fixed<gb, grad_int_bits>;  // §3.4 gradient field
  using packed_word_t = uint_t<word_bits>;
  using cpos_t = ufixed<widths::cpos_bits(profile_fields<P>()), a>;  // p clamped into [LO, HI]
  using frac_t = ufixed<widths::cell_frac_bits(profile_fields<P>()), 1>;  // f = p - i0
  using weight_t = ufixed<widths::lerp_weight_bits(profile_fields<P>()), 1, RND>;  // fq
  // Exact lerp results after 1, 2, 3 axes.
  using vlerp1_t = ufixed<widths::value_lerp_bits(profile_fields<P>(), 1), vb>;
  using vlerp2_t = ufixed<widths::value_lerp_bits(profile_fields<P>(), 2), vb>;
  using vlerp3_t = ufixed<widths::value_lerp_bits(profile_fields<P>(), 3), vb>;
  using glerp1_t = fixed<widths::grad_lerp_bits(profile_fields<P>(), 1), grad_int_bits>;
  using glerp2_t = fixed<widths::grad_lerp_bits(profile_fields<P>(), 2), grad_int_bits>;
  using glerp3_t = fixed<widths::grad_lerp_bits(profile_fields<P>(), 3), grad_int_bits>;
  // §3.5 results (the rounding happens into the *_rnd_t twins).
  static constexpr int sample_value_bits = widths::sample_value_bits(profile_fields<P>());
  static constexpr int sample_grad_bits = widths::sample_grad_bits(profile_fields<P>());
  using value_t = ufixed<sample_value_bits, vb>;
  using gradient_t = fixed<sample_grad_bits, sample_grad_int_bits>;
  using value_rnd_t = ufixed<sample_value_bits, vb, RND>;
  using gradient_rnd_t = fixed<sample_grad_bits, sample_grad_int_bits, RND>;
};

// Pipeline depths (clocks; see hls/geometry_processor.hpp, "Pipeline depths").
// The address generator (§3.1-3.3): clamp, i0, the weights and the bank word
// addresses in one clock. With stepping's clock it is the cycle model's
// `address` stage, which gives the mapping of the DIMM words to SDRAM bank, row
// and column (rtl_model/layout) no clock of its own (the model's assumption).
constexpr int address_generator_depth = 1;
// The interpolation unit (§3.4-3.5): the crossbar that puts bank j ^ parity's
// word at corner j (gather, which has no LATENCY pragma of its own yet), one
// clock, then three lerp levels (interpolation_processor), one clock each, the
// last with its Q_RND to sf.
constexpr int crossbar_depth = 1;
constexpr int lerp_depth = 3;
constexpr int interpolation_depth = crossbar_depth + lerp_depth;

// ---- 2. Voxel words and bank views ------------------------------------------------------------
template <class P>
struct VoxelWordFx {
  typename InterpolationParams<P>::voxel_value_t value;
  typename InterpolationParams<P>::voxel_grad_t g[3];
};

// §3.4 packed layout: value in [vb-1:0], component c in [vb+(c+1)gb-1 : vb+c·gb].
template <class P>
VOXCAST_HLS_HOST_INLINE VoxelWordFx<P> unpack_voxel_word(
    const typename InterpolationParams<P>::packed_word_t& w) {
  using I = InterpolationParams<P>;
  VoxelWordFx<P> v;
  write_bits(v.value, I::vb - 1, 0, read_bits(w, I::vb - 1, 0));
  [[gnu::unused]] unpack_loop : VOXCAST_HLS_HOST_UNROLL for (int c = 0; c < 3; ++c) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const typename I::packed_word_t field = w >> (I::vb + c * I::gb);
    write_bits(v.g[c], I::gb - 1, 0, read_bits(field, I::gb - 1, 0));
  }
  return v;
}

template <class P>
typename InterpolationParams<P>::packed_word_t pack_voxel_word(const VoxelWordFx<P>& v) {
  using I = InterpolationParams<P>;
  typename I::packed_word_t w = 0;
  write_bits(w, I::vb - 1, 0, read_bits(v.value, I::vb - 1, 0));
  [[gnu::unused]] pack_loop : VOXCAST_HLS_HOST_UNROLL for (int c = 0; c < 3; ++c) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    typename I::packed_word_t field = 0;
    write_bits(field, I::gb - 1, 0, read_bits(v.g[c], I::gb - 1, 0));
    w |= field << (I::vb + c * I::gb);
  }
  return w;
}

// The top level's voxel memory: 8 banks of packed words (one port each).
template <class P>
struct PackedBanks {
  const typename InterpolationParams<P>::packed_word_t* bank[8];
  VOXCAST_HLS_HOST_INLINE VoxelWordFx<P> read(
      int b, const typename InterpolationParams<P>::word_addr_t& addr) const {
    return unpack_voxel_word<P>(bank[b][addr.to_uint64()]);
  }
};

// ---- 3. The unit ----------------------------------------------------------------------------

// §3.1-3.3: one access to the 8 banks. Bank b is read at word addr[b]; the
// voxel at offset (dx, dy, dz) from i0 is in bank (dx,dy,dz) ^ parity.
template <class P>
struct BankAccess {
  typename InterpolationParams<P>::word_addr_t addr[8];
  typename InterpolationParams<P>::weight_t fq[3];  // w1 per axis (w0 = 1 - fq)
  unsigned parity;                                  // (i0x&1) | (i0y&1)<<1 | (i0z&1)<<2
};

// §3.1-3.2 along axis k: the position clamped into [LO, HI] (cp) and the
// cell's base voxel i0 = min(floor(cp), dim - 2) (0 if dim = 1). Space leaping
// (hls/space_leaping_unit.hpp) finds a sample's block from the same i0.
template <class P>
VOXCAST_HLS_HOST_INLINE typename GeometryParams<P>::coord_t sample_cell(
    const GeometryRegisters<P>& r, const typename GeometryParams<P>::pos_t& pk, int k,
    typename InterpolationParams<P>::cpos_t& cp) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using G = GeometryParams<P>;
  typename G::pos_t c = pk;
  if (c < r.LO[k]) c = r.LO[k];
  if (c > r.HI[k]) c = r.HI[k];
  cp = c;  // exact: 0 <= c < 2^a
  // floor(p) <= HI <= dim - 1.
  typename G::coord_t i0 = int_cast<typename G::coord_t>(cp);  // floor (truncation of a non-negative value)
  if (i0 == r.LAST[k] && i0 != 0u) i0 = i0 - 1u;
  return i0;
}

template <class P>
VOXCAST_HLS_HOST_INLINE BankAccess<P> address_generator(
    const GeometryRegisters<P>& r, const typename GeometryParams<P>::pos_t p[3]) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = address_generator_depth
                         max = address_generator_depth)
  using G = GeometryParams<P>;
  using I = InterpolationParams<P>;
  BankAccess<P> acc;
  typename G::coord_t half[3];  // i0 >> 1
  bool odd[3];                  // i0 & 1
  acc.parity = 0;
  [[gnu::unused]] axis_loop : VOXCAST_HLS_HOST_UNROLL for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    typename I::cpos_t cp;
    const typename G::coord_t i0 = sample_cell<P>(r, p[k], k, cp);  // §3.1-3.2
    const typename I::frac_t f = cp - i0;  // exact, in [0, 1]
    acc.fq[k] = f;                         // Q_RND(f, wb)
    odd[k] = i0[0];
    half[k] = i0 >> 1;
    if (odd[k]) acc.parity |= 1u << k;
  }
  // §3.3: bank b holds the corner with coordinate i0 (bank bit = parity bit) or
  // i0 + 1 (bank bit != parity bit); its word index along the axis is
  // (i0 >> 1) + 1 only for an even bank bit with odd i0. So every bank reads
  // base = word(i0) plus, per axis with odd i0 and an even bank bit, one more
  // word along that axis (1, HX or HXY).
  const typename I::word_addr_t base = half[0] + half[1] * r.HX + half[2] * r.HXY;
  using word_addr_t = typename I::word_addr_t;
  const word_addr_t zero = 0;
  const word_addr_t inc_x = odd[0] ? word_addr_t(1) : zero;
  const word_addr_t inc_y = odd[1] ? word_addr_t(r.HX) : zero;
  const word_addr_t inc_z = odd[2] ? word_addr_t(r.HXY) : zero;
  [[gnu::unused]] bank_loop : VOXCAST_HLS_HOST_UNROLL for (int b = 0; b < 8; ++b) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    word_addr_t addr = base;
    if ((b & 1) == 0) addr += inc_x;
    if ((b & 2) == 0) addr += inc_y;
    if ((b & 4) == 0) addr += inc_z;
    acc.addr[b] = addr;
  }
  return acc;
}

// §3.3 the crossbar: the card reads every bank at its own port in every
// access (bank b at addr[b], the same port each time), and routes the data:
// corner j = dx | dy<<1 | dz<<2 is the word of bank j ^ parity. An 8x8
// multiplexer on the words, selected by the cell's parity; no address or port
// is chosen at run time.
template <class P>
VOXCAST_HLS_HOST_INLINE void crossbar(const VoxelWordFx<P> word[8], unsigned parity,
                                      VoxelWordFx<P> corner[8]) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  [[gnu::unused]] crossbar_loop : VOXCAST_HLS_HOST_UNROLL for (int j = 0; j < 8; ++j) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    corner[j] = word[static_cast<unsigned>(j) ^ parity];
  }
}

// The bank reads and the crossbar on a bank view: bank b is read at the
// constant index b (one port per bank once the loop is unrolled), then the
// crossbar routes the words. The streamed top reads its eight bank ports
// itself (hls/vizard2_dataflow.hpp, interpolation_stage).
template <class P, class Banks>
VOXCAST_HLS_HOST_INLINE void gather(const Banks& banks, const BankAccess<P>& acc,
                                    VoxelWordFx<P> corner[8]) {
  VoxelWordFx<P> word[8];
  [[gnu::unused]] bank_read_loop : VOXCAST_HLS_HOST_UNROLL for (int b = 0; b < 8; ++b) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    word[b] = banks.read(b, acc.addr[b]);
  }
  crossbar<P>(word, acc.parity, corner);
}

// An interpolated sample (§3.5): value vb.sf unsigned, gradient (index space).
template <class P>
struct Sample {
  typename InterpolationParams<P>::value_t value;
  typename InterpolationParams<P>::gradient_t g[3];
};

// §3.5: trilinear interpolation, exact, then one Q_RND to sf per channel. The
// exact sum is evaluated as three rounds of exact lerps v0 + (v1 - v0)·fq
// (= v0·w0 + v1·w1); any exact order gives the same bits.
template <class P>
VOXCAST_HLS_HOST_INLINE Sample<P> interpolation_processor(
    const VoxelWordFx<P> corner[8], const typename InterpolationParams<P>::weight_t fq[3]) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = lerp_depth max = lerp_depth)
  using I = InterpolationParams<P>;
  typename I::vlerp1_t v1[4];
  typename I::glerp1_t g1[3][4];
  [[gnu::unused]] x_loop : VOXCAST_HLS_HOST_UNROLL for (int j = 0; j < 4; ++j) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const VoxelWordFx<P>& c0 = corner[2 * j];
    const VoxelWordFx<P>& c1 = corner[2 * j + 1];
    v1[j] = c0.value + (c1.value - c0.value) * fq[0];
    [[gnu::unused]] x_grad_loop : VOXCAST_HLS_HOST_UNROLL for (int c = 0; c < 3; ++c) {
      VOXCAST_HLS_PRAGMA(HLS UNROLL)
      g1[c][j] = c0.g[c] + (c1.g[c] - c0.g[c]) * fq[0];
    }
  }
  typename I::vlerp2_t v2[2];
  typename I::glerp2_t g2[3][2];
  [[gnu::unused]] y_loop : VOXCAST_HLS_HOST_UNROLL for (int j = 0; j < 2; ++j) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    v2[j] = v1[2 * j] + (v1[2 * j + 1] - v1[2 * j]) * fq[1];
    [[gnu::unused]] y_grad_loop : VOXCAST_HLS_HOST_UNROLL for (int c = 0; c < 3; ++c) {
      VOXCAST_HLS_PRAGMA(HLS UNROLL)
      g2[c][j] = g1[c][2 * j] + (g1[c][2 * j + 1] - g1[c][2 * j]) * fq[1];
    }
  }
  Sample<P> s;
  const typename I::vlerp3_t v3 = v2[0] + (v2[1] - v2[0]) * fq[2];
  const typename I::value_rnd_t vr = v3;  // Q_RND(·, sf)
  s.value = vr;
  [[gnu::unused]] z_loop : VOXCAST_HLS_HOST_UNROLL for (int c = 0; c < 3; ++c) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const typename I::glerp3_t g3 = g2[c][0] + (g2[c][1] - g2[c][0]) * fq[2];
    const typename I::gradient_rnd_t gr = g3;  // Q_RND(·, sf)
    s.g[c] = gr;
  }
  return s;
}

// §3: the whole unit for one sample position.
template <class P, class Banks>
VOXCAST_HLS_HOST_INLINE Sample<P> interpolate(const GeometryRegisters<P>& r, const Banks& banks,
                                              const typename GeometryParams<P>::pos_t p[3]) {
  const BankAccess<P> acc = address_generator<P>(r, p);
  VoxelWordFx<P> corner[8];
  gather<P>(banks, acc, corner);
  return interpolation_processor<P>(corner, acc.fq);
}

// The per-sample loop of one ray: stepping (§2) and interpolation (§3), one
// sample per clock. `sink(k, p, sample)` (p: the sample's position) consumes the samples (classification,
// shading, compositing) and returns false to end the ray early (early ray
// termination). The trip count is the ray's n (at most about sqrt(3)·2^a / step;
// the pragma gives a 256^3 volume at one sample per voxel).
template <class P, class Banks, class Sink>
void march_ray(const GeometryRegisters<P>& r, const Banks& banks, const RaySetup<P>& ray,
               Sink& sink) {
  using G = GeometryParams<P>;
  typename G::pos_t p[3] = {ray.p0[0], ray.p0[1], ray.p0[2]};
  const std::uint64_t n = ray.n.to_uint64();
  [[gnu::unused]] sample_loop : for (std::uint64_t k = 0; k < n; ++k) {
    VOXCAST_HLS_PRAGMA(HLS PIPELINE II = 1)
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 444 avg = 256)
    const Sample<P> s = interpolate<P>(r, banks, p);
    if (!sink(k, p, s)) break;
    step_position<P>(p, ray.s);
  }
}

// ---- Host side: a bank view on bittrue::VoxelMemory (simulation only) ------------------------
#if VOXCAST_HLS_HOST_CODE
namespace host {

// A host word's fields (bittrue::VoxelWord, or the hls engine's
// bittrue::PackedVoxelWord: `value` and `gradient[3]` as raw integers) as the
// voxel word the units read.
template <class P, class HostWord>
VOXCAST_HLS_HOST_INLINE VoxelWordFx<P> voxel_word_fx(const HostWord& w) {
  using I = InterpolationParams<P>;
  VoxelWordFx<P> v;
  v.value = w.value;
  [[gnu::unused]] field_loop : VOXCAST_HLS_HOST_UNROLL for (int c = 0; c < 3; ++c) {
    // The raw component as an integer, then moved below the binary point
    // (exact: the shift drops only the gfb zero fraction bits of t).
    const int_t<I::gb> raw = w.gradient[static_cast<std::size_t>(c)];
    fixed<I::gb + I::gfb, I::gb> t = raw;
    t >>= I::gfb;
    v.g[c] = t;
  }
  return v;
}

template <class P>
struct BitTrueBanks {
  const bittrue::VoxelWord* bank[8];

  explicit BitTrueBanks(const bittrue::VoxelMemory& mem) {
    [[gnu::unused]] bank_ptr_loop : for (int b = 0; b < 8; ++b) bank[b] =
                                         mem.banks[static_cast<std::size_t>(b)].data();
  }
  VOXCAST_HLS_HOST_INLINE VoxelWordFx<P> read(
      int b, const typename InterpolationParams<P>::word_addr_t& addr) const {
    return voxel_word_fx<P>(bank[b][addr.to_uint64()]);
  }
};

}  // namespace host
#endif

}  // namespace hls
}  // namespace voxcast
