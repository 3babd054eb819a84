// Parameters of the ray-casting pipeline model (rtl_model/pipeline/ray_pipeline.hpp).
//
// Latencies: each unit's pipeline depth is declared once, next to its kernel in
// hls/ (hls::interpolation_depth and so on; hls/geometry_processor.hpp,
// "Pipeline depths", says what they are), and UnitLatencies' defaults are those
// constants; the kernels' HLS LATENCY pragmas and the resource report read the
// same ones (tests/report/test_unit_depths.cpp). They are the model's
// assumptions for an FPGA implementation at the 100 MHz core clock; every unit
// is pipelined at one sample (or ray) per clock, as hls::march_ray's PIPELINE
// II=1 states. They move the fill and drain of the pipeline, not its
// throughput, which the memory sets.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "hls/classification_table.hpp"
#include "hls/geometry_processor.hpp"
#include "hls/interpolation_processor.hpp"
#include "hls/preintegration_table.hpp"
#include "hls/reflectance_map.hpp"
#include "hls/segment_opacity.hpp"
#include "hls/shader.hpp"
#include "hls/space_leaping_unit.hpp"
#include "rtl_model/pipeline/memory_port.hpp"
#include "rtl_model/sdram/controller.hpp"
#include "rtl_model/sdram/dimm.hpp"

namespace voxcast::rtl::pipeline {

enum class Traversal : std::uint8_t {
  kScanline,  // rows of the image, left to right (the baseline)
  kTiles,     // tiles of tile x tile pixels, tiles and pixels inside in scan-line order
};

const char* to_string(Traversal t);
// "scanline" | "tiles"; throws voxcast::Error otherwise.
Traversal parse_traversal(const std::string& name);

// How the address generator picks the ray whose next sample it issues
// (ray_pipeline.hpp, docs/performance.md §7).
enum class IssuePolicy : std::uint8_t {
  // The oldest ready ray, issue_burst samples at a time (VIZARD II: a ray to
  // its end).
  kOldest,
  // Ray-level FR-FCFS: the oldest ready ray whose next sample's four DIMM
  // words lie in the rows last requested in their banks (most DIMMs hit
  // first), else the oldest ready ray. The oldest ready ray is bypassed at
  // most issue_bypass_limit times in a row. In hardware: each ray slot holds
  // its next sample's (bank, row) per DIMM, computed by the address generator
  // one sample ahead, compared against 4 x 4 last-row registers.
  kRowHit,
};

const char* to_string(IssuePolicy p);
// {"oldest", "row-hit"}: the names parse_issue_policy accepts.
std::vector<std::string> issue_policy_names();
// One of issue_policy_names(); throws voxcast::Error otherwise.
IssuePolicy parse_issue_policy(const std::string& name);

// The order in which the ray setup unit takes the pixels: (x, y) pairs.
std::vector<std::pair<int, int>> pixel_order(int width, int height, Traversal t, int tile);

struct UnitLatencies {
  // Ray setup of a perspective camera: direction, rsqrt (two Newton steps),
  // step vector, six clip divisions (docs/pipeline.md §1), pipelined; a new ray
  // every `ray_setup_interval`.
  int ray_setup = hls::perspective_ray_setup_depth;
  int ray_setup_interval = 1;
  // Stepping + address generator (§2-3.3); the mapping to (bank, row, column)
  // takes no clock of its own.
  int address = hls::stepping_depth + hls::address_generator_depth;
  // Crossbar + three lerp levels, the last with its rounding (§3.4-3.5).
  int interpolation = hls::interpolation_depth;
  // Classification address and SRAM read (§4).
  int classification = hls::classification_depth;
  // Reflectance map (cell, table reads) and shader (§5-6).
  int shading = hls::reflectance_map_depth + hls::shader_depth;
  // Space leaping (docs/leaping.md), only in a design built with it. Each
  // sample's block look-up (min-max RAM read, two prefix-table reads and their
  // comparison) runs beside the address generator: `leap_lookup` more clocks
  // to the requests. A leap over an empty block holds its ray's issue for
  // `leap` clocks: the look-up, then the binary search of hls::leap_run
  // (hls::leap_search_depth; every leap costs the same).
  int leap_lookup = hls::leap_lookup_depth;
  int leap = hls::leap_depth;
  // The compositor's accumulation is a one-clock recurrence (§7,
  // hls::compositor_depth): one sample per clock of the same ray.
};

std::ostream& operator<<(std::ostream& os, const UnitLatencies& l);

// The latencies of the units a frame's design contains (elaboration,
// refmodel/scene/elaboration.hpp, docs/resources.md): a unit that is left out
// adds no pipeline stages. MIP has no classification or shading stages; an
// unshaded frame has no reflectance map, so its shading stage is the one
// clock of U(colour); a parallel camera has no rsqrt unit in its ray set-up.
// Only the fill and drain move; the image is the same bits.
struct ElaboratedUnits {
  bool mip = false;
  bool shaded = true;
  bool perspective = true;
  bool leaping = false;
  // render.partial_segments (docs/pipeline.md §7a): the segment-opacity unit
  // runs beside the reflectance map and the shader; the stage takes the longer
  // of the two (an unshaded frame's single clock grows to the unit's depth).
  bool partial_segments = false;
  // render.classification = "preintegrated" (docs/pipeline.md §4a): the 2-D
  // table replaces the classification table's read; the stage takes its depth
  // (one clock more: the cascaded RAM's output register).
  bool preintegration = false;
};
// Stages of the rsqrt unit inside UnitLatencies::ray_setup (docs/pipeline.md
// §1.2; hls/geometry_processor.hpp lists them).
inline constexpr int kRsqrtStages = hls::rsqrt_depth;
// The unshaded shader: U(colour, shade_bits), one rounding adder (hls/shader.hpp).
inline constexpr int kUnshadedShadeStages = hls::shader_depth;
UnitLatencies elaborate_latencies(UnitLatencies base, const ElaboratedUnits& units);

struct PipelineConfig {
  int ray_slots = 16;       // rays in flight (set up, issuing or draining)
  Traversal traversal = Traversal::kScanline;
  int tile = 8;             // kTiles: tile edge in pixels
  // Samples the address generator issues from one ray before it turns to the
  // next ray with samples left; 0: a ray is issued to its end (or its early
  // termination) before the next one starts.
  int issue_burst = 0;
  IssuePolicy issue = IssuePolicy::kOldest;
  int issue_bypass_limit = 64;  // kRowHit: issues that may bypass the oldest ready ray
  int sample_buffer = 64;   // samples in flight between address generator and interpolation
  int fifo_depth = 4;       // skid entries between stages (added to each stage's latency)
  int output_depth = 16;    // finished pixels waiting for the frame buffer
  // No FIFO moved and no command issued for this many cycles: deadlock.
  std::int64_t deadlock_cycles = 100'000;
  // Simulation speed only, never the result (the tests check equal cycles,
  // commands and image with both off): skip the cycles in which nothing can
  // move (RayPipeline::run, pipeline/reference_port.hpp), and run in-order +
  // eager memory on the event-driven port (pipeline/fast_in_order_port.hpp).
  bool fast_forward = true;
  MemoryModel memory_model = MemoryModel::kAuto;
  UnitLatencies latency;
  sdram::DimmConfig dimm;                // each of the four DIMMs
  sdram::ControllerConfig controller;    // each DIMM's controller
  sdram::SchedulerParams scheduler_params;  // reorder window, starvation limit
};

std::ostream& operator<<(std::ostream& os, const PipelineConfig& c);

}  // namespace voxcast::rtl::pipeline
