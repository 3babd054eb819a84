// Space leaping unit: the min-max block memory, the O(1) emptiness test and the
// leaping stepper (docs/leaping.md; the VIZARD II paper's future work). Its
// double twin is ref::LeapBlocks::skips, its bit-true twin bittrue::bt_skips.
//
// A sample belongs to the block of its cell's base voxel i0 (the address
// generator's, hls::sample_cell), block = i0 >> lb per axis. The block memory
// holds the minimum and maximum voxel value its cells read (the one-voxel
// apron included); a trilinear sample lies in [min, max], and the
// classification address is monotone in the value, so the sample's table
// entry lies in [addr(min), addr(max)]. The block is empty when every entry
// there has alpha = 0: one subtraction of a prefix count table (prefix[i] =
// entries below i with alpha != 0) built with the classification table.
//
// The leap: the samples of a ray that share a block are consecutive (each
// axis' block coordinate is monotone in the sample index: p_k = p0 + k·s is
// exact, and clamping, floor and shift are monotone). From the first sample in
// an empty block, a binary search over power-of-two multiples of the step
// (q + 2^j·s, exact: a shift and an add) finds the block's last sample; the
// stepper continues one step after it, at exactly the position stepping one by
// one would have reached. Each leap is one block-memory read and one clock of
// the issue stage; no voxel is read for a skipped sample.
//
// Layout: 1. LeapParams<P>; 2. LeapRegisters<P>, MinMaxMemory<P>;
// 3. the unit: block_coords, block_address, block_empty, leap_run,
//    sample_block_empty, march_ray_leaping;
// 4. host:: loading from bittrue::LeapTables (not synthesized).
#pragma once

#include <cstdint>

#include "hls/classification_table.hpp"
#include "hls/geometry_processor.hpp"
#include "hls/interpolation_processor.hpp"
#include "hls/pragma.hpp"
#include "hls/types.hpp"
#include "hls/widths.hpp"

#if VOXCAST_HLS_HOST_CODE
#include <string>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/error.hpp"
#endif

namespace voxcast {
namespace hls {

// ---- 1. Parameters ------------------------------------------------------------------------
// The widths are hls/widths.hpp's functions of the profile.
template <class P>
struct LeapParams {
  using G = GeometryParams<P>;
  static constexpr int a = P::addr_bits;
  static constexpr int vb = P::value_bits;
  static constexpr int ta = P::tf_addr_bits;
  static constexpr int entries = widths::class_entries(profile_fields<P>());
  // The on-chip block memory: 2^15 blocks (32^3: a 256^3 volume in 8^3 blocks,
  // 512^3 in 16^3) of two vb-bit values, 786 kbit at vb = 12. A volume needing
  // more blocks is refused at load (use a larger render.leap_block).
  static constexpr int block_addr_bits = 15;
  static constexpr int max_blocks = 1 << block_addr_bits;
  // The leap's binary search: leap_bits stages (widths::leap_bits says why at most 10).
  static constexpr int leap_bits = widths::leap_bits(profile_fields<P>());

