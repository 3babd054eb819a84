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
// same statistics (ControllerStats, DimmStats) except the tick counter. What
// makes it fast, as FastInOrderPort (fast_in_order_port.hpp), whose layout
// it follows:
//   - Timing from the same ConstraintTable, compiled (sdram/not_before.hpp):
//     a command's earliest cycle is one look-up; the scheduler's legality test
//     is that look-up, where the reference asks the Dimm referee for the full
//     legality check of every command it issues.
//   - Ticks only at cycles where something can happen (next_wake(): the
//     scheduler's wake as LookAheadActivation::wake computes it, an access's
//     last data beat, a REF due, a pushed request, a freed return slot).
//   - Column commands go in arrival order (the policy's contract), so one ring
//     holds every request from push to retire, as in FastInOrderPort: the
//     accesses in flight, then the pending requests. Row commands of later
//     requests fill in their outcome and first command in place.
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

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "rtl_model/pipeline/memory_port.hpp"
#include "rtl_model/sdram/not_before.hpp"
#include "rtl_model/sdram/timing.hpp"

namespace voxcast::rtl::pipeline {

class FastLookAheadPort final : public MemoryPort {
 public:
  // The most banks the port's masks hold; make_memory_port uses the
  // reference for a DIMM with more.
  static constexpr std::uint32_t kMaxBanks = 64;

  // `reorder_window` as SchedulerParams::reorder_window (at least 1). Throws
  // voxcast::Error for the configurations the Dimm and the Controller reject
  // and for more than kMaxBanks banks.
  FastLookAheadPort(const sdram::DimmConfig& dimm, const sdram::ControllerConfig& controller,
                    int reorder_window);

  bool ready() const override { return pending_count_ < queue_depth_; }
  void push(const sdram::Request& r) override {
    if (!ready()) [[unlikely]]
      fail("request queue is full", r.arrival);
    if (r.address.bank >= geometry_.banks || r.address.row >= geometry_.rows ||
        r.address.column >= geometry_.columns) [[unlikely]]
      fail("request outside the DIMM", r.arrival);
    if (r.kind != sdram::RequestKind::kRead) [[unlikely]]
      fail("a write request (this port serves reads; use the reference controller)", r.arrival);
    const std::size_t at = wrap(pending_head_ + pending_count_);
    accesses_[at].request = r;
    started_[at] = false;
    row_key_[at] = key(r.address.bank, r.address.row);
    ++pending_per_bank_[r.address.bank];
    ahead_known_ = false;
    ++cs_.requests;
    ++pending_count_;
    // A new oldest request, or a new candidate of the look-ahead window.
    wake_ = std::min(wake_, r.arrival);
  }
  void tick(sim::Cycle now) override {
    if (now >= wake_) step(now);
  }
  sim::Fifo<sdram::Completion>& completions() override { return completions_; }
  const sim::Fifo<sdram::Completion>& completions() const override { return completions_; }
  void popped(sim::Cycle now) override {
    if (flight_count_ + completions_.size() + 1 >= completions_.depth())
      wake_ = std::min(wake_, now + 1);
  }
  void set_observer(sdram::CommandObserver* o) override { observer_ = o; }

  std::size_t pending() const override { return pending_count_; }
  std::size_t in_flight() const override { return flight_count_; }
  bool idle() const override {
    return pending_count_ == 0 && flight_count_ == 0 && completions_.empty();
  }
  void expect_drained() const override;
  const sdram::ControllerStats& controller_stats() const override { return cs_; }
  const sdram::DimmStats& dimm_stats() const override { return ds_; }

 private:
  // i mod accesses_.size() for i < 2 * accesses_.size(), without a division.
  std::size_t wrap(std::size_t i) const { return i >= ring_size_ ? i - ring_size_ : i; }
  // The pending request `j` places behind the oldest (j < pending_count_).
  std::size_t pending_at(std::size_t j) const { return wrap(pending_head_ + j); }

