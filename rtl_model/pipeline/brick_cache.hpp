// One channel's brick cache on the DDR4 card (docs/sdram.md §10): direct
// mapped, a line per 64-byte burst, the line chosen by the Fibonacci hash of
// the brick's index in its channel (layout::brick_cache_line, as the burst
// study counted). This is the tag store; the lines' voxels live beside it in
// the card (burst_card.hpp), whose datapath type they have.
//
// A line is empty, pending (its burst was requested and has not returned:
// the tag is set at the miss, so a second sample wanting the same burst
// waits for the same request instead of fetching it again) or valid. A miss
// replaces the line whatever it holds: the samples that wait for a pending
// burst are registered with its miss register, not with the line, and are
// filled from the returning burst whether or not the line still holds it.
#pragma once

#include <bit>
#include <cstdint>
#include <string>
#include <vector>

#include "refmodel/error.hpp"
#include "rtl_model/layout/burst_layout.hpp"

namespace voxcast::rtl::pipeline {

struct BrickLine {
  std::uint64_t tag = 0;   // the brick's index + 1; 0: empty
  bool pending = false;    // requested, data not yet in
  std::uint32_t mshr = 0;  // pending: the miss register of the request
};

enum class CacheOutcome : std::uint8_t { kHit, kPendingHit, kMiss };

struct CacheStats {
  std::uint64_t hits = 0, pending_hits = 0, misses = 0;
  std::uint64_t lookups() const { return hits + pending_hits + misses; }
};

class BrickCache {
 public:
  // Throws voxcast::Error naming the value unless `lines` is a power of two.
  explicit BrickCache(std::uint32_t lines) {
    if (!std::has_single_bit(lines))
      throw Error("DDR4 card: the brick cache's lines per channel must be a power of two, not " +
                  std::to_string(lines));
    bits_ = std::countr_zero(lines);
    lines_.resize(lines);
  }

  std::uint32_t lines() const { return static_cast<std::uint32_t>(lines_.size()); }
  std::size_t line_of(std::uint64_t index) const { return layout::brick_cache_line(index, bits_); }
  BrickLine& line(std::size_t i) { return lines_[i]; }
  const BrickLine& line(std::size_t i) const { return lines_[i]; }

  // What a look-up of brick `index` finds (no state change).
  CacheOutcome probe(std::uint64_t index) const {
    const BrickLine& l = lines_[line_of(index)];
    if (l.tag != index + 1) return CacheOutcome::kMiss;
    return l.pending ? CacheOutcome::kPendingHit : CacheOutcome::kHit;
  }
  void count(CacheOutcome o) {
    (o == CacheOutcome::kHit          ? stats_.hits
     : o == CacheOutcome::kPendingHit ? stats_.pending_hits
                                      : stats_.misses)++;
  }
  const CacheStats& stats() const { return stats_; }

 private:
  int bits_ = 0;
  std::vector<BrickLine> lines_;
  CacheStats stats_;
};

}  // namespace voxcast::rtl::pipeline
