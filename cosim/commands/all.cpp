// The subcommand list and the options several subcommands share.
#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"

namespace voxcast::cosim::commands {

std::vector<Subcommand> add_all(CLI::App& voxcast) {
  return {add_render(voxcast),       add_cosim(voxcast),        add_sweep(voxcast),
          add_sweep_merge(voxcast),  add_sweep_status(voxcast), add_regress(voxcast),
          add_paper(voxcast),        add_bench(voxcast),        add_flythrough(voxcast),
          add_burst_study(voxcast),  add_demo(voxcast),         add_constraints(voxcast),
          add_synth_script(voxcast), add_report(voxcast),       add_fuzz_scenes(voxcast),
          add_tune(voxcast),         add_dram_trace(voxcast)};
}

void add_set_option(CLI::App& cmd, ref::Overrides& overrides) {
  cmd.add_option("--set", overrides,
                 "Override a scene key, e.g. --set render.oversampling=4 (repeatable)")
      ->take_all()
      ->allow_extra_args(false);
}

}  // namespace voxcast::cosim::commands
