// In-order open-page scheduling: the VIZARD II baseline.
//
// Only the oldest pending request is considered; its next command (ACT on an
// idle bank, PRE on a conflict, RD/WR on a hit) is issued at the first cycle
// the Dimm allows it. Rows stay open after the access (open page), so a
// stream of requests to one row costs one burst per max(tCCD, BL) cycles and
// a change of row in the same bank costs the full precharge and activate.
// No request overtakes another and no bank is prepared ahead of time: the
// reference against which FR-FCFS and look-ahead activation are measured.
#pragma once

#include <optional>
#include <string_view>

#include "rtl_model/sdram/scheduler.hpp"

namespace voxcast::rtl::sched {

class InOrderOpenPage final : public sdram::CommandScheduler {
 public:
  std::string_view name() const override { return "in-order open page"; }
  std::optional<sdram::Decision> pick(const sdram::SchedulerView& view) override;
  // When the oldest request's next command becomes legal.
  sdram::Cycle wake(const sdram::SchedulerView& view) const override;
};

}  // namespace voxcast::rtl::sched
