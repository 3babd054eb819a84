// The cycle model of the VIRIM card (docs/virim-rtl.md): every hardware number
// in one plain struct. Numbers the paper gives cite virim-1994.txt; the others
// are assumptions, named as such, and are parameters so they can be varied.
#pragma once

#include <cstdint>
#include <iosfwd>

#include "refmodel/scene/scene.hpp"

namespace voxcast::rtl::virim {

struct VirimRtlConfig {
  // "One rotator and 16 DSPs constitute one module"; "Four modules are required
  // for real-time visualization of volume data of 256x256x128 voxels"
  // (section "System Architecture").
  int modules = 4;
  int dsps_per_module = 16;
  // Clocks. DSP: "Running at a speed of 40 MHz" (section "DSP Board").
  // Rotator (and its memory): 40 MHz is our reading of "At peak speed, 160
  // million voxels/s can be rotated" for four modules at one voxel per clock.
  // Bus: "48 bit wide ... peak transfer rate of 240 MB/s" = 40 M words/s.
  double rotator_mhz = 40.0;
  double dsp_mhz = 40.0;
  double bus_mhz = 40.0;
  // Assumption: a RAM bank is busy for 2 rotator clocks per read, so only the
  // ping-pong pair of a unit sustains one read per clock ("To allow fast r/w
  // accesses, each unit is subdivided into two banks", footnote 4).
  int bank_cycle_clocks = 2;
  bool ping_pong = true;        // footnote 4: the two banks read alternately
  bool suppress_repeats = true; // footnote 4: "Accesses on the same address are suppressed"
  // Footnote 4: "addresses that lie out of the data cube range ... produce a 0"
  // without a RAM cycle; off, such a read costs a bank cycle like any other
  // (its data is still forced to 0), for measuring what the feature buys.
  bool zero_out_of_range = true;
  // Assumption: the DSP's cost per voxel. The paper: one 256-pixel line in 50 ms
  // at 40 MHz = 2,000,000 cycles for 256 x 256 voxels = 30.5 cycles per voxel;
  // 30 keeps the line within the 50 ms (49.2 ms).
  int dsp_cycles_per_voxel = 30;
  // Assumption: the DSP's input FIFO ("temporarily stored in a FIFO") holds
  // 4096 bus words (4K-deep FIFO chips were the common size).
  int dsp_fifo_words = 4096;
  // Assumption: the gradient processor's output buffer towards the bus, in
  // words; it must hold the two rows a line's last row releases (checked).
  int bus_fifo_words = 1024;
  // Assumption: pipeline latencies after the RAM read (rotator clocks).
  int interpolation_latency = 3;  // LUT, 8 products, adder tree
  int gradient_latency = 2;       // Sobel sums, bus word register
};

// Throws voxcast::Error naming the first out-of-range parameter.
void validate(const VirimRtlConfig& c);
// The scene's [heidelberg] modules and clocks over the paper's defaults.
VirimRtlConfig virim_rtl_config(const ref::HeidelbergDesc& h);
std::ostream& operator<<(std::ostream& os, const VirimRtlConfig& c);

}  // namespace voxcast::rtl::virim
