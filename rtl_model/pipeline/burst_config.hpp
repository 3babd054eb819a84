// Parameters of the DDR4 card model (rtl_model/pipeline/burst_card.hpp,
// docs/sdram.md §10): N ray pipelines at the board's core clock sharing four
// DDR4 channels at the memory clock through per-channel brick caches and
// clocked asynchronous FIFOs. The ray slots, sample buffer, traversal and unit
// latencies of each pipeline are PipelineConfig's; the channel's device is
// PipelineConfig::dimm and its controller PipelineConfig::controller.
#pragma once

#include <cstdint>
#include <iosfwd>

namespace voxcast::rtl::pipeline {

struct BurstCardConfig {
  // False: the SDR card (RayPipeline), every other field unused.
  bool enabled = false;
  // Ray pipelines (rtl.pipelines); pixel i of the traversal goes to pipeline
  // i mod pipelines.
  int pipelines = 1;
  // The board's core clock, the pipelines' (3333 ps: 300 MHz on the U250).
  std::int64_t core_period_ps = 3333;
  // Lines of each channel's direct-mapped brick cache (a power of two); a line
  // holds one 64-byte burst. 16K lines (1 MB per channel, 4 MB on the card:
  // 8 % of the XCU250's 54 MB of BRAM + URAM) is the burst study's size
  // (docs/sdram.md §9).
  std::uint32_t cache_lines = 16384;
  // Per channel: bursts in flight (miss status holding registers), misses
  // waiting for the crossing, and the depth of each asynchronous FIFO.
  int mshrs = 64;
  int miss_queue = 16;
  int crossing_depth = 16;
  int sync_stages = 2;
};

std::ostream& operator<<(std::ostream& os, const BurstCardConfig& c);

}  // namespace voxcast::rtl::pipeline
