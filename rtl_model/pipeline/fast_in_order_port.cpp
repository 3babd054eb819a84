#include "rtl_model/pipeline/fast_in_order_port.hpp"

#include <algorithm>
#include <sstream>

#include "refmodel/error.hpp"
#include "rtl_model/sdram/dimm.hpp"

namespace voxcast::rtl::pipeline {

using sdram::Command;
using sdram::RowOutcome;
using sdram::index_of;
using sim::Cycle;

FastInOrderPort::FastInOrderPort(const sdram::DimmConfig& dimm,
                                 const sdram::ControllerConfig& controller)
    : t_(sdram::Dimm(dimm).timing()),  // the Dimm validates the configuration
      geometry_(dimm.geometry),
      // The commands the port asks the table about (it issues no WR or RDA).
      not_before_(sdram::ConstraintTable(t_), dimm.geometry.banks, 0, 1,
                  sdram::NotBefore::asked(
                      {Command::kAct, Command::kRd, Command::kPre, Command::kPrea, Command::kRef})),
      banks_(dimm.geometry.banks),
      postpone_limit_(dimm.refresh_postpone_limit),
      completions_("sdram.completions", controller.return_depth) {
  if (controller.queue_depth == 0) throw Error("Controller: request queue depth 0");
  refresh_due_ = static_cast<Cycle>(t_.tREFI);
  overdue_at_ = static_cast<Cycle>(2 + postpone_limit_) * t_.tREFI;
  burst_bytes_ = static_cast<std::uint64_t>(t_.BL) * geometry_.bytes_per_beat();
  pending_.resize(controller.queue_depth);
  flight_.resize(controller.return_depth + 1);
  pending_depth_ = pending_.size();
  flight_depth_ = flight_.size();
  ds_.banks.resize(geometry_.banks);
}

void FastInOrderPort::fail(const std::string& what, Cycle now) const {
  std::ostringstream os;
  os << "fast in-order controller at cycle " << now << ": " << what;
  throw Error(os.str());
}

bool FastInOrderPort::all_idle() const {
  for (const Bank& b : banks_)
    if (b.open) return false;
  return true;
}

// The refresh sequence (EagerRefresh): close every row, then REF; its cycles
// are counted while it waits.
void FastInOrderPort::step_refresh(Cycle now) {
  refreshing_ = true;
  ++cs_.refresh_cycles;
  const Command cmd = all_idle() ? Command::kRef : Command::kPrea;
  if (earliest(cmd, 0) <= now) {
    issue_rank_command(cmd, now);
    if (cmd == Command::kRef) refreshing_ = false;
  }
}

// PREA or REF at `now`, legal by the table (step_refresh checked it).
void FastInOrderPort::issue_rank_command(Command cmd, Cycle now) {
  if (now <= last_command_) fail("two commands in one cycle", now);
  not_before_.raise(cmd, 0, now);
  head_known_ = false;
  if (cmd == Command::kPrea) {
    for (std::uint32_t b = 0; b < geometry_.banks; ++b)
      if (banks_[b].open) close(b, now);
    ++ds_.precharge_alls;
  } else {
    if (!all_idle()) fail("REF with a row open", now);
    ++ds_.refreshes;
    ds_.refresh_busy_cycles += t_.tRFC;
    ++refreshes_;
    refresh_due_ = (refreshes_ + 1) * t_.tREFI;
    overdue_at_ = (refreshes_ + 2 + postpone_limit_) * t_.tREFI;
  }
  issued(cmd, 0, 0, now);
}

void FastInOrderPort::expect_drained() const {
  if (pending_count_ != 0 || flight_count_ != 0) {
    std::ostringstream os;
    os << "controller: " << pending_count_ << " request(s) pending and " << flight_count_
       << " access(es) in flight at the end";
    throw Error(os.str());
  }
  completions_.expect_drained();
}

}  // namespace voxcast::rtl::pipeline
