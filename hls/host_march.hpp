// The hls engine's own march on the host (not synthesized): the bank view the
// engine hands to cast_ray / render_rows, and the sample loop cast_ray runs
// on it. Every number of a sample still comes from the units (sample_cell,
// interpolate, step_position, and the sink's classification, shading and
// compositing); what the engine adds around them is empty-space skipping the
// scene did not ask for, which does not change the image:
//
//   Before a frame the engine marks each min-max block of the volume
//   (bittrue::VoxelMemory::leap_blocks, 4^3 cells) empty when every
//   classification entry its values can address has alpha = 0: the unit's own
//   test (block_empty, docs/leaping.md). The march then takes the samples in
//   order, as march_ray does, but does not interpolate a sample whose cell's
//   block is empty: such a sample is transparent, and a transparent sample
//   changes nothing and is not tested for ERT (§7), so the pixel is the same
//   bits. It counts as a sample (the frame's counts are the scene's: without
//   space leaping every sample is interpolated).
//
//   Runs of such samples are passed over in one step, not one by one. Each
//   empty block also holds its chessboard distance d (in blocks) to the
//   nearest block that is not empty, so every block within d - 1 of it along
//   each axis is empty too. A sample's cell is a monotone function of its
//   position along each axis (clamp, floor, the last-cell rule of
//   sample_cell), and positions are exact sums p0 + k·s (pos_t and step_t have
//   the same fraction bits, the wrap-around adder of step_position), so the
//   number of samples the ray takes before its cell leaves that cube is a
//   division per axis (samples_inside), and the position after them is
//   p + run·s, the same bits as run additions.
//
// A frame that asks for render.space_leaping leaps with the unit
// (march_ray_leaping, on the same banks); a MIP frame and a pre-integrated
// one (§4a: a transparent sample may end a visible segment) take every sample.
#pragma once

#include "hls/pragma.hpp"

#if VOXCAST_HLS_HOST_CODE
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "hls/interpolation_processor.hpp"
#include "hls/space_leaping_unit.hpp"
#include "refmodel/bittrue/frame_setup.hpp"

namespace voxcast {
namespace hls {
namespace host {

// Which blocks of bittrue::VoxelMemory::leap_blocks hold only transparent
// samples for one frame's classification table (one byte per block, x fastest):
// 0 for a block that is not empty, else its chessboard distance in blocks to
// the nearest one that is (at most kMaxEmptyDistance; blocks outside the grid
// do not count: sample_cell clamps every position into it).
struct EmptyBlocks {
  static constexpr std::uint8_t kMaxEmptyDistance = 255;
  int lb = 0;                     // log2 of the block edge in cells
  std::int64_t n[3] = {0, 0, 0};  // blocks per axis
  std::vector<std::uint8_t> distance;

