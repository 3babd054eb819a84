// FastInOrderPort: the reference Controller with the in-order open-page
// scheduler and eager refresh (sdram/controller.hpp, sched/in_order.hpp,
// sched/refresh_eager.hpp), event-driven, for whole-frame simulations.
//
// Same decisions, same cycles: per tick the same three steps (refresh
// sequence, else the oldest request's next command as soon as it is legal,
// then retire), and the same statistics (ControllerStats, DimmStats) except
// the tick counters. The queue, the banks, the refresh sequence and the
// statistics are EventDrivenPort's (event_driven_port.hpp); what this port
// adds is the in-order choice, kept cheap because a tick runs in most cycles
// of a frame (four ports per cycle):
//   - Ticks only at cycles where something can happen (wake()): a REF due,
//     an access's last data beat, the oldest request's next command legal,
//     a new oldest request, a freed return slot.
//   - The pipeline inlines the per-request members (it calls them on this
//     final class, not through MemoryPort) and calls step() once per tick,
//     with its helpers inlined into it. The oldest request's next command and
//     its earliest cycle are kept up to date by the commands (after ACT its
//     READ, after PRE its ACT, after READ the next request's), each path with
//     its command a constant, not derived again per tick. The refresh
//     sequence is one compare per tick, and so is an empty queue (head_at_).
// tests/rtl/test_rtl_memory_port.cpp compares it with the reference command
// by command.
#pragma once

#include <cstddef>
#include <limits>

#include "rtl_model/pipeline/event_driven_port.hpp"

namespace voxcast::rtl::pipeline {

class FastInOrderPort final : public EventDrivenPort {
 public:
  // Throws voxcast::Error for the configurations the Dimm and the Controller reject.
  FastInOrderPort(const sdram::DimmConfig& dimm, const sdram::ControllerConfig& controller);

  void push(const sdram::Request& r) override {
    enqueue(r);
    if (++pending_count_ == 1) new_oldest(r.arrival);
  }
  // Controller::tick: the refresh sequence, else the oldest request's next
  // command as soon as it is legal, then retire (step()). The pipeline asks
  // wake() itself; the check here is for callers that tick every cycle.
  void tick(sim::Cycle now) override {
    if (now >= wake_) step(now);
  }

 private:
  // One tick at `now` (>= wake_), one call with its helpers inlined into
  // it (fast_in_order_port.cpp).
  void step(sim::Cycle now);
  // The oldest request's next command, at head_at_ (step() checked it).
  void issue_head(sim::Cycle now);
  sim::Cycle next_wake(sim::Cycle now) const;

  // A request became the oldest (the queue was empty): its command and
  // cycle, and a tick at its arrival.
  void new_oldest(sim::Cycle arrival);
  // head_cmd_ and head_at_ for the oldest pending request (pending_count_ > 0).
  void know_head();

  // The oldest pending request's next command and its earliest cycle, kept
  // up to date: they change only with a command (the banks and the table) or
  // a new oldest request. With no request pending, head_at_ is kNoRequest
  // (one test of the tick covers both).
  static constexpr sim::Cycle kNoRequest = std::numeric_limits<sim::Cycle>::max();
  sdram::Command head_cmd_ = sdram::Command::kNop;
  sim::Cycle head_at_ = kNoRequest;
  bool head_started_ = false;  // the oldest request had its first command (outcome set)
};

}  // namespace voxcast::rtl::pipeline
