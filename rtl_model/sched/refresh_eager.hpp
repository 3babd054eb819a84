// Eager refresh: start the refresh sequence in the first cycle a REF is due,
// whatever is pending. With a postponement limit of 0 the REF due at
// k * tREFI lands within refresh_entry_bound() cycles of it, far inside the
// deadline (k + 1) * tREFI. The VIZARD II baseline; it costs the streaming
// case tRP + tRFC + tRCD cycles per tREFI (docs/sdram.md §5).
#pragma once

#include <cstddef>
#include <string_view>

#include "rtl_model/sdram/refresh.hpp"

namespace voxcast::rtl::sched {

class EagerRefresh final : public sdram::RefreshPolicy {
 public:
  std::string_view name() const override { return "eager"; }
  bool refresh_now(const sdram::RefreshTracker& tracker, sdram::Cycle now,
                   std::size_t pending_requests) const override;
  // Nothing happens before the next REF falls due.
  sdram::Cycle wake(const sdram::RefreshTracker& tracker, sdram::Cycle now) const override;
};

}  // namespace voxcast::rtl::sched
