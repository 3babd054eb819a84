#include "rtl_model/pipeline/fast_lookahead_port.hpp"

#include <algorithm>
#include <sstream>

#include "refmodel/error.hpp"
#include "rtl_model/sdram/dimm.hpp"

namespace voxcast::rtl::pipeline {

using sdram::Command;
using sdram::RowOutcome;
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
    : t_(sdram::Dimm(with_few_banks(dimm)).timing()),  // the Dimm validates the configuration
      geometry_(dimm.geometry),
      // The commands the port asks the table about (it issues no WR).
      not_before_(sdram::ConstraintTable(t_), dimm.geometry.banks, 0, dimm.geometry.bank_groups,
                  sdram::NotBefore::asked({Command::kAct, Command::kRd, Command::kRda,
                                           Command::kPre, Command::kPrea, Command::kRef})),
      window_(static_cast<std::size_t>(std::max(reorder_window, 1))),
      auto_precharge_(controller.auto_precharge),
      postpone_limit_(dimm.refresh_postpone_limit),
      completions_("sdram.completions", controller.return_depth) {
  if (controller.queue_depth == 0) throw Error("Controller: request queue depth 0");
  refresh_due_ = static_cast<Cycle>(t_.tREFI);
  refresh_at_ = refresh_due_;
  overdue_at_ = static_cast<Cycle>(2 + postpone_limit_) * t_.tREFI;
  burst_ = t_.burst_cycles();
  burst_bytes_ = static_cast<std::uint64_t>(t_.BL) * geometry_.bytes_per_beat();
  data_first_ = t_.CL;
  read_to_precharge_ = t_.read_to_precharge();
  queue_depth_ = controller.queue_depth;
  accesses_.resize(controller.queue_depth + controller.return_depth);
  started_.resize(accesses_.size());
  row_key_.resize(accesses_.size());
  open_key_.assign(geometry_.banks, kClosed);
  activated_at_.assign(geometry_.banks, 0);
  pending_per_bank_.assign(geometry_.banks, 0);
  ring_size_ = accesses_.size();
  ds_.banks.resize(geometry_.banks);
}

void FastLookAheadPort::fail(const char* what, Cycle now) const {
  std::ostringstream os;
  os << "fast look-ahead controller at cycle " << now << ": " << what;
  throw Error(os.str());
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
  sdram::Completion& c = accesses_[at];
  const RowOutcome o = cmd == Command::kRd    ? RowOutcome::kHit
                       : cmd == Command::kAct ? RowOutcome::kMiss
                                              : RowOutcome::kConflict;
  c.outcome = o;
  c.first_command = now;
  ++(o == RowOutcome::kHit    ? cs_.row_hits
     : o == RowOutcome::kMiss ? cs_.row_misses
                              : cs_.row_conflicts);
  started_[at] = 1;
}

// ACT or PRE for the request at ring place `at` (schedule() checked the table).
void FastLookAheadPort::row_command(std::size_t at, Command cmd, Cycle now) {
  if (now <= last_command_) [[unlikely]]
    fail("two commands in one cycle", now);
  start(at, cmd, now);
  const sdram::Address& a = accesses_[at].request.address;
  not_before_.raise(cmd, a.bank, now);
  if (cmd == Command::kAct) {
    open_key_[a.bank] = key(a.bank, a.row);
    activated_at_[a.bank] = now;
    ++ds_.banks[a.bank].activates;
  } else {
    close(a.bank, now);  // a conflict: the bank has another row open
  }
  issued(cmd, a, now);
}

// The oldest request's READ, or RDA (auto precharge) when no other pending
// request wants its row and the table allows RDA now (Controller::schedule).
// It completes the request's commands: the request moves to in flight.
VOXCAST_HOT_INLINE void FastLookAheadPort::column_command(Cycle now) {
  if (now <= last_command_) [[unlikely]]
    fail("two commands in one cycle", now);
  const std::size_t head = pending_head_;
  start(head, Command::kRd, now);
  sdram::Completion& c = accesses_[head];
  const sdram::Address& a = c.request.address;
  const bool rda =
      auto_precharge_ && !row_wanted_by_another() && earliest(Command::kRda, a.bank) <= now;
  const Command cmd = rda ? Command::kRda : Command::kRd;
  not_before_.raise(cmd, a.bank, now);
  sdram::BankStats& bank = ds_.banks[a.bank];
  ++bank.reads;
  ds_.data_bus_busy_cycles += burst_;
  if (rda) {
    // The row closes where its internal precharge starts (Dimm::apply).
    ++cs_.auto_precharges;
    ++bank.auto_precharges;
    close(a.bank, now + read_to_precharge_);
  }
  ++cs_.reads;
  c.column_command = now;
  c.data = sdram::DataWindow{now + data_first_, now + data_first_ + burst_ - 1};
  issued(cmd, a, now);
  --pending_per_bank_[a.bank];
  pending_head_ = wrap(pending_head_ + 1);
  --pending_count_;
  ++flight_count_;
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

void FastLookAheadPort::close(std::uint32_t bank, Cycle closed_at) {
  if (open_key_[bank] == kClosed) [[unlikely]]
    fail("a row closed in an idle bank", closed_at);
  ds_.banks[bank].open_cycles += closed_at - activated_at_[bank];
  ++ds_.banks[bank].precharges;
  open_key_[bank] = kClosed;
}

// Every command's common accounting.
VOXCAST_HOT_INLINE void FastLookAheadPort::issued(Command cmd, const sdram::Address& a, Cycle now) {
  last_command_ = now;
  ahead_known_ = false;  // the queue or the banks changed
  ++ds_.commands;
  ++cs_.command_cycles;
  ++activity_;
  if (observer_) observer_->on_command(cmd, a, now);
}

// The accesses whose last data beat is at or before `now` (at least one).
VOXCAST_HOT_INLINE void FastLookAheadPort::retire(Cycle now) {
  do {
    const sdram::Completion& c = accesses_[flight_head_];
    ++cs_.completed;
    ++activity_;
    cs_.bytes += burst_bytes_;
    const Cycle latency = c.latency();
    cs_.latency_sum += latency;
    cs_.latency_max = std::max(cs_.latency_max, latency);
    completions_.push_copy(c);
    flight_head_ = wrap(flight_head_ + 1);
    --flight_count_;
  } while (flight_count_ != 0 && accesses_[flight_head_].data.last <= now);
}

// Controller::next_event with LookAheadActivation::wake: the next REF due
// (while the sequence runs, the next cycle: refresh_at_ is then kNever), the
// oldest in-flight access's last beat, the oldest request's next command
// (its column command only with a free return slot), and the row command of
// the one later request the policy would prepare. When the wake is the next
// cycle already, the window is not walked for it: waking early only costs a
// tick that issues nothing (in a row-hit stream the oldest request's next
// READ is at the next cycle, and the walk was a third of the port's work).
VOXCAST_HOT_INLINE Cycle FastLookAheadPort::next_wake(Cycle now) {
  Cycle w = refresh_at_;
  if (flight_count_ != 0) w = std::min(w, accesses_[flight_head_].data.last);
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

bool FastLookAheadPort::all_closed() const {
  return std::all_of(open_key_.begin(), open_key_.end(),
                     [](std::uint64_t k) { return k == kClosed; });
}

// The refresh sequence (EagerRefresh): close every row, then REF; its cycles
// are counted while it waits.
void FastLookAheadPort::step_refresh(Cycle now) {
  if (now >= overdue_at_) fail("refresh overdue", now);
  refresh_at_ = sdram::kNever;  // every tick until the REF
  ++cs_.refresh_cycles;
  const Command cmd = all_closed() ? Command::kRef : Command::kPrea;
  if (earliest(cmd, 0) <= now) {
    issue_rank_command(cmd, now);
    if (cmd == Command::kRef) refresh_at_ = refresh_due_;
  }
}

void FastLookAheadPort::issue_rank_command(Command cmd, Cycle now) {
  if (now <= last_command_) fail("two commands in one cycle", now);
  not_before_.raise(cmd, 0, now);
  if (cmd == Command::kPrea) {
    for (std::uint32_t b = 0; b < geometry_.banks; ++b)
      if (open_key_[b] != kClosed) close(b, now);
    ++ds_.precharge_alls;
  } else {
    if (!all_closed()) fail("REF with a row open", now);
    ++ds_.refreshes;
    ds_.refresh_busy_cycles += t_.tRFC;
    ++refreshes_;
    refresh_due_ = (refreshes_ + 1) * t_.tREFI;
    overdue_at_ = (refreshes_ + 2 + postpone_limit_) * t_.tREFI;
  }
  issued(cmd, sdram::Address{}, now);
}

void FastLookAheadPort::expect_drained() const {
  if (pending_count_ != 0 || flight_count_ != 0) {
    std::ostringstream os;
    os << "controller: " << pending_count_ << " request(s) pending and " << flight_count_
       << " access(es) in flight at the end";
    throw Error(os.str());
  }
  completions_.expect_drained();
}

#undef VOXCAST_HOT_INLINE

// One tick: its helpers above are inlined into it (it runs at about every
// other SDRAM cycle of a frame, and a call per helper cost more than most of
// their bodies).
void FastLookAheadPort::step(Cycle now) {
  ++cs_.cycles;
  if (now >= refresh_at_) [[unlikely]] {  // EagerRefresh: as soon as due
    step_refresh(now);
  } else if (pending_count_ != 0) {
    schedule(now);
  }
  if (flight_count_ != 0 && accesses_[flight_head_].data.last <= now) retire(now);
  completions_.sample();
  wake_ = next_wake(now);
}

}  // namespace voxcast::rtl::pipeline
