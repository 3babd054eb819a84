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

namespace {
// i mod n for i < 2n, without a division.
std::size_t wrap(std::size_t i, std::size_t n) { return i >= n ? i - n : i; }
}  // namespace

FastInOrderPort::FastInOrderPort(const sdram::DimmConfig& dimm,
                                 const sdram::ControllerConfig& controller)
    : t_(sdram::Dimm(dimm).timing()),  // the Dimm validates the configuration
      geometry_(dimm.geometry),
      not_before_(sdram::ConstraintTable(t_), dimm.geometry.banks, 0),
      banks_(dimm.geometry.banks),
      postpone_limit_(dimm.refresh_postpone_limit),
      completions_("sdram.completions", controller.return_depth) {
  if (controller.queue_depth == 0) throw Error("Controller: request queue depth 0");
  pending_.resize(controller.queue_depth);
  flight_.resize(controller.return_depth + 1);
  ds_.banks.resize(geometry_.banks);
}

void FastInOrderPort::fail(const std::string& what, Cycle now) const {
  std::ostringstream os;
  os << "fast in-order controller at cycle " << now << ": " << what;
  throw Error(os.str());
}

void FastInOrderPort::push(const sdram::Request& r) {
  if (!ready()) fail("request queue is full", r.arrival);
  if (r.address.bank >= geometry_.banks || r.address.row >= geometry_.rows ||
      r.address.column >= geometry_.columns)
    fail("request outside the DIMM", r.arrival);
  sdram::PendingRequest& p = pending_[wrap(pending_head_ + pending_count_, pending_.size())];
  p = sdram::PendingRequest{};
  p.request = r;
  // Only a new oldest request changes what the in-order scheduler does.
  if (++pending_count_ == 1) wake_ = std::min(wake_, r.arrival);
  ++cs_.requests;
}

void FastInOrderPort::popped(Cycle now) {
  if (flight_count_ + completions_.size() + 1 >= completions_.depth())
    wake_ = std::min(wake_, now + 1);
}

// ---- Timing: the compiled table --------------------------------------------------------------
Cycle FastInOrderPort::earliest(Command cmd, std::uint32_t bank) const {
  return not_before_.at(cmd, bank);
}

bool FastInOrderPort::all_idle() const {
  for (const Bank& b : banks_)
    if (b.open) return false;
  return true;
}

Command FastInOrderPort::next_command(const sdram::Address& a) const {
  const Bank& b = banks_[a.bank];
  if (!b.open) return Command::kAct;
  return b.row == a.row ? Command::kRd : Command::kPre;
}

// Dimm::apply's state and statistics, and the table's rows raised (NotBefore).
void FastInOrderPort::issue(Command cmd, std::uint32_t bank, std::uint32_t row, Cycle now) {
  if (now <= last_command_) fail("two commands in one cycle", now);
  if (earliest(cmd, bank) > now) fail("command before its earliest cycle", now);
  not_before_.raise(cmd, bank, now);
  auto close = [&](std::uint32_t b) {
    ds_.banks[b].open_cycles += now - banks_[b].activated_at;
    ++ds_.banks[b].precharges;
    banks_[b].open = false;
  };
  switch (cmd) {
    case Command::kAct:
      if (banks_[bank].open) fail("ACT to an open bank", now);
      banks_[bank] = Bank{true, row, now};
      ++ds_.banks[bank].activates;
      break;
    case Command::kRd:
      if (!banks_[bank].open || banks_[bank].row != row) fail("READ to a closed row", now);
      ++ds_.banks[bank].reads;
      ds_.data_bus_busy_cycles += t_.BL;
      break;
    case Command::kPre:
      if (banks_[bank].open) close(bank);
      break;
    case Command::kPrea:
      for (std::uint32_t b = 0; b < geometry_.banks; ++b)
        if (banks_[b].open) close(b);
      ++ds_.precharge_alls;
      break;
    case Command::kRef:
      if (!all_idle()) fail("REF with a row open", now);
      ++ds_.refreshes;
      ds_.refresh_busy_cycles += t_.tRFC;
      ++refreshes_;
      break;
    default:
      fail("unexpected command", now);
  }
  last_command_ = now;
  ++ds_.commands;
  ++cs_.command_cycles;
  ++activity_;
  if (observer_) observer_->on_command(cmd, sdram::Address{bank, row, 0}, now);
}

