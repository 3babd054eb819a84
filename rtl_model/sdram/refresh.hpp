// Refresh: the device's bookkeeping (RefreshTracker, owned by the Dimm) and
// the policy interface that decides when a controller refreshes
// (RefreshPolicy; implementations in rtl_model/sched/, one per file).
//
// The requirement (Micron 128Mb SDRAM data sheet, Rev. E, "AUTO REFRESH"):
// 4,096 AUTO REFRESH commands every 64 ms, either distributed, one every
// tREFI = 15.625 us, or in bursts. SDR SDRAM datasheets set no explicit limit
// on postponing (JEDEC DDR3/DDR4 allow 8); the model makes it a parameter:
//   owed(now) = floor(now / tREFI) - REFs issued so far,
//   due       when owed >= 1,
//   overdue   when owed > 1 + postpone_limit.
// With postpone_limit = 0 (the default) the REF that falls due at k * tREFI
// must be issued before (k + 1) * tREFI; the Dimm rejects every command once
// refresh is overdue. Issuing REF early (owed <= 0) is allowed, as the
// datasheet allows burst refresh. Refresh also bounds how long a row stays
// open: (2 + postpone_limit) * tREFI must stay below tRAS(max) = 120 us,
// which limits postpone_limit to 5 at PC100 (checked by the Dimm).
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string_view>

#include "rtl_model/sdram/timing.hpp"

namespace voxcast::rtl::sdram {

class RefreshTracker {
 public:
  // Throws voxcast::Error unless interval > 0 and 0 <= postpone_limit <= 8.
  RefreshTracker(Cycle interval, int postpone_limit);

  Cycle interval() const { return interval_; }
  int postpone_limit() const { return postpone_limit_; }
  std::int64_t issued() const { return issued_; }
  Cycle last_refresh() const { return last_refresh_; }  // kNever before the first

  std::int64_t owed(Cycle now) const { return now / interval_ - issued_; }
  // owed(now) >= 1 and owed(now) > 1 + postpone_limit as comparisons with
  // the cycles at which they start to hold (issued_ >= 0, so the truncating
  // division agrees with them for negative cycles too): the Dimm and the
  // eager policy ask every cycle, and a division per question was a visible
  // share of the controller's cycle.
  bool due(Cycle now) const { return now >= next_due_; }
  bool overdue(Cycle now) const { return now >= deadline_; }
  // The cycle at which the next REF falls due.
  Cycle next_due() const { return next_due_; }
  // The first cycle at which refresh is overdue.
  Cycle deadline() const { return deadline_; }

  void on_refresh(Cycle now);

 private:
  // next_due_ and deadline_ from issued_.
  void update_due();

  Cycle interval_;
  int postpone_limit_;
  std::int64_t issued_ = 0;
  Cycle last_refresh_;
  Cycle next_due_ = 0;  // (issued_ + 1) * interval_
  Cycle deadline_ = 0;  // (issued_ + 2 + postpone_limit_) * interval_
};

std::ostream& operator<<(std::ostream& os, const RefreshTracker& r);

// Worst-case cycles from the moment a controller decides to refresh to the
// REF command: a row opened (or a write issued) the cycle before must first
// close (max(tRAS, BL-1+tWR)), then precharge (tRP). A policy that starts by
// deadline() - refresh_entry_bound() - 1 always meets the deadline.
Cycle refresh_entry_bound(const TimingCycles& t);

// Contract (a refresh policy):
//   - refresh_now() is called by the Controller once per cycle, before the
//     command scheduler, with the device's tracker and the number of pending
//     requests. Returning true makes the controller stop issuing request
//     commands, close every open row (PREA) and issue REF at the earliest
//     legal cycles; once started, the sequence runs until the REF.
//   - A policy must return true early enough that the REF lands before
//     tracker.deadline() (see refresh_entry_bound); the Dimm rejects every
//     command once refresh is overdue, so a late policy fails loudly.
//   - Policies keep no device state of their own; they may keep statistics.
// Implementations: sched/refresh_eager.hpp (refresh as soon as a REF is due:
// the VIZARD II baseline). Planned: postpone while requests are pending, up to
// the postponement limit (elastic refresh).
class RefreshPolicy {
 public:
  virtual ~RefreshPolicy() = default;
  virtual std::string_view name() const = 0;
  virtual bool refresh_now(const RefreshTracker& tracker, Cycle now,
                           std::size_t pending_requests) const = 0;
  // A cycle > now before which refresh_now() stays false as long as nothing
  // else changes (no REF issued, the pending count unchanged): the
  // Controller's next-event hint (Controller::next_event). now + 1 is always
  // correct; a policy that can tell gives a later cycle.
  virtual Cycle wake(const RefreshTracker& /*tracker*/, Cycle now) const { return now + 1; }
};

}  // namespace voxcast::rtl::sdram
