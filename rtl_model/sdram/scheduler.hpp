// Memory requests and the command-scheduler interface of the Controller
// (rtl_model/sdram/controller.hpp). Policies live in rtl_model/sched/, one
// per file, as Ramulator 2's schedulers do.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <limits>
#include <optional>
#include <span>
#include <string_view>

#include "rtl_model/sdram/command.hpp"
#include "rtl_model/sdram/dimm.hpp"

namespace voxcast::rtl::sdram {

enum class RequestKind : std::uint8_t { kRead, kWrite };

// One beat-aligned access of BL beats at `address` (the column of the first
// beat). The id is the requester's; the controller returns it unchanged.
struct Request {
  std::uint64_t id = 0;
  RequestKind kind = RequestKind::kRead;
  Address address;
  Cycle arrival = 0;  // the cycle it entered the controller
};

std::ostream& operator<<(std::ostream& os, const Request& r);

// The column command that serves a request.
constexpr Command column_command(RequestKind k) {
  return k == RequestKind::kRead ? Command::kRd : Command::kWr;
}

// A request waiting in the controller, with what the controller learned
// about it so far.
struct PendingRequest {
  Request request;
  // Set when the first command for this request is issued: how its row met
  // its bank then (a row opened for an earlier request makes it a hit).
  std::optional<RowOutcome> outcome;
  Cycle first_command = kNever;
};

// What the scheduler wants on the command bus this cycle.
struct Decision {
  Command command = Command::kNop;
  Address address;
  // The pending request this command works for; a column command completes
  // it. Empty for housekeeping commands that serve no single request (a
  // close-page PRE, a speculative ACT).
  std::optional<std::size_t> request;
};

std::ostream& operator<<(std::ostream& os, const Decision& d);

// The tunables of the policies that look past the oldest request
// (sched/registry.hpp passes them; the in-order policy ignores them).
struct SchedulerParams {
  int reorder_window = 8;     // pending requests considered, oldest first (>= 1)
  int starvation_limit = 64;  // FR-FCFS: commands for younger requests while the oldest waits
};

// What a scheduler sees each cycle.
struct SchedulerView {
  std::span<const PendingRequest> pending;  // in arrival order, oldest first
  const Dimm& dimm;
  Cycle now;
  // False while the read-data return path has no free slot: column commands
  // must wait (back-pressure), row commands may still go.
  bool column_allowed;
};

// Contract (a command scheduler):
//   - pick() is called by the Controller once per cycle in which no refresh
//     is in progress. It returns the command to issue this cycle, or nothing
//     (the command bus idles).
//   - The command must be legal now: view.dimm.can_issue(command, address,
//     view.now). The Controller issues it through Dimm::issue, which throws on
//     an illegal command: a scheduler bug is an error, never a silent stall.
//   - A command for a request (Decision::request set) must be that request's
//     next command (Dimm::next_command); its column command completes it.
//     Column commands only when view.column_allowed.
//   - Row policy is the scheduler's: an open-page policy never precharges
//     except to resolve a conflict; refresh closes all rows (the Controller
//     does that, not the scheduler).
//   - Schedulers may keep state (a window position, statistics); the
//     Controller calls pick() with strictly increasing cycles.
//   - wake(view), asked after a cycle's pick(), is a cycle > view.now before
//     which pick() would return nothing provided nothing changes meanwhile:
//     no request arrives, no command issues, no return slot frees (the
//     Controller's next-event hint, Controller::next_event, lets the
//     simulation skip the cycles in between). Between such events the banks,
//     the pending list and column_allowed are fixed, so a command becomes
//     legal only when the timing table allows it: the earliest cycle over the
//     commands the policy would consider is exact. view.now + 1 (the
//     default) is always correct. kNoWake: never, until something changes.
// Implementations:
//   sched/in_order.hpp  in-order open page: only the oldest request, its next
//                       command as soon as it is legal (the VIZARD II
//                       baseline).
//   sched/fr_fcfs.hpp   FR-FCFS within a reorder window: row hits first, then
//                       oldest (Rixner et al., ISCA 2000), with a bound on
//                       how often the oldest request is bypassed.
//   sched/lookahead.hpp in order, plus PRE/ACT for a later request to a bank
//                       no older request uses while the current row streams.
class CommandScheduler {
 public:
  virtual ~CommandScheduler() = default;
  virtual std::string_view name() const = 0;
  virtual std::optional<Decision> pick(const SchedulerView& view) = 0;
  virtual Cycle wake(const SchedulerView& view) const { return view.now + 1; }
};

// "Nothing to do until something changes" (CommandScheduler::wake).
inline constexpr Cycle kNoWake = std::numeric_limits<Cycle>::max() / 4;

}  // namespace voxcast::rtl::sdram
