// `voxcast burst-study SCENE`: which layout of the volume in 64-byte DDR4
// bursts serves the design's samples best on a four-channel card (the U250,
// issue 23 part 2; rtl_model/layout/burst_layout.hpp, docs/sdram.md §9).
//
// The scene's first view is rendered by the hls kernels on the host (the bit-
// true banks: every sample the card interpolates, early ray termination
// included; with render.space_leaping the samples the leap passes over are not
// fetched), ray by ray in the card's traversal order (rtl.traversal), and each
// sample's cell (the interpolation unit's i0) is recorded. Every layout
// (brick shape x bank-group map) then counts the bursts that stream fetches
// under each reuse scheme, per channel, with bank-group changes, open-page
// row outcomes and the data bus's clocks.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "refmodel/scene/scene.hpp"
#include "rtl_model/layout/burst_layout.hpp"

namespace voxcast::cosim {

struct BurstStudyOptions {
  std::uint32_t cache_lines = 1024;  // per channel, the cache reuse scheme's lines
  std::string json;                  // also write the results here (empty: no)
  // The channel run (empty layout: none): the fetches of one layout under one
  // reuse scheme become four request traces, one per channel, each request
  // issued when its sample leaves N pipelines of one sample per core clock,
  // and run through the board's DDR4 channel model (rtl_model/trace/
  // request_trace.hpp: FR-FCFS, open page, refresh, the Dimm the referee).
  std::string channel_layout;  // a layout's name as the table prints it, "4x2x2-skewed-blocks"
  rtl::layout::Reuse channel_reuse = rtl::layout::Reuse::kCache;
  std::vector<int> pipelines{1, 2, 4, 8};
  double core_mhz = 300.0;  // the U250's kernel clock: the MIG's ui_clk, a quarter of 1200 MHz
  std::string board = "alveo_u250";
  std::size_t queue_depth = 32;  // the controller's request queue per channel
};

// One number of pipelines on the channel run. Open loop: a request enters its
// channel's controller when its sample is issued (or when the queue has room),
// so the channels' latency is assumed hidden by the ray slots; the frame
// ends when the slowest channel's last data is in, or when the pipelines have
// issued the last sample, whichever is later.
struct ChannelRunPoint {
  int pipelines = 0;
  double pipeline_us = 0;  // samples / (pipelines x core clock)
  double memory_us = 0;    // the slowest channel's last data
  double frame_us = 0;     // the later of the two
  double gsamples = 0;     // samples / frame time, 10^9 per second
  double ns_per_sample = 0;
  double bandwidth_gbs = 0;    // the four channels' bytes / frame time
  double row_hits = 0;         // fraction of the requests
  double latency_mean_ns = 0;  // the busiest channel's
  double latency_p99_ns = 0;
  std::uint64_t refreshes = 0;  // all channels
  std::string bound;            // "pipelines" or "memory"
};

struct ChannelRunResult {
  std::string layout, reuse, board, timing;
  double memory_mhz = 0, core_mhz = 0;
  std::size_t queue_depth = 0;
  std::uint64_t requests = 0;  // bursts fetched, all channels
  std::vector<ChannelRunPoint> points;
};

struct BurstReuseResult {
  double bursts_per_sample = 0;
  double busiest_channel_share = 0;  // the busiest channel's bursts / the mean channel's
  double same_group = 0;             // fraction of bursts in the bank group before them
  double row_hits = 0;               // fraction of bursts hitting the open row
  double bound_gsamples = 0;         // G samples/s the busiest channel's data bus allows
};

struct BurstLayoutResult {
  std::string name;  // "4x2x2-skewed"
  std::array<int, 3> brick{};
  std::array<int, 2> channel_axes{};
  std::vector<BurstReuseResult> reuse;  // by rtl::layout::kAllReuse
};

struct BurstStudyResult {
  std::string scene;
  std::array<int, 3> dims{};
  int voxel_bytes = 0;  // the profile's packed voxel word, rounded up to 4, 8 or 16 bytes
  int voxels_per_burst = 0;
  std::uint64_t rays = 0, samples = 0;
  std::uint32_t cache_lines = 0;
  rtl::layout::BurstMemory memory;
  std::vector<BurstLayoutResult> layouts;
  bool has_channel_run = false;
  ChannelRunResult channel_run;
};

// Throws voxcast::Error for a volume whose extents exceed 1024 (the recorded
// cell packs 10 bits per axis) or that does not fit a channel, and for the
// errors of the scene's set-up.
BurstStudyResult run_burst_study(const ref::Scene& scene, const BurstStudyOptions& options);

void print_burst_study(std::ostream& os, const BurstStudyResult& r);
void write_burst_study_json(const std::string& path, const BurstStudyResult& r);

}  // namespace voxcast::cosim