  using count_t = uint_t<widths::prefix_count_bits(profile_fields<P>())>;  // prefix counts
  using lb_t = uint_t<3>;  // log2 of the block edge, 2..6
  using bcoord_t = uint_t<widths::block_coord_bits(profile_fields<P>())>;  // i0 >> lb
  using baddr_wide_t = uint_t<widths::block_addr_wide_bits(profile_fields<P>())>;
  using block_addr_t = uint_t<block_addr_bits>;
  using voxel_value_t = typename InterpolationParams<P>::voxel_value_t;
  // A step and a position plus up to 2^leap_bits steps.
  using wide_step_t = fixed<widths::leap_step_bits(profile_fields<P>()),
                            widths::leap_step_int_bits(profile_fields<P>())>;
  using wide_pos_t = fixed<widths::leap_pos_bits(profile_fields<P>()),
                           widths::leap_pos_int_bits(profile_fields<P>())>;
};

// Pipeline depths (clocks; see hls/geometry_processor.hpp, "Pipeline depths").
// The block look-up beside the address generator (sample_block_empty): the
// min-max RAM read 1, the two prefix-table reads and their comparison 1. It
// adds its clocks to every sample's requests.
constexpr int leap_lookup_depth = 2;
// The leap's search (leap_run): widths::max_leap_bits compare stages, five to a
// clock (the cycle model's assumption; every leap costs the same). A leap holds
// its ray's issue for the look-up and the search.
constexpr int leap_stages_per_clock = 5;
constexpr int leap_search_depth =
    (widths::max_leap_bits + leap_stages_per_clock - 1) / leap_stages_per_clock;
constexpr int leap_depth = leap_lookup_depth + leap_search_depth;

// ---- 2. Registers and memories -------------------------------------------------------------
template <class P>
struct LeapRegisters {
  using L = LeapParams<P>;
  bool enabled = false;
  typename L::lb_t lb = 3;
  typename L::bcoord_t BX = 1;            // blocks along x
  typename L::block_addr_t BXY = 1;       // blocks per z slice
  // prefix[i] = entries j < i with alpha != 0 (2^ta + 1 words, loaded with the table).
  typename L::count_t prefix[L::entries + 1];
};

template <class P>
struct MinMaxEntry {
  typename LeapParams<P>::voxel_value_t lo, hi;
};

// One single-port RAM, one read per block visited.
template <class P>
struct MinMaxMemory {
  MinMaxEntry<P> block[LeapParams<P>::max_blocks];
};

// ---- 3. The unit ----------------------------------------------------------------------------

// The block coordinates of the sample at p: i0 >> lb per axis.
template <class P>
VOXCAST_HLS_HOST_INLINE void block_coords(const GeometryRegisters<P>& r, const LeapRegisters<P>& lr,
                                          const typename GeometryParams<P>::pos_t p[3],
                                          typename LeapParams<P>::bcoord_t b[3]) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using G = GeometryParams<P>;
  [[gnu::unused]] block_axis_loop : VOXCAST_HLS_HOST_UNROLL for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    typename InterpolationParams<P>::cpos_t cp;
    const typename G::coord_t i0 = sample_cell<P>(r, p[k], k, cp);
    b[k] = i0 >> lr.lb.to_uint();
  }
}

// The block memory address of block coordinates b, x fastest.
template <class P>
VOXCAST_HLS_HOST_INLINE typename LeapParams<P>::block_addr_t block_address(
    const LeapRegisters<P>& lr, const typename LeapParams<P>::bcoord_t b[3]) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using L = LeapParams<P>;
  const typename L::baddr_wide_t addr = b[0] + b[1] * lr.BX + b[2] * lr.BXY;
  return typename L::block_addr_t(addr);  // < BXY·blocks_z <= max_blocks (host-checked)
}

// Whether every classification entry a value in [e.lo, e.hi] can address has alpha = 0.
template <class P>
VOXCAST_HLS_HOST_INLINE bool block_empty(const LeapRegisters<P>& lr, const MinMaxEntry<P>& e) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using C = ClassificationParams<P>;
  const typename C::value_t lo = e.lo;  // exact: an integer in the value format
  const typename C::value_t hi = e.hi;
  const unsigned a_lo = class_address<P>(lo).to_uint();
  const unsigned a_hi = class_address<P>(hi).to_uint();
  return lr.prefix[a_hi + 1] == lr.prefix[a_lo];
}

// The samples from p (the ray's remaining `remaining` >= 1) that lie in p's
// block, whose coordinates are b; p is left at the last of them. Greedy binary
// search over q + 2^j·s (the block's samples are consecutive, see the header):
// each stage compares block coordinates, no memory read.
template <class P>
std::uint64_t leap_run(const GeometryRegisters<P>& r, const LeapRegisters<P>& lr,
                       typename GeometryParams<P>::pos_t p[3],
                       const typename GeometryParams<P>::step_t s[3], std::uint64_t remaining,
                       const typename LeapParams<P>::bcoord_t b[3]) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = leap_search_depth max = leap_search_depth)
  using G = GeometryParams<P>;
  using L = LeapParams<P>;
  std::uint64_t run = 1;
  [[gnu::unused]] leap_search_loop
      : VOXCAST_HLS_HOST_UNROLL for (int j = L::leap_bits - 1; j >= 0; --j) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const std::uint64_t add = std::uint64_t{1} << j;
    if (run + add > remaining) continue;  // past the ray's last sample
    typename G::pos_t cand[3];
    [[gnu::unused]] leap_axis_loop : VOXCAST_HLS_HOST_UNROLL for (int k = 0; k < 3; ++k) {
      VOXCAST_HLS_PRAGMA(HLS UNROLL)
      typename L::wide_step_t ws = s[k];
      ws <<= j;  // exact: 2^j·s
      const typename L::wide_pos_t q = p[k] + ws;
      cand[k] = q;  // exact: a sample of this ray, inside the position range
    }
    typename L::bcoord_t cb[3];
    block_coords<P>(r, lr, cand, cb);
    if (cb[0] == b[0] && cb[1] == b[1] && cb[2] == b[2]) {
      [[gnu::unused]] leap_take_loop : VOXCAST_HLS_HOST_UNROLL for (int k = 0; k < 3; ++k) {
        VOXCAST_HLS_PRAGMA(HLS UNROLL)
        p[k] = cand[k];
      }
      run += add;
    }
  }
  return run;
}

