// SDR SDRAM commands and addresses.
//
// The commands a controller puts on a PC100 DIMM's command bus, one per clock
// (Micron 128Mb SDRAM data sheet, Rev. E, "Truth Table 1 - Commands and DQM
// Operation"): ACTIVE, READ, WRITE, PRECHARGE (one bank, A10 low), PRECHARGE
// ALL (A10 high), AUTO REFRESH, NOP, and READ with auto precharge (A10 high
// with the READ: the bank precharges itself when the burst ends, saving the
// PRECHARGE's command-bus clock; the controller's auto_precharge option).
// WRITE with auto precharge, BURST TERMINATE, LOAD MODE REGISTER and self
// refresh are not modelled: the card only writes when the volume is uploaded,
// and the mode register is set once at power-up.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <limits>
#include <string_view>

#include "rtl_model/sim/clock.hpp"

namespace voxcast::rtl::sdram {

using sim::Cycle;

// "Never happened": far enough below zero that kNever + any delay stays in the
// past and cannot overflow.
inline constexpr Cycle kNever = std::numeric_limits<Cycle>::min() / 4;

enum class Command : std::uint8_t { kNop, kAct, kRd, kWr, kPre, kPrea, kRef, kRda };

inline constexpr std::size_t kCommandCount = 8;
inline constexpr std::array<Command, kCommandCount> kAllCommands{
    Command::kNop, Command::kAct,  Command::kRd,  Command::kWr,
    Command::kPre, Command::kPrea, Command::kRef, Command::kRda};

constexpr std::size_t index_of(Command c) { return static_cast<std::size_t>(c); }
// "ACT", "RD", ...
std::string_view name(Command c);
std::ostream& operator<<(std::ostream& os, Command c);

// PRECHARGE ALL and AUTO REFRESH address the whole rank, not one bank.
constexpr bool is_rank_command(Command c) { return c == Command::kPrea || c == Command::kRef; }
// READ, WRITE and READ with auto precharge carry a column address and move data.
constexpr bool is_column_command(Command c) {
  return c == Command::kRd || c == Command::kWr || c == Command::kRda;
}
// A READ, with or without auto precharge.
constexpr bool is_read_command(Command c) { return c == Command::kRd || c == Command::kRda; }

// A location in one DIMM (one rank): internal bank, row, column. A column is
// one beat of the 64-bit module bus (8 bytes).
struct Address {
  std::uint32_t bank = 0;
  std::uint32_t row = 0;
  std::uint32_t column = 0;

  friend bool operator==(const Address&, const Address&) = default;
};

std::ostream& operator<<(std::ostream& os, const Address& a);

}  // namespace voxcast::rtl::sdram
