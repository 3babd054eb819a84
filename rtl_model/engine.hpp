// The rtl engine: the cycle model of the VIZARD II card rendering one frame.
// Same inputs as the hls engine (the host's FrameSetup and VoxelMemory), the
// same image bit for bit, plus the card's timing (RtlStats).
//
// The runtime precision profile selects one of the compiled instantiations of
// the pipeline (the presets vizard2, balanced, precise), as cosim's hls engine
// does; any other profile is an error naming the compiled ones. The
// simulation of a frame is single-threaded and deterministic: the same cycles
// and bits on every run and host.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/precision/profile.hpp"
#include "refmodel/render/quant_image.hpp"
#include "refmodel/render/raycaster.hpp"
#include "rtl_model/layout/address_mapping.hpp"
#include "rtl_model/pipeline/burst_config.hpp"
#include "rtl_model/pipeline/config.hpp"
#include "rtl_model/pipeline/stats.hpp"
#include "rtl_model/trace/pipeline_trace.hpp"

namespace voxcast::rtl {

using pipeline::RtlStats;

struct RtlConfig {
  pipeline::PipelineConfig pipeline;  // ray slots, traversal, latencies, DIMM and controller
  layout::MappingSpec mapping;        // "linear" (the baseline), "bricked", "bricked-swizzled", "morton"
  std::string scheduler = "in-order"; // sched::make_scheduler
  std::string refresh = "eager";      // sched::make_refresh_policy
  // A DDR4 board (card.enabled): N pipelines on four DDR4 channels
  // (pipeline/burst_card.hpp); pipeline.dimm and pipeline.controller are then
  // each channel's, `mapping` is unused (the burst layout is fixed).
  pipeline::BurstCardConfig card;
};

std::ostream& operator<<(std::ostream& os, const RtlConfig& c);

// The VIZARD II baseline: in-order open-page controllers, eager refresh, scan-line
// traversal, the linear layout, PC100 CL2 at 100 MHz, BL 1 (the defaults), with
// the DIMMs' geometry, timing and clock read from the shipped board
// constraints/boards/vizard2_pci.toml (rtl_model/board/board_config.hpp).
RtlConfig vizard2_baseline();

struct RtlResult {
  ref::QuantImage image;
  RtlStats stats;
  std::uint64_t traced_commands = 0;  // SDRAM commands inside the VCD window (with a trace)
};

// One frame, on the SDR card or, with config.card.enabled, the DDR4 card.
// Throws voxcast::Error for a profile that is not compiled in, an
// unknown policy or mapping, a volume that does not fit the DIMMs, a deadlock
// or state left in the pipeline at the end.
// With `trace`, the frame's FIFO handshakes and SDRAM commands inside its
// window go to trace->out as a VCD (rtl_model/trace/pipeline_trace.hpp);
// the cycles and pixels are the same with and without. The DDR4 card has no
// trace (an error).
RtlResult rtl_render(const bittrue::FrameSetup& setup, const bittrue::VoxelMemory& memory,
                     const RtlConfig& config = {}, const trace::TraceOptions* trace = nullptr);

// The frame's counts as the other engines report them (ref::FrameStats):
// rays, rays_hit, rays_ert, the composited samples and the samples leapt over
// (both the hls engine's counts: what the issue stage issued or leapt over
// beyond an early termination, which depends on timing, is not in them).
ref::FrameStats frame_stats(const RtlStats& s);

bool rtl_supports(const PrecisionProfile& profile);
std::string rtl_supported_profiles();

}  // namespace voxcast::rtl
