// The top function a vendor HLS tool synthesizes: vizard2_frame_top, at global
// scope (Vitis HLS takes a plain name for set_top), for one precision profile
// and one set of units, both fixed at compile time. Layer 2 of the
// Vitis-Libraries split: the interface pragmas are here, in the top itself
// (a vendor tool reads INTERFACE pragmas only in the top function).
//
// `voxcast synth-script SCENE` writes the scene's elaborated_config.hpp
// (ref::elaborate: which units the scene needs; cosim/synth_script.hpp) and
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
#include "hls/vizard2_synth_config.hpp"
#include "hls/vizard2_top.hpp"

using voxcast::hls::top::Frame;
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
  const voxcast::hls::PackedBanks<TopProfile> banks{
      {bank0, bank1, bank2, bank3, bank4, bank5, bank6, bank7}};
  voxcast::hls::render_rows<TopProfile, TopUnits>(*frame, banks, width, 0, height, fb, samples);
}
