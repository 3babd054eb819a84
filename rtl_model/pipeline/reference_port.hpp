// ReferencePort: the reference sdram::Controller behind the MemoryPort
// interface (memory_port.hpp). It ticks the controller only at the cycles
// where a tick can change anything (wake()): the controller's own
// next-event hint after each tick (Controller::next_event: an access's last
// data beat, the refresh policy's and the scheduler's wake() hints, every
// cycle of a refresh sequence), a request pushed (its arrival), and a return
// slot freed by the consumer's pop while every slot was taken (the next
// cycle). Every policy gives such a hint (sdram/scheduler.hpp), so every
// policy runs event-driven. Skipping changes nothing but the controller's
// own tick counters (ControllerStats::cycles, and the completions FIFO's
// sampled cycles where no owner's clock samples it; the pipeline reports
// neither); tests/rtl compare it completion by completion with the controller
// ticked every cycle, and cycles, statistics and image on whole frames.
#pragma once

#include <algorithm>
#include <cstddef>
#include <memory>

#include "rtl_model/pipeline/memory_port.hpp"
#include "rtl_model/sdram/controller.hpp"

namespace voxcast::rtl::pipeline {

class ReferencePort final : public MemoryPort {
 public:
  // skip_idle_ticks false: tick the controller every cycle (the reference
  // the event-driven runs are compared with).
  ReferencePort(std::unique_ptr<sdram::Controller> controller, bool skip_idle_ticks)
      : c_(std::move(controller)), skip_(skip_idle_ticks) {}

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

  void set_observer(sdram::CommandObserver* o) override { c_->set_observer(o); }

  void push(const sdram::Request& r) override {
    c_->push(r);
    wake_ = std::min(wake_, r.arrival);
  }

  // The consumer popped a completion: a return slot is free from the next
  // cycle, which matters only if every slot was taken.
  void popped(sim::Cycle now) override {
    if (c_->in_flight() + c_->completions().size() + 1 >= c_->completions().depth())
      wake_ = std::min(wake_, now + 1);
  }

  // One SDRAM clock: ticks the controller unless it provably cannot act.
  // A cycle with a command is mostly followed by another in a memory-bound
  // frame: the hint is asked only after a cycle without one (waking early is
  // always correct, it only costs a tick).
  void tick(sim::Cycle now) override {
    if (skip_ && now < wake_) return;
    const sdram::Cycle commands = c_->stats().command_cycles;
    c_->tick(now);
    activity_ = static_cast<std::uint64_t>(c_->stats().command_cycles) + c_->stats().completed;
    if (!skip_) return;  // wake_ stays 0: tick every cycle
    wake_ = c_->stats().command_cycles != commands ? now + 1 : c_->next_event(now);
  }

 private:
  std::unique_ptr<sdram::Controller> c_;
  bool skip_;
};

}  // namespace voxcast::rtl::pipeline
