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

// The DDR4 card (burst_card.hpp); pipelines = 0 on the SDR card.
struct CardStats {
  int pipelines = 0;
  double memory_mhz = 0.0;
  Cycle memory_cycles = 0;  // memory clocks of the frame
  int burst_clocks = 4;     // data-bus clocks per burst (BL/2)
  int burst_bytes = 64;
  std::uint32_t cache_lines = 0;  // per channel
  // Brick cache look-ups (one per burst a sample needs): a hit, a burst
  // already requested by an earlier sample, or a miss (one request each).
  std::uint64_t cache_hits = 0, cache_pending_hits = 0, cache_misses = 0;
  std::array<std::uint64_t, 4> bursts{};      // requested per channel
  std::uint64_t busiest_pipeline_issues = 0;  // clocks the busiest issue stage issued or leapt

  double cache_hit_rate() const;  // hits / look-ups (pending hits are not hits)
  // The busiest channel's data-bus clocks over the frame's memory clocks.
  double channel_utilisation() const;
  // The busiest pipeline's issue clocks over the frame's core clocks.
  double pipeline_utilisation(Cycle core_cycles) const;
  // "pipelines" or "channels": the more utilised of the two, if it is at
  // least kSaturated busy; else "latency" (neither is: the samples wait for
  // their bursts longer than the ray slots and sample buffers cover).
  static constexpr double kSaturated = 0.9;
  const char* bound(Cycle core_cycles) const;
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
  CardStats card;
  // The memory's peak in bytes per core clock: four DIMMs of 8 bytes on the
  // SDR card; the DDR4 card sets its own.
  double bus_bytes_per_cycle = 32.0;
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
  double samples_per_second() const;
  // Over all four DIMMs.
  std::uint64_t row_hits() const;
  std::uint64_t row_misses() const;
  std::uint64_t row_conflicts() const;
  double row_hit_rate() const;
  std::uint64_t activates() const;
  std::uint64_t refreshes() const;
  std::uint64_t bytes_read() const;
  // Peak: bus_bytes_per_cycle per clock.
  double peak_bytes() const;
  double bandwidth_utilisation() const;
  double bandwidth_mb_s() const;
};

std::ostream& operator<<(std::ostream& os, const RtlStats& s);

}  // namespace voxcast::rtl::pipeline
