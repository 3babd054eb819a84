// FastInOrderPort: the reference Controller with the in-order open-page
// scheduler and eager refresh (sdram/controller.hpp, sched/in_order.hpp,
// sched/refresh_eager.hpp), event-driven, for whole-frame simulations.
//
// Same decisions, same cycles: per tick the same three steps (refresh
// sequence, else the oldest request's next command as soon as it is legal,
// then retire), and the same statistics (ControllerStats, DimmStats) except
// the tick counters. What makes it fast:
//   - Timing from the same ConstraintTable, compiled (sdram/not_before.hpp,
//     as the Dimm's): the earliest cycle of a command is one look-up.
//   - Ticks only at cycles where something can happen (wake()): a REF due,
//     an access's last data beat, the oldest request's next command legal,
//     a new oldest request, a freed return slot.
//   - A tick is cheap (it runs in most cycles of a frame, four ports per
//     cycle; the port was about 40% of a frame's instructions): the
//     pipeline inlines the per-request members defined here (it calls them
//     on this final class, not through MemoryPort) and calls step() once
//     per tick, with its helpers inlined into it. The oldest request's next
//     command and its earliest cycle are kept up to date by the commands
//     (after ACT its READ, after PRE its ACT, after READ the next request's),
//     each path with its command a constant, not derived again per tick.
//     The refresh sequence is one compare per tick (refresh_at_), and so is
//     an empty queue (head_at_).
//   - A request is written once: one ring holds it from push to retire
//     (pending, then in flight), its commands fill in its completion in
//     place, and retire copies it into the completions FIFO as one block.
//   - The refresh sequence, the rank commands and the errors are out of line.
// The bank states, the bus and the refresh deadline are kept as the Dimm
// keeps them; a violated invariant is an error, as the Dimm would throw.
// tests/rtl/test_rtl_memory_port.cpp compares it with the reference command
// by command.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "rtl_model/pipeline/memory_port.hpp"
#include "rtl_model/sdram/not_before.hpp"
#include "rtl_model/sdram/timing.hpp"

namespace voxcast::rtl::pipeline {

class FastInOrderPort final : public MemoryPort {
 public:
  // Throws voxcast::Error for the configurations the Dimm and the Controller reject.
  FastInOrderPort(const sdram::DimmConfig& dimm, const sdram::ControllerConfig& controller);

  bool ready() const override { return pending_count_ < queue_depth_; }
  void push(const sdram::Request& r) override {
    if (!ready()) [[unlikely]]
      fail("request queue is full", r.arrival);
    if (r.address.bank >= geometry_.banks || r.address.row >= geometry_.rows ||
        r.address.column >= geometry_.columns) [[unlikely]]
      fail("request outside the DIMM", r.arrival);
    // Only the request is written: the rest of the record is filled by the
    // request's commands.
    accesses_[wrap(pending_head_ + pending_count_)].request = r;
    ++cs_.requests;
    if (++pending_count_ == 1) new_oldest(r.arrival);
  }
  // Controller::tick: the refresh sequence, else the oldest request's next
  // command as soon as it is legal, then retire (step()). The pipeline asks
  // wake() itself; the check here is for callers that tick every cycle.
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
  struct Bank {
    bool open = false;
    std::uint32_t row = 0;
    sim::Cycle activated_at = 0;
  };

  // i mod accesses_.size() for i < 2 * accesses_.size(), without a division.
  std::size_t wrap(std::size_t i) const { return i >= ring_size_ ? i - ring_size_ : i; }

  // One tick at `now` (>= wake_), one call with its helpers inlined into
  // it (fast_in_order_port.cpp).
  void step(sim::Cycle now);
  // The oldest request's next command, at head_at_ (step() checked it).
  void issue_head(sim::Cycle now);
  void start_head(sdram::Completion& a, sim::Cycle now);
  void read(sdram::Completion& a, sim::Cycle now);
  void activate(const sdram::Address& a, sim::Cycle now);
  void precharge(const sdram::Address& a, sim::Cycle now);
  void issued(sdram::Command cmd, std::uint32_t bank, std::uint32_t row, sim::Cycle now);
  void close(std::uint32_t bank, sim::Cycle now);
  void retire(sim::Cycle now);
  sim::Cycle next_wake(sim::Cycle now) const;

  // A request became the oldest (the queue was empty): its command and
  // cycle, and a tick at its arrival.
  void new_oldest(sim::Cycle arrival);
  // head_cmd_ and head_at_ for the oldest pending request (pending_count_ > 0).
  void know_head();

  void step_refresh(sim::Cycle now);
  void issue_rank_command(sdram::Command cmd, sim::Cycle now);
  sim::Cycle earliest(sdram::Command cmd, std::uint32_t bank) const {
    return not_before_.at(cmd, bank);
  }
  bool all_idle() const;
  bool column_allowed() const { return flight_count_ + completions_.size() < completions_.depth(); }
  // Out of line and cold: the hot paths only branch to it.
  [[noreturn, gnu::cold, gnu::noinline]] void fail(const char* what, sim::Cycle now) const;

  sdram::TimingCycles t_;
  sdram::Geometry geometry_;
  sdram::NotBefore not_before_;  // the compiled table (a command's earliest cycle)
  std::vector<Bank> banks_;
  std::int64_t refreshes_ = 0;
  int postpone_limit_ = 0;
  // The first cycle the refresh sequence acts at: refresh_due_, or kNever
  // while the sequence runs (it acts, and counts its cycles, every tick).
  sim::Cycle refresh_at_ = 0;
  sim::Cycle refresh_due_ = 0;  // (refreshes_ + 1) * tREFI: the next REF falls due
  sim::Cycle overdue_at_ = 0;   // (refreshes_ + 2 + postpone limit) * tREFI: after refresh_due_
  sim::Cycle last_command_ = -1;
  std::uint64_t burst_bytes_ = 0;  // one access's data
  sim::Cycle data_first_ = 0;      // CL: a READ's first data beat after it
  sim::Cycle data_last_ = 0;       // CL + BL - 1: its last

  // Every request from push to retire, one ring, oldest first: the accesses
  // in flight (flight_count_ from flight_head_, their data on its way), then
  // the pending requests (pending_count_ from pending_head_, which follows
  // the last in flight). A request is written once, at push; its commands
  // fill in its completion (outcome, cycles) in place, and a READ moves it
  // from pending to in flight by moving pending_head_, without a copy.
  // At most queue_depth pending and return_depth in flight (a READ needs a
  // free return slot): the ring holds both.
  std::vector<sdram::Completion> accesses_;
  std::size_t ring_size_ = 0;  // accesses_.size(), kept (no division by 72)
  std::size_t queue_depth_ = 0;
  std::size_t flight_head_ = 0, flight_count_ = 0;
  std::size_t pending_head_ = 0, pending_count_ = 0;
  // The oldest pending request's next command and its earliest cycle, kept
  // up to date: they change only with a command (the banks and the table) or
  // a new oldest request. With no request pending, head_at_ is kNoRequest
  // (one test of the tick covers both).
  static constexpr sim::Cycle kNoRequest = std::numeric_limits<sim::Cycle>::max();
  sdram::Command head_cmd_ = sdram::Command::kNop;
  sim::Cycle head_at_ = kNoRequest;
  bool head_started_ = false;  // the oldest request had its first command (outcome set)
  sim::Fifo<sdram::Completion> completions_;
  sdram::ControllerStats cs_;
  sdram::DimmStats ds_;
  sdram::CommandObserver* observer_ = nullptr;
};

}  // namespace voxcast::rtl::pipeline
