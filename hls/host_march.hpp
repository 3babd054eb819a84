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
// A frame that asks for render.space_leaping leaps with the unit
// (march_ray_leaping, on the same banks); a MIP frame takes every sample.
#pragma once

#include "hls/pragma.hpp"

#if VOXCAST_HLS_HOST_CODE
#include <cstdint>
#include <memory>
#include <vector>

#include "hls/interpolation_processor.hpp"
#include "hls/space_leaping_unit.hpp"
#include "refmodel/bittrue/frame_setup.hpp"

namespace voxcast {
namespace hls {
namespace host {

// Which blocks of bittrue::VoxelMemory::leap_blocks hold only transparent
// samples for one frame's classification table (one byte per block, x fastest).
struct EmptyBlocks {
  int lb = 0;                    // log2 of the block edge in cells
  std::int64_t bx = 0, bxy = 0;  // blocks along x, per z slice
  std::vector<std::uint8_t> empty;
};

// The frame's empty blocks, or null when the engine does not skip: a MIP
// frame, a frame that leaps with the unit (render.space_leaping), or a memory
// without min-max blocks.
template <class P>
std::shared_ptr<const EmptyBlocks> empty_blocks(const bittrue::FrameSetup& fs,
                                                const bittrue::VoxelMemory& memory) {
  if (fs.leap || fs.regs.mode == ref::RenderMode::Mip || !memory.leap_blocks) return nullptr;
  const ref::MinMaxBlocks& b = *memory.leap_blocks;
  using L = LeapParams<P>;
  if (fs.class_table.size() != static_cast<std::size_t>(L::entries)) return nullptr;
  // The unit's prefix table and emptiness test (space_leaping_unit.hpp).
  auto lr = std::make_unique<LeapRegisters<P>>();
  const std::vector<std::uint32_t> prefix = bittrue::nonzero_prefix(fs.class_table);
  for (int i = 0; i <= L::entries; ++i) lr->prefix[i] = prefix[static_cast<std::size_t>(i)];
  auto out = std::make_shared<EmptyBlocks>();
  out->lb = b.block_log2;
  out->bx = b.blocks[0];
  out->bxy = std::int64_t{b.blocks[0]} * b.blocks[1];
  out->empty.resize(b.count());
  for (std::size_t i = 0; i < b.count(); ++i) {
    MinMaxEntry<P> e;
    e.lo = std::uint32_t{b.vmin[i]} << memory.value_shift;
    e.hi = std::uint32_t{b.vmax[i]} << memory.value_shift;
    out->empty[i] = block_empty<P>(*lr, e) ? 1 : 0;
  }
  return out;
}

// The engine's bank view: the card's eight banks (BitTrueBanks, read by the
// units exactly as on the card) and, for the engine's march, the frame's empty
// blocks and the counter of the samples it skipped (the caller's row).
template <class P>
struct EngineBanks : BitTrueBanks<P> {
  const EmptyBlocks* blocks = nullptr;  // null: no skipping
  std::uint64_t* skipped = nullptr;     // where skipped samples are counted

  explicit EngineBanks(const bittrue::VoxelMemory& mem) : BitTrueBanks<P>(mem) {}
};

// march_ray (interpolation_processor.hpp) on the engine's banks, found by
// argument-dependent lookup from cast_ray: the same samples in the same order,
// each either interpolated and given to the sink or, in an empty block,
// counted and passed over.
template <class P, class Sink>
void march_ray(const GeometryRegisters<P>& r, const EngineBanks<P>& banks, const RaySetup<P>& ray,
               Sink& sink) {
  if (!banks.blocks) {
    hls::march_ray<P>(r, static_cast<const BitTrueBanks<P>&>(banks), ray, sink);
    return;
  }
  using G = GeometryParams<P>;
  const EmptyBlocks& eb = *banks.blocks;
  const unsigned lb = static_cast<unsigned>(eb.lb);
  typename G::pos_t p[3] = {ray.p0[0], ray.p0[1], ray.p0[2]};
  const std::uint64_t n = ray.n.to_uint64();
  std::uint64_t skipped = 0;
  for (std::uint64_t k = 0; k < n; ++k) {
    std::int64_t block[3];
    VOXCAST_HLS_HOST_UNROLL for (int a = 0; a < 3; ++a) {
      typename InterpolationParams<P>::cpos_t cp;
      block[a] = static_cast<std::int64_t>(sample_cell<P>(r, p[a], a, cp).to_uint64() >> lb);
    }
    if (eb.empty[static_cast<std::size_t>(block[0] + block[1] * eb.bx + block[2] * eb.bxy)]) {
      ++skipped;
    } else {
      const Sample<P> s = interpolate<P>(r, banks, p);
      if (!sink(k, p, s)) break;
    }
    step_position<P>(p, ray.s);
  }
  *banks.skipped += skipped;
}

}  // namespace host
}  // namespace hls
}  // namespace voxcast
#endif
