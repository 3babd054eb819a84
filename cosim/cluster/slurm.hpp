// A sweep or a regression on a Slurm cluster (docs/cluster.md): one truth job,
// a job array of N shards that starts after it succeeded, and a merge job
// after every shard succeeded, each an sbatch script voxcast writes into
// DIR/slurm and submits through Slurm's own commands (sbatch; scontrol to
// watch). Dependencies are `afterok` with --kill-on-invalid-dep=yes, so a
// failed job cancels what waits on it instead of leaving it pending for ever
// (../shared/BUILD-NOTES.md). Each job records its exit status in
// DIR/slurm/status/NAME.exit when it ends, so the files alone say what finished
// even after the scheduler has forgotten the jobs.
//
//   DIR/slurm/plan.json      what the run is (kind, shards, the jobs' commands)
//   DIR/slurm/*.sbatch       truth, shards (array), merge
//   DIR/slurm/submit.sh      the sbatch calls with their dependencies
//   DIR/slurm/jobs.env       the job ids of the latest submission (submit.sh writes it)
//   DIR/slurm/logs/          NAME.log (shard-K.log for array task K; appended on resubmission)
//   DIR/slurm/status/        NAME.exit
#pragma once

#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace voxcast::cosim::cluster {

// In a shard's command, this stands for the array task's index.
inline constexpr char kShardToken[] = "@K@";

// What a cluster run is. Commands are argument vectors; paths in them are
// absolute, since the jobs run wherever the scheduler puts them.
struct ClusterPlan {
  std::string kind;                        // "sweep" or "regress"
  std::string dir;                         // the run's folder, absolute
  int shards = 1;
  std::vector<std::string> sbatch_options;  // one #SBATCH line each (--slurm-opt)
  std::vector<std::string> truth_command;   // empty: no truth job
  std::vector<std::string> shard_command;   // with kShardToken
  std::vector<std::string> merge_command;
};

// Which jobs a submission sends: all of them at first; on --resume only what
// has not finished.
struct SubmitRequest {
  bool truth = false;
  std::vector<int> shards;
  bool merge = true;
};

// The shell's single-quoted form of `word` ('it'\''s').
std::string shell_quote(const std::string& word);

// --slurm-opt "--partition=gpu --time=2:00:00": the sbatch options, one word
// each; a word that is not an option (does not start with '-') or holds a
// quote is an error naming it.
std::vector<std::string> parse_sbatch_options(const std::vector<std::string>& texts,
                                              const std::string& who);

// Writes DIR/slurm (plan.json, the scripts of the jobs in `req`, submit.sh)
// and clears the exit status of each job it will submit. Returns the paths
// written.
std::vector<std::string> write_cluster_scripts(const ClusterPlan& plan, const SubmitRequest& req);

struct Submission {
  std::string truth, shards, merge;  // job ids ("" where not submitted)
};

// Runs DIR/slurm/submit.sh (after checking that sbatch is on PATH) and reads
// the ids it wrote to jobs.env. A refusal by sbatch is an Error with its words.
Submission submit(const ClusterPlan& plan);

// "0-3", "1,3,5-7", "0-15%4" (a limit), "0-9:3" (a step): Slurm's array index lists.
std::vector<int> parse_array_indices(const std::string& spec);

// One record of `scontrol -o show job`, as its Key=Value pairs.
using JobRecord = std::map<std::string, std::string>;
std::vector<JobRecord> parse_scontrol_records(const std::string& text);

enum class JobState { Done, Running, Pending, Failed, NotStarted };
const char* state_name(JobState s);

struct JobStatus {
  std::string name;  // "truth", "shard 3", "merge"
  JobState state = JobState::NotStarted;
  std::string detail;  // exit status, Slurm's state and reason, points journaled
  std::string log;     // its log file
};

struct ClusterStatus {
  std::string kind;
  int shards = 0;
  std::vector<JobStatus> jobs;  // truth (if any), shard 0..N-1, merge
  bool scheduler_asked = false; // scontrol answered for at least one job
  bool regress_failed = false;  // a regression's merge exited 4: cases failed
  bool finished() const;        // every job Done
};

// The status of the run in DIR: from the exit files and logs in DIR/slurm,
// and from scontrol where the scheduler still knows the jobs of jobs.env.
ClusterStatus read_status(const std::string& dir);
void print_status(std::ostream& os, const ClusterStatus& s, const std::string& dir);

// The plan.json of an earlier run in `dir`, if there is one.
std::optional<nlohmann::json> read_plan(const std::string& dir);
nlohmann::json plan_json(const ClusterPlan& plan);

// --resume: the earlier run in plan.dir must be this one (same commands, same
// shards) and none of its jobs may still be pending or running; returns the
// jobs without a successful exit.
SubmitRequest resume_request(const ClusterPlan& plan);

// A fresh submission: every job; removes the earlier run's exit files.
SubmitRequest fresh_request(const ClusterPlan& plan);

// Prints what was written and submitted, the job ids and how to watch them.
void print_submission(std::ostream& os, const ClusterPlan& plan, const SubmitRequest& req,
                      const std::optional<Submission>& sub, const std::vector<std::string>& written);

}  // namespace voxcast::cosim::cluster
