// voxcast sweep SCENE --vary KEY=V1,V2,... --out DIR (docs/sweep.md).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/explore/sweep.hpp"

namespace voxcast::cosim::commands {

Subcommand add_sweep(CLI::App& voxcast) {
  struct Args {
    std::string scene, shard = "0/1", part = "xc7a200t";
    std::vector<std::string> vary;
    ref::Overrides sets;
    TruthSettings truth;
    sweep::SweepOptions options;
    bool no_plots = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand(
      "sweep", "Accuracy against the truth and modelled speed over a product of scene settings");
  cmd->add_option("scene", a->scene, "Scene file (TOML)")->required();
  cmd->add_option("--vary", a->vary, "KEY=V1,V2,... or KEY=A..B (integers); repeat for a product")
      ->take_all()
      ->allow_extra_args(false)
      ->required();
  cmd->add_option("--out", a->options.out_dir, "Output folder (results.csv, results.json, plots)")
      ->required();
  cmd->add_option("--jobs", a->options.jobs, "Points in parallel")->capture_default_str();
  cmd->add_option("--shard", a->shard, "Compute only the points with index % n == i (i/n)")
      ->capture_default_str();
  cmd->add_flag("--progress", a->options.progress, "Progress on stderr even when not a TTY");
  cmd->add_flag("--no-plots", a->no_plots, "Do not run gnuplot");
  cmd->add_flag("--resume", a->options.resume,
                "Keep the finished points of OUT/points (the same sweep, checked) and compute the rest");
  cmd->add_option("--truth-cache", a->options.truth_cache,
                  "Folder of truth images kept on disk, shared by shards and later runs "
                  "(default OUT/truth)");
  cmd->add_flag("--html", a->options.html,
                "Write OUT/sweep.html: the plots with every point labelled, the front marked");
  cmd->add_option("--part", a->part, "Part of the resource columns (voxcast report's parts)")
      ->capture_default_str();
  cmd->add_option("--truth-oversampling", a->truth.oversampling,
                  "Oversampling of the truth (the float reference)")
      ->capture_default_str();
  add_set_option(*cmd, a->sets);
  return {cmd, [a] {
            a->options.shard = sweep::parse_shard(a->shard);
            a->options.plots = !a->no_plots;
            sweep::Plan plan = sweep::make_plan(a->scene, a->sets, a->vary, a->truth);
            plan.part = a->part;
            sweep::print_sweep_summary(std::cout, sweep::run_sweep(plan, a->options));
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
