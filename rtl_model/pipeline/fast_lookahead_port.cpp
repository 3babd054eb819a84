#include "rtl_model/pipeline/fast_lookahead_port.hpp"

#include <algorithm>
#include <sstream>

#include "refmodel/error.hpp"

namespace voxcast::rtl::pipeline {

using sdram::Command;
using sim::Cycle;

namespace {
const sdram::DimmConfig& with_few_banks(const sdram::DimmConfig& dimm) {
  if (dimm.geometry.banks > FastLookAheadPort::kMaxBanks) {
    std::ostringstream os;
    os << "fast look-ahead controller: " << dimm.geometry.banks << " banks (at most "
       << FastLookAheadPort::kMaxBanks << ")";
    throw Error(os.str());
  }
  return dimm;
}
}  // namespace

FastLookAheadPort::FastLookAheadPort(const sdram::DimmConfig& dimm,
                                     const sdram::ControllerConfig& controller, int reorder_window)
    // The commands the port asks the table about (it issues no WR).
    : EventDrivenPort("fast look-ahead controller", with_few_banks(dimm), controller,
                      sdram::NotBefore::asked({Command::kAct, Command::kRd, Command::kRda,
                                               Command::kPre, Command::kPrea, Command::kRef})),
      window_(static_cast<std::size_t>(std::max(reorder_window, 1))),
      auto_precharge_(controller.auto_precharge),
      read_to_precharge_(t_.read_to_precharge()) {
  started_.resize(accesses_.size());
  row_key_.resize(accesses_.size());
  pending_per_bank_.assign(geometry_.banks, 0);
}

#define VOXCAST_HOT_INLINE [[gnu::always_inline]] inline

// LookAheadActivation's priorities: 1. the oldest request's row command,
// 2. the look-ahead row command, 3. the oldest request's column command,
// each if legal now (the table; a column command also needs a return slot).
VOXCAST_HOT_INLINE void FastLookAheadPort::schedule(Cycle now) {
  const std::size_t head = pending_head_;
  const sdram::Address& a = accesses_[head].request.address;
  const Command oldest = next_command(a);
  const bool column = oldest == Command::kRd;
  const bool oldest_legal = (!column || column_allowed()) && earliest(oldest, a.bank) <= now;
  if (!column && oldest_legal) return row_command(head, oldest, now);
  const std::size_t ahead = look_ahead();
  if (ahead != kNone && earliest(ahead_cmd_, accesses_[ahead].request.address.bank) <= now)
    return row_command(ahead, ahead_cmd_, now);
  if (oldest_legal) column_command(now);
}

VOXCAST_HOT_INLINE std::size_t FastLookAheadPort::look_ahead() {
  if (!ahead_known_) {
    ahead_ = walk_window(ahead_cmd_);
    ahead_known_ = true;
  }
  return ahead_;
}

// The walk stops at the first candidate, legal or not: the oldest such
// request's row comes first, no overtaking among rows (lookahead.cpp).
std::size_t FastLookAheadPort::walk_window(Command& cmd) const {
  const auto head_bank = static_cast<std::uint32_t>(row_key_[pending_head_] >> 32);
  if (pending_per_bank_[head_bank] == pending_count_) return kNone;  // one bank: none is first
  const std::size_t n = std::min(window_, pending_count_);
  std::uint64_t seen = std::uint64_t{1} << head_bank;
  for (std::size_t j = 1; j < n; ++j) {
    const std::size_t at = pending_at(j);
    const std::uint64_t k = row_key_[at];
    const auto bank = static_cast<std::uint32_t>(k >> 32);
    const std::uint64_t bit = std::uint64_t{1} << bank;
    if (seen & bit) continue;  // an older request needs this bank
    seen |= bit;
    const std::uint64_t open = open_key_[bank];
    if (open == k) continue;  // its row is open already
    cmd = open == kClosed ? Command::kAct : Command::kPre;
    return at;
  }
  return kNone;
}

VOXCAST_HOT_INLINE void FastLookAheadPort::start(std::size_t at, Command cmd, Cycle now) {
  if (started_[at]) return;
  first_command(accesses_[at], cmd, now);
  started_[at] = 1;
}

// ACT or PRE for the request at ring place `at` (schedule() checked the table).
void FastLookAheadPort::row_command(std::size_t at, Command cmd, Cycle now) {
  check_one_command(now);
  start(at, cmd, now);
  const sdram::Address& a = accesses_[at].request.address;
  if (cmd == Command::kAct) {
    activate(a, now);
  } else {
    precharge(a, now);  // a conflict: the bank has another row open
  }
  ahead_known_ = false;  // the banks changed
}

// The oldest request's READ, or RDA (auto precharge) when no other pending
// request wants its row and the table allows RDA now (Controller::schedule).
// It completes the request's commands: the request moves to in flight.
VOXCAST_HOT_INLINE void FastLookAheadPort::column_command(Cycle now) {
  check_one_command(now);
  const std::size_t head = pending_head_;
  start(head, Command::kRd, now);
  const sdram::Address& a = accesses_[head].request.address;
  const bool rda =
      auto_precharge_ && !row_wanted_by_another() && earliest(Command::kRda, a.bank) <= now;
  const Command cmd = rda ? Command::kRda : Command::kRd;
  not_before_.raise(cmd, a.bank, now);
  if (rda) {
    // The row closes where its internal precharge starts (Dimm::apply).
    ++cs_.auto_precharges;
    ++ds_.banks[a.bank].auto_precharges;
    close(a.bank, now + read_to_precharge_);
  }
  --pending_per_bank_[a.bank];
  read_issued(cmd, now);  // the request moves to in flight
  ahead_known_ = false;   // the queue changed
}

// Another pending request wants the oldest request's row (the reference asks
// every pending request, not only the window).
VOXCAST_HOT_INLINE bool FastLookAheadPort::row_wanted_by_another() const {
  const sdram::Address& a = accesses_[pending_head_].request.address;
  for (std::size_t j = 1; j < pending_count_; ++j) {
    const sdram::Address& b = accesses_[pending_at(j)].request.address;
    if (b.bank == a.bank && b.row == a.row) return true;
  }
  return false;
}

// Controller::next_event with LookAheadActivation::wake: the next REF due
// (while the sequence runs, the next cycle: next_refresh() is then kNever), the
// oldest in-flight access's last beat, the oldest request's next command
// (its column command only with a free return slot), and the row command of
// the one later request the policy would prepare. When the wake is the next
// cycle already, the window is not walked for it: waking early only costs a
// tick that issues nothing (in a row-hit stream the oldest request's next
// READ is at the next cycle, and the walk was a third of the port's work).
VOXCAST_HOT_INLINE Cycle FastLookAheadPort::next_wake(Cycle now) {
  Cycle w = next_retire(next_refresh());
  if (pending_count_ != 0) {
    const sdram::Address& a = accesses_[pending_head_].request.address;
    const Command oldest = next_command(a);
    if (oldest != Command::kRd || column_allowed()) w = std::min(w, earliest(oldest, a.bank));
    if (w > now + 1) {  // (at now + 1 anyway: the walk can wait for that tick)
      const std::size_t ahead = look_ahead();
      if (ahead != kNone)
        w = std::min(w, earliest(ahead_cmd_, accesses_[ahead].request.address.bank));
    }
  }
  return std::max(w, now + 1);
}

#undef VOXCAST_HOT_INLINE

// One tick: its helpers above are inlined into it (it runs at about every
// other SDRAM cycle of a frame, and a call per helper cost more than most of
// their bodies).
void FastLookAheadPort::step(Cycle now) {
  ++cs_.cycles;
  if (refresh_due(now)) [[unlikely]] {            // EagerRefresh: as soon as due
    if (step_refresh(now)) ahead_known_ = false;  // the banks changed
  } else if (pending_count_ != 0) {
    schedule(now);
  }
  if (retire_due(now)) retire(now);
  completions_.sample();
  wake_ = next_wake(now);
}

}  // namespace voxcast::rtl::pipeline
