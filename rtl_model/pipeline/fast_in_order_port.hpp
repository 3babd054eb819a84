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
//     cycle): the per-cycle members are defined here for the pipeline to
//     inline (it calls them on this final class, not through MemoryPort);
//     the oldest request's next command and its earliest cycle are computed
//     once per command, not once in the schedule and again for the wake;
//     the refresh deadlines are kept as cycles, not multiplied out per tick;
//     the refresh sequence, the rank commands and the errors are out of line.
// The bank states, the bus and the refresh deadline are kept as the Dimm
// keeps them; a violated invariant is an error, as the Dimm would throw.
// tests/rtl/test_rtl_memory_port.cpp compares it with the reference command
// by command.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rtl_model/pipeline/memory_port.hpp"
#include "rtl_model/sdram/not_before.hpp"
#include "rtl_model/sdram/timing.hpp"

namespace voxcast::rtl::pipeline {

class FastInOrderPort final : public MemoryPort {
 public:
  // Throws voxcast::Error for the configurations the Dimm and the Controller reject.
  FastInOrderPort(const sdram::DimmConfig& dimm, const sdram::ControllerConfig& controller);

  bool ready() const override { return pending_count_ < pending_depth_; }
  void push(const sdram::Request& r) override {
    if (!ready()) fail("request queue is full", r.arrival);
    if (r.address.bank >= geometry_.banks || r.address.row >= geometry_.rows ||
        r.address.column >= geometry_.columns)
      fail("request outside the DIMM", r.arrival);
    sdram::PendingRequest& p = pending_[wrap(pending_head_ + pending_count_, pending_depth_)];
    p = sdram::PendingRequest{};
    p.request = r;
    // Only a new oldest request changes what the in-order scheduler does.
    if (++pending_count_ == 1) {
      wake_ = std::min(wake_, r.arrival);
      head_known_ = false;
    }
    ++cs_.requests;
  }
  // Controller::tick: the refresh sequence, else the oldest request's next
  // command as soon as it is legal, then retire.
  void tick(sim::Cycle now) override {
    if (now < wake_) return;
    ++cs_.cycles;
    // The Dimm rejects every command once refresh is overdue.
    if (now >= overdue_at_) fail("refresh overdue", now);
    if (refreshing_ || now >= refresh_due_) {  // EagerRefresh: as soon as due
      step_refresh(now);
    } else if (pending_count_ != 0) {
      schedule(now);
    }
    if (flight_count_ > 0 && flight_[flight_head_].data.last <= now) retire(now);
    completions_.sample();
    wake_ = next_wake(now);
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

  // i mod n for i < 2n, without a division.
  static std::size_t wrap(std::size_t i, std::size_t n) { return i >= n ? i - n : i; }

  // The oldest request's next command and its earliest cycle (head_cmd_,
  // head_at_). They change only with a command (the banks and the table) or
  // a new oldest request, so they are computed once per change.
  void know_head() {
    if (head_known_) return;
    const sdram::Address& a = pending_[pending_head_].request.address;
    head_cmd_ = next_command(a);
    head_at_ = earliest(head_cmd_, a.bank);
    head_known_ = true;
  }

  void schedule(sim::Cycle now) {
    know_head();
    const sdram::Command cmd = head_cmd_;
    if (cmd == sdram::Command::kRd && !column_allowed()) return;
    if (head_at_ > now) return;
    sdram::PendingRequest& p = pending_[pending_head_];
    const sdram::Address& a = p.request.address;
    if (!p.outcome) {
      const sdram::RowOutcome o = cmd == sdram::Command::kRd    ? sdram::RowOutcome::kHit
                                  : cmd == sdram::Command::kAct ? sdram::RowOutcome::kMiss
                                                                : sdram::RowOutcome::kConflict;
      p.outcome = o;
      p.first_command = now;
      ++(o == sdram::RowOutcome::kHit    ? cs_.row_hits
         : o == sdram::RowOutcome::kMiss ? cs_.row_misses
                                         : cs_.row_conflicts);
    }
    // (head_at_ <= now is the earliest-cycle check issue() would repeat.)
    issue_bank_command(cmd, a.bank, a.row, now);
    if (cmd != sdram::Command::kRd) return;
    ++cs_.reads;
    sdram::Completion& c = flight_[wrap(flight_head_ + flight_count_, flight_depth_)];
    c.request = p.request;
    c.outcome = *p.outcome;
    c.first_command = p.first_command;
    c.column_command = now;
    c.data = sdram::DataWindow{now + t_.CL, now + t_.CL + t_.BL - 1};
    ++flight_count_;
    pending_head_ = wrap(pending_head_ + 1, pending_depth_);
    --pending_count_;
  }

  // ACT, READ or PRE of the oldest request at `now`, legal by the table
  // (schedule checked it): Dimm::apply's state and statistics.
  void issue_bank_command(sdram::Command cmd, std::uint32_t bank, std::uint32_t row,
                          sim::Cycle now) {
    if (now <= last_command_) fail("two commands in one cycle", now);
    not_before_.raise(cmd, bank, now);
    head_known_ = false;
    Bank& b = banks_[bank];
    sdram::BankStats& bs = ds_.banks[bank];
    switch (cmd) {
      case sdram::Command::kAct:
        if (b.open) fail("ACT to an open bank", now);
        b = Bank{true, row, now};
        ++bs.activates;
        break;
      case sdram::Command::kRd:
        if (!b.open || b.row != row) fail("READ to a closed row", now);
        ++bs.reads;
        ds_.data_bus_busy_cycles += t_.BL;
        break;
      case sdram::Command::kPre:
        if (b.open) close(bank, now);
        break;
      default:
        fail("unexpected command", now);
    }
    issued(cmd, bank, row, now);
  }

  // Every command's common accounting.
  void issued(sdram::Command cmd, std::uint32_t bank, std::uint32_t row, sim::Cycle now) {
    last_command_ = now;
    ++ds_.commands;
    ++cs_.command_cycles;
    ++activity_;
    if (observer_) observer_->on_command(cmd, sdram::Address{bank, row, 0}, now);
  }

  void close(std::uint32_t bank, sim::Cycle now) {
    ds_.banks[bank].open_cycles += now - banks_[bank].activated_at;
    ++ds_.banks[bank].precharges;
    banks_[bank].open = false;
  }

  // The accesses whose last data beat is at or before `now` (at least one).
  void retire(sim::Cycle now) {
    do {
      const sdram::Completion& c = flight_[flight_head_];
      ++cs_.completed;
      ++activity_;
      cs_.bytes += burst_bytes_;
      cs_.latency_sum += c.latency();
      cs_.latency_max = std::max(cs_.latency_max, c.latency());
      completions_.push(c);
      flight_head_ = wrap(flight_head_ + 1, flight_depth_);
      --flight_count_;
    } while (flight_count_ > 0 && flight_[flight_head_].data.last <= now);
  }

  sim::Cycle next_wake(sim::Cycle now) {
    if (refreshing_) return now + 1;  // the sequence counts its cycles
    sim::Cycle w = refresh_due_;      // the next REF falls due
    if (flight_count_ > 0) w = std::min(w, flight_[flight_head_].data.last);
    if (pending_count_ > 0) {
      know_head();
      if (head_cmd_ != sdram::Command::kRd || column_allowed()) w = std::min(w, head_at_);
    }
    return std::max(w, now + 1);
  }

  void step_refresh(sim::Cycle now);
  void issue_rank_command(sdram::Command cmd, sim::Cycle now);
  sdram::Command next_command(const sdram::Address& a) const {
    const Bank& b = banks_[a.bank];
    if (!b.open) return sdram::Command::kAct;
    return b.row == a.row ? sdram::Command::kRd : sdram::Command::kPre;
  }
  sim::Cycle earliest(sdram::Command cmd, std::uint32_t bank) const {
    return not_before_.at(cmd, bank);
  }
  bool all_idle() const;
  bool column_allowed() const { return flight_count_ + completions_.size() < completions_.depth(); }
  [[noreturn]] void fail(const std::string& what, sim::Cycle now) const;

  sdram::TimingCycles t_;
  sdram::Geometry geometry_;
  sdram::NotBefore not_before_;  // the compiled table (a command's earliest cycle)
  std::vector<Bank> banks_;
  std::int64_t refreshes_ = 0;
  int postpone_limit_ = 0;
  bool refreshing_ = false;
  sim::Cycle refresh_due_ = 0;  // (refreshes_ + 1) * tREFI: the next REF falls due
  sim::Cycle overdue_at_ = 0;   // (refreshes_ + 2 + postpone limit) * tREFI
  sim::Cycle last_command_ = -1;
  std::uint64_t burst_bytes_ = 0;  // one access's data

  std::vector<sdram::PendingRequest> pending_;  // ring, oldest first
  std::size_t pending_head_ = 0, pending_count_ = 0;
  bool head_known_ = false;  // head_cmd_ and head_at_ hold for pending_[pending_head_]
  sdram::Command head_cmd_ = sdram::Command::kNop;
  sim::Cycle head_at_ = 0;
  std::vector<sdram::Completion> flight_;  // ring, in data order
  std::size_t flight_head_ = 0, flight_count_ = 0;
  // The rings' sizes, kept (a vector's size is a division by the element's).
  std::size_t pending_depth_ = 0, flight_depth_ = 0;
  sim::Fifo<sdram::Completion> completions_;
  sdram::ControllerStats cs_;
  sdram::DimmStats ds_;
  sdram::CommandObserver* observer_ = nullptr;
};

}  // namespace voxcast::rtl::pipeline