  std::size_t index(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return static_cast<std::size_t>(x + n[0] * (y + n[1] * z));
  }
};

// The exact chessboard (L-infinity) distance transform of the empty map, in
// place: the two raster passes of the 3x3x3 unit-weight chamfer mask
// (Rosenfeld and Pfaltz's sequential algorithm in 3-D), each block taking the
// minimum over the 13 neighbours already visited in its pass, plus one.
inline void chessboard_distance(EmptyBlocks& eb) {
  const std::int64_t nx = eb.n[0], ny = eb.n[1], nz = eb.n[2];
  auto at = [&](std::int64_t x, std::int64_t y, std::int64_t z) -> std::uint8_t& {
    return eb.distance[eb.index(x, y, z)];
  };
  auto pass = [&](int dir) {
    for (std::int64_t zi = 0; zi < nz; ++zi)
      for (std::int64_t yi = 0; yi < ny; ++yi)
        for (std::int64_t xi = 0; xi < nx; ++xi) {
          const std::int64_t x = dir > 0 ? xi : nx - 1 - xi, y = dir > 0 ? yi : ny - 1 - yi,
                             z = dir > 0 ? zi : nz - 1 - zi;
          std::uint8_t& d = at(x, y, z);
          if (d == 0) continue;
          // The neighbours before (x, y, z) in this pass's raster order.
          for (int dz = -1; dz <= 0; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                if (dz == 0 && (dy > 0 || (dy == 0 && dx >= 0))) continue;
                const std::int64_t qx = x + dir * dx, qy = y + dir * dy, qz = z + dir * dz;
                if (qx < 0 || qy < 0 || qz < 0 || qx >= nx || qy >= ny || qz >= nz) continue;
                const std::uint8_t q = at(qx, qy, qz);
                if (q < d && q + 1 < d) d = static_cast<std::uint8_t>(q + 1);
              }
        }
  };
  pass(+1);
  pass(-1);
}

// The empty blocks of a memory for one classification table's nonzero-alpha
// prefix (bittrue::nonzero_prefix): the space-leaping unit's emptiness test
// (block_empty) per min-max block, then the distance transform.
template <class P>
std::shared_ptr<const EmptyBlocks> make_empty_blocks(const std::vector<std::uint32_t>& prefix,
                                                     const bittrue::VoxelMemory& memory) {
  const ref::MinMaxBlocks& b = *memory.leap_blocks;
  using L = LeapParams<P>;
  auto lr = std::make_unique<LeapRegisters<P>>();
  for (int i = 0; i <= L::entries; ++i) lr->prefix[i] = prefix[static_cast<std::size_t>(i)];
  auto out = std::make_shared<EmptyBlocks>();
  out->lb = b.block_log2;
  for (int a = 0; a < 3; ++a) out->n[a] = b.blocks[a];
  out->distance.resize(b.count());
  for (std::size_t i = 0; i < b.count(); ++i) {
    MinMaxEntry<P> e;
    e.lo = std::uint32_t{b.vmin[i]} << memory.value_shift;
    e.hi = std::uint32_t{b.vmax[i]} << memory.value_shift;
    out->distance[i] = block_empty<P>(*lr, e) ? EmptyBlocks::kMaxEmptyDistance : 0;
  }
  chessboard_distance(*out);
  return out;
}

// The frame's empty blocks, or null when the engine does not skip: a MIP
// frame, a frame that leaps with the unit (render.space_leaping), or a memory
// without min-max blocks.
//
// The last result is kept (per profile, for all threads): a frame of the same
// memory whose table has the same transparent entries reuses it, as a
// flythrough, a bench or an interactive session renders frame after frame.
// The key is the memory's min-max blocks (by identity: a memory freed since
// cannot match, the key holds it weakly) and the table's nonzero-alpha prefix,
// which is all the emptiness test reads.
template <class P>
std::shared_ptr<const EmptyBlocks> empty_blocks(const bittrue::FrameSetup& fs,
                                                const bittrue::VoxelMemory& memory) {
  // A pre-integrated frame classifies the segment in front of each sample, so a
  // sample in an empty block may end a visible segment: every sample is taken.
  if (fs.leap || fs.preint_table || fs.regs.mode == ref::RenderMode::Mip || !memory.leap_blocks)
    return nullptr;
  if (fs.class_table.size() != static_cast<std::size_t>(LeapParams<P>::entries)) return nullptr;
  const std::vector<std::uint32_t> prefix = bittrue::nonzero_prefix(fs.class_table);
  struct Last {
    std::mutex m;
    std::weak_ptr<const ref::MinMaxBlocks> blocks;
    int value_shift = 0;
    std::vector<std::uint32_t> prefix;
    std::shared_ptr<const EmptyBlocks> result;
  };
  static Last last;
  {
    const std::lock_guard<std::mutex> lock(last.m);
    if (last.result && last.blocks.lock() == memory.leap_blocks &&
        last.value_shift == memory.value_shift && last.prefix == prefix)
      return last.result;
  }
  std::shared_ptr<const EmptyBlocks> out = make_empty_blocks<P>(prefix, memory);
  const std::lock_guard<std::mutex> lock(last.m);
  last.blocks = memory.leap_blocks;
  last.value_shift = memory.value_shift;
  last.prefix = prefix;
  last.result = out;
  return out;
}

// The engine's bank view: the card's eight banks (BitTrueBanks, read by the
// units exactly as on the card) and, for the engine's march, the frame's empty
// blocks and the counter of the samples it skipped (the caller's row).
template <class P>
struct EngineBanks : BitTrueBanks<P> {
  // The profile's voxel word fits bittrue::PackedVoxelWord (fields of at most
  // 16 bits): the engine then reads the packed words, never the bank arrays.
  static constexpr bool kPacked =
      InterpolationParams<P>::vb <= 16 && InterpolationParams<P>::gb <= 16;

