#include "rtl_model/pipeline/event_driven_port.hpp"

#include <sstream>

#include "refmodel/error.hpp"
#include "rtl_model/sdram/dimm.hpp"

namespace voxcast::rtl::pipeline {

using sdram::Command;
using sim::Cycle;

EventDrivenPort::EventDrivenPort(const char* name, const sdram::DimmConfig& dimm,
                                 const sdram::ControllerConfig& controller,
                                 sdram::NotBefore::CommandSet asked)
    : t_(sdram::Dimm(dimm).timing()),  // the Dimm validates the configuration
      geometry_(dimm.geometry),
      not_before_(sdram::ConstraintTable(t_), dimm.geometry.banks, 0, dimm.geometry.bank_groups,
                  asked),
      completions_("sdram.completions", controller.return_depth),
      name_(name),
      postpone_limit_(dimm.refresh_postpone_limit) {
  if (controller.queue_depth == 0) throw Error("Controller: request queue depth 0");
  burst_ = t_.burst_cycles();
  data_first_ = t_.CL;
  data_last_ = t_.CL + burst_ - 1;
  burst_bytes_ = static_cast<std::uint64_t>(t_.BL) * geometry_.bytes_per_beat();
  open_key_.assign(geometry_.banks, kClosed);
  activated_at_.assign(geometry_.banks, 0);
  queue_depth_ = controller.queue_depth;
  accesses_.resize(controller.queue_depth + controller.return_depth);
  ring_size_ = accesses_.size();
  ds_.banks.resize(geometry_.banks);
  refresh_due_ = static_cast<Cycle>(t_.tREFI);
  refresh_at_ = refresh_due_;
  overdue_at_ = static_cast<Cycle>(2 + postpone_limit_) * t_.tREFI;
}

void EventDrivenPort::fail(const char* what, Cycle now) const {
  std::ostringstream os;
  os << name_ << " at cycle " << now << ": " << what;
  throw Error(os.str());
}

void EventDrivenPort::close(std::uint32_t bank, Cycle closed_at) {
  if (open_key_[bank] == kClosed) [[unlikely]]
    fail("a row closed in an idle bank", closed_at);
  ds_.banks[bank].open_cycles += closed_at - activated_at_[bank];
  ++ds_.banks[bank].precharges;
  open_key_[bank] = kClosed;
}

bool EventDrivenPort::all_closed() const {
  return std::all_of(open_key_.begin(), open_key_.end(),
                     [](std::uint64_t k) { return k == kClosed; });
}

bool EventDrivenPort::step_refresh(Cycle now) {
  // Refresh falls due before it is overdue (overdue_at_ > refresh_due_): the
  // deadline the Dimm enforces, after which it rejects every command.
  if (now >= overdue_at_) fail("refresh overdue", now);
  refresh_at_ = sdram::kNever;  // every tick until the REF
  ++cs_.refresh_cycles;
  const Command cmd = all_closed() ? Command::kRef : Command::kPrea;
  if (earliest(cmd, 0) > now) return false;
  issue_rank_command(cmd, now);
  if (cmd == Command::kRef) refresh_at_ = refresh_due_;
  return true;
}

// PREA or REF at `now`, legal by the table (step_refresh checked it).
void EventDrivenPort::issue_rank_command(Command cmd, Cycle now) {
  check_one_command(now);
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
  command_issued(cmd, sdram::Address{}, now);
}

void EventDrivenPort::expect_drained() const {
  if (pending_count_ != 0 || flight_count_ != 0) {
    std::ostringstream os;
    os << "controller: " << pending_count_ << " request(s) pending and " << flight_count_
       << " access(es) in flight at the end";
    throw Error(os.str());
  }
  completions_.expect_drained();
}

}  // namespace voxcast::rtl::pipeline
