// One 64-bit SDRAM DIMM (one rank of internal banks) as a cycle-accurate
// command-level device model: per-bank state, the constraint table as the
// only source of timing, refresh bookkeeping, read/write data windows and
// statistics. It is the referee of every controller and scheduler: issue()
// rejects any illegal command with a message naming the command, bank,
// cycle and the violated rule.
//
// Contract:
//   - Commands arrive in strictly increasing cycles, at most one per clock
//     (the single command bus of SDR SDRAM). NOP is always legal and changes
//     nothing.
//   - earliest()/gate() answer timing only: the first cycle >= now at which
//     every row of the constraint table allows the command. can_issue() and
//     violation() add everything else: address range, bank state (ACT needs
//     an idle bank; RD/WR/RDA need the addressed row open; REF needs all banks
//     idle), the command bus, overdue refresh and tRAS(max).
//   - PRE to an idle bank (or PREA with no bank open) is legal, as in the
//     datasheet's truth table (it acts as a NOP there); the model still times
//     it as a precharge, which is conservative.
//   - issue() changes nothing when it throws.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "rtl_model/sdram/command.hpp"
#include "rtl_model/sdram/geometry.hpp"
#include "rtl_model/sdram/not_before.hpp"
#include "rtl_model/sdram/observer.hpp"
#include "rtl_model/sdram/refresh.hpp"
#include "rtl_model/sdram/timing.hpp"
#include "rtl_model/sim/clock.hpp"

namespace voxcast::rtl::sdram {

struct DimmConfig {
  Geometry geometry = geometries::mt4lsdt864a();
  TimingNs timing = presets::pc100_cl2();
  sim::ClockDomain clock = sim::clocks::pc100();
  // Mode-register burst length. VIZARD II reads one 64-bit word per DIMM per
  // sample (four DIMMs give the 2x2x2 neighbourhood): BL 1.
  int burst_length = 1;
  // REFs that may be postponed beyond the one due (see refresh.hpp).
  int refresh_postpone_limit = 0;
};

std::ostream& operator<<(std::ostream& os, const DimmConfig& c);

enum class BankState : std::uint8_t { kIdle, kActive };

struct Bank {
  BankState state = BankState::kIdle;
  std::uint32_t open_row = 0;   // valid when active
  Cycle activated_at = kNever;  // the ACT that opened the row
};

std::ostream& operator<<(std::ostream& os, const Bank& b);

// How a request's row meets its bank.
enum class RowOutcome : std::uint8_t {
  kHit,       // the row is open
  kMiss,      // the bank is idle: ACT first
  kConflict,  // another row is open: PRE, then ACT
};

std::ostream& operator<<(std::ostream& os, RowOutcome o);

// The command a request meets first: its column command on a hit, ACT on a
// miss, PRE on a conflict.
constexpr Command first_command(RowOutcome o, Command column_command) {
  switch (o) {
    case RowOutcome::kHit:
      return column_command;
    case RowOutcome::kMiss:
      return Command::kAct;
    case RowOutcome::kConflict:
      return Command::kPre;
  }
  return Command::kNop;
}

// Cycles at which data beats are on the DQ bus, inclusive.
struct DataWindow {
  Cycle first = 0;
  Cycle last = 0;
};

std::ostream& operator<<(std::ostream& os, const DataWindow& w);

// The earliest cycle a command may be issued and the constraint that binds
// there (none when only `now` binds). For DDR4's tFAW the binding constraint
// is ConstraintTable::four_activate_window() and `since` the 4th-last ACT.
struct Gate {
  Cycle earliest = 0;
  const Constraint* binding = nullptr;
  Cycle since = kNever;          // cycle of the binding previous command
  std::uint32_t since_bank = 0;  // its bank (bank commands)
};

struct Issued {
  Command command = Command::kNop;
  Address address;
  Cycle cycle = 0;
  // RD: CL later; WR: from the command (SDR) or CWL later (DDR4); for
  // burst_cycles() clocks.
  std::optional<DataWindow> data;
};

std::ostream& operator<<(std::ostream& os, const Issued& i);

struct BankStats {
  std::uint64_t activates = 0;
  std::uint64_t reads = 0;
  std::uint64_t writes = 0;
  std::uint64_t precharges = 0;  // rows closed, by PRE, PREA or RDA
  std::uint64_t auto_precharges = 0;  // rows closed by RDA (in precharges too)
  Cycle open_cycles = 0;         // cycles with a row open (closed rows only)
};

struct DimmStats {
  std::vector<BankStats> banks;
  std::uint64_t commands = 0;  // excluding NOP
  std::uint64_t precharge_alls = 0;
  std::uint64_t refreshes = 0;     // every REF refreshes a row in every bank
  Cycle data_bus_busy_cycles = 0;  // clocks with data on the bus (SDR: beats; DDR: beats / 2)
  Cycle refresh_busy_cycles = 0;   // tRFC per REF

