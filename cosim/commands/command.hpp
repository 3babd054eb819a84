// The subcommands of `voxcast`, one file each in this folder. Each add_*
// function registers its subcommand on the app (its options, their checks and
// help) and returns what running it does; cosim/main.cpp only parses the
// command line, runs the chosen one and turns errors into exit statuses.
//
// A subcommand's run returns its exit status on the paths that are not errors
// (README, "Exit status"): 0, or its own verdict (3 cosim: the engines differ;
// 4 regress / constraints: golden files differ (sweep-status: a cluster regress); 5 tune: no point meets the
// target; 7 fuzz-scenes: findings; 8 cosim: not every engine ran; 9 sweep-status: a job
// failed or never ran; 10 sweep-status: jobs still pending or running). Errors are exceptions (voxcast::Error: 1;
// PrecisionHazardError: 6), caught in one place in main.
#pragma once

#include <functional>
#include <vector>

#include "refmodel/scene/scene_toml.hpp"

namespace CLI {
class App;
}

namespace voxcast::cosim::commands {

struct Subcommand {
  CLI::App* app = nullptr;   // the parsed node: true when the user chose it
  std::function<int()> run;  // the work, after every argument was checked
};

// Every subcommand, in the order `voxcast --help` lists them.
std::vector<Subcommand> add_all(CLI::App& voxcast);

Subcommand add_render(CLI::App& voxcast);
Subcommand add_cosim(CLI::App& voxcast);
Subcommand add_sweep(CLI::App& voxcast);
Subcommand add_sweep_merge(CLI::App& voxcast);
Subcommand add_sweep_status(CLI::App& voxcast);
Subcommand add_regress(CLI::App& voxcast);
Subcommand add_paper(CLI::App& voxcast);
Subcommand add_bench(CLI::App& voxcast);
Subcommand add_flythrough(CLI::App& voxcast);
Subcommand add_burst_study(CLI::App& voxcast);
Subcommand add_demo(CLI::App& voxcast);
Subcommand add_constraints(CLI::App& voxcast);
Subcommand add_synth_script(CLI::App& voxcast);
Subcommand add_report(CLI::App& voxcast);
Subcommand add_fuzz_scenes(CLI::App& voxcast);
Subcommand add_tune(CLI::App& voxcast);
Subcommand add_dram_trace(CLI::App& voxcast);

// --set KEY=VALUE (repeatable): the scene overrides every scene-reading
// subcommand takes.
void add_set_option(CLI::App& cmd, ref::Overrides& overrides);

}  // namespace voxcast::cosim::commands
