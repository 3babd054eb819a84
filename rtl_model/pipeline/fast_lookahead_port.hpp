// FastLookAheadPort: the reference Controller with the look-ahead activation
// scheduler and eager refresh (sdram/controller.hpp, sched/lookahead.hpp,
// sched/refresh_eager.hpp), open page or with auto precharge, event-driven,
// for whole-frame simulations: the row-hit goal configuration's memory
// (docs/performance.md §7, §12).
//
// Same decisions, same cycles: per tick the same three steps as
// Controller::tick (the refresh sequence; else the look-ahead choice: the
// oldest request's row command if legal, else the row command of the oldest
// request among the next reorder_window - 1 that is the first pending to its
// bank, if legal, else the oldest request's column command if legal; then
// retire), the same READ-or-RDA choice (RDA when auto precharge is on, no
// other pending request wants the row and the table allows RDA now), and the
// same statistics (ControllerStats, DimmStats) except the tick counter. The
// queue, the banks, the refresh sequence and the statistics are
// EventDrivenPort's (event_driven_port.hpp), as for FastInOrderPort; what this
// port adds is the look-ahead choice and its wake:
//   - The scheduler's legality test is the compiled table's look-up, where the
//     reference asks the Dimm referee for the full check of every command.
//   - Ticks only at cycles where something can happen (next_wake(): the
//     scheduler's wake as LookAheadActivation::wake computes it, an access's
//     last data beat, a REF due, a pushed request, a freed return slot).
//   - Column commands go in arrival order (the policy's contract), so the
//     shared ring serves it; row commands of later requests fill in their
//     outcome and first command in place.
//   - "First pending request to its bank" is a bit mask of the banks of the
//     requests before it, built as the window is walked (the reference scans
//     the older requests for each one).
// The rules the Dimm enforces and this port cannot break by construction (one
// command per tick, the bank state of the scheduler's own next command) are
// checked as the in-order port checks them; refresh overdue is an error.
// tRAS(max) cannot be exceeded: the eager refresh closes every row each tREFI,
// and the Dimm's constructor (which validates the configuration here too)
// rejects a postponement limit that would let a row stay open longer.
// tests/rtl/test_rtl_memory_port.cpp compares it with the reference command
// by command.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "rtl_model/pipeline/event_driven_port.hpp"

namespace voxcast::rtl::pipeline {

class FastLookAheadPort final : public EventDrivenPort {
 public:
  // The most banks the port's masks hold; make_memory_port uses the
  // reference for a DIMM with more.
  static constexpr std::uint32_t kMaxBanks = 64;

  // `reorder_window` as SchedulerParams::reorder_window (at least 1). Throws
  // voxcast::Error for the configurations the Dimm and the Controller reject
  // and for more than kMaxBanks banks.
  FastLookAheadPort(const sdram::DimmConfig& dimm, const sdram::ControllerConfig& controller,
                    int reorder_window);

  void push(const sdram::Request& r) override {
    const std::size_t at = enqueue(r);
    started_[at] = false;
    row_key_[at] = key(r.address.bank, r.address.row);
    ++pending_per_bank_[r.address.bank];
    ahead_known_ = false;
    ++pending_count_;
    // A new oldest request, or a new candidate of the look-ahead window.
    wake_ = std::min(wake_, r.arrival);
  }
  void tick(sim::Cycle now) override {
    if (now >= wake_) step(now);
  }

 private:
  // One tick at `now` (>= wake_).
  void step(sim::Cycle now);
  // LookAheadActivation::pick and Controller::schedule in one.
  void schedule(sim::Cycle now);
  // The later request the policy would prepare (its place in the ring), or
  // kNone: the oldest among the next window - 1 that is the first pending
  // to its bank and needs a row command; ahead_cmd_ is that command. Kept
  // until a push or a command changes the queue or the banks (schedule()
  // and next_wake() ask it in the same tick).
  std::size_t look_ahead();
  std::size_t walk_window(sdram::Command& cmd) const;
  void row_command(std::size_t at, sdram::Command cmd, sim::Cycle now);
  void column_command(sim::Cycle now);
  // The request at `at` had its first command unless started_ says so (first_command()).
  void start(std::size_t at, sdram::Command cmd, sim::Cycle now);
  bool row_wanted_by_another() const;
  sim::Cycle next_wake(sim::Cycle now);

  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

  // Per bank, the pending requests to it: when every one is to the oldest
  // request's bank (a row-hit stream), the look-ahead has nothing to walk.
  std::vector<std::uint32_t> pending_per_bank_;
  bool ahead_known_ = false;     // look_ahead()'s answer, while nothing changed
  std::size_t ahead_ = kNone;
  sdram::Command ahead_cmd_ = sdram::Command::kNop;
  std::size_t window_ = 1;
  bool auto_precharge_ = false;
  sim::Cycle read_to_precharge_ = 0;

  // Per ring place: started_[i], accesses_[i] had its first command (outcome
  // set); row_key_[i], key() of its address, a compact copy the look-ahead
  // walks (a Completion is 72 bytes: one host cache line per request
  // otherwise).
  std::vector<std::uint8_t> started_;
  std::vector<std::uint64_t> row_key_;
};

}  // namespace voxcast::rtl::pipeline