  BankStats total() const;
};

std::ostream& operator<<(std::ostream& os, const DimmStats& s);

class Dimm {
 public:
  // Throws voxcast::Error for an invalid geometry, a grade that cannot run at
  // the clock, or a postponement limit that would let an open row exceed
  // tRAS(max) between two refreshes.
  explicit Dimm(DimmConfig config);

  const DimmConfig& config() const { return config_; }
  const Geometry& geometry() const { return config_.geometry; }
  const TimingCycles& timing() const { return timing_; }
  const ConstraintTable& constraints() const { return table_; }
  const RefreshTracker& refresh() const { return refresh_; }
  const DimmStats& stats() const { return stats_; }
  const Bank& bank(std::uint32_t b) const { return banks_.at(b); }
  std::uint32_t bank_count() const { return config_.geometry.banks; }
  bool all_banks_idle() const { return open_banks_ == 0; }
  Cycle last_command_cycle() const { return last_command_; }
  // Told of every accepted command (a trace); nullptr: none.
  void set_observer(CommandObserver* o) { observer_ = o; }

  // Timing only (see the contract). `bank` is ignored for PREA and REF.
  // earliest() is one look-up in the table compiled as commands issue (see
  // NotBefore, not_before.hpp); gate() scans the table and names the binding row for
  // messages. Both give the same cycle (tests/rtl/test_sdram_dimm.cpp).
  Cycle earliest(Command cmd, std::uint32_t bank, Cycle now) const {
    if (cmd == Command::kNop) return now;
    if (!is_rank_command(cmd) && bank >= bank_count()) no_such_bank(cmd, bank);
    return std::max(now, not_before_.at(cmd, bank));
  }
  Gate gate(Command cmd, std::uint32_t bank, Cycle now) const;

  // Full legality at `now`.
  bool can_issue(Command cmd, const Address& a, Cycle now) const {
    return first_broken(cmd, a, now) == Rule::kNone;
  }
  // Why `cmd` is illegal at `now`, or nothing when it is legal.
  std::optional<std::string> violation(Command cmd, const Address& a, Cycle now) const;
  // Issues the command; throws voxcast::Error with violation()'s message.
  Issued issue(Command cmd, const Address& a, Cycle now);

  // Request-level queries for controllers (Ramulator's "prerequisite
  // command"): the row outcome, and the next command a read or write of `a`
  // needs now (ACT, PRE, or the column command itself).
  RowOutcome row_outcome(const Address& a) const {
    const Bank& k = banks_.at(a.bank);
    if (k.state == BankState::kIdle) return RowOutcome::kMiss;
    return k.open_row == a.row ? RowOutcome::kHit : RowOutcome::kConflict;
  }
  Command next_command(Command column_command, const Address& a) const {
    if (!is_column_command(column_command)) not_a_column_command(column_command);
    return first_command(row_outcome(a), column_command);
  }

 private:
  // The rules of the contract in the order they are checked; the first one a
  // command breaks names it in violation()'s message.
  enum class Rule : std::uint8_t {
    kNone,        // legal
    kNoSuchBank,  // step 1: the address exists
    kNoSuchRow,
    kNoSuchColumn,
    kCommandBus,      // step 2: one command per clock, in order
    kRefreshOverdue,  // step 3: refresh in time ...
    kRowOpenTooLong,  // ... and no row open beyond tRAS(max)
    kBankState,       // step 4: the bank state allows the command
    kTiming,          // step 5: the constraint table
  };

