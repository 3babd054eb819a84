#include "rtl_model/sched/refresh_eager.hpp"

#include <algorithm>

namespace voxcast::rtl::sched {

bool EagerRefresh::refresh_now(const sdram::RefreshTracker& tracker, sdram::Cycle now,
                               std::size_t /*pending_requests*/) const {
  return tracker.due(now);
}

sdram::Cycle EagerRefresh::wake(const sdram::RefreshTracker& tracker, sdram::Cycle now) const {
  return std::max(now + 1, tracker.next_due());
}

}  // namespace voxcast::rtl::sched
