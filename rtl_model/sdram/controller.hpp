// The reference SDRAM controller of one DIMM: a bounded request buffer, a
// pluggable command scheduler and refresh policy, the Dimm as referee, and a
// read-data return FIFO. Later models (the row-activate scheduler, the volume
// memory layout, the four-DIMM memory system) build on it.
//
// Per cycle, tick(now):
//   1. retire: accesses whose last data beat is at or before `now` move from
//      the in-flight list into the completions FIFO (valid/ready);
//   2. refresh: if a refresh sequence is running, or the refresh policy says
//      to start one, issue PREA while a row is open, then REF, each at its
//      earliest legal cycle; no request command is issued meanwhile;
//   3. otherwise ask the scheduler and issue its decision; a column command
//      completes its request.
// A request pushed before tick(now) has arrival `now` and may get its first
// command in the same cycle (the front end's registers belong to the models
// that feed the controller).
//
// Back-pressure: every column command reserves a completions slot, so a read
// is only issued when the in-flight accesses plus the FIFO's occupancy leave
// room for its data (credits), and the FIFO never overflows.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <iosfwd>
#include <memory>
#include <vector>

#include "rtl_model/sdram/dimm.hpp"
#include "rtl_model/sdram/refresh.hpp"
#include "rtl_model/sdram/scheduler.hpp"
#include "rtl_model/sim/fifo.hpp"

namespace voxcast::rtl::sdram {

struct ControllerConfig {
  std::size_t queue_depth = 8;   // pending requests (the scheduler's window at most)
  std::size_t return_depth = 8;  // completions FIFO entries
  // Adaptive page policy: a READ whose row no other pending request wants is
  // issued as READ with auto precharge (when tRAS allows it then), so the
  // row change that follows costs an ACT but no PRE on the command bus. Off:
  // open page, rows closed by PRE (VIZARD II).
  bool auto_precharge = false;
};

// A served request.
struct Completion {
  Request request;
  RowOutcome outcome = RowOutcome::kHit;
  Cycle first_command = 0;   // the request's first command (ACT, PRE or the column command)
  Cycle column_command = 0;  // its RD or WR
  DataWindow data;           // its beats on the data bus

  // Arrival to first data beat.
  Cycle latency() const { return data.first - request.arrival; }
};

std::ostream& operator<<(std::ostream& os, const Completion& c);

struct ControllerStats {
  Cycle cycles = 0;  // ticks
  std::uint64_t requests = 0;
  std::uint64_t reads = 0;
  std::uint64_t writes = 0;
  std::uint64_t row_hits = 0;
  std::uint64_t row_misses = 0;
  std::uint64_t row_conflicts = 0;
  std::uint64_t auto_precharges = 0;  // READs issued as RDA (auto_precharge)
  std::uint64_t bytes = 0;   // data moved by completed accesses
  Cycle command_cycles = 0;  // cycles with a command on the bus
  Cycle refresh_cycles = 0;  // cycles spent in refresh sequences
  Cycle latency_sum = 0;     // over completed requests
  Cycle latency_max = 0;
  std::uint64_t completed = 0;

  double mean_latency() const;
};

std::ostream& operator<<(std::ostream& os, const ControllerStats& s);

class Controller {
 public:
  // Throws voxcast::Error for a null policy or a zero depth.
  Controller(DimmConfig dimm, std::unique_ptr<CommandScheduler> scheduler,
             std::unique_ptr<RefreshPolicy> refresh, ControllerConfig config = {});

  // valid/ready request port.
  bool ready() const { return pending_.size() < config_.queue_depth; }
  // Enqueues `r` (its arrival is taken as given). Throws voxcast::Error when
  // not ready or when the address is outside the DIMM.
  void push(const Request& r);

  // One SDRAM clock; cycles strictly increasing.
  void tick(Cycle now);
  // After tick(now): a cycle > now before which tick() would change nothing
  // but the tick counters (ControllerStats::cycles, the completions FIFO's
  // samples), provided no request is pushed and no completion popped
  // meanwhile: the earliest of a retiring access's last beat, the refresh
  // policy's and the scheduler's wake() hints; now + 1 while refreshing.
  Cycle next_event(Cycle now) const;

  // Served requests, in data order (valid/ready).
  sim::Fifo<Completion>& completions() { return completions_; }
  const sim::Fifo<Completion>& completions() const { return completions_; }

  std::size_t pending() const { return pending_.size(); }
  std::size_t in_flight() const { return in_flight_.size(); }
  // Nothing pending, in flight or waiting in the completions FIFO.
  bool idle() const { return pending_.empty() && in_flight_.empty() && completions_.empty(); }
  // Throws voxcast::Error naming what is left: pending requests, accesses in
  // flight, undrained completions.
  void expect_drained() const;

  const Dimm& dimm() const { return dimm_; }
  const CommandScheduler& scheduler() const { return *scheduler_; }
  const RefreshPolicy& refresh_policy() const { return *refresh_; }
  const ControllerStats& stats() const { return stats_; }
  void set_observer(CommandObserver* o) { dimm_.set_observer(o); }

 private:
  void retire(Cycle now);
  bool step_refresh(Cycle now);  // true while a refresh sequence owns the bus
  void schedule(Cycle now);
  bool column_allowed() const;
  bool row_wanted_by_another(std::size_t request) const;

  Dimm dimm_;
  std::unique_ptr<CommandScheduler> scheduler_;
  std::unique_ptr<RefreshPolicy> refresh_;
  ControllerConfig config_;
  std::vector<PendingRequest> pending_;
  std::deque<Completion> in_flight_;  // in data order
  sim::Fifo<Completion> completions_;
  bool refreshing_ = false;
  Cycle last_tick_ = kNever;
  ControllerStats stats_;
};

}  // namespace voxcast::rtl::sdram
