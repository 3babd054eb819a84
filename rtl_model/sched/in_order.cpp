#include "rtl_model/sched/in_order.hpp"

namespace voxcast::rtl::sched {

std::optional<sdram::Decision> InOrderOpenPage::pick(const sdram::SchedulerView& view) {
  if (view.pending.empty()) return std::nullopt;
  const sdram::Request& oldest = view.pending.front().request;
  const sdram::Command cmd =
      view.dimm.next_command(sdram::column_command(oldest.kind), oldest.address);
  if (sdram::is_column_command(cmd) && !view.column_allowed) return std::nullopt;
  if (!view.dimm.can_issue(cmd, oldest.address, view.now)) return std::nullopt;
  return sdram::Decision{.command = cmd, .address = oldest.address, .request = 0};
}

}  // namespace voxcast::rtl::sched
