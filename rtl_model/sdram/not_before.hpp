// The constraint table (timing.hpp) compiled for a simulation that asks "when
// may this command go?" far more often than commands issue: per bank and
// command (and for the rank commands) the first cycle that every row issued
// so far allows. Issuing a command raises those cycles; asking is one look-up.
// The Dimm (dimm.hpp) and FastInOrderPort (pipeline/fast_in_order_port.hpp)
// keep their timing in one of these.
//
// Contract: after raise(p, b, t) for every command issued so far, at(cmd, bank)
// is the largest (t + delay) over the table's rows (p -> cmd) whose scope
// couples b with bank, read as Dimm::gate reads them: a rank command (PREA,
// REF) on either side binds every bank, and a rank command after a bank
// command sees every bank as "other". Rows that do not apply leave the
// initial cycle. tests/rtl/test_sdram_dimm.cpp checks Dimm::earliest against
// the table scan (Dimm::gate) on random legal sequences.
//
// What makes raise() cheap: the rows of one previous command are folded when
// the table is compiled into, per later command, the largest delay for the
// command's own bank and for the other banks (max(t + a, t + b) = t + max(a, b)),
// and a delay that binds every bank alike raises one rank-wide cycle, which
// at() combines with the bank's own: a READ raises 5 cycles instead of
// walking its rows and their scopes bank by bank.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "rtl_model/sdram/timing.hpp"

namespace voxcast::rtl::sdram {

class NotBefore {
 public:
  // Every bank and rank cycle starts at `initial` (kNever: no command yet).
  NotBefore(const ConstraintTable& table, std::uint32_t banks, Cycle initial)
      : banks_(banks), bank_(banks) {
    for (auto& b : bank_) b.fill(initial);
    every_.fill(initial);
    rank_.fill(initial);
    // Fold the rows by previous command: per later command the delay to the
    // issuing bank, to the other banks, and to a rank command.
    struct Fold {
      Cycle own = kNone, other = kNone, rank = kNone;
    };
    std::array<std::array<Fold, kCommandCount>, kCommandCount> fold{};
    for (const Constraint& c : table.rows()) {
      const bool rank = is_rank_command(c.prev);
      Fold& f = fold[index_of(c.prev)][index_of(c.next)];
      if (is_rank_command(c.next)) {
        if (rank || c.scope != Scope::kSameBank) f.rank = std::max(f.rank, c.cycles);
      } else if (!rank && c.scope == Scope::kSameBank) {
        f.own = std::max(f.own, c.cycles);
      } else {
        f.other = std::max(f.other, c.cycles);
        // A rank command is issued with bank 0: it binds every bank alike.
        if (rank || c.scope != Scope::kOtherBank) f.own = std::max(f.own, c.cycles);
      }
    }
    for (std::size_t p = 0; p < kCommandCount; ++p)
      for (std::size_t n = 0; n < kCommandCount; ++n) {
        const Fold& f = fold[p][n];
        if (f.rank != kNone) after_[p].push_back(Entry{Kind::kRank, n, f.rank, kNone});
        if (f.own == kNone && f.other == kNone) continue;
        const Kind k = f.own == f.other    ? Kind::kEveryBank
                       : f.other == kNone ? Kind::kOwnBank
                                          : Kind::kPerBank;
        after_[p].push_back(Entry{k, n, f.own, f.other});
      }
  }

  // The first cycle `cmd` to `bank` is allowed by the commands issued so far
  // (the initial cycle if none binds); `bank` is ignored for rank commands.
  Cycle at(Command cmd, std::uint32_t bank) const {
    const std::size_t n = index_of(cmd);
    if (is_rank_command(cmd)) return rank_[n];
    const Cycle own = bank_[bank][n], every = every_[n];
    return own < every ? every : own;
  }

  // `cmd` to `bank` issued at `now` (bank 0 for a rank command).
  void raise(Command cmd, std::uint32_t bank, Cycle now) {
    // Values, not references, so that the maxima compile to conditional
    // moves: which way they go is data, and a branch would mispredict often.
    auto up = [](Cycle& c, Cycle v) {
      const Cycle cur = c;
      c = cur < v ? v : cur;
    };
    for (const Entry& e : after_[index_of(cmd)]) {
      switch (e.kind) {
        case Kind::kRank:
          up(rank_[e.next], now + e.own);
          break;
        case Kind::kEveryBank:
          up(every_[e.next], now + e.own);
          break;
        case Kind::kOwnBank:
          up(bank_[bank][e.next], now + e.own);
          break;
        case Kind::kPerBank:  // kNone + now stays below every cycle
          for (std::uint32_t b = 0; b < banks_; ++b)
            up(bank_[b][e.next], now + (b == bank ? e.own : e.other));
          break;
      }
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
    kEveryBank,  // every bank, own = other
    kOwnBank,    // the issuing bank only (own)
    kPerBank,    // own to the issuing bank, other to the rest (either may be kNone)
  };
  struct Entry {
    Kind kind;
    std::size_t next;  // the later command
    Cycle own, other;
  };

  std::uint32_t banks_;
  std::array<std::vector<Entry>, kCommandCount> after_;  // by previous command
  std::vector<std::array<Cycle, kCommandCount>> bank_;   // [bank][command]
  std::array<Cycle, kCommandCount> every_{};             // [command], every bank
  std::array<Cycle, kCommandCount> rank_{};              // PREA, REF
};

}  // namespace voxcast::rtl::sdram
