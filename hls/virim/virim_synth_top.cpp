// The VIRIM top a vendor HLS tool synthesizes: virim_frame_top, at global
// scope, for VIRIM's published widths (VirimTraits). Layer 2 of the
// Vitis-Libraries split, as hls/vizard2_synth_top.cpp: the interface pragmas
// are in the top itself. The 16 gray-value banks (8 interpolation units x 2
// parity banks, docs/heidelberg.md §7.2) are one AXI master port each; the
// kernel (hls/virim/virim_top.hpp) takes them as an array of 16 pointers.
// C++14; CMake compiles it as the vendor tool sees it (-D__SYNTHESIS__, no
// exceptions, no RTTI) and tools/synth_lint checks it.
// A synthesized top's translation unit never takes the host-side loaders
// (C++20, hls/pragma.hpp): not under a vendor's synthesis, and not in a C
// simulation or a plain C++14 compile against the vendor's simulation headers.
#ifndef VOXCAST_HLS_KERNELS_ONLY
#define VOXCAST_HLS_KERNELS_ONLY
#endif
#include <cstdint>

#include "hls/pragma.hpp"
#include "hls/virim/virim_top.hpp"
#include "refmodel/precision/profile_traits.hpp"

using VirimFrameState = voxcast::hls::virim::VirimFrame<voxcast::VirimTraits>;
using VirimMemoryStats = voxcast::hls::virim::MemoryStats;

// Image lines [k_lo, k_hi) of a frame: 8-bit levels and the background flags
// out, the memory statistics of the frame's reads.
void virim_frame_top(const VirimFrameState* frame, const std::uint16_t* bank0,
                     const std::uint16_t* bank1, const std::uint16_t* bank2,
                     const std::uint16_t* bank3, const std::uint16_t* bank4,
                     const std::uint16_t* bank5, const std::uint16_t* bank6,
                     const std::uint16_t* bank7, const std::uint16_t* bank8,
                     const std::uint16_t* bank9, const std::uint16_t* bank10,
                     const std::uint16_t* bank11, const std::uint16_t* bank12,
                     const std::uint16_t* bank13, const std::uint16_t* bank14,
                     const std::uint16_t* bank15, int k_lo, int k_hi, std::uint32_t* level,
                     bool* background, VirimMemoryStats* stats) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = k_lo)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = k_hi)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = frame offset = slave bundle = gmem_frame)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank0 offset = slave bundle = unit0)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank1 offset = slave bundle = unit0)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank2 offset = slave bundle = unit1)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank3 offset = slave bundle = unit1)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank4 offset = slave bundle = unit2)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank5 offset = slave bundle = unit2)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank6 offset = slave bundle = unit3)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank7 offset = slave bundle = unit3)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank8 offset = slave bundle = unit4)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank9 offset = slave bundle = unit4)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank10 offset = slave bundle = unit5)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank11 offset = slave bundle = unit5)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank12 offset = slave bundle = unit6)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank13 offset = slave bundle = unit6)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank14 offset = slave bundle = unit7)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank15 offset = slave bundle = unit7)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = level offset = slave bundle = gmem_out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = background offset = slave bundle = gmem_out)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = stats offset = slave bundle = gmem_out)
  const std::uint16_t* const banks[16] = {bank0, bank1, bank2,  bank3,  bank4,  bank5,
                                          bank6, bank7, bank8,  bank9,  bank10, bank11,
                                          bank12, bank13, bank14, bank15};
  voxcast::hls::virim::virim_frame<voxcast::VirimTraits>(frame, banks, k_lo, k_hi, level,
                                                         background, stats);
}