// The block look-up of the sample at p: its coordinates (into b) and whether
// the block is empty (one block-memory read, two prefix-table reads).
template <class P>
VOXCAST_HLS_HOST_INLINE bool sample_block_empty(const GeometryRegisters<P>& r,
                                                const LeapRegisters<P>& lr,
                                                const MinMaxMemory<P>& mm,
                                                const typename GeometryParams<P>::pos_t p[3],
                                                typename LeapParams<P>::bcoord_t b[3]) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = leap_lookup_depth max = leap_lookup_depth)
  block_coords<P>(r, lr, p, b);
  return block_empty<P>(lr, mm.block[block_address<P>(lr, b).to_uint()]);
}

// march_ray (hls/interpolation_processor.hpp) with space leaping: per clock
// either one sample (as march_ray) or one leap over an empty block's samples.
// `skip(run)` is told each leap's sample count.
template <class P, class Banks, class Sink, class Skip>
void march_ray_leaping(const GeometryRegisters<P>& r, const LeapRegisters<P>& lr,
                       const MinMaxMemory<P>& mm, const Banks& banks, const RaySetup<P>& ray,
                       Sink& sink, Skip& skip) {
  using G = GeometryParams<P>;
  typename G::pos_t p[3] = {ray.p0[0], ray.p0[1], ray.p0[2]};
  const std::uint64_t n = ray.n.to_uint64();
  std::uint64_t k = 0;
  [[gnu::unused]] leap_sample_loop : while (k < n) {
    VOXCAST_HLS_PRAGMA(HLS PIPELINE II = 1)
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 444 avg = 256)
    typename LeapParams<P>::bcoord_t b[3];
    if (sample_block_empty<P>(r, lr, mm, p, b)) {
      const std::uint64_t run = leap_run<P>(r, lr, p, ray.s, n - k, b);
      skip(run);
      k += run;
    } else {
      const Sample<P> s = interpolate<P>(r, banks, p);
      if (!sink(k, p, s)) break;
      ++k;
    }
    step_position<P>(p, ray.s);
  }
}

// ---- 4. Host side: loading (not synthesized) ------------------------------------------------
#if VOXCAST_HLS_HOST_CODE
namespace host {

// Loads the registers and the block memory from the shared set-up; throws
// voxcast::Error naming `engine` when the volume needs more blocks than the
// memory holds or the prefix table does not match the profile.
template <class P>
void load_leap(const bittrue::LeapTables& t, LeapRegisters<P>& lr, MinMaxMemory<P>& mm,
               const std::string& engine) {
  using L = LeapParams<P>;
  const ref::MinMaxBlocks& b = *t.blocks;
  if (b.count() > static_cast<std::size_t>(L::max_blocks))
    throw Error(engine + ": space leaping needs " + std::to_string(b.count()) +
                " blocks of " + std::to_string(1 << b.block_log2) +
                "^3 cells; the min-max memory holds " + std::to_string(L::max_blocks) +
                " (raise render.leap_block)");
  if (t.nonzero_prefix.size() != static_cast<std::size_t>(L::entries + 1))
    throw Error(engine + ": space leaping prefix table size does not match the profile");
  lr.enabled = true;
  lr.lb = static_cast<unsigned>(b.block_log2);
  lr.BX = static_cast<unsigned>(b.blocks[0]);
  lr.BXY = static_cast<unsigned>(b.blocks[0] * b.blocks[1]);
  for (int i = 0; i <= L::entries; ++i)
    lr.prefix[i] = t.nonzero_prefix[static_cast<std::size_t>(i)];
  for (std::size_t i = 0; i < b.count(); ++i) {
    mm.block[i].lo = std::uint32_t{b.vmin[i]} << t.value_shift;
    mm.block[i].hi = std::uint32_t{b.vmax[i]} << t.value_shift;
  }
}

}  // namespace host
#endif

}  // namespace hls
}  // namespace voxcast
