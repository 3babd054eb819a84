// Policies by name, for configurations and the command line.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "rtl_model/sdram/refresh.hpp"
#include "rtl_model/sdram/scheduler.hpp"

namespace voxcast::rtl::sched {

// "in-order" (InOrderOpenPage), "fr-fcfs" (FrFcfs), "lookahead"
// (LookAheadActivation). Throws voxcast::Error naming the known ones, or for
// parameters out of range.
std::unique_ptr<sdram::CommandScheduler> make_scheduler(const std::string& name,
                                                        const sdram::SchedulerParams& params = {});
std::vector<std::string> scheduler_names();

// "eager" (EagerRefresh). Throws voxcast::Error naming the known ones.
std::unique_ptr<sdram::RefreshPolicy> make_refresh_policy(const std::string& name);
std::vector<std::string> refresh_policy_names();

}  // namespace voxcast::rtl::sched
