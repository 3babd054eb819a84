// voxcast sweep SCENE --vary KEY=V1,V2,... --out DIR (docs/sweep.md).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/cluster/cluster_runs.hpp"
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
    cluster::SlurmOptions slurm;
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
  cmd->add_flag("--truth-only", a->options.truth_only,
                "Render the truth of every point into the truth cache, nothing else "
                "(a cluster run's truth job)");
  cmd->add_flag("--truth-from-cache", a->options.truth_from_cache,
                "Read every truth from the truth cache and never render one; a missing truth "
                "is an error (a cluster run's shards)");
  cmd->add_flag("--resume-if-started", a->options.resume_if_started,
                "--resume when OUT holds this sweep's journal, else start afresh (a shard that "
                "may run again)");
  CLI::Option* slurm =
      cmd->add_option("--slurm", a->slurm.shards,
                      "Run on Slurm as N shards: a truth job, a job array of N shards after it, "
                      "a merge job after them, all in OUT (docs/cluster.md)");
  cmd->add_option("--slurm-opt", a->slurm.options,
                  "sbatch options of every job, e.g. \"--partition=long --time=4:00:00 --mem=8G\"")
      ->needs(slurm);
  cmd->add_flag("--dry-run", a->slurm.dry_run,
                "With --slurm: write the scripts into OUT/slurm, submit nothing")
      ->needs(slurm);
  add_set_option(*cmd, a->sets);
  return {cmd, [a] {
            if (a->slurm.shards != 0) {
              if (a->shard != "0/1") throw Error("sweep: --slurm N makes the shards itself; leave out --shard");
              if (a->options.truth_only || a->options.truth_from_cache || a->options.resume_if_started)
                throw Error("sweep: --truth-only, --truth-from-cache and --resume-if-started are the "
                            "cluster jobs' own options, not --slurm's");
              a->slurm.resume = a->options.resume;
              // Checked here, before anything is written or submitted.
              (void)sweep::make_plan(a->scene, a->sets, a->vary, a->truth);
              cluster::run_on_slurm(
                  cluster::sweep_cluster_plan({a->scene, a->vary, a->sets, a->truth.oversampling,
                                               a->part, a->options.jobs, !a->no_plots, a->options.html,
                                               a->options.out_dir},
                                              a->slurm),
                  a->slurm, std::cout);
              return 0;
            }
            a->options.shard = sweep::parse_shard(a->shard);
            a->options.plots = !a->no_plots;
            sweep::Plan plan = sweep::make_plan(a->scene, a->sets, a->vary, a->truth);
            plan.part = a->part;
            sweep::print_sweep_summary(std::cout, sweep::run_sweep(plan, a->options));
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
