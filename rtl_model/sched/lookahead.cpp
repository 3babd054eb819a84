#include "rtl_model/sched/lookahead.hpp"

#include <algorithm>

#include "rtl_model/sched/window.hpp"

namespace voxcast::rtl::sched {

LookAheadActivation::LookAheadActivation(const sdram::SchedulerParams& params)
    : window_(static_cast<std::size_t>(std::max(params.reorder_window, 1))) {}

std::optional<sdram::Decision> LookAheadActivation::pick(const sdram::SchedulerView& view) {
  if (view.pending.empty()) return std::nullopt;
  const auto decide = [&view](std::size_t i, sdram::Command cmd) {
    return sdram::Decision{.command = cmd, .address = view.pending[i].request.address, .request = i};
  };
  const sdram::Command oldest = next_command(view, 0);
  const bool oldest_legal = legal_now(view, oldest, 0);
  if (!sdram::is_column_command(oldest) && oldest_legal) return decide(0, oldest);
  const std::size_t n = std::min(window_, view.pending.size());
  for (std::size_t j = 1; j < n; ++j) {
    if (!first_to_its_bank(view, j)) continue;
    const sdram::Command cmd = next_command(view, j);
    if (sdram::is_column_command(cmd)) continue;  // its row is open already
    if (legal_now(view, cmd, j)) return decide(j, cmd);
    break;  // the oldest such request's row comes first: no overtaking among rows
  }
  if (oldest_legal) return decide(0, oldest);
  return std::nullopt;
}

sdram::Cycle LookAheadActivation::wake(const sdram::SchedulerView& view) const {
  if (view.pending.empty()) return sdram::kNoWake;
  sdram::Cycle w = earliest_after_now(view, next_command(view, 0), 0);
  const std::size_t n = std::min(window_, view.pending.size());
  for (std::size_t j = 1; j < n; ++j) {
    if (!first_to_its_bank(view, j)) continue;
    const sdram::Command cmd = next_command(view, j);
    if (sdram::is_column_command(cmd)) continue;
    return std::min(w, earliest_after_now(view, cmd, j));  // pick() looks no further
  }
  return w;
}

}  // namespace voxcast::rtl::sched
