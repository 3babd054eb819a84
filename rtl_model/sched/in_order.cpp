#include "rtl_model/sched/in_order.hpp"

#include "rtl_model/sched/window.hpp"

namespace voxcast::rtl::sched {

std::optional<sdram::Decision> InOrderOpenPage::pick(const sdram::SchedulerView& view) {
  if (view.pending.empty()) return std::nullopt;
  const sdram::Request& oldest = view.pending.front().request;
  const sdram::Command cmd = next_command(view, 0);
  if (!legal_now(view, cmd, 0)) return std::nullopt;
  return sdram::Decision{.command = cmd, .address = oldest.address, .request = 0};
}

sdram::Cycle InOrderOpenPage::wake(const sdram::SchedulerView& view) const {
  if (view.pending.empty()) return sdram::kNoWake;
  return earliest_after_now(view, next_command(view, 0), 0);
}

}  // namespace voxcast::rtl::sched
