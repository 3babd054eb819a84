#include "rtl_model/pipeline/fast_in_order_port.hpp"

namespace voxcast::rtl::pipeline {

using sdram::Command;
using sim::Cycle;

FastInOrderPort::FastInOrderPort(const sdram::DimmConfig& dimm,
                                 const sdram::ControllerConfig& controller)
    // The commands the port asks the table about (it issues no WR or RDA).
    : EventDrivenPort("fast in-order controller", dimm, controller,
                      sdram::NotBefore::asked({Command::kAct, Command::kRd, Command::kPre,
                                               Command::kPrea, Command::kRef})) {}

// The helpers of step() are inlined into it: it runs in most SDRAM cycles
// of a frame, and a call per helper cost more than its body.
#define VOXCAST_HOT_INLINE [[gnu::always_inline]] inline

// The in-order scheduler's command: the oldest request's ACT, PRE or READ,
// legal by the table at head_at_ <= now (the earliest-cycle check the Dimm
// would repeat). Each command is its own path with the command a constant
// (the table's raise and look-up specialize to it), and knows the request's
// next command: after ACT its READ, after PRE its ACT, after READ the next
// request's.
VOXCAST_HOT_INLINE void FastInOrderPort::issue_head(Cycle now) {
  sdram::Completion& a = accesses_[pending_head_];
  if (!head_started_) {
    first_command(a, head_cmd_, now);
    head_started_ = true;
  }
  check_one_command(now);
  const sdram::Address& address = a.request.address;
  switch (head_cmd_) {
    case Command::kRd:
      not_before_.raise(Command::kRd, address.bank, now);
      if (open_key_[address.bank] != key(address.bank, address.row)) [[unlikely]]
        fail("READ to a closed row", now);
      read_issued(Command::kRd, now);  // the next request becomes the oldest
      head_started_ = false;
      if (pending_count_ != 0) {
        know_head();
      } else {
        head_at_ = kNoRequest;
      }
      break;
    case Command::kAct:
      activate(address, now);
      head_cmd_ = Command::kRd;
      head_at_ = earliest(Command::kRd, address.bank);
      break;
    case Command::kPre:
      precharge(address, now);
      head_cmd_ = Command::kAct;
      head_at_ = earliest(Command::kAct, address.bank);
      break;
    default:
      fail("unexpected command", now);
  }
}

VOXCAST_HOT_INLINE Cycle FastInOrderPort::next_wake(Cycle now) const {
  // The next REF falls due; while the sequence runs, the next cycle (it
  // counts its cycles): next_refresh() is then kNever, below now + 1.
  Cycle w = next_retire(next_refresh());
  // The oldest request's command (head_at_ is kNoRequest if there is none).
  if (head_cmd_ != Command::kRd || column_allowed()) w = std::min(w, head_at_);
  return std::max(w, now + 1);
}

// The in-order open-page scheduler's choice by the bank's row, each with
// the command a constant (the table's look-up specializes to it).
VOXCAST_HOT_INLINE void FastInOrderPort::know_head() {
  const sdram::Address& a = accesses_[pending_head_].request.address;
  switch (next_command(a)) {
    case Command::kAct:
      head_cmd_ = Command::kAct;
      head_at_ = earliest(Command::kAct, a.bank);
      break;
    case Command::kRd:
      head_cmd_ = Command::kRd;
      head_at_ = earliest(Command::kRd, a.bank);
      break;
    default:
      head_cmd_ = Command::kPre;
      head_at_ = earliest(Command::kPre, a.bank);
  }
}

#undef VOXCAST_HOT_INLINE

void FastInOrderPort::step(Cycle now) {
  ++cs_.cycles;
  if (refresh_due(now)) [[unlikely]] {  // EagerRefresh: as soon as due
    // The rows and the table changed under the oldest request.
    if (step_refresh(now) && pending_count_ != 0) know_head();
  } else if (head_at_ <= now && (head_cmd_ != Command::kRd || column_allowed())) {
    issue_head(now);
  }
  if (retire_due(now)) retire(now);
  completions_.sample();
  wake_ = next_wake(now);
}

void FastInOrderPort::new_oldest(Cycle arrival) {
  wake_ = std::min(wake_, arrival);
  know_head();
}

}  // namespace voxcast::rtl::pipeline
