#include "rtl_model/sched/fr_fcfs.hpp"

#include <algorithm>

#include "rtl_model/sched/window.hpp"

namespace voxcast::rtl::sched {

FrFcfs::FrFcfs(const sdram::SchedulerParams& params)
    : window_(static_cast<std::size_t>(std::max(params.reorder_window, 1))),
      limit_(std::max(params.starvation_limit, 0)),
      next_(window_) {}

void FrFcfs::track_oldest(const sdram::Request& oldest) {
  if (oldest.id == oldest_id_ && oldest.arrival == oldest_arrival_) return;
  oldest_id_ = oldest.id;
  oldest_arrival_ = oldest.arrival;
  bypasses_ = 0;
}

std::optional<sdram::Decision> FrFcfs::decide(const sdram::SchedulerView& view, std::size_t i,
                                              sdram::Command cmd) {
  if (i > 0) ++bypasses_;
  return sdram::Decision{.command = cmd, .address = view.pending[i].request.address, .request = i};
}

std::optional<sdram::Decision> FrFcfs::pick(const sdram::SchedulerView& view) {
  if (view.pending.empty()) return std::nullopt;
  track_oldest(view.pending.front().request);
  const std::size_t n = std::min(window_, view.pending.size());

  if (bypasses_ >= limit_) {  // starved: in order until the oldest is served
    const sdram::Command cmd = next_command(view, 0);
    if (!legal_now(view, cmd, 0)) return std::nullopt;
    return decide(view, 0, cmd);
  }
  for (std::size_t i = 0; i < n; ++i) {  // 1. row hits, oldest first
    const sdram::Command cmd = next_[i] = next_command(view, i);
    if (sdram::is_column_command(cmd) && legal_now(view, cmd, i)) return decide(view, i, cmd);
  }
  for (std::size_t i = 0; i < n; ++i) {  // 2. row commands, oldest first
    const sdram::Command cmd = next_[i];
    if (sdram::is_column_command(cmd)) continue;
    if (cmd == sdram::Command::kPre && open_row_wanted(view, view.pending[i].request.address.bank, n))
      continue;
    if (legal_now(view, cmd, i)) return decide(view, i, cmd);
  }
  return std::nullopt;
}

sdram::Cycle FrFcfs::wake(const sdram::SchedulerView& view) const {
  if (view.pending.empty()) return sdram::kNoWake;
  if (bypasses_of(view.pending.front().request) >= limit_)
    return earliest_after_now(view, next_command(view, 0), 0);
  const std::size_t n = std::min(window_, view.pending.size());
  sdram::Cycle w = sdram::kNoWake;
  for (std::size_t i = 0; i < n; ++i) {
    const sdram::Command cmd = next_command(view, i);
    if (cmd == sdram::Command::kPre && open_row_wanted(view, view.pending[i].request.address.bank, n))
      continue;
    w = std::min(w, earliest_after_now(view, cmd, i));
  }
  return w;
}

}  // namespace voxcast::rtl::sched
