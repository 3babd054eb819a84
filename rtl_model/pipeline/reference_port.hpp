// ReferencePort: the reference sdram::Controller behind the MemoryPort
// interface (memory_port.hpp). It ticks the controller and,
// for policies whose next action is predictable from outside, knows the first
// cycle at which a tick can change anything (wake()), so the pipeline need
// not tick a controller that is only waiting for a timing constraint.
//
// Predictable: the in-order open-page scheduler with eager refresh
// (sched/in_order.hpp, sched/refresh_eager.hpp). After any tick, their next
// tick acts only
//   - when a REF is due (eager refresh starts then and runs to the REF),
//   - when an access's last data beat is at now (retire),
//   - when the oldest request's next command is legal at now, which, with no
//     command issued and no request retired in between, is
//     Dimm::earliest(command, bank) (the bank states do not change), and for
//     a column command only with a free return slot (freed by the consumer's
//     pop, after which the port ticks again at once).
// The port mirrors what it needs with the controller's public state: the
// requests it pushed (oldest first; the in-order scheduler completes them in
// that order) and the data windows of the reads issued. Any other policy is
// ticked every cycle. Skipping changes nothing but the controller's own tick
// counters (ControllerStats::cycles, the completions FIFO's sampled cycles);
// tests/rtl check cycles, commands and image against ticking every cycle.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

#include "rtl_model/pipeline/memory_port.hpp"
#include "rtl_model/sdram/controller.hpp"

namespace voxcast::rtl::pipeline {

class ReferencePort final : public MemoryPort {
 public:
  ReferencePort(std::unique_ptr<sdram::Controller> controller, bool predictable,
                std::size_t queue_depth, std::size_t return_depth)
      : c_(std::move(controller)), predictable_(predictable) {
    pending_.resize(queue_depth);
    retire_.resize(return_depth + 1);
  }

  const sdram::Controller& controller() const { return *c_; }
  bool ready() const override { return c_->ready(); }
  sim::Fifo<sdram::Completion>& completions() override { return c_->completions(); }
  const sim::Fifo<sdram::Completion>& completions() const override { return c_->completions(); }
  std::size_t pending() const override { return c_->pending(); }
  std::size_t in_flight() const override { return c_->in_flight(); }
  bool idle() const override { return c_->idle(); }
  void expect_drained() const override { c_->expect_drained(); }
  const sdram::ControllerStats& controller_stats() const override { return c_->stats(); }
  const sdram::DimmStats& dimm_stats() const override { return c_->dimm().stats(); }

  // The first cycle at which tick() must run (kNever-free: a cycle >= 0).
  sim::Cycle wake() const override { return predictable_ ? wake_ : 0; }
  void set_observer(sdram::CommandObserver* o) override { c_->set_observer(o); }

  void push(const sdram::Request& r) override {
    c_->push(r);
    if (!predictable_) return;
    pending_[(pending_head_ + pending_count_) % pending_.size()] = r;
    // Only a new oldest request changes what the in-order scheduler does.
    if (++pending_count_ == 1) wake_ = std::min(wake_, r.arrival);
  }

  // The consumer popped a completion: a return slot is free from the next
  // cycle, which matters only if every slot was taken.
  void popped(sim::Cycle now) override {
    if (c_->in_flight() + c_->completions().size() + 1 >= c_->completions().depth())
      wake_ = std::min(wake_, now + 1);
  }

  // One SDRAM clock: ticks the controller unless it provably cannot act.
  void tick(sim::Cycle now) override {
    if (predictable_ && now < wake_) return;
    const std::uint64_t reads = c_->stats().reads;
    const std::uint64_t completed = c_->stats().completed;
    c_->tick(now);
    if (!predictable_) return;
    if (c_->stats().reads != reads) {  // the oldest request's READ: its data window
      pending_head_ = (pending_head_ + 1) % pending_.size();
      --pending_count_;
      const auto& t = c_->dimm().timing();
      retire_[(retire_head_ + retire_count_) % retire_.size()] = now + t.CL + t.BL - 1;
      ++retire_count_;
    }
    for (std::uint64_t n = c_->stats().completed - completed; n > 0; --n) {
      retire_head_ = (retire_head_ + 1) % retire_.size();
      --retire_count_;
    }
    wake_ = next_wake(now);
  }

 private:
  sim::Cycle next_wake(sim::Cycle now) const {
    const sdram::Dimm& dimm = c_->dimm();
    sim::Cycle w = std::max(now + 1, dimm.refresh().next_due());
    if (retire_count_ > 0) w = std::min(w, retire_[retire_head_]);
    if (pending_count_ > 0) {
      const sdram::Request& r = pending_[pending_head_];
      const sdram::Command cmd = dimm.next_command(sdram::Command::kRd, r.address);
      const bool slot_free =
          c_->in_flight() + c_->completions().size() < c_->completions().depth();
      if (!sdram::is_column_command(cmd) || slot_free)
        w = std::min(w, dimm.earliest(cmd, r.address.bank, now + 1));
    }
    return std::max(w, now + 1);
  }

  std::unique_ptr<sdram::Controller> c_;
  bool predictable_;
  sim::Cycle wake_ = 0;
  std::vector<sdram::Request> pending_;  // ring: requests pushed, oldest first
  std::size_t pending_head_ = 0, pending_count_ = 0;
  std::vector<sim::Cycle> retire_;  // ring: last data beat of each read in flight
  std::size_t retire_head_ = 0, retire_count_ = 0;
};

}  // namespace voxcast::rtl::pipeline
