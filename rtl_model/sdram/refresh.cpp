#include "rtl_model/sdram/refresh.hpp"

#include <algorithm>
#include <ostream>
#include <sstream>

#include "refmodel/error.hpp"

namespace voxcast::rtl::sdram {

RefreshTracker::RefreshTracker(Cycle interval, int postpone_limit)
    : interval_(interval), postpone_limit_(postpone_limit), last_refresh_(kNever) {
  if (interval_ <= 0) throw Error("refresh: tREFI must be at least one cycle");
  // JEDEC DDR3/DDR4 allow at most 8 postponed REFs; SDR datasheets name no
  // limit, so the model caps it at the same 8.
  if (postpone_limit_ < 0 || postpone_limit_ > 8) {
    std::ostringstream os;
    os << "refresh: postponement limit " << postpone_limit_ << " is outside [0, 8]";
    throw Error(os.str());
  }
  update_due();
}

void RefreshTracker::on_refresh(Cycle now) {
  ++issued_;
  last_refresh_ = now;
  update_due();
}

void RefreshTracker::update_due() {
  next_due_ = (issued_ + 1) * interval_;
  deadline_ = (issued_ + 2 + postpone_limit_) * interval_;
}

std::ostream& operator<<(std::ostream& os, const RefreshTracker& r) {
  os << "refresh: " << r.issued() << " REF issued";
  if (r.last_refresh() != kNever) os << " (last at cycle " << r.last_refresh() << ")";
  return os << ", tREFI " << r.interval() << " cycles, next due " << r.next_due() << ", deadline "
            << r.deadline() << ", postpone limit " << r.postpone_limit();
}

Cycle refresh_entry_bound(const TimingCycles& t) {
  return std::max(t.tRAS, t.write_to_precharge()) + t.tRP;
}

}  // namespace voxcast::rtl::sdram
