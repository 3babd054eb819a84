#include "rtl_model/pipeline/fast_in_order_port.hpp"

#include <algorithm>
#include <sstream>

#include "refmodel/error.hpp"
#include "rtl_model/sdram/dimm.hpp"

namespace voxcast::rtl::pipeline {

using sdram::Command;
using sdram::RowOutcome;
using sdram::index_of;
using sim::Cycle;

FastInOrderPort::FastInOrderPort(const sdram::DimmConfig& dimm,
                                 const sdram::ControllerConfig& controller)
    : t_(sdram::Dimm(dimm).timing()),  // the Dimm validates the configuration
      geometry_(dimm.geometry),
      // The commands the port asks the table about (it issues no WR or RDA).
      not_before_(sdram::ConstraintTable(t_), dimm.geometry.banks, 0, 1,
                  sdram::NotBefore::asked(
                      {Command::kAct, Command::kRd, Command::kPre, Command::kPrea, Command::kRef})),
      banks_(dimm.geometry.banks),
      postpone_limit_(dimm.refresh_postpone_limit),
      completions_("sdram.completions", controller.return_depth) {
  if (controller.queue_depth == 0) throw Error("Controller: request queue depth 0");
  refresh_due_ = static_cast<Cycle>(t_.tREFI);
  refresh_at_ = refresh_due_;
  overdue_at_ = static_cast<Cycle>(2 + postpone_limit_) * t_.tREFI;
  burst_bytes_ = static_cast<std::uint64_t>(t_.BL) * geometry_.bytes_per_beat();
  data_first_ = t_.CL;
  data_last_ = t_.CL + t_.BL - 1;
  queue_depth_ = controller.queue_depth;
  accesses_.resize(controller.queue_depth + controller.return_depth);
  ring_size_ = accesses_.size();
  ds_.banks.resize(geometry_.banks);
}

void FastInOrderPort::fail(const char* what, Cycle now) const {
  std::ostringstream os;
  os << "fast in-order controller at cycle " << now << ": " << what;
  throw Error(os.str());
}

bool FastInOrderPort::all_idle() const {
  for (const Bank& b : banks_)
    if (b.open) return false;
  return true;
}

// The helpers of step() are inlined into it: it runs in most SDRAM cycles
// of a frame, and a call per helper cost more than its body.
#define VOXCAST_HOT_INLINE [[gnu::always_inline]] inline

// The in-order scheduler's command: the oldest request's ACT, PRE or READ,
// legal by the table at head_at_ <= now (the earliest-cycle check the Dimm
// would repeat). Each command is its own path with the command a constant
// (the table's raise and look-up specialize to it), and knows the request's
// next command: after ACT its READ, after PRE its ACT, after READ the next
// request's.
VOXCAST_HOT_INLINE void FastInOrderPort::issue_head(Cycle now) {
  sdram::Completion& a = accesses_[pending_head_];
  if (!head_started_) start_head(a, now);
  if (now <= last_command_) [[unlikely]]
    fail("two commands in one cycle", now);
  switch (head_cmd_) {
    case Command::kRd:
      read(a, now);
      break;
    case Command::kAct:
      activate(a.request.address, now);
      break;
    case Command::kPre:
      precharge(a.request.address, now);
      break;
    default:
      fail("unexpected command", now);
  }
}

// The request's first command tells how its row met its bank.
VOXCAST_HOT_INLINE void FastInOrderPort::start_head(sdram::Completion& a, Cycle now) {
  const RowOutcome o = head_cmd_ == Command::kRd    ? RowOutcome::kHit
                       : head_cmd_ == Command::kAct ? RowOutcome::kMiss
                                                    : RowOutcome::kConflict;
  a.outcome = o;
  a.first_command = now;
  ++(o == RowOutcome::kHit    ? cs_.row_hits
     : o == RowOutcome::kMiss ? cs_.row_misses
                              : cs_.row_conflicts);
  head_started_ = true;
}

// The READ completes the request's commands: it moves from pending to in
// flight, and the next request (if any) becomes the oldest.
VOXCAST_HOT_INLINE void FastInOrderPort::read(sdram::Completion& a, Cycle now) {
  const std::uint32_t bank = a.request.address.bank, row = a.request.address.row;
  not_before_.raise(Command::kRd, bank, now);
  const Bank& b = banks_[bank];
  if (!b.open || b.row != row) [[unlikely]]
    fail("READ to a closed row", now);
  ++ds_.banks[bank].reads;
  ds_.data_bus_busy_cycles += t_.BL;
  ++cs_.reads;
  a.column_command = now;
  a.data = sdram::DataWindow{now + data_first_, now + data_last_};
  issued(Command::kRd, bank, row, now);
  pending_head_ = wrap(pending_head_ + 1);
  --pending_count_;
  ++flight_count_;
  head_started_ = false;
  if (pending_count_ != 0) {
    know_head();
  } else {
    head_at_ = kNoRequest;
  }
}

VOXCAST_HOT_INLINE void FastInOrderPort::activate(const sdram::Address& a, Cycle now) {
  not_before_.raise(Command::kAct, a.bank, now);
  Bank& b = banks_[a.bank];
  if (b.open) [[unlikely]]
    fail("ACT to an open bank", now);
  b = Bank{true, a.row, now};
  ++ds_.banks[a.bank].activates;
  issued(Command::kAct, a.bank, a.row, now);
  head_cmd_ = Command::kRd;
  head_at_ = earliest(Command::kRd, a.bank);
}

VOXCAST_HOT_INLINE void FastInOrderPort::precharge(const sdram::Address& a, Cycle now) {
  not_before_.raise(Command::kPre, a.bank, now);
  if (banks_[a.bank].open) close(a.bank, now);
  issued(Command::kPre, a.bank, a.row, now);
  head_cmd_ = Command::kAct;
  head_at_ = earliest(Command::kAct, a.bank);
}

// Every command's common accounting.
VOXCAST_HOT_INLINE void FastInOrderPort::issued(Command cmd, std::uint32_t bank, std::uint32_t row,
                                                Cycle now) {
  last_command_ = now;
  ++ds_.commands;
  ++cs_.command_cycles;
  ++activity_;
  if (observer_) observer_->on_command(cmd, sdram::Address{bank, row, 0}, now);
}

void FastInOrderPort::close(std::uint32_t bank, Cycle now) {
  ds_.banks[bank].open_cycles += now - banks_[bank].activated_at;
  ++ds_.banks[bank].precharges;
  banks_[bank].open = false;
}

// The accesses whose last data beat is at or before `now` (at least one).
VOXCAST_HOT_INLINE void FastInOrderPort::retire(Cycle now) {
  do {
    const sdram::Completion& c = accesses_[flight_head_];
    ++cs_.completed;
    ++activity_;
    cs_.bytes += burst_bytes_;
    const Cycle latency = c.latency();
    cs_.latency_sum += latency;
    cs_.latency_max = std::max(cs_.latency_max, latency);
    completions_.push_copy(c);  // as one block
    flight_head_ = wrap(flight_head_ + 1);
    --flight_count_;
  } while (flight_count_ != 0 && accesses_[flight_head_].data.last <= now);
}

VOXCAST_HOT_INLINE Cycle FastInOrderPort::next_wake(Cycle now) const {
  // The next REF falls due; while the sequence runs, the next cycle (it
  // counts its cycles): refresh_at_ is then kNever, below now + 1.
  Cycle w = refresh_at_;
  if (flight_count_ != 0) w = std::min(w, accesses_[flight_head_].data.last);
  // The oldest request's command (head_at_ is kNoRequest if there is none).
  if (head_cmd_ != Command::kRd || column_allowed()) w = std::min(w, head_at_);
  return std::max(w, now + 1);
}

// The in-order open-page scheduler's choice by the bank's row, each with
// the command a constant (the table's look-up specializes to it).
VOXCAST_HOT_INLINE void FastInOrderPort::know_head() {
  const sdram::Address& a = accesses_[pending_head_].request.address;
  const Bank& b = banks_[a.bank];
  if (!b.open) {
    head_cmd_ = Command::kAct;
    head_at_ = earliest(Command::kAct, a.bank);
  } else if (b.row == a.row) {
    head_cmd_ = Command::kRd;
    head_at_ = earliest(Command::kRd, a.bank);
  } else {
    head_cmd_ = Command::kPre;
    head_at_ = earliest(Command::kPre, a.bank);
  }
}

#undef VOXCAST_HOT_INLINE

void FastInOrderPort::step(Cycle now) {
  ++cs_.cycles;
  // Refresh falls due before it is overdue (overdue_at_ > refresh_due_), so
  // step_refresh() checks the deadline the Dimm enforces.
  if (now >= refresh_at_) [[unlikely]] {  // EagerRefresh: as soon as due
    step_refresh(now);
  } else if (head_at_ <= now && (head_cmd_ != Command::kRd || column_allowed())) {
    issue_head(now);
  }
  if (flight_count_ != 0 && accesses_[flight_head_].data.last <= now) retire(now);
  completions_.sample();
  wake_ = next_wake(now);
}

void FastInOrderPort::new_oldest(Cycle arrival) {
  wake_ = std::min(wake_, arrival);
  know_head();
}

// The refresh sequence (EagerRefresh): close every row, then REF; its cycles
// are counted while it waits.
void FastInOrderPort::step_refresh(Cycle now) {
  // The Dimm rejects every command once refresh is overdue.
  if (now >= overdue_at_) fail("refresh overdue", now);
  refresh_at_ = sdram::kNever;  // every tick until the REF
  ++cs_.refresh_cycles;
  const Command cmd = all_idle() ? Command::kRef : Command::kPrea;
  if (earliest(cmd, 0) <= now) {
    issue_rank_command(cmd, now);
    if (cmd == Command::kRef) refresh_at_ = refresh_due_;
  }
}

// PREA or REF at `now`, legal by the table (step_refresh checked it).
void FastInOrderPort::issue_rank_command(Command cmd, Cycle now) {
  if (now <= last_command_) fail("two commands in one cycle", now);
  not_before_.raise(cmd, 0, now);
  if (cmd == Command::kPrea) {
    for (std::uint32_t b = 0; b < geometry_.banks; ++b)
      if (banks_[b].open) close(b, now);
    ++ds_.precharge_alls;
  } else {
    if (!all_idle()) fail("REF with a row open", now);
    ++ds_.refreshes;
    ds_.refresh_busy_cycles += t_.tRFC;
    ++refreshes_;
    refresh_due_ = (refreshes_ + 1) * t_.tREFI;
    overdue_at_ = (refreshes_ + 2 + postpone_limit_) * t_.tREFI;
  }
  issued(cmd, 0, 0, now);
  // The rows and the table changed under the oldest request.
  if (pending_count_ != 0) know_head();
}

void FastInOrderPort::expect_drained() const {
  if (pending_count_ != 0 || flight_count_ != 0) {
    std::ostringstream os;
    os << "controller: " << pending_count_ << " request(s) pending and " << flight_count_
       << " access(es) in flight at the end";
    throw Error(os.str());
  }
  completions_.expect_drained();
}

}  // namespace voxcast::rtl::pipeline
