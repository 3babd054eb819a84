// What one frame on the VIRIM cycle model cost (docs/virim-rtl.md §3).
#pragma once

#include <cstdint>
#include <iosfwd>

namespace voxcast::rtl::virim {

struct VirimStalls {
  std::uint64_t rotator_bank_busy = 0;  // rotator clocks waiting for a RAM bank
  std::uint64_t rotator_bus_full = 0;   // rotator clocks waiting for room in the bus buffer
  std::uint64_t bus_dsp_fifo_full = 0;  // bus clocks waiting for room in the selected DSP's FIFO
  std::uint64_t dsp_starved = 0;        // DSP clocks idle with a line unfinished and an empty FIFO
};

struct VirimRtlStats {
  int modules = 0, dsps = 0;
  double rotator_mhz = 0.0, dsp_mhz = 0.0;
  std::uint64_t voxels = 0;             // output voxels rotated (W x D x H)
  std::uint64_t cycles = 0;             // frame, in rotator clocks (until the last DSP finishes)
  double frame_ns = 0.0;
  std::uint64_t rotating_cycles = 0;    // summed over modules: voxels issued + bank stalls
  // Parity memory: 8 unit reads per output voxel.
  std::uint64_t unit_reads = 0, ram_reads = 0, suppressed = 0, out_of_range = 0;
  std::uint64_t bank_reads[2] = {0, 0};
  std::uint64_t access_cycles = 0;      // summed request-to-data time of the unit reads
  std::uint64_t bus_words = 0;
  std::uint64_t dsp_busy_cycles = 0;    // summed over DSPs
  VirimStalls stalls;

  double frame_seconds() const { return frame_ns * 1e-9; }
  double fps() const { return frame_ns > 0 ? 1e9 / frame_ns : 0.0; }
  double ns_per_voxel() const { return voxels ? frame_ns / static_cast<double>(voxels) : 0.0; }
  // Output voxels per second over the frame.
  double voxels_per_second() const { return frame_ns > 0 ? static_cast<double>(voxels) / frame_seconds() : 0.0; }
  // Voxels per second while the rotators rotate (bus stalls excluded), all modules.
  double rotation_rate() const;
  // The peak: every module's rotator one voxel per clock.
  double peak_rotation_rate() const { return modules * rotator_mhz * 1e6; }
  // Mean request-to-data time of a unit read: a suppressed or out-of-range
  // read costs 0 (data held on the line / constant 0), a RAM read its wait
  // for the bank plus the bank cycle.
  double mean_access_ns() const;
  double dsp_utilisation() const;  // busy cycles / (DSPs x frame DSP cycles)
};

std::ostream& operator<<(std::ostream& os, const VirimRtlStats& s);

}  // namespace voxcast::rtl::virim
