// EventDrivenPort: what the event-driven memory ports share (FastInOrderPort,
// FastLookAheadPort): the reference Controller's request queue, in-flight
// accesses and completions FIFO, the banks' open rows, the eager refresh
// sequence and the statistics, kept as the Dimm and the Controller keep them
// (sdram/dimm.hpp, sdram/controller.hpp, sched/refresh_eager.hpp). A port
// derived from it adds its scheduler's choice of the next request command
// and its wake, and calls these members on its final class, so they inline
// into its tick (the pipeline calls the ports as their final classes; the
// hot members are always_inline: a call each cost more than their bodies).
//
//   - Timing from the Dimm's ConstraintTable, compiled (sdram/not_before.hpp):
//     a command's earliest cycle is one look-up.
//   - One ring holds every request from push to retire, oldest first: the
//     accesses in flight (flight_count_ from flight_head_, their data on its
//     way), then the pending requests (pending_count_ from pending_head_).
//     A request is written once, at push; its commands fill in its completion
//     in place, a column command moves it from pending to in flight by moving
//     pending_head_, and retire copies it into the completions FIFO as one
//     block. Column commands therefore go in arrival order: the contract of
//     both schedulers.
//   - The banks' state is one word per bank (key(bank, open row), or kClosed)
//     and its activation cycle.
//   - The refresh sequence (EagerRefresh: as soon as a REF is due, PREA while
//     a row is open, then REF) acts at refresh_at_, one compare per tick.
// A violated invariant is an error, as the Dimm would throw.
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

class EventDrivenPort : public MemoryPort {
 public:
  bool ready() const final { return pending_count_ < queue_depth_; }
  sim::Fifo<sdram::Completion>& completions() final { return completions_; }
  const sim::Fifo<sdram::Completion>& completions() const final { return completions_; }
  // A freed return slot can let a column command go at the next cycle.
  void popped(sim::Cycle now) final {
    if (flight_count_ + completions_.size() + 1 >= completions_.depth())
      wake_ = std::min(wake_, now + 1);
  }
  void set_observer(sdram::CommandObserver* o) final { observer_ = o; }

  std::size_t pending() const final { return pending_count_; }
  std::size_t in_flight() const final { return flight_count_; }
  bool idle() const final {
    return pending_count_ == 0 && flight_count_ == 0 && completions_.empty();
  }
  void expect_drained() const final;
  const sdram::ControllerStats& controller_stats() const final { return cs_; }
  const sdram::DimmStats& dimm_stats() const final { return ds_; }

 protected:
  // `name` prefixes the errors ("fast in-order controller"). `asked`: the
  // commands the port asks the table about. Throws voxcast::Error for the
  // configurations the Dimm and the Controller reject.
  EventDrivenPort(const char* name, const sdram::DimmConfig& dimm,
                  const sdram::ControllerConfig& controller, sdram::NotBefore::CommandSet asked);
  ~EventDrivenPort() override = default;

