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

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <span>
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

// The Controller's pending requests, oldest first and contiguous (the
// scheduler's view is a span). Serving the oldest, which a row-hit stream
// does with nearly every command, advances the start instead of moving the
// rest down (a memmove per command in a std::vector); a later request moves
// the shorter side. The storage holds twice the depth, and the entries move
// back to its start when the end reaches it: at most once per `depth`
// requests served.
class PendingQueue {
 public:
  explicit PendingQueue(std::size_t depth) : slots_(2 * depth) {}

  std::size_t size() const { return end_ - begin_; }
  bool empty() const { return end_ == begin_; }
  std::span<const PendingRequest> span() const { return {slots_.data() + begin_, size()}; }
  PendingRequest& operator[](std::size_t i) { return slots_[begin_ + i]; }
  const PendingRequest& operator[](std::size_t i) const { return slots_[begin_ + i]; }
  const PendingRequest& front() const { return slots_[begin_]; }

  // The caller keeps size() below the depth.
  void push_back(const PendingRequest& p) {
    if (end_ == slots_.size()) compact();
    slots_[end_++] = p;
  }
  // Removes entry i; the others keep their order.
  void erase(std::size_t i) {
    const auto first = slots_.begin() + static_cast<std::ptrdiff_t>(begin_);
    const auto at = first + static_cast<std::ptrdiff_t>(i);
    if (i < size() / 2) {
      std::copy_backward(first, at, at + 1);
      ++begin_;
    } else {
      std::copy(at + 1, slots_.begin() + static_cast<std::ptrdiff_t>(end_), at);
      --end_;
    }
  }

 private:
  void compact() {
    std::copy(slots_.begin() + static_cast<std::ptrdiff_t>(begin_),
              slots_.begin() + static_cast<std::ptrdiff_t>(end_), slots_.begin());
    end_ -= begin_;
    begin_ = 0;
  }

  std::vector<PendingRequest> slots_;
  std::size_t begin_ = 0, end_ = 0;  // the entries: slots_[begin_, end_)
};

// The Controller's accesses in flight, in data order: a ring of a fixed
// number of slots (column_allowed() keeps them within the return depth).
// Not a sim::Fifo: no statistics or protocol checks are wanted for a list
// the Controller alone fills and drains, once per command.
class InFlight {
 public:
  explicit InFlight(std::size_t depth) : slots_(depth) {}

  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  const Completion& front() const { return slots_[head_]; }
  void push(const Completion& c) { slots_[wrap(head_ + count_++)] = c; }
  void pop() {
    head_ = wrap(head_ + 1);
    --count_;
  }

 private:
  // i mod depth for i < 2 * depth.
  std::size_t wrap(std::size_t i) const { return i >= slots_.size() ? i - slots_.size() : i; }

  std::vector<Completion> slots_;
  std::size_t head_ = 0, count_ = 0;
};

class Controller {
 public:
  // Throws voxcast::Error for a null policy or a zero depth.
  Controller(DimmConfig dimm, std::unique_ptr<CommandScheduler> scheduler,
             std::unique_ptr<RefreshPolicy> refresh, ControllerConfig config = {});

  // valid/ready request port.
  bool ready() const { return pending_.size() < config_.queue_depth; }
  // Enqueues `r` (its arrival is taken as given). Throws voxcast::Error when
  // not ready or when the address is outside the DIMM. Inline: the pipeline
  // pushes about one request per cycle and DIMM.
  void push(const Request& r) {
    if (!ready()) queue_full(r);
    const Geometry& g = dimm_.geometry();
    if (r.address.bank >= g.banks || r.address.row >= g.rows || r.address.column >= g.columns)
      outside_the_dimm(r);
    PendingRequest p;
    p.request = r;
    pending_.push_back(p);
    ++stats_.requests;
  }

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
  // push()'s errors; the messages are built only here (a stream per request
  // cost more than the rest of the controller's cycle).
  [[noreturn]] void queue_full(const Request& r) const;
  [[noreturn]] void outside_the_dimm(const Request& r) const;
  void retire(Cycle now);
  bool step_refresh(Cycle now);  // true while a refresh sequence owns the bus
  void schedule(Cycle now);
  bool column_allowed() const;
  bool row_wanted_by_another(std::size_t request) const;

  Dimm dimm_;
  std::unique_ptr<CommandScheduler> scheduler_;
  std::unique_ptr<RefreshPolicy> refresh_;
  ControllerConfig config_;
  PendingQueue pending_;
  sim::Fifo<Completion> completions_;
  // In data order (a std::deque here allocated and freed a block every few
  // accesses).
  InFlight in_flight_;
  bool refreshing_ = false;
  Cycle last_tick_ = kNever;
  ControllerStats stats_;
};

}  // namespace voxcast::rtl::sdram
