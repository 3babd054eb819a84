#include "rtl_model/pipeline/burst_channel.hpp"

#include <algorithm>

#include "refmodel/error.hpp"
#include "rtl_model/sched/registry.hpp"

namespace voxcast::rtl::pipeline {

BurstChannel::BurstChannel(int index, const sdram::DimmConfig& dimm, const std::string& scheduler,
                           const sdram::SchedulerParams& params, const std::string& refresh,
                           const sdram::ControllerConfig& controller, const BurstCardConfig& card)
    : index_(index),
      requests_("channel" + std::to_string(index) + ".requests",
                static_cast<std::size_t>(card.crossing_depth), card.sync_stages),
      returns_("channel" + std::to_string(index) + ".returns",
               static_cast<std::size_t>(card.crossing_depth), card.sync_stages),
      controller_(dimm, sched::make_scheduler(scheduler, params),
                  sched::make_refresh_policy(refresh), controller) {}

void BurstChannel::core_clock() {
  requests_.write_clock();
  returns_.read_clock();
}

void BurstChannel::memory_clock(sdram::Cycle m) {
  requests_.read_clock();
  returns_.write_clock();
  // A request seen across the crossing enters the controller's queue; it may
  // get its first command at this edge.
  if (requests_.valid() && controller_.ready()) {
    const BurstRequest r = requests_.pop();
    sdram::Request q;
    q.id = r.mshr;
    q.kind = sdram::RequestKind::kRead;
    q.address = r.address;
    q.arrival = m;
    controller_.push(q);
    wake_ = m;
  }
  if (m >= wake_) {
    controller_.tick(m);
    wake_ = controller_.next_event(m);
  }
  // A burst whose last beat is in leaves for the core, one per edge.
  auto& done = controller_.completions();
  if (done.valid() && returns_.ready()) {
    returns_.push(BurstReturn{static_cast<std::uint32_t>(done.pop().request.id)});
    wake_ = std::min(wake_, m + 1);
  }
}

bool BurstChannel::idle() const {
  return requests_.size() == 0 && returns_.size() == 0 && controller_.idle();
}

void BurstChannel::expect_drained() const {
  requests_.expect_drained();
  returns_.expect_drained();
  controller_.expect_drained();
}

std::string BurstChannel::state() const {
  return "channel " + std::to_string(index_) + ": " + std::to_string(requests_.size()) +
         " requests crossing, " + std::to_string(controller_.pending()) + " pending, " +
         std::to_string(controller_.in_flight()) + " in flight, " +
         std::to_string(returns_.size()) + " returns crossing";
}

}  // namespace voxcast::rtl::pipeline