  // A bank and row as one word, for the look-ahead walk's comparisons.
  static std::uint64_t key(std::uint32_t bank, std::uint32_t row) {
    return std::uint64_t{bank} << 32 | row;
  }
  static constexpr std::uint64_t kClosed = std::numeric_limits<std::uint64_t>::max();

  // The command request `a` needs next: ACT (its bank idle), its READ (its
  // row open) or PRE (another row open): Dimm::next_command.
  sdram::Command next_command(const sdram::Address& a) const {
    const std::uint64_t open = open_key_[a.bank];
    if (open == kClosed) return sdram::Command::kAct;
    return open == key(a.bank, a.row) ? sdram::Command::kRd : sdram::Command::kPre;
  }
  bool all_closed() const;
  sim::Cycle earliest(sdram::Command cmd, std::uint32_t bank) const {
    return not_before_.at(cmd, bank);
  }
  bool column_allowed() const { return flight_count_ + completions_.size() < completions_.depth(); }

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
  // The request's first command tells how its row met its bank.
  void start(std::size_t at, sdram::Command cmd, sim::Cycle now);
  bool row_wanted_by_another() const;
  void close(std::uint32_t bank, sim::Cycle closed_at);
  void issued(sdram::Command cmd, const sdram::Address& a, sim::Cycle now);
  void retire(sim::Cycle now);
  sim::Cycle next_wake(sim::Cycle now);
  void step_refresh(sim::Cycle now);
  void issue_rank_command(sdram::Command cmd, sim::Cycle now);
  [[noreturn, gnu::cold, gnu::noinline]] void fail(const char* what, sim::Cycle now) const;

  static constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

  sdram::TimingCycles t_;
  sdram::Geometry geometry_;
  sdram::NotBefore not_before_;
  // The banks' state, one word per bank: key(bank, its open row), or
  // kClosed (the form the look-ahead walk compares), and when its row opened.
  std::vector<std::uint64_t> open_key_;
  std::vector<sim::Cycle> activated_at_;
  // Per bank, the pending requests to it: when every one is to the oldest
  // request's bank (a row-hit stream), the look-ahead has nothing to walk.
  std::vector<std::uint32_t> pending_per_bank_;
  bool ahead_known_ = false;     // look_ahead()'s answer, while nothing changed
  std::size_t ahead_ = kNone;
  sdram::Command ahead_cmd_ = sdram::Command::kNop;
  std::size_t window_ = 1;
  bool auto_precharge_ = false;
  std::int64_t refreshes_ = 0;
  int postpone_limit_ = 0;
  // The first cycle the refresh sequence acts at: refresh_due_, or kNever
  // while the sequence runs (it acts, and counts its cycles, every tick).
  sim::Cycle refresh_at_ = 0;
  sim::Cycle refresh_due_ = 0;
  sim::Cycle overdue_at_ = 0;
  sim::Cycle last_command_ = -1;
  std::uint64_t burst_bytes_ = 0;
  sim::Cycle burst_ = 0;       // data-bus clocks of one access
  sim::Cycle data_first_ = 0;  // CL
  sim::Cycle read_to_precharge_ = 0;

  // Every request from push to retire, oldest first: flight_count_ accesses
  // from flight_head_, then pending_count_ requests from pending_head_.
  // started_[i]: accesses_[i] had its first command (outcome set).
  std::vector<sdram::Completion> accesses_;
  std::vector<std::uint8_t> started_;
  // key() of each request's address, a compact copy the look-ahead walks
  // (a Completion is 72 bytes: one host cache line per request otherwise).
  std::vector<std::uint64_t> row_key_;
  std::size_t ring_size_ = 0;
  std::size_t queue_depth_ = 0;
  std::size_t flight_head_ = 0, flight_count_ = 0;
  std::size_t pending_head_ = 0, pending_count_ = 0;
  sim::Fifo<sdram::Completion> completions_;
  sdram::ControllerStats cs_;
  sdram::DimmStats ds_;
  sdram::CommandObserver* observer_ = nullptr;
};

}  // namespace voxcast::rtl::pipeline
