// Sweeps and regressions on a Slurm cluster (issue 24, docs/cluster.md): the
// sbatch scripts voxcast writes, run here by bash as Slurm would run them
// (#SBATCH lines are comments to bash; the array index comes from
// SLURM_ARRAY_TASK_ID), give results byte-identical to one machine's, render
// each truth once, and leave exit files from which sweep-status and --resume
// know what finished. The same scripts under a real slurmctld/slurmd are
// .ci/cluster.sh's (the CI's `cluster` step).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cosim/cluster/slurm.hpp"
#include "cosim/verify/regress.hpp"
#include "refmodel/error.hpp"
#include "tests/common/voxcast_cli.hpp"

namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;
namespace cl = voxcast::cosim::cluster;
using voxcast::test::Command;

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("voxcast_cluster_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(d);
  return d;
}

// 8 points on the MIP scene, each a few tenths of a second; 2 distinct truths
// (the truth does not depend on the profile or the oversampling, only on
// what it renders: here the ERT threshold is not part of it either, so 1).
std::string sweep_args(const fs::path& out) {
  return "sweep " + std::string(VOXCAST_SOURCE_DIR) +
         "/scenes/mip.toml --set render.width=32 --set render.height=32 --truth-oversampling 2 "
         "--vary precision.profile=vizard2,balanced --vary render.oversampling=1,2 "
         "--vary render.ert_threshold=0.95,0.99 --no-plots --out " + out.string();
}

// Runs one of the written scripts as Slurm would (task k for the array).
Command run_script(const fs::path& dir, const std::string& script, int task = -1) {
  const std::string env = task >= 0 ? "SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " " : "";
  const fs::path log = dir / "slurm" / "logs" /
                       (task >= 0 ? "shard-" + std::to_string(task) + ".log" : script + ".log");
  return voxcast::test::run_command("env " + env + "bash " + (dir / "slurm" / (script + ".sbatch")).string() +
                                    " >> " + log.string());
}

TEST(ClusterScripts, ShellQuotingSurvivesTheShell) {
  for (const std::string word : {"plain", "it's", "a b", "$HOME", "\"q\"", "back\\slash", ""}) {
    const Command r = voxcast::test::run_command("printf '%s' " + cl::shell_quote(word));
    EXPECT_EQ(r.output, word) << cl::shell_quote(word);
  }
}

TEST(ClusterScripts, SbatchOptionsAreCheckedWordByWord) {
  EXPECT_EQ(cl::parse_sbatch_options({"--partition=long --time=4:00:00", "--mem=8G"}, "sweep"),
            (std::vector<std::string>{"--partition=long", "--time=4:00:00", "--mem=8G"}));
  for (const std::string bad : {"partition=long", "--comment='x'", "--array=0-3",
                                "--dependency=afterok:1", "--output=x.log", "--job-name=x"})
    EXPECT_THROW(cl::parse_sbatch_options({bad}, "sweep"), voxcast::Error) << bad;
}

