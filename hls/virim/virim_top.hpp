// VIRIM's rotator and slice processor as one streaming line kernel
// (docs/heidelberg.md §7.6): for image line k (the view cube's plane z = k),
// the geometry processor, the parity memory and the interpolation processor
// produce the plane row by row (depth j = 0 nearest the viewer); the gradient
// processor turns three rows into bus words; the slice processor consumes
// them. Top-level functions with interface pragmas are at the end.
#pragma once

#include <cstdint>

#include "hls/pragma.hpp"
#include "hls/virim/geometry_processor.hpp"
#include "hls/virim/gradient_processor.hpp"
#include "hls/virim/interpolation_processor.hpp"
#include "hls/virim/parity_memory.hpp"
#include "hls/virim/slice_processor.hpp"

namespace voxcast {
namespace hls {
namespace virim {

template <class HP>
struct VirimFrame {
  GeometryRegisters<HP> geometry;
  MemoryRegisters<HP> memory;
  InterpolationTables<HP> tables;
  SliceRegisters<HP> slice;
};

// One rotated voxel: address, 8 reads, LUT, 8 weights.
template <class HP>
typename VirimParams<HP>::density_t rotator_voxel(const VirimFrame<HP>& f, ParityMemory<HP>& mem,
                                                  int i, int j, int k) {
  const Address<HP> a = geometry_processor<HP>(f.geometry, i, j, k);
  std::uint16_t value[8];
  bool valid[8];
  mem.read8(a.x0, value, valid);
  uint_t<3 * HP::weight_bits> addr = 0;
  write_bits(addr, HP::weight_bits - 1, 0, a.q[0].to_uint64());
  write_bits(addr, 2 * HP::weight_bits - 1, HP::weight_bits, a.q[1].to_uint64());
  write_bits(addr, 3 * HP::weight_bits - 1, 2 * HP::weight_bits, a.q[2].to_uint64());
  return interpolation_processor<HP>(f.tables, addr, value, valid);
}

// Image line k: level[x] and background[x] for x < W. `mem` is reset first,
// so the counts of one line do not depend on which lines ran before.
template <class HP>
void virim_line(const VirimFrame<HP>& f, ParityMemory<HP>& mem, int k, std::uint32_t* level,
                bool* background) {
  using V = VirimParams<HP>;
  using density_t = typename V::density_t;
  using light_t = typename V::light_t;
  const int W = f.geometry.W, D = f.geometry.D;
  mem.reset();
  density_t ring[3][V::max_view];
  light_t t0[V::max_view], t45[V::max_view];
  typename V::acc_t acc[V::max_view];
  [[gnu::unused]] init_loop : for (int x = 0; x < W; ++x) {
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT max = 512)
    t0[x] = 1;
    t45[x] = 1;
    acc[x] = 0;
  }
  [[gnu::unused]] row_loop : for (int j = 0; j <= D; ++j) {
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT max = 513)
    if (j < D) {
      [[gnu::unused]] rotate_loop : for (int x = 0; x < W; ++x) {
        VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT max = 512)
        VOXCAST_HLS_PRAGMA(HLS PIPELINE II = 1)
        ring[j % 3][x] = rotator_voxel<HP>(f, mem, x, j, k);
      }
    }
    if (j >= 1) {
      const int r = j - 1;
      const density_t* above = r >= 1 ? ring[(r + 2) % 3] : nullptr;
      const density_t* row = ring[r % 3];
      const density_t* below = r + 1 < D ? ring[(r + 1) % 3] : nullptr;
      // Descending x: the 45 deg light leaving x lands in x + 1 of the next row,
      // already consumed in this one.
      [[gnu::unused]] slice_loop : for (int x = W - 1; x >= 0; --x) {
        VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT max = 512)
        const typename V::bus_t word = pack_bus_word<HP>(gradient_processor<HP>(above, row, below, x, W));
        const light_t out45 = slice_voxel<HP>(f.slice, unpack_bus_word<HP>(word), t45[x], t0[x], acc[x]);
        if (x + 1 < W) t45[x + 1] = out45;
      }
      t45[0] = 1;  // light enters the cube's side unattenuated
    }
  }
  [[gnu::unused]] out_loop : for (int x = 0; x < W; ++x) {
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT max = 512)
    level[x] = output_level<HP>(acc[x]);
    background[x] = t0[x] > f.slice.threshold;
  }
}

// Lines [k_lo, k_hi) of a frame from the 16 banks. The interface pragmas are
// in the synthesized top, hls/virim/virim_synth_top.cpp.
template <class HP>
void virim_frame(const VirimFrame<HP>* frame, const std::uint16_t* const banks[16], int k_lo,
                 int k_hi, std::uint32_t* level, bool* background, MemoryStats* stats) {
  ParityMemory<HP> mem;
  [[gnu::unused]] bank_loop : for (int b = 0; b < 16; ++b) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    mem.bank[b] = banks[b];
  }
  mem.regs = frame->memory;
  mem.stats = MemoryStats{};
  const int W = frame->geometry.W;
  [[gnu::unused]] line_loop : for (int k = k_lo; k < k_hi; ++k) {
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT max = 512)
    virim_line<HP>(*frame, mem, k, level + (k - k_lo) * W, background + (k - k_lo) * W);
  }
  *stats = mem.stats;
}

}  // namespace virim
}  // namespace hls
}  // namespace voxcast
