// Random legal command sequences on a Dimm, for the tests that compare the
// compiled table (Dimm::earliest, sdram/not_before.hpp) with the table scan
// (Dimm::gate): test_sdram_dimm.cpp for SDR, test_sdram_ddr4.cpp for DDR4.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <random>

#include "rtl_model/sdram/dimm.hpp"

namespace voxcast::rtl::sdram::test_sequences {

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

}  // namespace voxcast::rtl::sdram::test_sequences