  // The legality test of every command (the referee runs it at least once
  // per command): comparisons only, no strings; explain() builds the message
  // for the rule it returns.
  Rule first_broken(Command cmd, const Address& a, Cycle now) const {
    if (cmd == Command::kNop) return Rule::kNone;
    const Geometry& g = config_.geometry;
    if (!is_rank_command(cmd)) {
      if (a.bank >= g.banks) return Rule::kNoSuchBank;
      if ((cmd == Command::kAct || is_column_command(cmd)) && a.row >= g.rows)
        return Rule::kNoSuchRow;
      if (is_column_command(cmd) && a.column >= g.columns) return Rule::kNoSuchColumn;
    }
    if (now <= last_command_) return Rule::kCommandBus;
    if (refresh_.overdue(now)) return Rule::kRefreshOverdue;
    // The oldest open row is the first to exceed tRAS(max).
    if (now - oldest_activation_ > timing_.tRAS_max) return Rule::kRowOpenTooLong;
    if (!state_allows(cmd, a)) return Rule::kBankState;
    if (earliest(cmd, a.bank, now) > now) return Rule::kTiming;
    return Rule::kNone;
  }
  // Step 4 of first_broken(); state_violation() says why not.
  bool state_allows(Command cmd, const Address& a) const {
    switch (cmd) {
      case Command::kAct:
        return banks_[a.bank].state == BankState::kIdle;
      case Command::kRd:
      case Command::kWr:
      case Command::kRda:
        return banks_[a.bank].state == BankState::kActive && banks_[a.bank].open_row == a.row;
      case Command::kRef:
        return open_banks_ == 0;
      case Command::kNop:
      case Command::kPre:
      case Command::kPrea:
        return true;
    }
    return true;
  }
  // The messages (built only for an illegal command).
  std::string explain(Rule rule, Command cmd, const Address& a, Cycle now) const;
  std::string state_violation(Command cmd, const Address& a) const;
  void apply(Command cmd, const Address& a, Cycle now);
  void close_row(std::uint32_t b, Cycle now);
  // open_banks_ and oldest_activation_ from banks_ (after a row closed).
  void summarize_open_rows();
  void check_bank_exists(Command cmd, std::uint32_t bank) const;
  [[noreturn]] void no_such_bank(Command cmd, std::uint32_t bank) const;
  [[noreturn]] static void not_a_column_command(Command cmd);

  DimmConfig config_;
  TimingCycles timing_;
  ConstraintTable table_;
  RefreshTracker refresh_;
  std::vector<Bank> banks_;
  // Summaries of banks_ for the checks of every command: the banks with a
  // row open, and the earliest activated_at among them (kNoOpenRow: none).
  static constexpr Cycle kNoOpenRow = std::numeric_limits<Cycle>::max() / 4;
  std::uint32_t open_banks_ = 0;
  Cycle oldest_activation_ = kNoOpenRow;
  // Cycle of the last command of each kind per bank (ACT, RD, WR, PRE) and
  // for the rank (PREA, REF).
  std::vector<std::array<Cycle, kCommandCount>> last_by_bank_;
  std::array<Cycle, kCommandCount> last_by_rank_;
  // DDR4's four-activate window: the last four ACTs (cycle, bank), a ring
  // whose entry activates_[oldest_activate_] is the 4th-last.
  struct Activate {
    Cycle cycle = kNever;
    std::uint32_t bank = 0;
  };
  std::array<Activate, ConstraintTable::kActivatesPerWindow> activates_{};
  std::size_t oldest_activate_ = 0;
  Cycle last_command_ = kNever;
  // Per bank and command (and for the rank commands) the first cycle every
  // row issued so far allows: the simulation asks earliest() several times
  // per cycle per DIMM.
  NotBefore not_before_;
  DimmStats stats_;
  CommandObserver* observer_ = nullptr;
};

// "RD to bank 2 row 7 col 12", "PREA", ...
std::string describe(Command cmd, const Address& a);

}  // namespace voxcast::rtl::sdram