  // ---- The ring ---------------------------------------------------------------------------------
  // i mod the ring's size for i < 2 * size, without a division.
  std::size_t wrap(std::size_t i) const { return i >= ring_size_ ? i - ring_size_ : i; }
  // The pending request `j` places behind the oldest (j < pending_count_).
  std::size_t pending_at(std::size_t j) const { return wrap(pending_head_ + j); }
  // Push's checks and the request's place at the ring's tail (only the
  // request is written: its commands fill in the rest); the caller counts it
  // pending.
  [[gnu::always_inline]] std::size_t enqueue(const sdram::Request& r) {
    if (!ready()) [[unlikely]]
      fail("request queue is full", r.arrival);
    if (r.address.bank >= geometry_.banks || r.address.row >= geometry_.rows ||
        r.address.column >= geometry_.columns) [[unlikely]]
      fail("request outside the DIMM", r.arrival);
    if (r.kind != sdram::RequestKind::kRead) [[unlikely]]
      fail("a write request (this port serves reads; use the reference controller)", r.arrival);
    const std::size_t at = pending_at(pending_count_);
    accesses_[at].request = r;
    ++cs_.requests;
    return at;
  }
  // A column command may go: its data has a return slot (Controller's credits).
  bool column_allowed() const { return flight_count_ + completions_.size() < completions_.depth(); }
  // The oldest request's column command `cmd` (READ or RDA) at `now`, legal by
  // the table: its accounting, its data window, and the request moves from
  // pending to in flight. The caller has raised the table.
  [[gnu::always_inline]] void read_issued(sdram::Command cmd, sim::Cycle now) {
    sdram::Completion& c = accesses_[pending_head_];
    const std::uint32_t bank = c.request.address.bank;
    ++ds_.banks[bank].reads;
    ds_.data_bus_busy_cycles += burst_;
    ++cs_.reads;
    c.column_command = now;
    c.data = sdram::DataWindow{now + data_first_, now + data_last_};
    command_issued(cmd, c.request.address, now);
    pending_head_ = wrap(pending_head_ + 1);
    --pending_count_;
    ++flight_count_;
  }
  // The accesses whose last data beat is at or before `now` into the
  // completions FIFO (Controller::retire).
  bool retire_due(sim::Cycle now) const {
    return flight_count_ != 0 && accesses_[flight_head_].data.last <= now;
  }
  [[gnu::always_inline]] void retire(sim::Cycle now) {
    do {
      const sdram::Completion& c = accesses_[flight_head_];
      ++cs_.completed;
      ++activity_;
      cs_.bytes += burst_bytes_;
      const sim::Cycle latency = c.latency();
      cs_.latency_sum += latency;
      cs_.latency_max = std::max(cs_.latency_max, latency);
      completions_.push_copy(c);  // as one block
      flight_head_ = wrap(flight_head_ + 1);
      --flight_count_;
    } while (retire_due(now));
  }
  // The oldest in-flight access's last data beat (retire's next cycle).
  sim::Cycle next_retire(sim::Cycle w) const {
    return flight_count_ != 0 ? std::min(w, accesses_[flight_head_].data.last) : w;
  }

  // ---- The banks --------------------------------------------------------------------------------
  // A bank and row as one word, for comparisons of a request with a bank.
  static std::uint64_t key(std::uint32_t bank, std::uint32_t row) {
    return std::uint64_t{bank} << 32 | row;
  }
  static constexpr std::uint64_t kClosed = std::numeric_limits<std::uint64_t>::max();
  // The command request address `a` needs next: ACT (its bank idle), its READ
  // (its row open) or PRE (another row open): Dimm::next_command.
  sdram::Command next_command(const sdram::Address& a) const {
    const std::uint64_t open = open_key_[a.bank];
    if (open == kClosed) return sdram::Command::kAct;
    return open == key(a.bank, a.row) ? sdram::Command::kRd : sdram::Command::kPre;
  }
  sim::Cycle earliest(sdram::Command cmd, std::uint32_t bank) const {
    return not_before_.at(cmd, bank);
  }
  // ACT of `a`'s row at `now`: the table raised, the bank's row open.
  [[gnu::always_inline]] void activate(const sdram::Address& a, sim::Cycle now) {
    not_before_.raise(sdram::Command::kAct, a.bank, now);
    if (open_key_[a.bank] != kClosed) [[unlikely]]
      fail("ACT to an open bank", now);
    open_key_[a.bank] = key(a.bank, a.row);
    activated_at_[a.bank] = now;
    ++ds_.banks[a.bank].activates;
    command_issued(sdram::Command::kAct, a, now);
  }
  // PRE of `a`'s bank at `now`, which has another row open (a conflict).
  [[gnu::always_inline]] void precharge(const sdram::Address& a, sim::Cycle now) {
    not_before_.raise(sdram::Command::kPre, a.bank, now);
    close(a.bank, now);
    command_issued(sdram::Command::kPre, a, now);
  }
  // The bank's row closes at `closed_at` (a PRE, PREA or an RDA's internal
  // precharge).
  void close(std::uint32_t bank, sim::Cycle closed_at);
  bool all_closed() const;

