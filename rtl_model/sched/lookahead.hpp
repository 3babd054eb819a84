// Look-ahead activation: in-order data, early rows.
//
// Column commands are issued strictly in arrival order, as the in-order
// open-page baseline does (sched/in_order.hpp). Row commands are not: while
// the current row streams, the PRE and ACT that a later request in another
// bank needs go on the command bus as soon as they are legal, so that its
// row is open when its turn comes. Priority each cycle:
//   1. the oldest request's row command (ACT, or PRE on a conflict), if legal;
//   2. the row command of the oldest request among the next
//      `reorder_window - 1` that is the first pending request to its bank
//      (no older request needs that bank, so preparing it disturbs nothing),
//      if legal;
//   3. the oldest request's column command, if legal.
// A row command steals one command-bus cycle from the stream (SDR SDRAM has
// one command bus and BL 1 puts a READ on it every cycle), but tRP and tRCD
// elapse under the stream: a row change costs one cycle per row command
// instead of tRP + tRCD (docs/performance.md, tests/rtl/test_sched_policies.cpp).
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

#include "rtl_model/sdram/scheduler.hpp"

namespace voxcast::rtl::sched {

class LookAheadActivation final : public sdram::CommandScheduler {
 public:
  explicit LookAheadActivation(const sdram::SchedulerParams& params);
  std::string_view name() const override { return "look-ahead activation"; }
  std::optional<sdram::Decision> pick(const sdram::SchedulerView& view) override;
  // The earlier of the oldest request's next command and the row command of
  // the one later request pick() would prepare.
  sdram::Cycle wake(const sdram::SchedulerView& view) const override;

 private:
  std::size_t window_;
};

}  // namespace voxcast::rtl::sched
