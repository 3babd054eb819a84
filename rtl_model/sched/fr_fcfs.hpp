// FR-FCFS with a reorder window: "first ready, first come first served"
// (Rixner et al., "Memory Access Scheduling", ISCA 2000, §4).
//
// Each cycle, among the oldest `reorder_window` pending requests:
//   1. the oldest row hit whose column command is legal now (row hits
//      first: they use the open row before it is closed);
//   2. otherwise the oldest request whose row command (ACT, or PRE on a
//      conflict) is legal now, except a PRE that would close a row that a
//      request in the window still hits (open page: a row is kept while it
//      has customers);
//   3. otherwise nothing.
// Starvation bound: every command for a younger request while the oldest
// waits is a bypass; once the oldest has been bypassed `starvation_limit`
// times, only the oldest's commands are issued (in order) until it is
// served. A request is thus overtaken at most starvation_limit times once it
// is the oldest. With a window of 1, or a limit of 0, this is the in-order
// policy (sched/in_order.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "rtl_model/sdram/scheduler.hpp"

namespace voxcast::rtl::sched {

class FrFcfs final : public sdram::CommandScheduler {
 public:
  explicit FrFcfs(const sdram::SchedulerParams& params);
  std::string_view name() const override { return "FR-FCFS"; }
  std::optional<sdram::Decision> pick(const sdram::SchedulerView& view) override;
  // The earliest cycle over the commands pick() considers: the oldest
  // request's when it is starved, else every request's in the window except
  // a PRE that would close a row the window still hits.
  sdram::Cycle wake(const sdram::SchedulerView& view) const override;

  // Bypasses of the current oldest request so far.
  int bypasses() const { return bypasses_; }

 private:
  void track_oldest(const sdram::Request& oldest);
  // Bypasses of `oldest` so far (0 for a request not yet tracked).
  int bypasses_of(const sdram::Request& oldest) const {
    return oldest.id == oldest_id_ && oldest.arrival == oldest_arrival_ ? bypasses_ : 0;
  }
  std::optional<sdram::Decision> decide(const sdram::SchedulerView& view, std::size_t i,
                                        sdram::Command cmd);

  std::size_t window_;
  int limit_;
  std::uint64_t oldest_id_ = 0;
  sdram::Cycle oldest_arrival_ = sdram::kNever;
  int bypasses_ = 0;
  std::vector<sdram::Command> next_;  // pick(): each window entry's next command, asked once
};

}  // namespace voxcast::rtl::sched
