#include "rtl_model/sched/registry.hpp"

#include "refmodel/error.hpp"
#include "rtl_model/sched/in_order.hpp"
#include "rtl_model/sched/refresh_eager.hpp"

namespace voxcast::rtl::sched {

std::unique_ptr<sdram::CommandScheduler> make_scheduler(const std::string& name) {
  if (name == "in-order") return std::make_unique<InOrderOpenPage>();
  throw Error("unknown command scheduler '" + name + "' (known: in-order)");
}

std::vector<std::string> scheduler_names() { return {"in-order"}; }

std::unique_ptr<sdram::RefreshPolicy> make_refresh_policy(const std::string& name) {
  if (name == "eager") return std::make_unique<EagerRefresh>();
  throw Error("unknown refresh policy '" + name + "' (known: eager)");
}

std::vector<std::string> refresh_policy_names() { return {"eager"}; }

}  // namespace voxcast::rtl::sched
