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
// The bank states, the bus and the refresh deadline are kept as the Dimm
// keeps them; a violated invariant is an error, as the Dimm would throw.
// tests/rtl/test_rtl_memory_port.cpp compares it with the reference command
// by command.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "rtl_model/pipeline/memory_port.hpp"
#include "rtl_model/sdram/not_before.hpp"
#include "rtl_model/sdram/timing.hpp"

namespace voxcast::rtl::pipeline {

class FastInOrderPort final : public MemoryPort {
 public:
  // Throws voxcast::Error for the configurations the Dimm and the Controller reject.
  FastInOrderPort(const sdram::DimmConfig& dimm, const sdram::ControllerConfig& controller);

  bool ready() const override { return pending_count_ < pending_.size(); }
  void push(const sdram::Request& r) override;
  void tick(sim::Cycle now) override;
  sim::Fifo<sdram::Completion>& completions() override { return completions_; }
  const sim::Fifo<sdram::Completion>& completions() const override { return completions_; }
  void popped(sim::Cycle now) override;
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

  bool step_refresh(sim::Cycle now);
  void schedule(sim::Cycle now);
  void retire(sim::Cycle now);
  void issue(sdram::Command cmd, std::uint32_t bank, std::uint32_t row, sim::Cycle now);
  sdram::Command next_command(const sdram::Address& a) const;
  sim::Cycle earliest(sdram::Command cmd, std::uint32_t bank) const;
  bool all_idle() const;
  bool column_allowed() const {
    return flight_count_ + completions_.size() < completions_.depth();
  }
  sim::Cycle next_wake(sim::Cycle now) const;
  [[noreturn]] void fail(const std::string& what, sim::Cycle now) const;

  sdram::TimingCycles t_;
  sdram::Geometry geometry_;
  sdram::NotBefore not_before_;  // the compiled table (a command's earliest cycle)
  std::vector<Bank> banks_;
  std::int64_t refreshes_ = 0;
  int postpone_limit_ = 0;
  bool refreshing_ = false;
  sim::Cycle last_command_ = -1;

  std::vector<sdram::PendingRequest> pending_;  // ring, oldest first
  std::size_t pending_head_ = 0, pending_count_ = 0;
  std::vector<sdram::Completion> flight_;  // ring, in data order
  std::size_t flight_head_ = 0, flight_count_ = 0;
  sim::Fifo<sdram::Completion> completions_;
  sdram::ControllerStats cs_;
  sdram::DimmStats ds_;
  sdram::CommandObserver* observer_ = nullptr;
};

}  // namespace voxcast::rtl::pipeline
