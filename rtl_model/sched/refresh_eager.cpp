#include "rtl_model/sched/refresh_eager.hpp"

namespace voxcast::rtl::sched {

bool EagerRefresh::refresh_now(const sdram::RefreshTracker& tracker, sdram::Cycle now,
                               std::size_t /*pending_requests*/) const {
  return tracker.due(now);
}

}  // namespace voxcast::rtl::sched
