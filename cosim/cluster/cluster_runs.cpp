#include "cosim/cluster/cluster_runs.hpp"

#include <unistd.h>

#include <filesystem>

#include "cosim/reports/files.hpp"
#include "refmodel/error.hpp"

namespace voxcast::cosim::cluster {
namespace fs = std::filesystem;

namespace {

std::string absolute(const std::string& path) {
  return fs::weakly_canonical(fs::absolute(path)).string();
}

void check_slurm_options(const SlurmOptions& s, const std::string& who) {
  if (s.shards < 1 || s.shards > 10000)
    throw Error(who + ": --slurm " + std::to_string(s.shards) + ": give 1 to 10000 shards");
}

std::string joined(const std::vector<std::string>& values) {
  std::string s;
  for (const std::string& v : values) s += (s.empty() ? "" : ",") + v;
  return s;
}

// "16" rather than "16.000000": the number as the user would type it.
std::string number_text(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

}  // namespace

std::string this_executable() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw Error("cannot find the running voxcast (/proc/self/exe): " + ec.message());
  return p.string();
}

ClusterPlan sweep_cluster_plan(const SweepCommandLine& cmd, const SlurmOptions& slurm) {
  check_slurm_options(slurm, "sweep");
  if (cmd.out.empty()) throw Error("sweep --slurm: --out DIR is required");
  if (!fs::is_regular_file(cmd.scene)) throw Error("sweep --slurm: " + cmd.scene + ": no such scene file");
  ClusterPlan p;
  p.kind = "sweep";
  p.dir = absolute(cmd.out);
  p.shards = slurm.shards;
  p.sbatch_options = parse_sbatch_options(slurm.options, "sweep");
  const std::string exe = this_executable();
  std::vector<std::string> common = {exe, "sweep", absolute(cmd.scene)};
  for (const std::string& v : cmd.vary) common.insert(common.end(), {"--vary", v});
  for (const std::string& s : cmd.sets) common.insert(common.end(), {"--set", s});
  common.insert(common.end(), {"--truth-oversampling", number_text(cmd.truth_oversampling),
                               "--part", cmd.part, "--jobs", std::to_string(cmd.jobs)});
  const std::string truth_dir = (fs::path(p.dir) / "truth").string();
  p.truth_command = common;
  p.truth_command.insert(p.truth_command.end(),
                         {"--out", p.dir, "--truth-only", "--truth-cache", truth_dir});
  p.shard_command = common;
  p.shard_command.insert(
      p.shard_command.end(),
      {"--out", (fs::path(p.dir) / "shards" / kShardToken).string(), "--shard",
       std::string(kShardToken) + "/" + std::to_string(p.shards), "--truth-cache", truth_dir,
       "--truth-from-cache", "--resume-if-started", "--no-plots"});
  p.merge_command = {exe, "sweep-merge"};
  for (int k = 0; k < p.shards; ++k)
    p.merge_command.push_back((fs::path(p.dir) / "shards" / std::to_string(k)).string());
  p.merge_command.insert(p.merge_command.end(), {"--out", p.dir});
  if (!cmd.plots) p.merge_command.push_back("--no-plots");
  if (cmd.html) p.merge_command.push_back("--html");
  return p;
}

ClusterPlan regress_cluster_plan(const RegressOptions& r, const std::string& out,
                                 const SlurmOptions& slurm) {
  check_slurm_options(slurm, "regress");
  if (out.empty()) throw Error("regress --slurm: --out DIR is required (the shards' results and logs)");
  if (r.bless) throw Error("regress --slurm: --bless writes the golden files: run it on one machine");
  if (!fs::is_directory(r.scenes_dir)) throw Error(r.scenes_dir + ": not a folder of scenes");
  ClusterPlan p;
  p.kind = "regress";
  p.dir = absolute(out);
  p.shards = slurm.shards;
  p.sbatch_options = parse_sbatch_options(slurm.options, "regress");
  const std::string exe = this_executable();
  std::vector<std::string> common = {exe,      "regress", "--scenes", absolute(r.scenes_dir),
                                     "--golden", absolute(r.golden_dir), "--profiles",
                                     joined(r.profiles)};
  for (const std::string& s : r.only_scenes) common.insert(common.end(), {"--scene", s});
  for (const std::string& s : r.overrides) common.insert(common.end(), {"--set", s});
  p.shard_command = common;
  p.shard_command.insert(
      p.shard_command.end(),
      {"--shard", std::string(kShardToken) + "/" + std::to_string(p.shards), "--results",
       (fs::path(p.dir) / "shards" / (std::string(kShardToken) + ".json")).string()});
  p.merge_command = {exe, "regress", "--merge"};
  for (int k = 0; k < p.shards; ++k)
    p.merge_command.push_back((fs::path(p.dir) / "shards" / (std::to_string(k) + ".json")).string());
  if (!r.junit_path.empty()) p.merge_command.insert(p.merge_command.end(), {"--junit", absolute(r.junit_path)});
  return p;
}

void run_on_slurm(const ClusterPlan& plan, const SlurmOptions& slurm, std::ostream& os) {
  make_output_dir(plan.dir);
  const SubmitRequest req = slurm.resume ? resume_request(plan) : fresh_request(plan);
  if (!slurm.resume) {
    // A fresh run: the shards start afresh too (a shard keeps its journal only on --resume).
    std::error_code ec;
    fs::remove_all(fs::path(plan.dir) / "shards", ec);
  }
  const bool nothing = !req.truth && req.shards.empty() && !req.merge;
  std::vector<std::string> written;
  if (!nothing) written = write_cluster_scripts(plan, req);
  std::optional<Submission> sub;
  if (!nothing && !slurm.dry_run) sub = submit(plan);
  print_submission(os, plan, req, sub, written);
}

}  // namespace voxcast::cosim::cluster
