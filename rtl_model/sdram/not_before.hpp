// The constraint table (timing.hpp) compiled for a simulation that asks "when
// may this command go?" far more often than commands issue: per bank and
// command (and for the rank commands) the first cycle that every row issued
// so far allows. Issuing a command raises those cycles; asking is one look-up.
// DDR4's bank groups split "other bank" into the same and another group.
// The Dimm (dimm.hpp) and the event-driven memory ports
// (pipeline/event_driven_port.hpp) keep their timing in one of these.
//
// Contract: after raise(p, b, t) for every command issued so far, at(cmd, bank)
// is the largest (t + delay) over the table's rows (p -> cmd) whose scope
// couples b with bank, read as Dimm::gate reads them: a rank command (PREA,
// REF) on either side binds every bank, and a rank command after a bank
// command sees every bank as "other". Rows that do not apply leave the
// initial cycle. With a four-activate window (DDR4 tFAW), at(ACT, bank) is
// also at least the 4th-last ACT's cycle + tFAW. tests/rtl/test_sdram_dimm.cpp
// and test_sdram_ddr4.cpp check Dimm::earliest against the table scan
// (Dimm::gate) on random legal sequences.
//
// What makes raise() cheap: the rows of one previous command are folded when
// the table is compiled into, per later command, the largest delay for the
// command's own bank and for the other banks (max(t + a, t + b) = t + max(a, b)),
// and a delay that binds every bank alike raises one rank-wide cycle, which
// at() combines with the bank's own: a READ raises 5 cycles instead of
// walking its rows and their scopes bank by bank. The folded rows are then
// expanded per issuing command and bank into a flat list of (cycle, delay)
// steps over one array of cycles, so raise() is one loop of maxima without
// a branch on the row's kind or the bank (it runs for every command of a
// frame: about 10% of the cycle model's instructions before the expansion).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <initializer_list>
#include <vector>

#include "rtl_model/sdram/timing.hpp"

namespace voxcast::rtl::sdram {

class NotBefore {
 public:
  // Bit index_of(c) set: at(c, ...) is asked (kAllCommandsAsked: every command).
  using CommandSet = std::uint32_t;
  static constexpr CommandSet kAllCommandsAsked = (1u << kCommandCount) - 1u;
  static constexpr CommandSet asked(std::initializer_list<Command> commands) {
    CommandSet s = 0;
    for (const Command c : commands) s |= 1u << index_of(c);
    return s;
  }

  // Every bank and rank cycle starts at `initial` (kNever: no command yet).
  // `bank_groups` divides `banks` (group g: banks g * banks / bank_groups on).
  // Only the commands in `asked` may be asked of at(): a controller that
  // never issues WR or RDA (the in-order read port) keeps no cycles for them,
  // and raise() does less per command.
  NotBefore(const ConstraintTable& table, std::uint32_t banks, Cycle initial,
            std::uint32_t bank_groups = 1, CommandSet asked = kAllCommandsAsked)
      : banks_(banks), group_(banks), asked_(asked), cycles_((banks + 2) * kCommandCount, initial) {
    for (std::uint32_t b = 0; b < banks; ++b) group_[b] = b / (banks / bank_groups);
    if (const Constraint* w = table.four_activate_window()) faw_ = w->cycles;
    activates_.fill(kNever);
    // Fold the rows by previous command: per later command the delay to the
    // issuing bank, to the other banks of its group, to the banks of the
    // other groups, and to a rank command.
    struct Fold {
      Cycle own = kNone, group = kNone, other = kNone, rank = kNone;
    };
    std::array<std::array<Fold, kCommandCount>, kCommandCount> fold{};
    for (const Constraint& c : table.rows()) {
      const bool rank = is_rank_command(c.prev);
      Fold& f = fold[index_of(c.prev)][index_of(c.next)];
      const auto raise_to = [&](Cycle& to) { to = std::max(to, c.cycles); };
      if (is_rank_command(c.next)) {
        if (rank || c.scope != Scope::kSameBank) raise_to(f.rank);
        continue;
      }
      // A rank command is issued with bank 0: it binds every bank alike.
      const Scope scope = rank ? Scope::kAnyBank : c.scope;
      const bool own =
          scope == Scope::kSameBank || scope == Scope::kAnyBank || scope == Scope::kSameBankGroup;
      const bool group =
          scope == Scope::kOtherBank || scope == Scope::kAnyBank || scope == Scope::kSameBankGroup;
      const bool other =
          scope == Scope::kOtherBank || scope == Scope::kAnyBank || scope == Scope::kOtherBankGroup;
      if (own) raise_to(f.own);
      if (group) raise_to(f.group);
      if (other) raise_to(f.other);
    }
    for (std::size_t p = 0; p < kCommandCount; ++p)
      for (std::size_t n = 0; n < kCommandCount; ++n) {
        const Fold& f = fold[p][n];
        if (f.rank != kNone) after_[p].push_back(Entry{Kind::kRank, n, f.rank, kNone, kNone});
        if (f.own == kNone && f.group == kNone && f.other == kNone) continue;
        const Kind k = f.own == f.group && f.group == f.other ? Kind::kEveryBank
                       : f.group == kNone && f.other == kNone ? Kind::kOwnBank
                                                              : Kind::kPerBank;
        after_[p].push_back(Entry{k, n, f.own, f.group, f.other});
      }
    expand_steps();
  }

