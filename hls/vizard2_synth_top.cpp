// The top function a vendor HLS tool synthesizes: vizard2_frame_top, at global
// scope (Vitis HLS takes a plain name for set_top), for one precision profile
// and one set of units, both fixed at compile time. Layer 2 of the
// Vitis-Libraries split: the interface pragmas are here, in the top itself
// (a vendor tool reads INTERFACE pragmas only in the top function).
//
// Shaped like the card (docs/synthesis.md, "The streamed top"):
//   1. Load phase: the frame's registers and tables, which the host wrote to
//      external memory (gmem_frame), are copied into on-chip memories bound
//      and partitioned below, as the card's PCI upload filled its SRAMs and
//      registers between frames.
//   2. The streamed pipeline (hls/vizard2_dataflow.hpp): six processes under
//      DATAFLOW, one sample per clock, run once per image row. Its only
//      external memory is the eight voxel banks, each at its own port (two
//      per DIMM bundle, as the card's four DIMM channels), and the frame
//      buffer; tools/synth_lint --region checks that on the compiler's AST.
//
// `voxcast synth-script SCENE` writes the scene's elaborated_config.hpp
// (ref::elaborate: which units the scene needs; cosim/hardware/synth_script.hpp) and
// its Tcl passes it with `-include`, so the top instantiates only those units
// (hls/units.hpp, docs/synthesis.md): a MIP top has no classification, shader
// or compositor, a parallel top no direction or rsqrt unit. Without the header
// the top is the full run-time-configurable design (AllUnits) for the preset
// -DVOXCAST_SYNTH_PROFILE=Vizard2Traits | BalancedTraits | PreciseTraits
// names. C++14, as the vendor front ends read it; CMake compiles this file as
// the vendor tool sees it (-D__SYNTHESIS__, no exceptions, no RTTI, g++ and
// clang++ -std=c++14, on voxcast's types and on Xilinx's and Catapult's) for
// each preset (hls/CMakeLists.txt) and for two elaborated scenes
// (tests/CMakeLists.txt), and tools/synth_lint checks it.
// A synthesized top's translation unit never takes the host-side loaders
// (C++20, hls/pragma.hpp): not under a vendor's synthesis, and not in a C
// simulation or a plain C++14 compile against the vendor's simulation headers.
#ifndef VOXCAST_HLS_KERNELS_ONLY
#define VOXCAST_HLS_KERNELS_ONLY
#endif
#include <cstdint>

#include "hls/pragma.hpp"
#include "hls/vizard2_dataflow.hpp"
#include "hls/vizard2_synth_config.hpp"

using voxcast::hls::top::Frame;
using voxcast::hls::top::kReflectanceBanks;
using voxcast::hls::top::Pixel;
using voxcast::hls::top::TopProfile;
using voxcast::hls::top::TopUnits;
using voxcast::hls::top::Word;

// The frame state and the 8 voxel banks in external memory (one AXI master
// each, two banks per DIMM channel of the card), the frame buffer and the
// sample count out; width, height and start on the AXI-lite control port.
void vizard2_frame_top(const Frame* frame, const Word* bank0, const Word* bank1,
                       const Word* bank2, const Word* bank3, const Word* bank4, const Word* bank5,
                       const Word* bank6, const Word* bank7, int width, int height, Pixel* fb,
                       std::uint64_t* samples) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = width)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = height)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = frame offset = slave bundle = gmem_frame)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank0 offset = slave bundle = dimm0)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank1 offset = slave bundle = dimm0)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank2 offset = slave bundle = dimm1)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank3 offset = slave bundle = dimm1)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank4 offset = slave bundle = dimm2)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank5 offset = slave bundle = dimm2)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank6 offset = slave bundle = dimm3)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank7 offset = slave bundle = dimm3)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = fb offset = slave bundle = gmem_fb)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = samples offset = slave bundle = gmem_fb)

  // The on-chip state. Static: it is the card's SRAMs and registers, kept
  // between frames (and, in a C simulation, megabytes off the stack).
  static Frame state;
  // Registers read three at a time (one per axis, §1-3): flip-flops.
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.geometry.A type = complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.geometry.B type = complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.geometry.C type = complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.geometry.O type = complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.geometry.Pcol type = complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.geometry.Rrow type = complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.geometry.U type = complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.geometry.K type = complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.geometry.LO type = complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.geometry.HI type = complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.geometry.dims type = complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.geometry.LAST type = complete)
#if VOXCAST_TOP_HAS_RSQRT
  // §1.2 seed ROM: one read per ray, 2^rsqrt_seed_bits small words.
  VOXCAST_HLS_PRAGMA(HLS BIND_STORAGE variable = state.rsqrt.seed type = ram_1p impl = lutram)
