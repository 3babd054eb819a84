// The checks the SDR (test_sdram_dimm.cpp) and DDR4 (test_sdram_ddr4.cpp)
// device tests share: one constraint-table row illegal one cycle early and
// legal on time, and random legal command sequences on which the compiled
// table (Dimm::earliest, sdram/not_before.hpp) equals the table scan
// (Dimm::gate).
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <optional>
#include <random>
#include <set>
#include <string>

#include "refmodel/error.hpp"
#include "rtl_model/sdram/dimm.hpp"

namespace voxcast::rtl::sdram::dimm_checks {

// Each bank gets its own row so a wrong-row access cannot pass unnoticed.
inline Address at(std::uint32_t bank, std::uint32_t column = 0) {
  return {bank, 10 + bank, column};
}

// The banks of a row's previous and later command.
struct Banks {
  std::uint32_t prev;
  std::uint32_t next;
};

// When the set-up stops binding: its ACTs `spacing` cycles apart from cycle 1,
// then `c.prev` at `t0`, long after them (tRC, tRAS and, on DDR4, tFAW over).
struct Setup {
  Cycle spacing;
  Cycle t0;
};

// Puts the DIMM in a state where `c.prev` is legal on bank b.prev and, after
// it, `c.next` on bank b.next; issues `c.prev` at setup.t0; then checks
// `c.next` one cycle early (illegal: earliest, gate, can_issue, violation and
// issue all name or keep to the row) and exactly on time (legal).
inline void check_constraint(const DimmConfig& cfg, const Constraint& c, Banks b, Setup setup) {
  Dimm d(cfg);
  std::set<std::uint32_t> open;
  if (is_column_command(c.prev) || c.prev == Command::kPre || c.prev == Command::kPrea)
    open.insert(b.prev);
  const bool prev_opens_it = c.prev == Command::kAct && b.next == b.prev;
  if (is_column_command(c.next) && !prev_opens_it) open.insert(b.next);
  Cycle now = 1;
  for (std::uint32_t bank : open) {
    d.issue(Command::kAct, at(bank), now);
    now += setup.spacing;
  }
  d.issue(c.prev, at(b.prev), setup.t0);
  // ACT after ACT to the same bank needs the row closed in between.
  if (c.next == Command::kAct && d.bank(b.next).state == BankState::kActive)
    d.issue(Command::kPre, at(b.next), d.earliest(Command::kPre, b.next, setup.t0 + 1));

  const Cycle bound = setup.t0 + c.cycles;
  // Illegal one cycle early; nothing else binds later (legal on time).
  EXPECT_EQ(d.earliest(c.next, b.next, bound - 1), bound);
  EXPECT_EQ(d.gate(c.next, b.next, bound - 1).earliest, bound);
  EXPECT_FALSE(d.can_issue(c.next, at(b.next), bound - 1));
  if (bound - 1 > d.last_command_cycle()) {
    const std::optional<std::string> why = d.violation(c.next, at(b.next), bound - 1);
    ASSERT_TRUE(why.has_value());
    EXPECT_NE(why->find("violates " + std::string(c.parameter)), std::string::npos) << *why;
    try {
      d.issue(c.next, at(b.next), bound - 1);
      ADD_FAILURE() << "issue one cycle early did not throw";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(c.parameter), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(d.can_issue(c.next, at(b.next), bound));
  EXPECT_NO_THROW(d.issue(c.next, at(b.next), bound));
}

// For `cycles` clocks: first, every command of `checked` to every bank must
// have the same earliest cycle by the compiled table and by the scan; then one
// of `kinds` (a random bank; the open row of an open bank, else one of 8 rows)
// is issued if it is legal there. Returns how many were issued (0 after a
// failed comparison).
template <std::size_t K, std::size_t C>
std::uint64_t run_random_sequence(Dimm& dimm, const std::array<Command, K>& kinds,
                                  const std::array<Command, C>& checked, Cycle cycles,
                                  unsigned seed) {
  std::mt19937 rng(seed);
  std::uint64_t issued = 0;
  for (Cycle now = 0; now < cycles; ++now) {
    for (Command c : checked)
      for (std::uint32_t b = 0; b < dimm.bank_count(); ++b) {
        const Cycle compiled = dimm.earliest(c, b, now), scanned = dimm.gate(c, b, now).earliest;
        EXPECT_EQ(compiled, scanned) << c << " bank " << b << " at " << now;
        if (compiled != scanned) return 0;
      }
    const Command c = kinds[rng() % kinds.size()];
    const auto bank = static_cast<std::uint32_t>(rng() % dimm.bank_count());
    const std::uint32_t row = dimm.bank(bank).state == BankState::kActive
                                  ? dimm.bank(bank).open_row
                                  : static_cast<std::uint32_t>(rng() % 8);
    const Address a{bank, row, static_cast<std::uint32_t>(rng() % 64)};
    if (dimm.can_issue(c, a, now)) {
      dimm.issue(c, a, now);
      ++issued;
    }
  }
  return issued;
}

}  // namespace voxcast::rtl::sdram::dimm_checks