// ---- One cycle: Controller::tick -------------------------------------------------------------
void FastInOrderPort::tick(Cycle now) {
  if (now < wake_) return;
  ++cs_.cycles;
  // The Dimm rejects every command once refresh is overdue.
  if (now >= (refreshes_ + 2 + postpone_limit_) * t_.tREFI) fail("refresh overdue", now);
  if (!step_refresh(now)) schedule(now);
  retire(now);
  completions_.sample();
  wake_ = next_wake(now);
}

bool FastInOrderPort::step_refresh(Cycle now) {
  if (!refreshing_) {
    if (now < (refreshes_ + 1) * t_.tREFI) return false;  // EagerRefresh: as soon as due
    refreshing_ = true;
  }
  ++cs_.refresh_cycles;
  const Command cmd = all_idle() ? Command::kRef : Command::kPrea;
  if (earliest(cmd, 0) <= now) {
    issue(cmd, 0, 0, now);
    if (cmd == Command::kRef) refreshing_ = false;
  }
  return true;
}

void FastInOrderPort::schedule(Cycle now) {
  if (pending_count_ == 0) return;
  sdram::PendingRequest& p = pending_[pending_head_];
  const sdram::Address& a = p.request.address;
  const Command cmd = next_command(a);
  if (cmd == Command::kRd && !column_allowed()) return;
  if (earliest(cmd, a.bank) > now) return;
  if (!p.outcome) {
    const RowOutcome o = cmd == Command::kRd    ? RowOutcome::kHit
                         : cmd == Command::kAct ? RowOutcome::kMiss
                                                : RowOutcome::kConflict;
    p.outcome = o;
    p.first_command = now;
    ++(o == RowOutcome::kHit    ? cs_.row_hits
       : o == RowOutcome::kMiss ? cs_.row_misses
                                : cs_.row_conflicts);
  }
  issue(cmd, a.bank, a.row, now);
  if (cmd != Command::kRd) return;
  ++cs_.reads;
  flight_[wrap(flight_head_ + flight_count_, flight_.size())] = sdram::Completion{
      .request = p.request,
      .outcome = *p.outcome,
      .first_command = p.first_command,
      .column_command = now,
      .data = sdram::DataWindow{now + t_.CL, now + t_.CL + t_.BL - 1},
  };
  ++flight_count_;
  pending_head_ = wrap(pending_head_ + 1, pending_.size());
  --pending_count_;
}

void FastInOrderPort::retire(Cycle now) {
  const std::uint64_t burst_bytes = static_cast<std::uint64_t>(t_.BL) * geometry_.bytes_per_beat();
  while (flight_count_ > 0 && flight_[flight_head_].data.last <= now) {
    const sdram::Completion c = flight_[flight_head_];
    flight_head_ = wrap(flight_head_ + 1, flight_.size());
    --flight_count_;
    completions_.push(c);
    ++cs_.completed;
    ++activity_;
    cs_.bytes += burst_bytes;
    cs_.latency_sum += c.latency();
    cs_.latency_max = std::max(cs_.latency_max, c.latency());
  }
}

Cycle FastInOrderPort::next_wake(Cycle now) const {
  if (refreshing_) return now + 1;  // the sequence counts its cycles
  Cycle w = (refreshes_ + 1) * t_.tREFI;  // the next REF falls due
  if (flight_count_ > 0) w = std::min(w, flight_[flight_head_].data.last);
  if (pending_count_ > 0) {
    const sdram::Address& a = pending_[pending_head_].request.address;
    const Command cmd = next_command(a);
    if (cmd != Command::kRd || column_allowed()) w = std::min(w, earliest(cmd, a.bank));
  }
  return std::max(w, now + 1);
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
