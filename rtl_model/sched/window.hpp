// Queries on the scheduler's view shared by the policies that look past the
// oldest request (fr_fcfs.hpp, lookahead.hpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "rtl_model/sdram/scheduler.hpp"

namespace voxcast::rtl::sched {

// The next command pending request `i` needs now (ACT, PRE or its column command).
inline sdram::Command next_command(const sdram::SchedulerView& view, std::size_t i) {
  const sdram::Request& r = view.pending[i].request;
  return view.dimm.next_command(sdram::column_command(r.kind), r.address);
}

// `cmd` for request `i` may go on the bus now (column commands also need a
// free return slot). `cmd` is the request's next command, so the bank state
// allows it and the address exists (the Controller checked it on push); one
// command per cycle holds as the Controller asks once per cycle; what is left
// is the timing table, one look-up (Dimm::earliest). An overdue refresh or a
// row open beyond tRAS(max) is not a reason to wait: Dimm::issue rejects the
// command with its message rather than the scheduler stalling silently.
inline bool legal_now(const sdram::SchedulerView& view, sdram::Command cmd, std::size_t i) {
  if (sdram::is_column_command(cmd) && !view.column_allowed) return false;
  return view.dimm.earliest(cmd, view.pending[i].request.address.bank, view.now) <= view.now;
}

// The first cycle after view.now at which `cmd` for request `i` could be
// legal with the banks and column_allowed as they are now
// (CommandScheduler::wake): the timing table's earliest cycle, or kNoWake
// for a column command without a free return slot.
inline sdram::Cycle earliest_after_now(const sdram::SchedulerView& view, sdram::Command cmd,
                                       std::size_t i) {
  if (sdram::is_column_command(cmd) && !view.column_allowed) return sdram::kNoWake;
  return view.dimm.earliest(cmd, view.pending[i].request.address.bank, view.now + 1);
}

// A request among the first `n` hits the row open in `bank`.
inline bool open_row_wanted(const sdram::SchedulerView& view, std::uint32_t bank, std::size_t n) {
  const sdram::Bank& b = view.dimm.bank(bank);
  if (b.state != sdram::BankState::kActive) return false;
  for (std::size_t j = 0; j < n; ++j) {
    const sdram::Address& a = view.pending[j].request.address;
    if (a.bank == bank && a.row == b.open_row) return true;
  }
  return false;
}

// Request `j` is the oldest pending request to its bank: preparing its row
// cannot disturb an older request.
inline bool first_to_its_bank(const sdram::SchedulerView& view, std::size_t j) {
  const std::uint32_t bank = view.pending[j].request.address.bank;
  for (std::size_t i = 0; i < j; ++i)
    if (view.pending[i].request.address.bank == bank) return false;
  return true;
}

}  // namespace voxcast::rtl::sched
