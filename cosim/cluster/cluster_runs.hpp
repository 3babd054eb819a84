// `voxcast sweep ... --slurm N` and `voxcast regress ... --slurm N`
// (docs/cluster.md): the jobs of each kind of run, as a ClusterPlan
// (cosim/cluster/slurm.hpp), and their submission.
//
// A sweep on N shards, in DIR:
//   truth  voxcast sweep SCENE ... --out DIR --truth-only
//          renders each distinct truth image once into DIR/truth;
//   shard  voxcast sweep SCENE ... --out DIR/shards/K --shard K/N --truth-cache DIR/truth
//          --truth-from-cache --resume-if-started --no-plots
//          reads the truths and never renders one; a shard run again keeps its
//          journaled points;
//   merge  voxcast sweep-merge DIR/shards/0 ... DIR/shards/N-1 --out DIR
//          byte-identical to a single-machine run's results.
// A regression on N shards: each shard runs the cases K, K+N, ... of the
// scene x preset list (regress --shard K/N --results DIR/shards/K.json); the
// merge prints the table and exits as a local regress does (4: a case failed).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "cosim/cluster/slurm.hpp"
#include "cosim/verify/regress.hpp"

namespace voxcast::cosim::cluster {

struct SlurmOptions {
  int shards = 0;                    // --slurm N; 0: not on a cluster
  std::vector<std::string> options;  // --slurm-opt (sbatch options)
  bool dry_run = false;              // write the scripts, submit nothing
  bool resume = false;               // submit only what did not finish
};

// The sweep's own command line, as the jobs repeat it.
struct SweepCommandLine {
  std::string scene;
  std::vector<std::string> vary, sets;
  double truth_oversampling = 16.0;
  std::string part;
  int jobs = 1;  // --jobs: points at once within a job
  bool plots = true, html = false;
  std::string out;
};

ClusterPlan sweep_cluster_plan(const SweepCommandLine& cmd, const SlurmOptions& slurm);
ClusterPlan regress_cluster_plan(const RegressOptions& regress, const std::string& out,
                                 const SlurmOptions& slurm);

// Writes the scripts and, unless --dry-run, submits; prints what it did.
void run_on_slurm(const ClusterPlan& plan, const SlurmOptions& slurm, std::ostream& os);

// The absolute path of the running voxcast (the jobs run the same binary).
std::string this_executable();

}  // namespace voxcast::cosim::cluster
