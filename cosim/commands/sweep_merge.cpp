// voxcast sweep-merge DIR... --out DIR: the shards of a sweep joined.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/explore/sweep.hpp"

namespace voxcast::cosim::commands {

Subcommand add_sweep_merge(CLI::App& voxcast) {
  struct Args {
    std::vector<std::string> dirs;
    std::string out;
    bool no_plots = false, html = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand(
      "sweep-merge", "Join the outputs of sweep --shard i/n runs into the single run's results");
  cmd->add_option("dirs", a->dirs, "Output folders of the shards")->required();
  cmd->add_option("--out", a->out, "Output folder")->required();
  cmd->add_flag("--no-plots", a->no_plots, "Do not run gnuplot");
  cmd->add_flag("--html", a->html, "Write OUT/sweep.html (as sweep --html)");
  return {cmd, [a] {
            sweep::print_sweep_summary(std::cout,
                                       sweep::run_sweep_merge(a->dirs, a->out, !a->no_plots, a->html));
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