TEST(ClusterScripts, ArrayIndexListsAsSlurmWritesThem) {
  EXPECT_EQ(cl::parse_array_indices("0-3"), (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(cl::parse_array_indices("1,3,5-7"), (std::vector<int>{1, 3, 5, 6, 7}));
  EXPECT_EQ(cl::parse_array_indices("0-5%2"), (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(cl::parse_array_indices("0-9:3"), (std::vector<int>{0, 3, 6, 9}));
  EXPECT_EQ(cl::parse_array_indices("2"), (std::vector<int>{2}));
}

TEST(ClusterScripts, ScontrolRecordsOneLinePerJob) {
  // `scontrol -o show job 12` of an array: a finished task and the pending rest.
  const std::string text =
      "JobId=13 ArrayJobId=12 ArrayTaskId=0 JobName=voxcast-sweep-shard JobState=COMPLETED "
      "Reason=None Dependency=(null) ExitCode=0:0 Command=/tmp/a b/shards.sbatch\n"
      "JobId=12 ArrayJobId=12 ArrayTaskId=1-3 JobName=voxcast-sweep-shard JobState=PENDING "
      "Reason=Dependency Dependency=afterok:11_*(unfulfilled) ExitCode=0:0\n";
  const std::vector<cl::JobRecord> r = cl::parse_scontrol_records(text);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0].at("JobState"), "COMPLETED");
  EXPECT_EQ(r[0].at("Command"), "/tmp/a b/shards.sbatch");
  EXPECT_EQ(r[1].at("ArrayTaskId"), "1-3");
  EXPECT_EQ(r[1].at("Reason"), "Dependency");
}

// The dependencies are afterok with --kill-on-invalid-dep=yes: a failure
// never leaves a job pending for ever (../shared/BUILD-NOTES.md).
TEST(ClusterScripts, DryRunWritesTheJobsAndTheirDependencies) {
  const fs::path dir = temp_dir("dry");
  const Command r = voxcast::test::run_voxcast(sweep_args(dir) +
                                               " --slurm 4 --slurm-opt \"--partition=debug --time=0:10:00\" --dry-run");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("dry run: nothing submitted"), std::string::npos) << r.output;
  const std::string submit = read_all(dir / "slurm" / "submit.sh");
  EXPECT_NE(submit.find("sbatch --parsable truth.sbatch"), std::string::npos) << submit;
  EXPECT_NE(submit.find("--dependency=afterok:$truth --kill-on-invalid-dep=yes --array=0-3 shards.sbatch"),
            std::string::npos) << submit;
  EXPECT_NE(submit.find("--dependency=afterok:$shards --kill-on-invalid-dep=yes merge.sbatch"),
            std::string::npos) << submit;
  for (const char* s : {"truth.sbatch", "shards.sbatch", "merge.sbatch"}) {
    const std::string text = read_all(dir / "slurm" / s);
    EXPECT_NE(text.find("#SBATCH --partition=debug\n#SBATCH --time=0:10:00\n"), std::string::npos) << s;
    EXPECT_EQ(voxcast::test::run_command("bash -n " + (dir / "slurm" / s).string()).status, 0) << s;
  }
  EXPECT_NE(read_all(dir / "slurm" / "shards.sbatch").find("--truth-from-cache"), std::string::npos);
  EXPECT_EQ(voxcast::test::run_command("bash -n " + (dir / "slurm" / "submit.sh").string()).status, 0);
  fs::remove_all(dir);
}

TEST(ClusterScripts, WithoutSbatchTheSubmissionSaysSoInOneLine) {
  const fs::path dir = temp_dir("nosbatch");
  const Command r = voxcast::test::run_voxcast(sweep_args(dir) + " --slurm 2", "env PATH=/nonexistent");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("sbatch is not on PATH"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

TEST(ClusterScripts, AShardWithoutItsTruthFailsInsteadOfRenderingIt) {
  const fs::path dir = temp_dir("notruth");
  const Command r = voxcast::test::run_voxcast(sweep_args(dir) + " --shard 0/2 --truth-from-cache");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("is not in the truth cache"), std::string::npos) << r.output;
  fs::remove_all(dir);
}

// The whole run as the cluster would make it: truth, 4 shards, merge; then a
// failed shard found and resumed. One test, not several: ctest runs each test
// in a process of its own, and the run is the cost.
TEST(ClusterRun, ScriptsRunAsSlurmWouldRunThemAndResumeAFailedShard) {
  const fs::path whole = temp_dir("whole"), dir = temp_dir("run");
  const Command w = voxcast::test::run_voxcast(sweep_args(whole));
  ASSERT_EQ(w.status, 0) << w.output;
  const Command d = voxcast::test::run_voxcast(sweep_args(dir) + " --slurm 4 --dry-run");
  ASSERT_EQ(d.status, 0) << d.output;
  ASSERT_EQ(run_script(dir, "truth").status, 0) << read_all(dir / "slurm/logs/truth.log");
  for (int k = 0; k < 4; ++k)
    ASSERT_EQ(run_script(dir, "shards", k).status, 0)
        << read_all(dir / "slurm/logs" / ("shard-" + std::to_string(k) + ".log"));
  ASSERT_EQ(run_script(dir, "merge").status, 0) << read_all(dir / "slurm/logs/merge.log");

  {
    SCOPED_TRACE("the merged results are byte-identical to one machine's");
    for (const char* f : {"results.csv", "results.json"})
      EXPECT_EQ(read_all(dir / f), read_all(whole / f)) << f;
  }
  {
    SCOPED_TRACE("the truth is rendered once, by the truth job only");
    EXPECT_NE(read_all(dir / "slurm/logs/truth.log").find("1 rendered, 0 already in the cache"),
              std::string::npos) << read_all(dir / "slurm/logs/truth.log");
    for (int k = 0; k < 4; ++k) {
      const std::string log = read_all(dir / "slurm/logs" / ("shard-" + std::to_string(k) + ".log"));
      EXPECT_NE(log.find("(0 truth images rendered)"), std::string::npos) << log;
    }
  }
  {
    SCOPED_TRACE("sweep-status from the files alone");
    const Command s = voxcast::test::run_voxcast("sweep-status " + dir.string());
    EXPECT_EQ(s.status, 0) << s.output;
    EXPECT_NE(s.output.find("finished"), std::string::npos) << s.output;
  }
  {
    SCOPED_TRACE("a failed shard: named by sweep-status, resubmitted alone by --resume");
    const fs::path exit2 = dir / "slurm/status/shard-2.exit";
    { std::ofstream(exit2) << "1\n"; }
    fs::remove_all(dir / "shards/2");
    const Command s = voxcast::test::run_voxcast("sweep-status " + dir.string());
    EXPECT_EQ(s.status, 9) << s.output;
    EXPECT_NE(s.output.find("shard 2   FAILED  exit status 1  log "), std::string::npos) << s.output;
    // --resume sends shard 2 and the merge only: the truth job succeeded.
    const Command r = voxcast::test::run_voxcast(sweep_args(dir) + " --slurm 4 --resume --dry-run");
    ASSERT_EQ(r.status, 0) << r.output;
    const std::string submit = read_all(dir / "slurm/submit.sh");
    EXPECT_EQ(submit.find("truth.sbatch"), std::string::npos) << submit;
    EXPECT_NE(submit.find("--array=2 shards.sbatch"), std::string::npos) << submit;
    EXPECT_FALSE(fs::exists(exit2));
    ASSERT_EQ(run_script(dir, "shards", 2).status, 0);
    ASSERT_EQ(run_script(dir, "merge").status, 0);
    EXPECT_EQ(read_all(dir / "results.csv"), read_all(whole / "results.csv"));
  }
  {
    SCOPED_TRACE("another sweep in the same folder is refused, naming what differs");
    const Command other =
        voxcast::test::run_voxcast(sweep_args(dir) + " --slurm 3 --resume --dry-run");
    EXPECT_EQ(other.status, 1) << other.output;
    EXPECT_NE(other.output.find("holds another run: its shards was 4"), std::string::npos)
        << other.output;
  }
  fs::remove_all(whole);
  fs::remove_all(dir);
}

// A regression spread over shards fails exactly as the local run: same lines,
// same summary, same count (here every golden is missing: all cases fail).
TEST(ClusterRegress, ShardsMergedEqualTheLocalRun) {
  const fs::path dir = temp_dir("regress");
  voxcast::cosim::RegressOptions o;
  o.scenes_dir = std::string(VOXCAST_SOURCE_DIR) + "/tests/regress";
  o.golden_dir = (dir / "no-goldens").string();
  o.profiles = {"vizard2", "balanced"};
  o.overrides = {"render.width=24", "render.height=24"};
  std::ostringstream local;
  const int local_failed = voxcast::cosim::run_regress(o, local);
  EXPECT_GT(local_failed, 0);
  std::vector<std::string> files;
  for (int k = 0; k < 3; ++k) {
    voxcast::cosim::RegressOptions s = o;
    s.shard_index = k;
    s.shard_count = 3;
    s.results_path = (dir / (std::to_string(k) + ".json")).string();
    std::ostringstream ignored;
    voxcast::cosim::run_regress(s, ignored);
    files.push_back(s.results_path);
  }
  std::ostringstream merged;
  EXPECT_EQ(voxcast::cosim::run_regress_merge(files, o, merged), local_failed);
  EXPECT_EQ(merged.str(), local.str());
  // A shard's results missing: an error naming the first case without one.
  files.pop_back();
  std::ostringstream partial;
  EXPECT_THROW(voxcast::cosim::run_regress_merge(files, o, partial), voxcast::Error);
  fs::remove_all(dir);
}

}  // namespace VOXCAST_UNITY_ID