  // The first cycle `cmd` to `bank` is allowed by the commands issued so far
  // (the initial cycle if none binds); `bank` is ignored for rank commands.
  Cycle at(Command cmd, std::uint32_t bank) const {
    const std::size_t n = index_of(cmd);
    if (is_rank_command(cmd)) return cycles_[rank_index(n)];
    const Cycle own = cycles_[bank_index(bank, n)], every = cycles_[every_index(n)];
    const Cycle c = own < every ? every : own;
    if (cmd != Command::kAct || faw_ == 0) return c;
    return std::max(c, activates_[oldest_] + faw_);
  }

  // `cmd` to `bank` issued at `now` (bank 0 for a rank command).
  void raise(Command cmd, std::uint32_t bank, Cycle now) {
    if (cmd == Command::kAct && faw_ != 0) {  // the 4th-last ACT moves on
      activates_[oldest_] = now;
      oldest_ = (oldest_ + 1) % activates_.size();
    }
    const std::size_t list = index_of(cmd) * banks_ + bank;
    Cycle* const cycles = cycles_.data();
    for (std::uint32_t i = first_step_[list]; i < first_step_[list + 1]; ++i) {
      // Values, not references, so that the maxima compile to conditional
      // moves: which way they go is data, and a branch would mispredict often.
      const Step st = steps_[i];
      const Cycle cur = cycles[st.index], v = now + st.delay;
      cycles[st.index] = cur < v ? v : cur;
    }
  }

 private:
  // "No row": below every cycle a command can be allowed at, also after a
  // cycle is added to it (kNever is min / 4, this min / 2).
  static constexpr Cycle kNone = kNever * 2;
  // How one later command's delays after one previous command reach the
  // banks. Most rows bind every bank alike (the data bus, the rank commands),
  // so they raise one rank-wide cycle instead of one per bank.
  enum class Kind : std::uint8_t {
    kRank,       // the later command is PREA or REF: own is its delay
    kEveryBank,  // every bank, own = group = other
    kOwnBank,    // the issuing bank only (own)
    kPerBank,    // own to the issuing bank, group to the rest of its bank
                 // group, other to the other groups (any may be kNone)
  };
  struct Entry {
    Kind kind;
    std::size_t next;  // the later command
    Cycle own, group, other;
  };

  // One raise: cycles_[index] up to (the command's cycle + delay).
  struct Step {
    std::uint32_t index;
    Cycle delay;
  };

  // cycles_ holds, per bank and command, the bank's own cycle, then per
  // command the cycle that binds every bank, then the rank commands' cycles.
  std::size_t bank_index(std::uint32_t bank, std::size_t cmd) const {
    return bank * kCommandCount + cmd;
  }
  std::size_t every_index(std::size_t cmd) const { return banks_ * kCommandCount + cmd; }
  std::size_t rank_index(std::size_t cmd) const { return (banks_ + 1) * kCommandCount + cmd; }

  // The folded rows (after_) as steps per issuing command and bank, in the
  // order raise() walked them. A kNone delay raised nothing (kNone + now
  // stays below every cycle) and is left out, and so is a later command
  // nobody asks for. A per-bank row that gives every other bank the same
  // delay x, and the issuing bank at least x, raises the every-bank cycle
  // by x and the issuing bank's by its own (at() takes the larger of the
  // two): ACT -> ACT (tRC, tRRD) is two steps instead of one per bank.
  void expand_steps() {
    first_step_.clear();
    steps_.clear();
    for (std::size_t p = 0; p < kCommandCount; ++p)
      for (std::uint32_t bank = 0; bank < banks_; ++bank) {
        first_step_.push_back(static_cast<std::uint32_t>(steps_.size()));
        std::size_t next = 0;  // the later command of the entry being expanded
        auto add = [this, &next](std::size_t index, Cycle delay) {
          if (delay == kNone || (asked_ >> next & 1u) == 0) return;
          steps_.push_back(Step{static_cast<std::uint32_t>(index), delay});
        };
        for (const Entry& e : after_[p]) {
          next = e.next;
          switch (e.kind) {
            case Kind::kRank:
              add(rank_index(e.next), e.own);
              break;
            case Kind::kEveryBank:
              add(every_index(e.next), e.own);
              break;
            case Kind::kOwnBank:
              add(bank_index(bank, e.next), e.own);
              break;
            case Kind::kPerBank: {
              auto delay = [&](std::uint32_t b) {
                return b == bank ? e.own : group_[b] == group_[bank] ? e.group : e.other;
              };
              const Cycle others = banks_ > 1 ? delay(bank == 0 ? 1 : 0) : kNone;
              bool common = banks_ > 1;
              for (std::uint32_t b = 0; b < banks_ && common; ++b)
                common = b == bank || delay(b) == others;
              if (common && others != kNone && e.own >= others) {
                add(every_index(e.next), others);
                if (e.own > others) add(bank_index(bank, e.next), e.own);
                break;
              }
              for (std::uint32_t b = 0; b < banks_; ++b) add(bank_index(b, e.next), delay(b));
              break;
            }
          }
        }
      }
    first_step_.push_back(static_cast<std::uint32_t>(steps_.size()));
  }

  std::uint32_t banks_;
  std::vector<std::uint32_t> group_;  // [bank] its bank group
  CommandSet asked_;
  Cycle faw_ = 0;                     // tFAW; 0: no four-activate window
  // The last four ACTs' cycles, a ring: activates_[oldest_] is the 4th-last.
  std::array<Cycle, ConstraintTable::kActivatesPerWindow> activates_{};
  std::size_t oldest_ = 0;
  std::array<std::vector<Entry>, kCommandCount> after_;  // by previous command
  std::vector<Step> steps_;                // expand_steps(): by issuing command and bank
  std::vector<std::uint32_t> first_step_;  // [command * banks + bank]: its first step
  std::vector<Cycle> cycles_;              // [bank_index], [every_index], [rank_index]
};

}  // namespace voxcast::rtl::sdram
