// voxcast regress: every scene x preset against the golden hashes; on a Slurm
// cluster, the cases spread over a job array (--slurm N) and joined (--merge).
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "cosim/cluster/cluster_runs.hpp"
#include "cosim/commands/command.hpp"
#include "cosim/explore/sweep_plan.hpp"
#include "cosim/verify/regress.hpp"
#include "refmodel/error.hpp"

namespace voxcast::cosim::commands {

Subcommand add_regress(CLI::App& voxcast) {
  struct Args {
    RegressOptions options{"scenes", "tests/golden/regress", {"vizard2", "balanced", "precise"}, false, {}};
    std::string shard = "0/1", out;
    std::vector<std::string> merge;
    cluster::SlurmOptions slurm;
  };
  auto a = std::make_shared<Args>();
  RegressOptions& opt = a->options;
  CLI::App* cmd = voxcast.add_subcommand(
      "regress", "Bit-accuracy regression: every scene x preset, hls == bit-true == golden hash");
  cmd->add_option("--scenes", opt.scenes_dir, "Folder of scenes")->capture_default_str();
  cmd->add_option("--golden", opt.golden_dir, "Folder of golden files")->capture_default_str();
  cmd->add_option("--profiles", opt.profiles, "Presets to run")->delimiter(',');
  cmd->add_option("--scene", opt.only_scenes,
                  "Only this scene of --scenes (its file name without .toml; repeatable)");
  cmd->add_flag("--bless", opt.bless,
                "Measure accuracy against the float reference and (re)write the golden files "
                "of the cases that meet their floor");
  cmd->add_option("--junit", opt.junit_path,
                  "Write the cases as JUnit XML here (Jenkins, GitLab): one per scene x preset");
  cmd->add_option("--shard", a->shard,
                  "Run only the cases whose index in the scene x preset list is i modulo n (i/n)")
      ->capture_default_str();
  cmd->add_option("--results", opt.results_path,
                  "Write this run's cases as JSON for --merge; the run then exits 0 once its "
                  "cases ran, failed or not: the verdict is the merge's");
  cmd->add_option("--merge", a->merge,
                  "Join the --results files of the shards: the table, the summary, --junit and "
                  "the exit status of one local run")
      ->take_all();
  CLI::Option* slurm = cmd->add_option(
      "--slurm", a->slurm.shards,
      "Run on Slurm: the cases over a job array of N shards and a merge job after them, "
      "in --out DIR (docs/cluster.md)");
  cmd->add_option("--out", a->out, "With --slurm: the folder of the scripts, logs and results")
      ->needs(slurm);
  cmd->add_option("--slurm-opt", a->slurm.options,
                  "sbatch options of every job, e.g. \"--partition=ci --time=0:30:00\"")
      ->needs(slurm);
  cmd->add_flag("--dry-run", a->slurm.dry_run, "With --slurm: write the scripts, submit nothing")
      ->needs(slurm);
  cmd->add_flag("--resume", a->slurm.resume,
                "With --slurm: submit again only the shards (and merge) that did not finish")
      ->needs(slurm);
  add_set_option(*cmd, opt.overrides);
  return {cmd, [a] {
            RegressOptions& o = a->options;
            if (a->slurm.shards != 0) {
              if (a->shard != "0/1" || !o.results_path.empty() || !a->merge.empty())
                throw Error("regress: --slurm N makes the shards and the merge itself; leave out "
                            "--shard, --results and --merge");
              cluster::run_on_slurm(cluster::regress_cluster_plan(o, a->out, a->slurm), a->slurm,
                                    std::cout);
              return 0;
            }
            int failed = 0;
            if (!a->merge.empty()) {
              if (a->shard != "0/1" || !o.results_path.empty() || o.bless)
                throw Error("regress --merge joins results: leave out --shard, --results and --bless");
              failed = run_regress_merge(a->merge, o, std::cout);
            } else {
              const sweep::Shard s = sweep::parse_shard(a->shard);
              o.shard_index = s.index;
              o.shard_count = s.count;
              failed = run_regress(o, std::cout);
              if (!o.results_path.empty()) return 0;  // the merge gives the verdict
            }
            if (failed == 0) return 0;
            std::cerr << "voxcast: regress: " << failed << " case(s) failed\n";
            return 4;
          }};
}

}  // namespace voxcast::cosim::commands
