#include "rtl_model/pipeline/memory_port.hpp"

#include "rtl_model/pipeline/fast_in_order_port.hpp"
#include "rtl_model/pipeline/fast_lookahead_port.hpp"
#include "rtl_model/pipeline/reference_port.hpp"
#include "rtl_model/sched/registry.hpp"

namespace voxcast::rtl::pipeline {

std::unique_ptr<MemoryPort> make_memory_port(MemoryModel model, const std::string& scheduler,
                                             const std::string& refresh,
                                             const sdram::DimmConfig& dimm,
                                             const sdram::ControllerConfig& controller,
                                             bool skip_idle_ticks,
                                             const sdram::SchedulerParams& params) {
  // Both names are checked even when the fast port is used.
  auto s = sched::make_scheduler(scheduler, params);
  auto r = sched::make_refresh_policy(refresh);
  // The fast port implements the open-page in-order controller only.
  const bool in_order_eager =
      scheduler == "in-order" && refresh == "eager" && !controller.auto_precharge;
  if (model == MemoryModel::kAuto && in_order_eager)
    return std::make_unique<FastInOrderPort>(dimm, controller);
  // The look-ahead port: open page or auto precharge.
  const bool lookahead_eager = scheduler == "lookahead" && refresh == "eager" &&
                               dimm.geometry.banks <= FastLookAheadPort::kMaxBanks;
  if (model == MemoryModel::kAuto && lookahead_eager)
    return std::make_unique<FastLookAheadPort>(dimm, controller, params.reorder_window);
  return std::make_unique<ReferencePort>(
      std::make_unique<sdram::Controller>(dimm, std::move(s), std::move(r), controller),
      skip_idle_ticks);
}

}  // namespace voxcast::rtl::pipeline
