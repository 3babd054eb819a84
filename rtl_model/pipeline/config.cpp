#include "rtl_model/pipeline/config.hpp"

#include <algorithm>
#include <ostream>

#include "refmodel/error.hpp"
#include "rtl_model/pipeline/burst_config.hpp"

namespace voxcast::rtl::pipeline {

const char* to_string(Traversal t) { return t == Traversal::kScanline ? "scanline" : "tiles"; }

Traversal parse_traversal(const std::string& name) {
  if (name == "scanline") return Traversal::kScanline;
  if (name == "tiles") return Traversal::kTiles;
  throw Error("unknown ray traversal '" + name + "' (known: scanline, tiles)");
}

const char* to_string(IssuePolicy p) { return p == IssuePolicy::kOldest ? "oldest" : "row-hit"; }

std::vector<std::string> issue_policy_names() {
  return {to_string(IssuePolicy::kOldest), to_string(IssuePolicy::kRowHit)};
}

IssuePolicy parse_issue_policy(const std::string& name) {
  for (IssuePolicy p : {IssuePolicy::kOldest, IssuePolicy::kRowHit})
    if (name == to_string(p)) return p;
  throw Error("unknown issue policy '" + name + "' (known: oldest, row-hit)");
}

std::vector<std::pair<int, int>> pixel_order(int width, int height, Traversal t, int tile) {
  std::vector<std::pair<int, int>> order;
  order.reserve(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  if (t == Traversal::kScanline) {
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) order.emplace_back(x, y);
    return order;
  }
  if (tile < 1) throw Error("ray traversal 'tiles': tile edge must be at least 1");
  for (int ty = 0; ty < height; ty += tile)
    for (int tx = 0; tx < width; tx += tile)
      for (int y = ty; y < std::min(ty + tile, height); ++y)
        for (int x = tx; x < std::min(tx + tile, width); ++x) order.emplace_back(x, y);
  return order;
}

std::ostream& operator<<(std::ostream& os, const UnitLatencies& l) {
  return os << "latencies: ray setup " << l.ray_setup << " (every " << l.ray_setup_interval
            << "), address " << l.address << ", interpolation " << l.interpolation
            << ", classification " << l.classification << ", shading " << l.shading
            << ", compositing 1";
}

UnitLatencies elaborate_latencies(UnitLatencies l, const ElaboratedUnits& units) {
  if (!units.perspective) l.ray_setup = std::max(1, l.ray_setup - kRsqrtStages);
  if (!units.leaping) l.leap_lookup = 0;
  if (units.mip) {
    l.classification = 0;
    l.shading = 0;
  } else if (!units.shaded) {
    l.shading = std::min(l.shading, kUnshadedShadeStages);
  }
  if (units.partial_segments && !units.mip)
    l.shading = std::max(l.shading, hls::segment_opacity_depth);
  if (units.preintegration && !units.mip)
    l.classification = std::max(l.classification, hls::preintegration_depth);
  return l;
}

std::ostream& operator<<(std::ostream& os, const PipelineConfig& c) {
  os << c.ray_slots << " ray slots, " << to_string(c.traversal);
  if (c.traversal == Traversal::kTiles) os << " " << c.tile;
  os << " traversal, issue " << to_string(c.issue);
  if (c.issue == IssuePolicy::kOldest)
    os << " (burst " << c.issue_burst << ")";
  else
    os << " (bypass limit " << c.issue_bypass_limit << ")";
  return os << ", sample buffer "
            << c.sample_buffer << ", FIFO skid " << c.fifo_depth << ", output " << c.output_depth
            << ", " << c.latency << "; controller queue " << c.controller.queue_depth
            << ", return " << c.controller.return_depth
            << (c.controller.auto_precharge ? ", auto precharge" : ", open page");
}

std::ostream& operator<<(std::ostream& os, const BurstCardConfig& c) {
  return os << "DDR4 card: " << c.pipelines << " pipeline(s) at a " << c.core_period_ps
            << " ps core clock, brick cache " << c.cache_lines << " lines per channel, " << c.mshrs
            << " miss registers, miss queue " << c.miss_queue << ", crossing FIFOs "
            << c.crossing_depth << " deep (" << c.sync_stages << " synchroniser stages)";
}

}  // namespace voxcast::rtl::pipeline