  // ---- Commands ---------------------------------------------------------------------------------
  // A request's first command `cmd` at `now` tells how its row met its bank
  // (READ: a hit, ACT: a miss, PRE: a conflict): its outcome and the count.
  [[gnu::always_inline]] void first_command(sdram::Completion& c, sdram::Command cmd,
                                            sim::Cycle now) {
    const sdram::RowOutcome o = cmd == sdram::Command::kRd    ? sdram::RowOutcome::kHit
                                : cmd == sdram::Command::kAct ? sdram::RowOutcome::kMiss
                                                              : sdram::RowOutcome::kConflict;
    c.outcome = o;
    c.first_command = now;
    ++(o == sdram::RowOutcome::kHit    ? cs_.row_hits
       : o == sdram::RowOutcome::kMiss ? cs_.row_misses
                                       : cs_.row_conflicts);
  }
  // One command per cycle: a second one in the same cycle is an error.
  void check_one_command(sim::Cycle now) const {
    if (now <= last_command_) [[unlikely]]
      fail("two commands in one cycle", now);
  }
  // Every command's common accounting.
  [[gnu::always_inline]] void command_issued(sdram::Command cmd, const sdram::Address& a,
                                             sim::Cycle now) {
    last_command_ = now;
    ++ds_.commands;
    ++cs_.command_cycles;
    ++activity_;
    if (observer_) observer_->on_command(cmd, a, now);
  }

  // ---- Refresh ----------------------------------------------------------------------------------
  // The refresh sequence acts at `now` (>= refresh_at_): it counts the cycle,
  // and issues PREA while a row is open, then REF, each when the table allows
  // it. True if it issued a command (the banks and the table changed).
  // refresh_at_ is kNever while the sequence runs and the next REF's due
  // cycle after it.
  bool refresh_due(sim::Cycle now) const { return now >= refresh_at_; }
  sim::Cycle next_refresh() const { return refresh_at_; }
  bool step_refresh(sim::Cycle now);

  // Out of line and cold: the hot paths only branch to it.
  [[noreturn, gnu::cold, gnu::noinline]] void fail(const char* what, sim::Cycle now) const;

  sdram::TimingCycles t_;
  sdram::Geometry geometry_;
  sdram::NotBefore not_before_;  // the compiled table (a command's earliest cycle)
  sim::Cycle last_command_ = -1;
  sim::Cycle burst_ = 0;           // data-bus clocks of one access
  sim::Cycle data_first_ = 0;      // CL: a READ's first data beat after it
  sim::Cycle data_last_ = 0;       // its last: CL + burst - 1
  std::uint64_t burst_bytes_ = 0;  // one access's data

  // The banks: key(bank, open row) or kClosed, and when the row opened.
  std::vector<std::uint64_t> open_key_;
  std::vector<sim::Cycle> activated_at_;

  // Every request from push to retire (see the top of this file). At most
  // queue_depth pending and return_depth in flight: the ring holds both.
  std::vector<sdram::Completion> accesses_;
  std::size_t ring_size_ = 0;  // accesses_.size(), kept (no division)
  std::size_t queue_depth_ = 0;
  std::size_t flight_head_ = 0, flight_count_ = 0;
  std::size_t pending_head_ = 0, pending_count_ = 0;

  sim::Fifo<sdram::Completion> completions_;
  sdram::ControllerStats cs_;
  sdram::DimmStats ds_;
  sdram::CommandObserver* observer_ = nullptr;

 private:
  void issue_rank_command(sdram::Command cmd, sim::Cycle now);

  const char* name_;
  std::int64_t refreshes_ = 0;
  int postpone_limit_ = 0;
  // The first cycle the refresh sequence acts at: refresh_due_, or kNever
  // while the sequence runs (it acts, and counts its cycles, every tick).
  sim::Cycle refresh_at_ = 0;
  sim::Cycle refresh_due_ = 0;  // (refreshes_ + 1) * tREFI: the next REF falls due
  sim::Cycle overdue_at_ = 0;   // (refreshes_ + 2 + postpone limit) * tREFI: after refresh_due_
};

}  // namespace voxcast::rtl::pipeline
