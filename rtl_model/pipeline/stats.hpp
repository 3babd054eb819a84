// Statistics of one frame of the pipeline model, as member counters.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "rtl_model/sdram/controller.hpp"
#include "rtl_model/sdram/dimm.hpp"
#include "rtl_model/sim/fifo.hpp"

namespace voxcast::rtl::pipeline {

using sim::Cycle;

// Cycles in which a unit could not do its work, by cause.
struct StallStats {
  // Address generator (one sample per clock at most):
  Cycle issue_no_ray = 0;      // no ray with samples left is set up (frame start/end, setup)
  Cycle issue_buffer_full = 0; // every sample-buffer entry is in flight
  Cycle issue_memory_full = 0; // a DIMM's request queue is full (memory back-pressure)
  Cycle issue_idle = 0;        // every pixel's samples are issued
  // Interpolation (the sample buffer's head):
  Cycle interp_wait_memory = 0;  // the head sample still waits for a DIMM word
  Cycle interp_blocked = 0;      // the next stage's FIFO is full
  // Ray setup:
  Cycle setup_no_slot = 0;  // every ray slot is busy
  // Compositor:
  Cycle composite_blocked = 0;  // the output FIFO is full
};

std::ostream& operator<<(std::ostream& os, const StallStats& s);

struct DimmReport {
  sdram::ControllerStats controller;
  sdram::DimmStats dimm;
};

struct NamedFifoStats {
  std::string name;
  std::size_t depth = 0;
  sim::FifoStats stats;
};

struct RtlStats {
  double clock_mhz = 0.0;  // core = SDRAM clock
  Cycle cycles = 0;        // the frame, first ray setup to the last pixel written
  std::uint64_t rays = 0;
  std::uint64_t rays_hit = 0;       // rays that entered the volume (ray set-up's hit flag)
  std::uint64_t rays_ert = 0;       // rays ERT ended before their last sample
                                    // (ref::FrameStats::rays_terminated_early)
  std::uint64_t samples = 0;        // samples composited (the hls engine's count)
  std::uint64_t samples_issued = 0; // samples read from memory
  std::uint64_t samples_discarded = 0;  // issued beyond an early termination
  std::uint64_t samples_skipped = 0;    // space leaping: never issued (docs/leaping.md)
  std::uint64_t samples_skipped_discarded = 0;  // of those, leapt beyond an early termination
  std::uint64_t leaps = 0;              // space leaping: empty blocks leapt over
  std::uint64_t issue_bypasses = 0;     // row-hit issue: samples issued ahead of the oldest ready ray
  std::uint64_t issue_longest_bypass = 0;  // row-hit issue: most bypasses of one oldest ray in a row
  std::array<DimmReport, 4> dimms{};
  StallStats stalls;
  std::vector<NamedFifoStats> fifos;
  // The simulation, not the card: cycles evaluated one by one (the rest were
  // fast-forwarded, PipelineConfig::fast_forward).
  Cycle evaluated_cycles = 0;

  double period_ns() const { return 1000.0 / clock_mhz; }
  double seconds() const { return static_cast<double>(cycles) * period_ns() * 1e-9; }
  double fps() const { return cycles == 0 ? 0.0 : 1.0 / seconds(); }
  // The paper's figure of merit: frame time per composited sample.
  double ns_per_sample() const;
  double ns_per_issued_sample() const;
  double samples_per_cycle() const;
  // Over all four DIMMs.
  std::uint64_t row_hits() const;
  std::uint64_t row_misses() const;
  std::uint64_t row_conflicts() const;
  double row_hit_rate() const;
  std::uint64_t activates() const;
  std::uint64_t refreshes() const;
  std::uint64_t bytes_read() const;
  // Peak: 8 bytes per clock per DIMM.
  double peak_bytes() const;
  double bandwidth_utilisation() const;
  double bandwidth_mb_s() const;
};

std::ostream& operator<<(std::ostream& os, const RtlStats& s);

}  // namespace voxcast::rtl::pipeline
