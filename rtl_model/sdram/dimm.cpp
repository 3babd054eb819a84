#include "rtl_model/sdram/dimm.hpp"

#include <algorithm>
#include <ostream>
#include <sstream>
#include <utility>

#include "refmodel/error.hpp"

namespace voxcast::rtl::sdram {

// ---- Printing ----------------------------------------------------------------------------
std::string describe(Command cmd, const Address& a) {
  std::ostringstream os;
  os << cmd;
  switch (cmd) {
    case Command::kAct:
      os << " to bank " << a.bank << " row " << a.row;
      break;
    case Command::kRd:
    case Command::kWr:
    case Command::kRda:
      os << " to bank " << a.bank << " row " << a.row << " col " << a.column;
      break;
    case Command::kPre:
      os << " to bank " << a.bank;
      break;
    case Command::kNop:
    case Command::kPrea:
    case Command::kRef:
      break;
  }
  return os.str();
}

std::ostream& operator<<(std::ostream& os, const DimmConfig& c) {
  return os << c.geometry << "; " << c.timing.name << " [" << c.timing.part << "] at " << c.clock
            << "; BL " << c.burst_length << "; refresh postpone limit " << c.refresh_postpone_limit;
}

std::ostream& operator<<(std::ostream& os, const Bank& b) {
  if (b.state == BankState::kIdle) return os << "idle";
  return os << "active, row " << b.open_row << " open since cycle " << b.activated_at;
}

std::ostream& operator<<(std::ostream& os, RowOutcome o) {
  switch (o) {
    case RowOutcome::kHit:
      return os << "hit";
    case RowOutcome::kMiss:
      return os << "miss";
    case RowOutcome::kConflict:
      return os << "conflict";
  }
  return os << "?";
}

std::ostream& operator<<(std::ostream& os, const DataWindow& w) {
  return os << "data cycles " << w.first << ".." << w.last;
}

std::ostream& operator<<(std::ostream& os, const Issued& i) {
  os << describe(i.command, i.address) << " at cycle " << i.cycle;
  if (i.data) os << ", " << *i.data;
  return os;
}

BankStats DimmStats::total() const {
  BankStats t;
  for (const BankStats& b : banks) {
    t.activates += b.activates;
    t.reads += b.reads;
    t.writes += b.writes;
    t.precharges += b.precharges;
    t.auto_precharges += b.auto_precharges;
    t.open_cycles += b.open_cycles;
  }
  return t;
}

std::ostream& operator<<(std::ostream& os, const DimmStats& s) {
  const BankStats t = s.total();
  os << s.commands << " commands: " << t.activates << " ACT, " << t.reads << " RD, " << t.writes
     << " WR, " << t.precharges << " rows closed (" << s.precharge_alls << " PREA, "
     << t.auto_precharges << " by RDA), " << s.refreshes
     << " REF; data bus busy " << s.data_bus_busy_cycles << " cycles, refresh busy "
     << s.refresh_busy_cycles << " cycles";
  for (std::size_t b = 0; b < s.banks.size(); ++b) {
    const BankStats& k = s.banks[b];
    os << "\n  bank " << b << ": " << k.activates << " ACT, " << k.reads << " RD, " << k.writes
       << " WR, " << k.precharges << " closed, open " << k.open_cycles << " cycles";
  }
  return os;
}

// ---- Construction ------------------------------------------------------------------------
namespace {
const Geometry& validated(const Geometry& g) {
  if (g.banks == 0 || g.rows == 0 || g.columns == 0 || g.bus_bits == 0 || g.bus_bits % 8 != 0 ||
      g.bank_groups == 0 || g.banks % g.bank_groups != 0) {
    std::ostringstream os;
    os << "DIMM geometry '" << g.module << "' is invalid: " << g;
    throw Error(os.str());
  }
  return g;
}
}  // namespace

Dimm::Dimm(DimmConfig config)
    : config_(std::move(config)),
      timing_(to_cycles(config_.timing, config_.clock, config_.burst_length)),
      table_(timing_),
      refresh_(timing_.tREFI, config_.refresh_postpone_limit),
      banks_(validated(config_.geometry).banks),
      last_by_bank_(config_.geometry.banks),
      not_before_(table_, config_.geometry.banks, kNever, config_.geometry.bank_groups) {
  for (auto& last : last_by_bank_) last.fill(kNever);
  last_by_rank_.fill(kNever);
  stats_.banks.resize(config_.geometry.banks);
  // An open-page controller may leave a row open from just after one REF to
  // the next, which can come as late as the refresh deadline: that span must
  // stay within tRAS(max).
  const Cycle longest_open = (2 + config_.refresh_postpone_limit) * timing_.tREFI;
  if (longest_open > timing_.tRAS_max) {
    std::ostringstream os;
    os << "refresh postpone limit " << config_.refresh_postpone_limit << " lets a row stay open "
       << longest_open << " cycles between refreshes, beyond tRAS(max) = " << timing_.tRAS_max
       << " cycles";
    throw Error(os.str());
  }
}

// ---- Timing: the constraint table --------------------------------------------------------
void Dimm::check_bank_exists(Command cmd, std::uint32_t bank) const {
  if (is_rank_command(cmd) || bank < bank_count()) return;
  no_such_bank(cmd, bank);
}

void Dimm::no_such_bank(Command cmd, std::uint32_t bank) const {
  std::ostringstream os;
  os << cmd << ": bank " << bank << " does not exist (the DIMM has " << bank_count() << " banks)";
  throw Error(os.str());
}

void Dimm::not_a_column_command(Command cmd) {
  throw Error("Dimm::next_command: " + std::string(name(cmd)) + " is not a column command");
}

Gate Dimm::gate(Command cmd, std::uint32_t bank, Cycle now) const {
  Gate g{.earliest = now};
  if (cmd == Command::kNop) return g;
  const bool rank_cmd = is_rank_command(cmd);
  check_bank_exists(cmd, bank);
  const Geometry& geo = config_.geometry;
  // Does a row of scope `scope` couple a previous command on bank b with this one?
  const auto couples = [&](Scope scope, std::uint32_t b) {
    const bool same = !rank_cmd && b == bank;
    const bool same_group = !rank_cmd && geo.group_of(b) == geo.group_of(bank);
    switch (scope) {
      case Scope::kSameBank:
        return same;
      case Scope::kOtherBank:
        return !same;
      case Scope::kAnyBank:
        return true;
      case Scope::kSameBankGroup:
        return same_group;
      case Scope::kOtherBankGroup:
        return !same_group;
    }
    return true;
  };
  for (std::size_t i : table_.rows_before(cmd)) {
    const Constraint& c = table_.rows()[i];
    auto consider = [&](Cycle prev_cycle, std::uint32_t prev_bank) {
      if (prev_cycle == kNever) return;
      const Cycle bound = prev_cycle + c.cycles;
      if (bound > g.earliest) g = Gate{bound, &c, prev_cycle, prev_bank};
    };
    if (is_rank_command(c.prev)) {
      consider(last_by_rank_[index_of(c.prev)], 0);
      continue;
    }
    for (std::uint32_t b = 0; b < bank_count(); ++b) {
      if (couples(c.scope, b)) consider(last_by_bank_[b][index_of(c.prev)], b);
    }
  }
  // DDR4 tFAW: the fifth ACT in any window of tFAW clocks is illegal.
  const Constraint* faw = table_.four_activate_window();
  const Activate& fourth_last = activates_[oldest_activate_];
  if (cmd == Command::kAct && faw != nullptr && fourth_last.cycle != kNever &&
      fourth_last.cycle + faw->cycles > g.earliest) {
    g = Gate{fourth_last.cycle + faw->cycles, faw, fourth_last.cycle, fourth_last.bank};
  }
  return g;
}

// ---- Legality ----------------------------------------------------------------------------
std::optional<std::string> Dimm::violation(Command cmd, const Address& a, Cycle now) const {
  const Rule rule = first_broken(cmd, a, now);
  if (rule == Rule::kNone) return std::nullopt;
  return explain(rule, cmd, a, now);
}

std::string Dimm::explain(Rule rule, Command cmd, const Address& a, Cycle now) const {
  std::ostringstream os;
  os << describe(cmd, a) << " at cycle " << now << ": ";
  const Geometry& g = config_.geometry;
  switch (rule) {
    case Rule::kNone:
      break;
    case Rule::kNoSuchBank:
      os << "no such bank (the DIMM has " << g.banks << ")";
      break;
    case Rule::kNoSuchRow:
      os << "no such row (a bank has " << g.rows << ")";
      break;
    case Rule::kNoSuchColumn:
      os << "no such column (a row has " << g.columns << ")";
      break;
    case Rule::kCommandBus:
      os << "the command bus already carried a command at cycle " << last_command_
         << " (one command per clock, in cycle order)";
      break;
    case Rule::kRefreshOverdue:
      os << "refresh overdue: " << refresh_.owed(now) << " REF owed (deadline was cycle "
         << refresh_.deadline() << "; " << refresh_ << ")";
      break;
    case Rule::kRowOpenTooLong:
      // The first bank over the limit, as a scan in bank order finds it.
      for (std::uint32_t b = 0; b < bank_count(); ++b) {
        const Bank& k = banks_[b];
        if (k.state == BankState::kActive && now - k.activated_at > timing_.tRAS_max) {
          os << "bank " << b << " has held row " << k.open_row << " open since cycle "
             << k.activated_at << ", beyond tRAS(max) = " << timing_.tRAS_max << " cycles";
          break;
        }
      }
      break;
    case Rule::kBankState:
      os << state_violation(cmd, a);
      break;
    case Rule::kTiming: {
      // The table scan names the binding row.
      const Gate gt = gate(cmd, a.bank, now);
      const Constraint& c = *gt.binding;
      if (&c == table_.four_activate_window()) {
        os << "violates " << c.parameter << " (" << ConstraintTable::kActivatesPerWindow
           << " ACTs since the ACT to bank " << gt.since_bank << " at cycle " << gt.since
           << ": a fifth needs " << c.cycles << " cycles after it; earliest cycle " << gt.earliest
           << ")";
        break;
      }
      os << "violates " << c.parameter << " (" << c.prev;
      if (!is_rank_command(c.prev)) os << " to bank " << gt.since_bank;
      os << " at cycle " << gt.since << ", " << c.scope << ", needs " << c.cycles
         << " cycles; earliest cycle " << gt.earliest << ")";
      break;
    }
  }
  return os.str();
}

std::string Dimm::state_violation(Command cmd, const Address& a) const {
  switch (cmd) {
    case Command::kAct: {
      const Bank& k = banks_[a.bank];
      return "bank " + std::to_string(a.bank) + " already has row " + std::to_string(k.open_row) +
             " open (precharge first)";
    }
    case Command::kRd:
    case Command::kWr:
    case Command::kRda: {
      const Bank& k = banks_[a.bank];
      if (k.state == BankState::kIdle)
        return "bank " + std::to_string(a.bank) + " is idle (no open row)";
      return "bank " + std::to_string(a.bank) + " has row " + std::to_string(k.open_row) +
             " open, not row " + std::to_string(a.row);
    }
    case Command::kRef:
      for (std::uint32_t b = 0; b < bank_count(); ++b) {
        if (banks_[b].state == BankState::kActive) {
          return "bank " + std::to_string(b) + " has row " + std::to_string(banks_[b].open_row) +
                 " open; AUTO REFRESH needs every bank precharged";
        }
      }
      break;
    case Command::kNop:
    case Command::kPre:
    case Command::kPrea:
      break;
  }
  return {};
}

// ---- Issue -------------------------------------------------------------------------------
Issued Dimm::issue(Command cmd, const Address& a, Cycle now) {
  // The message is built only for a rejected command: a string per command
  // cost more than the check.
  if (const Rule rule = first_broken(cmd, a, now); rule != Rule::kNone)
    throw Error(explain(rule, cmd, a, now));
  Issued issued;
  issued.command = cmd;
  issued.address = a;
  issued.cycle = now;
  if (cmd == Command::kNop) return issued;
  const Cycle burst = timing_.burst_cycles();
  if (is_read_command(cmd)) {
    // Data on the bus CL clocks after the READ, for a burst (SDR: one beat a
    // clock; DDR4: two, BL8 in 4 clocks, JESD79-4B READ timing).
    issued.data = DataWindow{now + timing_.CL, now + timing_.CL + burst - 1};
  } else if (cmd == Command::kWr) {
    // SDR: write latency 0, data-in registered with the WRITE and after it;
    // DDR4: CWL clocks after it.
    issued.data = DataWindow{now + timing_.CWL, now + timing_.CWL + burst - 1};
  }
  apply(cmd, a, now);
  if (observer_) observer_->on_command(cmd, a, now);
  return issued;
}

void Dimm::apply(Command cmd, const Address& a, Cycle now) {
  switch (cmd) {
    case Command::kAct:
      banks_[a.bank] = Bank{BankState::kActive, a.row, now};
      ++open_banks_;
      oldest_activation_ = std::min(oldest_activation_, now);
      ++stats_.banks[a.bank].activates;
      activates_[oldest_activate_] = Activate{now, a.bank};
      oldest_activate_ = (oldest_activate_ + 1) % activates_.size();
      break;
    case Command::kRd:
      ++stats_.banks[a.bank].reads;
      stats_.data_bus_busy_cycles += timing_.burst_cycles();
      break;
    case Command::kRda:
      // The row closes where its internal PRECHARGE starts; the bank takes no
      // other command for it (the table's RDA rows time what follows).
      ++stats_.banks[a.bank].reads;
      ++stats_.banks[a.bank].auto_precharges;
      stats_.data_bus_busy_cycles += timing_.burst_cycles();
      close_row(a.bank, now + timing_.read_to_precharge());
      break;
    case Command::kWr:
      ++stats_.banks[a.bank].writes;
      stats_.data_bus_busy_cycles += timing_.burst_cycles();
      break;
    case Command::kPre:
      if (banks_[a.bank].state == BankState::kActive) close_row(a.bank, now);
      break;
    case Command::kPrea:
      for (std::uint32_t b = 0; b < bank_count(); ++b) {
        if (banks_[b].state == BankState::kActive) close_row(b, now);
      }
      ++stats_.precharge_alls;
      break;
    case Command::kRef:
      ++stats_.refreshes;
      stats_.refresh_busy_cycles += timing_.tRFC;
      refresh_.on_refresh(now);
      break;
    case Command::kNop:
      return;
  }
  not_before_.raise(cmd, a.bank, now);
  if (is_rank_command(cmd)) {
    last_by_rank_[index_of(cmd)] = now;
  } else {
    last_by_bank_[a.bank][index_of(cmd)] = now;
  }
  last_command_ = now;
  ++stats_.commands;
}

void Dimm::close_row(std::uint32_t b, Cycle now) {
  stats_.banks[b].open_cycles += now - banks_[b].activated_at;
  ++stats_.banks[b].precharges;
  banks_[b].state = BankState::kIdle;
  summarize_open_rows();
}

void Dimm::summarize_open_rows() {
  open_banks_ = 0;
  oldest_activation_ = kNoOpenRow;
  for (const Bank& k : banks_) {
    if (k.state != BankState::kActive) continue;
    ++open_banks_;
    oldest_activation_ = std::min(oldest_activation_, k.activated_at);
  }
}

}  // namespace voxcast::rtl::sdram