  const EmptyBlocks* blocks = nullptr;  // null: no skipping
  std::uint64_t* skipped = nullptr;     // where skipped samples are counted
  // The memory's words in the host's layout (VoxelMemory::packed: the eight
  // banks interleaved, 8 bytes a word), the same fields in fewer cache lines
  // per cell. Not null when kPacked (engine_packed_words).
  const bittrue::PackedVoxelWord* packed = nullptr;

  EngineBanks(const bittrue::VoxelMemory& mem, const bittrue::PackedVoxelWord* packed_words)
      : BitTrueBanks<P>(mem), packed(packed_words) {}

  VOXCAST_HLS_HOST_INLINE VoxelWordFx<P> read(
      int b, const typename InterpolationParams<P>::word_addr_t& addr) const {
    // A constant condition: one of the two reads is compiled per profile.
    if (!kPacked) return BitTrueBanks<P>::read(b, addr);
    return voxel_word_fx<P>(packed[8 * addr.to_uint64() + static_cast<unsigned>(b)]);
  }
};

// gather (interpolation_processor.hpp) on the engine's banks, found by
// argument-dependent lookup from interpolate: corner j is read from its bank
// j ^ parity directly, the crossbar's routing folded into the read instead of a
// second copy of the eight words through a run-time index. The same word in
// every corner.
template <class P>
VOXCAST_HLS_HOST_INLINE void gather(const EngineBanks<P>& banks, const BankAccess<P>& acc,
                                    VoxelWordFx<P> corner[8]) {
  VOXCAST_HLS_HOST_UNROLL for (int j = 0; j < 8; ++j) {
    const unsigned b = static_cast<unsigned>(j) ^ acc.parity;
    corner[j] = banks.read(static_cast<int>(b), acc.addr[b]);
  }
}

// The packed words an EngineBanks<P> reads: the memory's own, or, for a memory
// made without them (by hand, or with fields wider than 16 bits at run time
// while P's fit), a copy the caller keeps for the frame; null when P does not
// read packed words.
template <class P>
std::shared_ptr<const std::vector<bittrue::PackedVoxelWord>> engine_packed_words(
    const bittrue::VoxelMemory& mem) {
  if (!EngineBanks<P>::kPacked) return nullptr;
  return mem.packed ? mem.packed : bittrue::pack_banks(mem);
}

// The two's-complement value of a fixed-point number of at most 64 bits.
template <class T>
std::int64_t signed_raw(const T& x) {
  static_assert(T::width <= 64, "signed_raw: more than 64 bits");
  const std::uint64_t u = read_bits(x);
  if (T::width == 64) return static_cast<std::int64_t>(u);
  const std::uint64_t sign = std::uint64_t{1} << (T::width - 1);
  return static_cast<std::int64_t>(u ^ sign) - static_cast<std::int64_t>(sign);
}

// How many samples from position p (raw, axis a) on keep the cell's block
// along a within [lo_block, hi_block] when the ray steps by s (raw): at least
// 1 (the sample at p is inside), or `unlimited` when the ray never leaves
// along this axis. The block of a position is sample_cell's cell >> lb: the
// position clamped into [LO, HI], floored, and the last cell folded onto the
// one before; all monotone, so the samples inside are a run from p on.
template <class P>
std::uint64_t samples_inside(const GeometryRegisters<P>& r, int a, std::int64_t p, std::int64_t s,
                             std::int64_t lo_block, std::int64_t hi_block, unsigned lb,
                             std::uint64_t unlimited) {
  using G = GeometryParams<P>;
  constexpr int F = G::pos_t::width - fixed_iwidth<typename G::pos_t>::value;
  if (s == 0) return unlimited;
  const std::int64_t last = static_cast<std::int64_t>(r.LAST[a].to_uint64());
  // The crop box is in whole voxels (box_t, an integer); positions in pos_t.
  const std::int64_t lo_raw = r.LO[a].to_int64() * (std::int64_t{1} << F);
  if (s > 0) {
    // The highest cell a position can reach, and the first cell past the range.
    std::int64_t max_cell = r.HI[a].to_int64();
    if (max_cell == last && last != 0) max_cell = last - 1;
    const std::int64_t t = (hi_block + 1) << lb;
    if (t > max_cell) return unlimited;
    const std::int64_t t_raw = t << F;  // <= HI: a position reaches cell t from here on
    return static_cast<std::uint64_t>((t_raw - p + s - 1) / s);
  }
  // Below the range: cells below lo_block << lb, reached only above LO.
  if (lo_block <= 0) return unlimited;
  const std::int64_t x = lo_block << lb;
  const std::int64_t x_raw = x << F;
  if (x_raw <= lo_raw) return unlimited;
  return static_cast<std::uint64_t>((p - x_raw) / -s + 1);
}

// march_ray (interpolation_processor.hpp) on the engine's banks, found by
// argument-dependent lookup from cast_ray: the same samples in the same order,
// each either interpolated and given to the sink or, in an empty block,
// counted and passed over.
template <class P, class Sink>
void march_ray(const GeometryRegisters<P>& r, const EngineBanks<P>& banks, const RaySetup<P>& ray,
               Sink& sink) {
  if (!banks.blocks) {
    hls::march_ray<P>(r, banks, ray, sink);  // EngineBanks::read: the packed words
    return;
  }
  using G = GeometryParams<P>;
  using pos_t = typename G::pos_t;
  using step_t = typename G::step_t;
  static_assert(pos_t::width - fixed_iwidth<pos_t>::value ==
                    step_t::width - fixed_iwidth<step_t>::value,
                "a run of samples is p + run·s only when positions and steps share their "
                "fraction bits");
  const EmptyBlocks& eb = *banks.blocks;
  const unsigned lb = static_cast<unsigned>(eb.lb);
  pos_t p[3] = {ray.p0[0], ray.p0[1], ray.p0[2]};
  const std::uint64_t n = ray.n.to_uint64();
  const std::int64_t s_raw[3] = {signed_raw(ray.s[0]), signed_raw(ray.s[1]), signed_raw(ray.s[2])};
  // Positions an unwrapped run may reach without the adder wrapping.
  constexpr std::int64_t kPosMax = (std::int64_t{1} << (pos_t::width - 1)) - 1;
  constexpr std::int64_t kPosMin = -kPosMax - 1;
  std::uint64_t skipped = 0;
  for (std::uint64_t k = 0; k < n;) {
    std::int64_t block[3];
    VOXCAST_HLS_HOST_UNROLL for (int a = 0; a < 3; ++a) {
      typename InterpolationParams<P>::cpos_t cp;
      block[a] = static_cast<std::int64_t>(sample_cell<P>(r, p[a], a, cp).to_uint64() >> lb);
    }
    const std::uint8_t d = eb.distance[eb.index(block[0], block[1], block[2])];
    if (d == 0) {
      const Sample<P> s = interpolate<P>(r, banks, p);
      if (!sink(k, p, s)) break;
      step_position<P>(p, ray.s);
      ++k;
      continue;
    }
    // Every block within d - 1 of this one is empty: pass over the samples
    // whose cells stay in that cube.
    const std::int64_t margin = d - 1;
    std::uint64_t run = n - k;
    std::int64_t p_raw[3];
    for (int a = 0; a < 3; ++a) {
      p_raw[a] = signed_raw(p[a]);
      const std::uint64_t inside = samples_inside<P>(
          r, a, p_raw[a], s_raw[a], block[a] - margin, block[a] + margin, lb, run);
      if (inside < run) run = inside;
    }
    bool wraps = false;
    for (int a = 0; a < 3; ++a) {
      const std::int64_t end = p_raw[a] + static_cast<std::int64_t>(run - 1) * s_raw[a];
      wraps = wraps || end > kPosMax || end < kPosMin;
    }
    if (wraps) run = 1;  // never for a ray clipped to the volume; one step is always exact
    for (int a = 0; a < 3; ++a)
      write_bits(p[a], static_cast<std::uint64_t>(p_raw[a] + static_cast<std::int64_t>(run) * s_raw[a]));
    skipped += run;
    k += run;
  }
  *banks.skipped += skipped;
}

}  // namespace host
}  // namespace hls
}  // namespace voxcast
#endif
