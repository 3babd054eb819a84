// voxcast sweep-status DIR: what a cluster run (sweep or regress --slurm) has
// done, per job, from the files in DIR and from scontrol.
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "cosim/cluster/slurm.hpp"
#include "cosim/commands/command.hpp"

namespace voxcast::cosim::commands {

Subcommand add_sweep_status(CLI::App& voxcast) {
  auto dir = std::make_shared<std::string>();
  CLI::App* cmd = voxcast.add_subcommand(
      "sweep-status",
      "Per job of a cluster run (sweep or regress --slurm): done, running, pending or failed, "
      "with its exit status and log");
  cmd->add_option("dir", *dir, "The run's folder (its --out)")->required();
  return {cmd, [dir] {
            const cluster::ClusterStatus s = cluster::read_status(*dir);
            cluster::print_status(std::cout, s, *dir);
            // Still running dominates: 9 means nothing more will happen without a resume.
            if (s.finished()) return s.regress_failed ? 4 : 0;
            for (const cluster::JobStatus& j : s.jobs)
              if (j.state == cluster::JobState::Running || j.state == cluster::JobState::Pending)
                return 10;
            return 9;
          }};
}

}  // namespace voxcast::cosim::commands
