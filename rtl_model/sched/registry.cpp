#include "rtl_model/sched/registry.hpp"

#include <string>

#include "refmodel/error.hpp"
#include "rtl_model/sched/fr_fcfs.hpp"
#include "rtl_model/sched/in_order.hpp"
#include "rtl_model/sched/lookahead.hpp"
#include "rtl_model/sched/refresh_eager.hpp"

namespace voxcast::rtl::sched {

std::unique_ptr<sdram::CommandScheduler> make_scheduler(const std::string& name,
                                                        const sdram::SchedulerParams& params) {
  if (params.reorder_window < 1)
    throw Error("command scheduler: reorder window " + std::to_string(params.reorder_window) +
                " (must be at least 1)");
  if (params.starvation_limit < 0)
    throw Error("command scheduler: starvation limit " + std::to_string(params.starvation_limit) +
                " (must be at least 0)");
  if (name == "in-order") return std::make_unique<InOrderOpenPage>();
  if (name == "fr-fcfs") return std::make_unique<FrFcfs>(params);
  if (name == "lookahead") return std::make_unique<LookAheadActivation>(params);
  throw Error("unknown command scheduler '" + name + "' (known: in-order, fr-fcfs, lookahead)");
}

std::vector<std::string> scheduler_names() { return {"in-order", "fr-fcfs", "lookahead"}; }

std::unique_ptr<sdram::RefreshPolicy> make_refresh_policy(const std::string& name) {
  if (name == "eager") return std::make_unique<EagerRefresh>();
  throw Error("unknown refresh policy '" + name + "' (known: eager)");
}

std::vector<std::string> refresh_policy_names() { return {"eager"}; }

}  // namespace voxcast::rtl::sched