#endif
#if VOXCAST_TOP_HAS_CLASSIFICATION
  // §4: one entry per sample, packed into one word (the paper's two 32-bit
  // SRAMs read in parallel), one single-port block RAM.
  VOXCAST_HLS_PRAGMA(HLS AGGREGATE variable = state.class_table.entry compact = bit)
  VOXCAST_HLS_PRAGMA(HLS BIND_STORAGE variable = state.class_table.entry type = ram_1p impl = bram)
#endif
#if VOXCAST_TOP_HAS_REFLECTANCE_MAP
  // §5: diffuse and specular, two memories read in the same clock; bilinear
  // mode reads four entries of each (kReflectanceBanks, vizard2_synth_config.hpp).
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.reflectance.diffuse type = cyclic factor = kReflectanceBanks)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.reflectance.specular type = cyclic factor = kReflectanceBanks)
  VOXCAST_HLS_PRAGMA(HLS BIND_STORAGE variable = state.reflectance.diffuse type = ram_2p impl = bram)
  VOXCAST_HLS_PRAGMA(HLS BIND_STORAGE variable = state.reflectance.specular type = ram_2p impl = bram)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = state.reflectance_regs.IS type = complete)
#endif
#if VOXCAST_TOP_HAS_SPACE_LEAPING
  // docs/leaping.md: one min-max block read and two prefix-table reads (the
  // block's lowest and highest classification address) per sample.
  VOXCAST_HLS_PRAGMA(HLS BIND_STORAGE variable = state.minmax.block type = ram_1p impl = bram)
  VOXCAST_HLS_PRAGMA(HLS BIND_STORAGE variable = state.leap.prefix type = ram_2p impl = bram)
#endif
#if VOXCAST_TOP_HAS_PARTIAL_SEGMENTS
  // docs/pipeline.md §7a: the optical depth at the classification address
  // (beside the class table's read) and two adjacent ROM entries per weighted
  // sample: a single-port block RAM and a dual-port LUT ROM.
  VOXCAST_HLS_PRAGMA(HLS BIND_STORAGE variable = state.segments.tau type = ram_1p impl = bram)
  VOXCAST_HLS_PRAGMA(HLS BIND_STORAGE variable = state.segments.rom type = ram_2p impl = lutram)
#endif
#if VOXCAST_TOP_HAS_PREINTEGRATION
  // docs/pipeline.md §4a: one (front, back) entry per sample, packed into one
  // word as the classification table's; 2^(2 preint_addr_bits) words, a
  // cascade of block RAMs on every part `voxcast report` prices (impl = uram
  // on an UltraScale+ part: 16 blocks at 8 bits per end).
  VOXCAST_HLS_PRAGMA(HLS AGGREGATE variable = state.preint.entry compact = bit)
  VOXCAST_HLS_PRAGMA(HLS BIND_STORAGE variable = state.preint.entry type = ram_1p impl = bram)
#endif
  (void)kReflectanceBanks;

  voxcast::hls::load_frame_state<TopProfile, TopUnits>(*frame, state);
  std::uint64_t count = 0;
  voxcast::hls::render_frame_streamed<TopProfile, TopUnits>(state, bank0, bank1, bank2, bank3,
                                                            bank4, bank5, bank6, bank7, width,
                                                            height, fb, count);
  *samples = count;
}
