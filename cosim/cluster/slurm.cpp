#include "cosim/cluster/slurm.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cosim/cluster/process.hpp"
#include "cosim/explore/sweep_plot.hpp"  // on_path
#include "cosim/reports/files.hpp"
#include "refmodel/error.hpp"

namespace voxcast::cosim::cluster {
namespace fs = std::filesystem;

namespace {

fs::path slurm_dir(const std::string& dir) { return fs::path(dir) / "slurm"; }
fs::path exit_file(const std::string& dir, const std::string& job) {
  return slurm_dir(dir) / "status" / (job + ".exit");
}
fs::path log_file(const std::string& dir, const std::string& job) {
  return slurm_dir(dir) / "logs" / (job + ".log");
}
std::string shard_job(int k) { return "shard-" + std::to_string(k); }

std::string read_file_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

// The exit status a job recorded, if it recorded one.
std::optional<int> recorded_exit(const std::string& dir, const std::string& job) {
  std::ifstream in(exit_file(dir, job));
  int rc = 0;
  if (in >> rc) return rc;
  return std::nullopt;
}

// The command line as the shell reads it; kShardToken becomes the task index.
std::string command_line(const std::vector<std::string>& argv) {
  std::string line;
  for (const std::string& a : argv) {
    std::string q = shell_quote(a);
    for (std::size_t at = q.find(kShardToken); at != std::string::npos;
         at = q.find(kShardToken, at + 6))
      q.replace(at, sizeof kShardToken - 1, "'\"$k\"'");
    line += (line.empty() ? "" : " ") + q;
  }
  return line;
}

// One job's sbatch script. `job` names its log and exit files ("$k"-relative
// for the array); the exit file is written atomically when the command ends.
std::string job_script(const ClusterPlan& plan, const std::string& title, const std::string& job,
                       const std::vector<std::string>& argv, bool array) {
  const fs::path sd = slurm_dir(plan.dir);
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# voxcast " << plan.kind << " on Slurm: " << title
    << " (written by voxcast; docs/cluster.md). submit.sh submits it with its dependencies.\n"
    << "#SBATCH --job-name=voxcast-" << plan.kind << "-" << (array ? "shard" : job) << "\n"
    << "#SBATCH --output=" << (sd / "logs" / (array ? "shard-%a.log" : job + ".log")).string()
    << "\n"
    << "#SBATCH --open-mode=append\n";
  for (const std::string& o : plan.sbatch_options) s << "#SBATCH " << o << "\n";
  s << "set -u\n";
  if (array)
    s << "k=${SLURM_ARRAY_TASK_ID:?this script runs as a task of a Slurm job array}\n";
  const std::string name = array ? "shard-\"$k\"" : job;
  const std::string status = shell_quote((sd / "status").string() + "/");
  s << "echo \"=== voxcast " << plan.kind << " " << (array ? "shard $k" : job)
    << " on $(hostname) at $(date -u +%Y-%m-%dT%H:%M:%SZ), Slurm job ${SLURM_JOB_ID:-?}\"\n"
    << command_line(argv) << "\n"
    << "rc=$?\n"
    << "echo \"=== exit status $rc\"\n"
    << "printf '%s\\n' \"$rc\" > " << status << name << ".exit.tmp && mv -f " << status << name
    << ".exit.tmp " << status << name << ".exit\n"
    << "exit \"$rc\"\n";
  return s.str();
}

// "0-3" or "1,3": the --array value of these shards.
std::string array_spec(const std::vector<int>& shards) {
  std::vector<int> k = shards;
  std::sort(k.begin(), k.end());
  bool contiguous = true;
  for (std::size_t i = 1; i < k.size(); ++i) contiguous = contiguous && k[i] == k[i - 1] + 1;
  if (contiguous && k.size() > 1) return std::to_string(k.front()) + "-" + std::to_string(k.back());
  std::string spec;
  for (int i : k) spec += (spec.empty() ? "" : ",") + std::to_string(i);
  return spec;
}

std::string submit_script(const ClusterPlan& plan, const SubmitRequest& req) {
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# Submits this " << plan.kind << "'s jobs to Slurm with their dependencies (written by voxcast;\n"
    << "# docs/cluster.md) and writes their ids to jobs.env. afterok with\n"
    << "# --kill-on-invalid-dep=yes: a failed job cancels the jobs that wait on it.\n"
    << "set -euo pipefail\n"
    << "cd " << shell_quote(slurm_dir(plan.dir).string()) << "\n"
    << "truth= shards= merge=\n";
  std::string after;  // the dependency of the next job
  if (req.truth) {
    s << "truth=$(sbatch --parsable truth.sbatch)\ntruth=${truth%%;*}\n";
    after = "$truth";
  }
  if (!req.shards.empty()) {
    s << "shards=$(sbatch --parsable"
      << (after.empty() ? "" : " --dependency=afterok:" + after + " --kill-on-invalid-dep=yes")
      << " --array=" << array_spec(req.shards) << " shards.sbatch)\nshards=${shards%%;*}\n";
    after = "$shards";
  }
  if (req.merge)
    s << "merge=$(sbatch --parsable"
      << (after.empty() ? "" : " --dependency=afterok:" + after + " --kill-on-invalid-dep=yes")
      << " merge.sbatch)\nmerge=${merge%%;*}\n";
  s << "printf 'truth=%s\\nshards=%s\\narray=%s\\nmerge=%s\\n' \"$truth\" \"$shards\" "
    << shell_quote(req.shards.empty() ? "" : array_spec(req.shards))
    << " \"$merge\" > jobs.env.tmp\nmv -f jobs.env.tmp jobs.env\ncat jobs.env\n";
  return s.str();
}

std::map<std::string, std::string> read_env(const fs::path& p) {
  std::map<std::string, std::string> env;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);) {
    const std::size_t eq = line.find('=');
    if (eq != std::string::npos) env[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return env;
}

bool is_active(const std::string& slurm_state) {
  return slurm_state == "PENDING" || slurm_state == "RUNNING" || slurm_state == "CONFIGURING" ||
         slurm_state == "COMPLETING" || slurm_state == "SUSPENDED" || slurm_state == "REQUEUED" ||
         slurm_state == "RESIZING";
}

// The records scontrol has of `id` (an array's records for every task), or
// nothing when scontrol is missing or the job is unknown (finished long ago).
std::optional<std::vector<JobRecord>> ask_scontrol(const std::string& id) {
  if (id.empty() || !sweep::on_path("scontrol")) return std::nullopt;
  const Captured c = run_captured({"scontrol", "-o", "show", "job", id});
  if (!c.ok()) return std::nullopt;
  std::vector<JobRecord> r = parse_scontrol_records(c.out);
  if (r.empty()) return std::nullopt;
  return r;
}

// The record of task k of an array (its own, or a pending range holding it).
const JobRecord* task_record(const std::vector<JobRecord>& records, int k) {
  for (const JobRecord& r : records) {
    const auto it = r.find("ArrayTaskId");
    if (it == r.end()) continue;
    const std::vector<int> ks = parse_array_indices(it->second);
    if (std::find(ks.begin(), ks.end(), k) != ks.end()) return &r;
  }
  return nullptr;
}

// A key's value in an scontrol record or in jobs.env; empty when absent.
std::string value_of(const std::map<std::string, std::string>& r, const std::string& key) {
  const auto it = r.find(key);
  return it == r.end() ? std::string() : it->second;
}

// A job's state from its exit file, else from what Slurm says of it.
JobStatus job_status(const std::string& dir, const std::string& name, const std::string& job,
                     const JobRecord* record, const std::string& job_id) {
  JobStatus st;
  st.name = name;
  const fs::path log = log_file(dir, job);
  if (fs::exists(log)) st.log = log.string();
  if (const std::optional<int> rc = recorded_exit(dir, job)) {
    st.state = *rc == 0 ? JobState::Done : JobState::Failed;
    st.detail = "exit status " + std::to_string(*rc);
    return st;
  }
  if (record) {
    const std::string s = value_of(*record, "JobState");
    const std::string reason = value_of(*record, "Reason");
    st.detail = "Slurm job " + job_id + ": " + s +
                (reason.empty() || reason == "None" ? "" : " (" + reason + ")");
    if (s == "RUNNING" || s == "COMPLETING" || s == "CONFIGURING")
      st.state = JobState::Running;
    else if (is_active(s))
      st.state = JobState::Pending;
    else if (s == "COMPLETED")
      st.state = JobState::Failed, st.detail += ", but it recorded no exit status";
    else
      st.state = JobState::Failed, st.detail += ", exit code " + value_of(*record, "ExitCode");
    return st;
  }
  st.state = JobState::NotStarted;
  st.detail = job_id.empty() ? "not submitted" : "no exit status; Slurm does not know job " + job_id;
  return st;
}

// Points journaled so far by a running sweep shard (DIR/shards/K/points).
std::size_t journaled_points(const std::string& dir, int k) {
  const fs::path p = fs::path(dir) / "shards" / std::to_string(k) / "points";
  std::size_t n = 0;
  std::error_code ec;
  for (fs::directory_iterator it(p, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".json" && it->path().filename() != "sweep.json") ++n;
  return n;
}

}  // namespace

std::string shell_quote(const std::string& word) {
  std::string q = "'";
  for (char c : word) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::vector<std::string> parse_sbatch_options(const std::vector<std::string>& texts,
                                              const std::string& who) {
  std::vector<std::string> words;
  for (const std::string& t : texts) {
    std::istringstream in(t);
    for (std::string w; in >> w;) {
      if (w.front() != '-')
        throw Error(who + ": \"" + w + "\" in --slurm-opt is not an sbatch option (each word starts with '-', e.g. --partition=debug --time=1:00:00)");
      if (w.find_first_of("'\"\\`$") != std::string::npos)
        throw Error(who + ": \"" + w + "\" in --slurm-opt holds a quote or a shell character: give values without them (--slurm-opt is written to #SBATCH lines as it is)");
      if (w.rfind("--array", 0) == 0 || w.rfind("--dependency", 0) == 0 || w.rfind("-d", 0) == 0 ||
          w.rfind("--output", 0) == 0 || w.rfind("-o", 0) == 0 || w.rfind("--job-name", 0) == 0)
        throw Error(who + ": \"" + w + "\" in --slurm-opt is set by voxcast itself (array, dependencies, logs, job names)");
      words.push_back(w);
    }
  }
  return words;
}

nlohmann::json plan_json(const ClusterPlan& plan) {
  return {{"kind", plan.kind},
          {"shards", plan.shards},
          {"truth_command", plan.truth_command},
          {"shard_command", plan.shard_command},
          {"merge_command", plan.merge_command}};
}

std::optional<nlohmann::json> read_plan(const std::string& dir) {
  const fs::path p = slurm_dir(dir) / "plan.json";
  if (!fs::exists(p)) return std::nullopt;
  try {
    return nlohmann::json::parse(read_file_text(p));
  } catch (const nlohmann::json::exception& e) {
    throw Error(p.string() + ": not a voxcast cluster plan (" + e.what() + ")");
  }
}

std::vector<std::string> write_cluster_scripts(const ClusterPlan& plan, const SubmitRequest& req) {
  const fs::path sd = slurm_dir(plan.dir);
  for (const char* sub : {"logs", "status"}) make_output_dir((sd / sub).string());
  std::vector<std::string> written;
  const auto put = [&](const std::string& name, const std::string& text, bool exec) {
    const fs::path p = sd / name;
    write_file_atomically(p.string(), text);
    if (exec)
      fs::permissions(p, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec,
                      fs::perm_options::add);
    written.push_back(p.string());
  };
  put("plan.json", plan_json(plan).dump(2) + "\n", false);
  if (!plan.truth_command.empty())
    put("truth.sbatch", job_script(plan, "the truth images, once", "truth", plan.truth_command, false),
        true);
  put("shards.sbatch",
      job_script(plan, "shard $SLURM_ARRAY_TASK_ID of " + std::to_string(plan.shards), "",
                 plan.shard_command, true),
      true);
  put("merge.sbatch", job_script(plan, "the shards joined", "merge", plan.merge_command, false),
      true);
  put("submit.sh", submit_script(plan, req), true);
  // What this submission sends starts without an exit status.
  std::error_code ec;
  if (req.truth) fs::remove(exit_file(plan.dir, "truth"), ec);
  for (int k : req.shards) fs::remove(exit_file(plan.dir, shard_job(k)), ec);
  if (req.merge) fs::remove(exit_file(plan.dir, "merge"), ec);
  return written;
}

Submission submit(const ClusterPlan& plan) {
  if (!sweep::on_path("sbatch"))
    throw Error(plan.kind + " --slurm: sbatch is not on PATH (install slurm-client, or write the "
                "scripts only with --dry-run and submit " +
                (slurm_dir(plan.dir) / "submit.sh").string() + " where Slurm is)");
  const Captured c = run_captured({"bash", (slurm_dir(plan.dir) / "submit.sh").string()});
  if (!c.ok())
    throw Error(plan.kind + " --slurm: submission failed (" +
                (slurm_dir(plan.dir) / "submit.sh").string() + ", exit status " +
                std::to_string(c.status) + "): " + c.first_line());
  const std::map<std::string, std::string> env = read_env(slurm_dir(plan.dir) / "jobs.env");
  return {value_of(env, "truth"), value_of(env, "shards"), value_of(env, "merge")};
}

std::vector<int> parse_array_indices(const std::string& spec) {
  std::vector<int> out;
  const std::string body = spec.substr(0, spec.find('%'));
  std::istringstream in(body);
  for (std::string part; std::getline(in, part, ',');) {
    if (part.empty()) continue;
    int step = 1;
    if (const std::size_t colon = part.find(':'); colon != std::string::npos) {
      step = std::max(1, std::atoi(part.c_str() + colon + 1));
      part.resize(colon);
    }
    const std::size_t dash = part.find('-');
    const int a = std::atoi(part.c_str());
    const int b = dash == std::string::npos ? a : std::atoi(part.c_str() + dash + 1);
    for (int i = a; i <= b; i += step) out.push_back(i);
  }
  return out;
}

std::vector<JobRecord> parse_scontrol_records(const std::string& text) {
  std::vector<JobRecord> records;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    JobRecord r;
    std::istringstream words(line);
    std::string last;
    for (std::string w; words >> w;) {
      const std::size_t eq = w.find('=');
      if (eq == std::string::npos || eq == 0) {
        if (!last.empty()) r[last] += " " + w;  // a value with a space in it
        continue;
      }
      last = w.substr(0, eq);
      r[last] = w.substr(eq + 1);
    }
    if (r.count("JobId")) records.push_back(std::move(r));
  }
  return records;
}

const char* state_name(JobState s) {
  switch (s) {
    case JobState::Done: return "done";
    case JobState::Running: return "running";
    case JobState::Pending: return "pending";
    case JobState::Failed: return "FAILED";
    case JobState::NotStarted: return "not started";
  }
  return "?";
}

bool ClusterStatus::finished() const {
  return std::all_of(jobs.begin(), jobs.end(),
                     [](const JobStatus& j) { return j.state == JobState::Done; });
}

ClusterStatus read_status(const std::string& dir) {
  const std::optional<nlohmann::json> plan = read_plan(dir);
  if (!plan)
    throw Error(dir + ": no cluster run here (" + (slurm_dir(dir) / "plan.json").string() +
                " does not exist; sweep --slurm N or regress --slurm N writes it)");
  ClusterStatus st;
  st.kind = plan->value("kind", "");
  st.shards = plan->value("shards", 0);
  if (st.shards < 1) throw Error((slurm_dir(dir) / "plan.json").string() + ": no shard count");
  const std::map<std::string, std::string> env = read_env(slurm_dir(dir) / "jobs.env");
  const auto id = [&](const char* k) { return value_of(env, k); };
  const auto single = [&](const std::string& name, const std::string& job_id) {
    const std::optional<std::vector<JobRecord>> r = ask_scontrol(job_id);
    st.scheduler_asked = st.scheduler_asked || r.has_value();
    st.jobs.push_back(job_status(dir, name, name, r ? &r->front() : nullptr, job_id));
  };
  if (!plan->value("truth_command", nlohmann::json::array()).empty()) single("truth", id("truth"));
  const std::optional<std::vector<JobRecord>> array = ask_scontrol(id("shards"));
  st.scheduler_asked = st.scheduler_asked || array.has_value();
  const std::vector<int> submitted = parse_array_indices(id("array"));
  for (int k = 0; k < st.shards; ++k) {
    const bool in_last = std::find(submitted.begin(), submitted.end(), k) != submitted.end();
    const JobRecord* r = array && in_last ? task_record(*array, k) : nullptr;
    const std::string task_id = in_last ? id("shards") + "_" + std::to_string(k) : std::string();
    JobStatus js = job_status(dir, "shard " + std::to_string(k), shard_job(k), r, task_id);
    if (js.state == JobState::NotStarted && array && in_last) {
      // Slurm still holds the array but not this task: a pending task that
      // was cancelled leaves no record behind. It will never run.
      js.state = JobState::Failed;
      js.detail = "Slurm job " + task_id + ": gone from its array before it ran (cancelled while pending)";
    }
    if (st.kind == "sweep" && js.state == JobState::Running)
      js.detail += ", " + std::to_string(journaled_points(dir, k)) + " points journaled";
    st.jobs.push_back(std::move(js));
  }
  single("merge", id("merge"));
  // A regression's merge exits 4 when cases failed, as a local regress does:
  // the run finished, and its verdict is that status.
  JobStatus& merge = st.jobs.back();
  if (st.kind == "regress" && recorded_exit(dir, "merge") == 4) {
    merge.state = JobState::Done;
    merge.detail = "exit status 4: case(s) failed (the table is in its log)";
    st.regress_failed = true;
  }
  return st;
}

void print_status(std::ostream& os, const ClusterStatus& s, const std::string& dir) {
  os << s.kind << " on Slurm in " << dir << ": " << s.shards << " shard"
     << (s.shards == 1 ? "" : "s")
     << (s.scheduler_asked ? "" : " (the scheduler knows none of the jobs: from the files only)")
     << "\n";
  for (const JobStatus& j : s.jobs) {
    os << "  " << j.name << std::string(j.name.size() < 10 ? 10 - j.name.size() : 1, ' ')
       << state_name(j.state) << (j.detail.empty() ? "" : "  " + j.detail);
    if (!j.log.empty() && (j.state != JobState::Done || s.regress_failed)) os << "  log " << j.log;
    os << "\n";
  }
  if (s.finished() && s.regress_failed)
    os << "finished: the regression FAILED; its table is in " << s.jobs.back().log << "\n";
  else if (s.finished())
    os << "finished: the merged results are in " << dir << "\n";
  else if (std::any_of(s.jobs.begin(), s.jobs.end(), [](const JobStatus& j) {
             return j.state == JobState::Failed || j.state == JobState::NotStarted;
           }))
    os << "to go on with only what did not finish: the same " << s.kind
       << " command with --slurm " << s.shards << " --resume\n";
}

SubmitRequest fresh_request(const ClusterPlan& plan) {
  SubmitRequest req;
  req.truth = !plan.truth_command.empty();
  for (int k = 0; k < plan.shards; ++k) req.shards.push_back(k);
  req.merge = true;
  std::error_code ec;
  fs::remove_all(slurm_dir(plan.dir) / "status", ec);
  return req;
}

SubmitRequest resume_request(const ClusterPlan& plan) {
  const std::optional<nlohmann::json> before = read_plan(plan.dir);
  const std::string who = plan.kind + " --slurm --resume";
  if (!before)
    throw Error(who + ": " + plan.dir + " holds no cluster run to resume (run it without --resume)");
  const nlohmann::json mine = plan_json(plan);
  for (const char* key : {"kind", "shards", "truth_command", "shard_command", "merge_command"})
    if ((*before)[key] != mine[key])
      throw Error(who + ": " + plan.dir + " holds another run: its " + key + " was " +
                  (*before)[key].dump() + ", this one's is " + mine[key].dump() +
                  " (resume with the same command and the same --slurm N)");
  const ClusterStatus st = read_status(plan.dir);
  for (const JobStatus& j : st.jobs)
    if (j.state == JobState::Running || j.state == JobState::Pending)
      throw Error(who + ": " + j.name + " is still " + state_name(j.state) + " (" + j.detail +
                  "): wait for it, or scancel it, then resume");
  SubmitRequest req;
  std::size_t at = 0;
  if (!plan.truth_command.empty()) req.truth = st.jobs[at++].state != JobState::Done;
  for (int k = 0; k < plan.shards; ++k)
    if (st.jobs[at++].state != JobState::Done) req.shards.push_back(k);
  req.merge = !req.shards.empty() || req.truth || st.jobs[at].state != JobState::Done;
  return req;
}

void print_submission(std::ostream& os, const ClusterPlan& plan, const SubmitRequest& req,
                      const std::optional<Submission>& sub,
                      const std::vector<std::string>& written) {
  for (const std::string& w : written) os << "wrote    " << w << "\n";
  const std::string submit_sh = (slurm_dir(plan.dir) / "submit.sh").string();
  if (!req.truth && req.shards.empty() && !req.merge) {
    os << "nothing to submit: every job of " << plan.dir << " finished\n";
    return;
  }
  if (!sub) {
    os << "dry run: nothing submitted; submit with: bash " << submit_sh << "\n";
    return;
  }
  if (req.truth) os << "truth    job " << sub->truth << "\n";
  if (!req.shards.empty())
    os << "shards   job array " << sub->shards << " (tasks " << array_spec(req.shards) << " of "
       << plan.shards << ")" << (req.truth ? ", after the truth job succeeds" : "") << "\n";
  if (req.merge) os << "merge    job " << sub->merge << ", after every shard succeeds\n";
  std::string ids;
  for (const std::string* id : {&sub->truth, &sub->shards, &sub->merge})
    if (!id->empty()) ids += (ids.empty() ? "" : ",") + *id;
  os << "watch:   voxcast sweep-status " << plan.dir << "   (or: squeue -j " << ids << ")\n";
}

}  // namespace voxcast::cosim::cluster
