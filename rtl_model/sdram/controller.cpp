#include "rtl_model/sdram/controller.hpp"

#include <algorithm>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>

#include "refmodel/error.hpp"

namespace voxcast::rtl::sdram {

// ---- Printing ----------------------------------------------------------------------------
std::ostream& operator<<(std::ostream& os, const Request& r) {
  return os << "request " << r.id << " " << (r.kind == RequestKind::kRead ? "read" : "write") << " "
            << r.address << " arrived at cycle " << r.arrival;
}

std::ostream& operator<<(std::ostream& os, const Decision& d) {
  os << describe(d.command, d.address);
  if (d.request) os << " for pending request #" << *d.request;
  return os;
}

std::ostream& operator<<(std::ostream& os, const Completion& c) {
  return os << c.request << ": row " << c.outcome << ", first command at " << c.first_command
            << ", column command at " << c.column_command << ", " << c.data << ", latency "
            << c.latency();
}

double ControllerStats::mean_latency() const {
  return completed == 0 ? 0.0 : static_cast<double>(latency_sum) / static_cast<double>(completed);
}

std::ostream& operator<<(std::ostream& os, const ControllerStats& s) {
  os << s.cycles << " cycles: " << s.requests << " requests (" << s.reads << " reads, "
            << s.writes << " writes), rows " << s.row_hits << " hit / " << s.row_misses
            << " miss / " << s.row_conflicts << " conflict, " << s.completed << " completed, "
            << s.bytes << " bytes, mean latency " << s.mean_latency() << " (max " << s.latency_max
            << ") cycles, command bus busy " << s.command_cycles << " cycles, refreshing "
            << s.refresh_cycles << " cycles";
  if (s.auto_precharges > 0) os << ", " << s.auto_precharges << " reads with auto precharge";
  return os;
}

// ---- Controller --------------------------------------------------------------------------
Controller::Controller(DimmConfig dimm, std::unique_ptr<CommandScheduler> scheduler,
                       std::unique_ptr<RefreshPolicy> refresh, ControllerConfig config)
    : dimm_(std::move(dimm)),
      scheduler_(std::move(scheduler)),
      refresh_(std::move(refresh)),
      config_(config),
      pending_(config.queue_depth),
      completions_("sdram.completions", config.return_depth),
      in_flight_(config.return_depth) {
  if (!scheduler_ || !refresh_)
    throw Error("Controller: a scheduler and a refresh policy are required");
  if (config_.queue_depth == 0) throw Error("Controller: request queue depth 0");
}

void Controller::queue_full(const Request& r) const {
  std::ostringstream os;
  os << "controller request queue (depth " << config_.queue_depth << ") is full: push of " << r;
  throw Error(os.str());
}

void Controller::outside_the_dimm(const Request& r) const {
  std::ostringstream os;
  os << "controller: " << r << " is outside the DIMM (" << dimm_.geometry() << ")";
  throw Error(os.str());
}

void Controller::tick(Cycle now) {
  if (now <= last_tick_) {
    throw Error("controller: tick(" + std::to_string(now) + ") after tick(" +
                std::to_string(last_tick_) + ")");
  }
  last_tick_ = now;
  ++stats_.cycles;
  if (!step_refresh(now)) schedule(now);
  retire(now);
  completions_.sample();
}

Cycle Controller::next_event(Cycle now) const {
  if (refreshing_) return now + 1;  // the sequence counts its cycles
  Cycle w = refresh_->wake(dimm_.refresh(), now);
  if (!in_flight_.empty()) w = std::min(w, in_flight_.front().data.last);
  if (!pending_.empty())
    w = std::min(w, scheduler_->wake(SchedulerView{pending_.span(), dimm_, now, column_allowed()}));
  return std::max(w, now + 1);
}

bool Controller::step_refresh(Cycle now) {
  if (!refreshing_) {
    if (!refresh_->refresh_now(dimm_.refresh(), now, pending_.size())) return false;
    refreshing_ = true;
  }
  ++stats_.refresh_cycles;
  // Close every open row, then refresh, each as soon as the table allows.
  const Command cmd = dimm_.all_banks_idle() ? Command::kRef : Command::kPrea;
  if (dimm_.can_issue(cmd, Address{}, now)) {
    dimm_.issue(cmd, Address{}, now);
    ++stats_.command_cycles;
    if (cmd == Command::kRef) refreshing_ = false;
  }
  return true;
}

bool Controller::column_allowed() const {
  return in_flight_.size() + completions_.size() < completions_.depth();
}

void Controller::schedule(Cycle now) {
  const SchedulerView view{pending_.span(), dimm_, now, column_allowed()};
  const std::optional<Decision> d = scheduler_->pick(view);
  if (!d || d->command == Command::kNop) return;

  // Step 1: hold the scheduler to its contract (scheduler.hpp).
  auto fail = [&](const std::string& what) {
    std::ostringstream os;
    os << "scheduler '" << scheduler_->name() << "' at cycle " << now << ": " << *d << ": " << what;
    throw Error(os.str());
  };
  if (is_column_command(d->command) && !view.column_allowed) {
    fail("column command while the return FIFO has no free slot");
  }
  std::optional<RowOutcome> outcome;
  if (d->request) {
    if (*d->request >= pending_.size()) fail("no such pending request");
    const Request& r = pending_[*d->request].request;
    outcome = dimm_.row_outcome(r.address);
    const Command expected = first_command(*outcome, column_command(r.kind));
    if (d->command != expected || d->address != r.address) {
      fail("not the request's next command (" + describe(expected, r.address) + ")");
    }
  } else if (is_column_command(d->command)) {
    fail("a column command must serve a request");
  }

  // Step 2: issue; the Dimm rejects anything illegal. With auto_precharge, a
  // READ that is the last the queue holds for its row closes the row itself.
  Command command = d->command;
  if (config_.auto_precharge && command == Command::kRd && !row_wanted_by_another(*d->request) &&
      dimm_.can_issue(Command::kRda, d->address, now)) {
    command = Command::kRda;
    ++stats_.auto_precharges;
  }
  const Issued issued = dimm_.issue(command, d->address, now);
  ++stats_.command_cycles;
  if (!d->request) return;

  // Step 3: account the request; a column command completes it.
  PendingRequest& p = pending_[*d->request];
  if (!p.outcome) {
    p.outcome = outcome;
    p.first_command = now;
    switch (*outcome) {
      case RowOutcome::kHit:
        ++stats_.row_hits;
        break;
      case RowOutcome::kMiss:
        ++stats_.row_misses;
        break;
      case RowOutcome::kConflict:
        ++stats_.row_conflicts;
        break;
    }
  }
  if (is_column_command(d->command)) {
    ++(d->command == Command::kRd ? stats_.reads : stats_.writes);
    in_flight_.push(Completion{
        .request = p.request,
        .outcome = *p.outcome,
        .first_command = p.first_command,
        .column_command = now,
        .data = *issued.data,
    });
    pending_.erase(*d->request);
  }
}

bool Controller::row_wanted_by_another(std::size_t request) const {
  const Address& a = pending_[request].request.address;
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    const Address& b = pending_[i].request.address;
    if (i != request && b.bank == a.bank && b.row == a.row) return true;
  }
  return false;
}

void Controller::retire(Cycle now) {
  const std::uint64_t burst_bytes =
      static_cast<std::uint64_t>(dimm_.timing().BL) * dimm_.geometry().bytes_per_beat();
  while (!in_flight_.empty() && in_flight_.front().data.last <= now) {
    const Completion& c = in_flight_.front();
    const Cycle latency = c.latency();
    completions_.push_copy(c);  // (as one block) a slot was reserved at the column command
    in_flight_.pop();
    ++stats_.completed;
    stats_.bytes += burst_bytes;
    stats_.latency_sum += latency;
    stats_.latency_max = std::max(stats_.latency_max, latency);
  }
}

void Controller::expect_drained() const {
  if (!pending_.empty() || !in_flight_.empty()) {
    std::ostringstream os;
    os << "controller: " << pending_.size() << " request(s) pending and " << in_flight_.size()
       << " access(es) in flight at the end";
    if (!pending_.empty()) os << "; oldest: " << pending_.front().request;
    throw Error(os.str());
  }
  completions_.expect_drained();
}

}  // namespace voxcast::rtl::sdram
