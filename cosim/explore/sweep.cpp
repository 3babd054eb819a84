#include "cosim/explore/sweep.hpp"
#include "cosim/explore/pages.hpp"
#include "cosim/reports/files.hpp"
#include "cosim/reports/progress.hpp"

#include <toml++/toml.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>

#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <filesystem>
#include <fstream>
#include <future>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <thread>

#include "cosim/reports/metrics.hpp"
#include "cosim/hardware/report.hpp"
#include "cosim/explore/sweep_plot.hpp"
#include "cosim/engines/truth.hpp"
#include "cosim/reports/stopwatch.hpp"
#include "cosim/engines/warnings.hpp"
#include "refmodel/error.hpp"
#include "refmodel/parallel.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/scene_config.hpp"
#include "refmodel/scene/elaboration.hpp"

namespace voxcast::cosim::sweep {
namespace {

using Kind = Column::Kind;

// --- Column groups ---------------------------------------------------------------

std::vector<Cell> measure_accuracy_cells(const PointContext& p) {
  const Accuracy a = measure_accuracy(p.design, p.truth);
  return {Cell::txt(p.design_is_hls ? "hls" : "bittrue"),
          Cell::num(a.psnr_db),
          Cell::num(a.max_abs_err_lsb),
          Cell::num(a.mean_abs_err_lsb),
          Cell::num(a.rms_err_lsb),
          Cell::num(a.pct_within_1lsb),
          std::isnan(a.ssim) ? Cell::na("SSIM needs an image of at least 11x11 pixels")
                             : Cell::num(a.ssim)};
}

// The precision guard's verdict on the point (cosim/engines/warnings.hpp): a point
// whose error is hazard-limited says so next to its accuracy.
std::vector<Cell> measure_hazard_cells(const PointContext& p) {
  const std::vector<Hazard> hazards = precision_hazards(p.scene, p.volume.volume);
  return {Cell::num(static_cast<double>(hazards.size())), Cell::num(largest_worst_lsb(hazards)),
          Cell::txt(hazard_keys(hazards))};
}

std::vector<Cell> measure_rtl_cells(const PointContext& p) {
  if (!rtl::rtl_supports(p.scene.precision)) {
    const Cell na =
        Cell::na("rtl runs only the compiled presets (" + rtl::rtl_supported_profiles() +
                 "); this profile is " + p.scene.precision_name);
    return {na, na, na};
  }
  try {
    const rtl::RtlResult r = rtl::rtl_render(p.setup, p.memory, rtl::rtl_config(p.scene.rtl));
    if (p.design_is_hls && r.image.pixels != p.design.pixels)
      throw Error("the rtl image differs from hls (run voxcast cosim on this point)");
    return {Cell::num(r.stats.fps()), Cell::num(r.stats.ns_per_sample()),
            Cell::num(static_cast<double>(r.stats.cycles))};
  } catch (const Error& e) {
    const Cell na = Cell::na(std::string("rtl: ") + e.what());
    return {na, na, na};
  }
}

// The resource model of `voxcast report` (docs/resources.md) for the point's
// elaborated design, on the sweep's part (--part, checked by run_sweep).
// On a DDR4 board (rtl.board = "alveo_u250") the design is the card: N =
// rtl.pipelines pipelines, their shared tables and the four channels' caches,
// crossings and controllers (cosim/hardware/card_price.cpp), so a sweep over
// rtl.pipelines prices what it measures.
std::vector<Cell> measure_resource_cells(const PointContext& p) {
  const Part& part = find_part(p.part);
  const ref::Elaboration e = ref::elaborate(p.scene, p.volume.volume, p.volume.gradients);
  const std::optional<CardPrice> card = price_scene_card(p.scene, e, part);
  const Resources total = card ? card->total : estimate_resources(e, part).total;
  return {Cell::txt(part.name),
          Cell::num(total.luts),
          Cell::num(total.ffs),
          Cell::num(total.dsps),
          Cell::num(total.brams),
          Cell::num(total.urams),
          Cell::num(100.0 * cost(total, part)),
          Cell::num(100.0 * binding_share(total, part))};
}

// --- Shared inputs -----------------------------------------------------------------

// Values computed once per key by the first caller; others wait for it.
template <typename V>
class OnceCache {
 public:
  template <typename Make>
  std::shared_ptr<const V> get(const std::string& key, Make&& make) {
    std::promise<std::shared_ptr<const V>> promise;
    std::shared_future<std::shared_ptr<const V>> future;
    bool mine = false;
    {
      const std::lock_guard lock(mutex_);
      auto it = values_.find(key);
      mine = it == values_.end();
      if (mine) it = values_.emplace(key, promise.get_future().share()).first;
      future = it->second;
    }
    if (mine) {
      try {
        promise.set_value(std::make_shared<const V>(make()));
      } catch (...) {
        promise.set_exception(std::current_exception());
      }
    }
    return future.get();
  }

 private:
  std::mutex mutex_;
  std::map<std::string, std::shared_future<std::shared_ptr<const V>>> values_;
};

// The [volume] table of the scene: what the loaded volume and its gradients depend on.
std::string volume_key(const ref::Scene& scene) {
  const toml::table root = toml::parse(ref::scene_to_toml(scene));
  std::ostringstream os;
  if (const toml::table* v = root["volume"].as_table()) os << *v;
  return os.str();
}

struct Caches {
  OnceCache<SceneVolume> volumes;
  TruthCache truths;
};

// --- One point ----------------------------------------------------------------------

struct PointOutcome {
  Row row;
  double seconds = 0.0;
};

std::size_t measured_columns() {
  std::size_t n = 0;
  for (const ColumnGroup& g : column_groups()) n += g.columns.size();
  return n;
}

PointOutcome run_point(const Plan& plan, std::size_t index, int threads, Caches& caches) {
  const auto t0 = StopwatchClock::now();
  PointOutcome out;
  out.row.index = index;
  for (const std::string& v : plan.values(index)) out.row.cells.push_back(Cell::txt(v));
  ref::Scene scene = plan.scene(index);
  scene.render.threads = threads;  // results do not depend on it (parallel.hpp)
  try {
    const std::shared_ptr<const SceneVolume> sv =
        caches.volumes.get(volume_key(scene), [&] { return load_scene_volume(scene); });
    check_fixed_point(scene, *sv, false);
    const std::shared_ptr<const ref::Image> truth = caches.truths.get(scene, *sv, plan.truth);
    const ref::CameraPose pose = ref::frame_poses(scene.camera, 1).front();
    const ref::RenderInputs in = ref::make_render_inputs(scene, sv->volume, sv->gradients, pose);
    const bittrue::FrameSetup setup = bittrue::make_frame_setup(scene.precision, scene, in);
    const bittrue::VoxelMemory memory =
        bittrue::make_voxel_memory(scene.precision, sv->volume, sv->gradients);
    const bool hls = hls_supports(scene.precision);
    const ref::QuantImage design = hls ? hls_render_image(setup, memory, threads)
                                       : bittrue::bt_render_image(setup, memory, threads);
    const PointContext ctx{scene, *sv, setup, memory, design, hls, *truth, plan.part};
    out.row.cells.push_back(Cell::txt("ok"));
    for (const ColumnGroup& g : column_groups()) {
      std::vector<Cell> cells = g.measure(ctx);
      if (cells.size() != g.columns.size())
        throw std::logic_error("column group " + g.name + " returned the wrong number of cells");
      for (Cell& c : cells) out.row.cells.push_back(std::move(c));
    }
  } catch (const TruthMissingError&) {
    throw;  // not the point's: the run cannot go on
  } catch (const Error& e) {
    // The point cannot run (a width that cannot hold the volume, ...): its row
    // says why; the rest of the sweep goes on.
    out.row.cells.resize(plan.axes.size());
    out.row.cells.push_back(Cell::txt(std::string("infeasible: ") + e.what()));
    for (std::size_t i = 0; i < measured_columns(); ++i)
      out.row.cells.push_back(Cell::na(std::string("infeasible: ") + e.what()));
  }
  out.seconds = seconds_since(t0);
  return out;
}

// --- Table --------------------------------------------------------------------------

nlohmann::json sweep_meta(const Plan& plan, const Shard& shard) {
  nlohmann::json axes = nlohmann::json::array();
  for (const Axis& a : plan.axes) axes.push_back({{"key", a.key}, {"values", a.values}});
  nlohmann::json m = {
      {"scene", plan.scene_path},
      {"sets", plan.sets},
      {"axes", axes},
      {"points_total", plan.size()},
      {"truth",
       {{"reference", "float"},
        {"oversampling", plan.truth.oversampling},
        {"ert_threshold", kTruthErtThreshold}}},
      {"part", plan.part},
      {"rtl_config", "VIZARD II baseline: in-order open page, linear layout, scan-line order"}};
  if (shard.count > 1) m["shard"] = std::to_string(shard.index) + "/" + std::to_string(shard.count);
  return m;
}

std::vector<Column> table_columns(const Plan& plan) {
  std::vector<Column> cols;
  for (const Axis& a : plan.axes) cols.push_back({a.key, Kind::Text, "", "the varied scene key"});
  cols.push_back({"status", Kind::Text, "", "ok, or infeasible: the reason the point cannot run"});
  for (const ColumnGroup& g : column_groups())
    for (const Column& c : g.columns) cols.push_back(c);
  return cols;
}

void mark_fronts(Table& t, bool complete) {
  for (const Front& f : pareto_fronts()) {
    if (complete) {
      mark_front(t, f);
      continue;
    }
    t.columns.push_back(f.column);
    for (Row& r : t.rows) r.cells.push_back(Cell::na("a shard: sweep-merge marks the front"));
  }
}

void write_run_json(const std::string& path, const SweepOptions& o, const SweepSummary& s,
                    const std::vector<PointOutcome>& outcomes) {
  nlohmann::json j = {
      {"jobs", o.jobs},
      {"shard", std::to_string(o.shard.index) + "/" + std::to_string(o.shard.count)},
      {"seconds", s.seconds},
      {"truth_renders", s.truth_renders},
      {"point_seconds", nlohmann::json::object()}};
  for (const PointOutcome& p : outcomes)
    j["point_seconds"][std::to_string(p.row.index)] = p.seconds;
  write_json_file(path, j);
}

// --- The journal: every finished point on disk ---------------------------------------

namespace fs = std::filesystem;

fs::path points_dir(const SweepOptions& o) { return fs::path(o.out_dir) / "points"; }

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// What makes two runs the same sweep: the table's description without the
// shard, its columns, and the scene file's bytes (an edited scene is another
// sweep even under the same name).
nlohmann::json sweep_identity(const Plan& plan, const std::vector<Column>& columns) {
  nlohmann::json id = sweep_meta(plan, Shard{});
  id["columns"] = nlohmann::json::array();
  for (const Column& c : columns) id["columns"].push_back(c.name);
  id["scene_file"] = read_text(plan.scene_path);
  return id;
}

// "its axes differ" for the first key two identities disagree on.
std::string identity_difference(const nlohmann::json& mine, const nlohmann::json& theirs) {
  for (auto it = mine.begin(); it != mine.end(); ++it)
    if (!theirs.contains(it.key()) || theirs.at(it.key()) != it.value())
      return it.key() == "scene_file" ? "the scene file's contents differ"
                                      : "its " + it.key() + " differ";
  for (auto it = theirs.begin(); it != theirs.end(); ++it)
    if (!mine.contains(it.key())) return "it has a " + it.key() + " this sweep has not";
  return "";
}

std::string point_file(const fs::path& dir, std::size_t index) {
  char name[32];
  std::snprintf(name, sizeof name, "%06zu.json", index);
  return (dir / name).string();
}

// A fresh journal: DIR/points emptied, its sweep.json written.
void start_journal(const fs::path& dir, const nlohmann::json& identity) {
  std::error_code ec;
  fs::remove_all(dir, ec);
  if (ec) throw Error("sweep: cannot clear " + dir.string() + " (" + ec.message() + ")");
  make_output_dir(dir.string());
  write_file_atomically((dir / "sweep.json").string(),
                        nlohmann::json{{"identity", identity}}.dump(2) + "\n");
}

// --resume: the journal must be this sweep's; leftovers of writes a kill
// interrupted are removed.
void check_journal(const fs::path& dir, const nlohmann::json& identity) {
  const std::string path = (dir / "sweep.json").string();
  if (!fs::exists(path))
    throw Error("sweep --resume: " + path + " does not exist: " + dir.parent_path().string() +
                " holds no sweep to resume (run it without --resume)");
  nlohmann::json stored;
  try {
    stored = nlohmann::json::parse(read_text(path)).at("identity");
  } catch (const nlohmann::json::exception& e) {
    throw Error("sweep --resume: " + path + ": not a sweep journal (" + e.what() + ")");
  }
  if (const std::string d = identity_difference(identity, stored); !d.empty())
    throw Error("sweep --resume: " + dir.parent_path().string() +
                " holds another sweep: " + d + " (run it without --resume, or use another --out)");
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename().string().find(".tmp.") != std::string::npos) fs::remove(e.path());
}

void journal_point(const fs::path& dir, const Table& header, const PointOutcome& p) {
  Table one{header.meta, header.columns, {p.row}};
  nlohmann::json j = to_json(one);
  j["seconds"] = p.seconds;
  write_file_atomically(point_file(dir, p.row.index),
                        j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
}

std::optional<PointOutcome> read_point(const fs::path& dir, std::size_t index,
                                       std::size_t columns) {
  const std::string path = point_file(dir, index);
  if (!fs::exists(path)) return std::nullopt;
  PointOutcome p;
  try {
    const nlohmann::json j = nlohmann::json::parse(read_text(path));
    const Table t = table_from_json(j, path);
    if (t.rows.size() != 1 || t.rows[0].index != index || t.rows[0].cells.size() != columns)
      throw Error(path + ": not the journal entry of point " + std::to_string(index));
    p.row = t.rows[0];
    p.seconds = j.at("seconds").get<double>();
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": not a journal entry (" + e.what() + ")");
  }
  return p;
}

// --- Stopping on SIGINT / SIGTERM -------------------------------------------------------

std::atomic<int> g_stop_signal{0};
extern "C" void on_stop_signal(int sig) { g_stop_signal.store(sig); }

// For a run's duration: SIGINT and SIGTERM set a flag that a watcher turns
// into one line and an immediate exit (128 + the signal). Finished points are
// already on disk; the points in flight are dropped (a Slurm job has seconds
// between SIGTERM and SIGKILL, a point may take minutes).
class StopOnSignal {
 public:
  StopOnSignal(std::function<std::string()> what_was_kept)
      : what_was_kept_(std::move(what_was_kept)) {
    g_stop_signal.store(0);
    struct sigaction sa {};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &old_int_);
    sigaction(SIGTERM, &sa, &old_term_);
    watcher_ = std::jthread([this](std::stop_token stop) {
      while (!stop.stop_requested()) {
        if (const int sig = g_stop_signal.load()) {
          std::cerr << "\nvoxcast: sweep: stopped by " << (sig == SIGINT ? "SIGINT" : "SIGTERM")
                    << ": " << what_was_kept_() << std::endl;
          std::_Exit(128 + sig);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
    });
  }
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;
  ~StopOnSignal() {
    watcher_.request_stop();
    watcher_.join();
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }

 private:
  std::function<std::string()> what_was_kept_;
  struct sigaction old_int_ {}, old_term_ {};
  std::jthread watcher_;
};

}  // namespace

const std::vector<ColumnGroup>& column_groups() {
  static const std::vector<ColumnGroup> groups = {
      {"accuracy",
       {{"engine", Kind::Text, "",
         "engine of the accuracy figures: hls, or bittrue (bit-exact "
         "with hls) for a profile hls is not compiled for"},
        {"psnr_db", Kind::Number, "dB", "PSNR against the truth (peak 2^out_bits - 1)"},
        {"max_err_lsb", Kind::Number, "LSB", "largest channel error against the truth"},
        {"mean_err_lsb", Kind::Number, "LSB", "mean channel error against the truth"},
        {"rms_err_lsb", Kind::Number, "LSB", "rms channel error against the truth"},
        {"pct_within_1lsb", Kind::Number, "%", "pixels whose three channels are within 1 LSB"},
        {"ssim", Kind::Number, "", "mean SSIM of the colour channels against the truth"}},
       measure_accuracy_cells},
      {"hazards",
       {{"hazards", Kind::Number, "", "precision hazards the guard predicts (cosim/engines/warnings.hpp)"},
        {"hazard_worst_lsb", Kind::Number, "LSB",
         "the largest predicted worst-case error of a hazard (0: none)"},
        {"hazard_keys", Kind::Text, "", "the scene keys of the hazards, space-separated"}},
       measure_hazard_cells},
      {"rtl",
       {{"rtl_fps", Kind::Number, "frames/s",
         "the cycle model's frames per second at the board's core clock (100 MHz on the VIZARD II "
         "card, 300 MHz on the U250)"},
        {"rtl_ns_per_sample", Kind::Number, "ns", "the cycle model's ns per composited sample"},
        {"rtl_cycles", Kind::Number, "cycles", "the cycle model's cycles for the frame"}},
       measure_rtl_cells},
      {"resources",
       {{"part", Kind::Text, "", "the part of the resource columns (--part)"},
        {"luts", Kind::Number, "LUT",
         "estimated LUTs (resource model, docs/resources.md); on a DDR4 board the whole card: "
         "N pipelines and the four channels"},
        {"ffs", Kind::Number, "FF", "estimated flip-flops"},
        {"dsps", Kind::Number, "DSP", "DSP slices (DSP48E1, DSP48E2 or MULT18X18)"},
        {"brams", Kind::Number, "RAMB18", "block RAMs"},
        {"urams", Kind::Number, "URAM288", "UltraRAM blocks (0 on a part without)"},
        {"part_pct", Kind::Number, "%",
         "the part's share used: voxcast report's cost, the sum of the resources' shares"},
        {"part_max_pct", Kind::Number, "%",
         "the scarcest resource's share of the part (over 100: does not fit)"}},
       measure_resource_cells},
  };
  return groups;
}

const std::vector<Front>& pareto_fronts() {
  static const std::vector<Front> fronts = {
      {{"pareto_psnr_fps", Kind::Text, "",
        "on the Pareto front of PSNR against the truth (max) and rtl frames/s (max)"},
       {{"psnr_db", true}, {"rtl_fps", true}}},
      {{"pareto_psnr_resources", Kind::Text, "",
        "on the Pareto front of PSNR against the truth (max) and the part share (min)"},
       {{"psnr_db", true}, {"part_pct", false}}},
      {{"pareto_fps_resources", Kind::Text, "",
        "on the Pareto front of rtl frames/s (max) and the scarcest resource's share of the part "
        "(min)"},
       {{"rtl_fps", true}, {"part_max_pct", false}}},
  };
  return fronts;
}

namespace {

// Runs work(t) for t in [0, count) on `jobs` threads (this one included),
// each item once, stepping the progress line after each; then rethrows the
// first item's exception in item order, if any failed.
template <class Work>
void run_on_jobs(std::size_t count, int jobs, Progress& progress, Work&& work) {
  std::vector<std::exception_ptr> failures(count);
  std::atomic<std::size_t> next{0};
  const auto worker = [&] {
    for (std::size_t t = next.fetch_add(1); t < count; t = next.fetch_add(1)) {
      try {
        work(t);
      } catch (...) {
        failures[t] = std::current_exception();
      }
      progress.step();
    }
  };
  {
    std::vector<std::jthread> pool;
    for (int j = 1; j < std::min<int>(jobs, static_cast<int>(count)); ++j) pool.emplace_back(worker);
    worker();
  }
  for (const std::exception_ptr& f : failures)
    if (f) std::rethrow_exception(f);
}

// --truth-only: each point's truth into the cache, in parallel over --jobs;
// points whose widths cannot hold the scene need none (their rows say
// "infeasible" without one).
SweepSummary render_truths(const Plan& plan, const SweepOptions& o,
                           const std::vector<std::size_t>& points, const std::string& cache_dir) {
  const auto t0 = StopwatchClock::now();
  Caches caches{{}, TruthCache(cache_dir)};
  const int threads = std::max(1, ref::worker_count(0) / o.jobs);
  Progress progress("truth", points.size(), o.progress);
  run_on_jobs(points.size(), o.jobs, progress, [&](std::size_t t) {
    ref::Scene scene = plan.scene(points[t]);
    scene.render.threads = threads;
    const std::shared_ptr<const SceneVolume> sv =
        caches.volumes.get(volume_key(scene), [&] { return load_scene_volume(scene); });
    bool feasible = true;
    try {
      check_fixed_point(scene, *sv, false);
    } catch (const Error&) {
      feasible = false;
    }
    if (feasible) caches.truths.get(scene, *sv, plan.truth);
  });
  SweepSummary s;
  s.truth_only = true;
  s.points_total = plan.size();
  s.truth_images = caches.truths.images();
  s.truth_renders = caches.truths.renders();
  s.written.push_back(cache_dir);
  s.seconds = seconds_since(t0);
  return s;
}

}  // namespace

SweepSummary run_sweep(const Plan& plan, const SweepOptions& o) {
  if (o.jobs < 1 || o.jobs > 256) throw Error("sweep: --jobs must be in [1, 256]");
  if (o.out_dir.empty()) throw Error("sweep: --out DIR is required");
  try {
    find_part(plan.part);
  } catch (const Error& e) {
    throw Error(std::string("sweep: --part: ") + e.what());
  }
  make_output_dir(o.out_dir);
  const auto t0 = StopwatchClock::now();
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < plan.size(); ++i)
    if (o.shard.owns(i)) mine.push_back(i);

  const std::string cache_dir =
      o.truth_cache.empty() ? (fs::path(o.out_dir) / "truth").string() : o.truth_cache;
  if (o.truth_only) {
    if (o.truth_from_cache) throw Error("sweep: --truth-only renders the truths; --truth-from-cache only reads them");
    return render_truths(plan, o, mine, cache_dir);
  }

  Table table;
  table.meta = sweep_meta(plan, o.shard);
  table.columns = table_columns(plan);
  const fs::path journal = points_dir(o);
  const nlohmann::json identity = sweep_identity(plan, table.columns);
  const bool resume = o.resume || (o.resume_if_started && fs::exists(journal / "sweep.json"));
  if (resume)
    check_journal(journal, identity);
  else
    start_journal(journal, identity);

  // The points already in the journal (--resume), then the rest in parallel;
  // each writes only its own slot, so the table's order and contents depend
  // neither on --jobs nor on where a run was stopped.
  std::vector<PointOutcome> outcomes(mine.size());
  std::vector<std::size_t> todo;
  std::size_t resumed = 0;
  for (std::size_t k = 0; k < mine.size(); ++k) {
    std::optional<PointOutcome> p;
    if (resume) p = read_point(journal, mine[k], table.columns.size());
    if (p) {
      outcomes[k] = std::move(*p);
      ++resumed;
    } else {
      todo.push_back(k);
    }
  }
  Caches caches{{}, TruthCache(cache_dir, !o.truth_from_cache)};
  const int threads = std::max(1, ref::worker_count(0) / o.jobs);
  // Journal writes take this lock; a stop takes it for good before it counts,
  // so the count it prints is exactly the entries on disk.
  std::mutex journal_mutex;
  std::size_t kept = resumed;
  const StopOnSignal stop_on_signal([&] {
    journal_mutex.lock();  // never released: the process ends next
    return std::to_string(kept) + " of " + std::to_string(mine.size()) + " points kept in " +
           journal.string() + "; the same command with --resume goes on";
  });
  Progress progress("sweep", todo.size(), o.progress);
  run_on_jobs(todo.size(), o.jobs, progress, [&](std::size_t t) {
    const std::size_t k = todo[t];
    outcomes[k] = run_point(plan, mine[k], threads, caches);
    const std::lock_guard lock(journal_mutex);
    journal_point(journal, table, outcomes[k]);
    ++kept;
  });

  for (PointOutcome& p : outcomes) table.rows.push_back(p.row);
  mark_fronts(table, o.shard.count == 1);

  SweepSummary s;
  s.points = mine.size();
  s.points_resumed = resumed;
  s.points_total = plan.size();
  s.truth_renders = caches.truths.renders();
  s.written = write_outputs(table, o.out_dir, o.plots && o.shard.count == 1,
                            o.html && o.shard.count == 1, s.warnings);
  s.seconds = seconds_since(t0);
  const std::string run = (std::filesystem::path(o.out_dir) / "run.json").string();
  write_run_json(run, o, s, outcomes);
  s.written.push_back(run);
  return s;
}

SweepSummary run_sweep_merge(const std::vector<std::string>& dirs, const std::string& out_dir,
                             bool plots, bool html) {
  if (dirs.empty()) throw Error("sweep-merge: give the output folders of the shards");
  const auto t0 = StopwatchClock::now();
  std::vector<Table> shards;
  std::vector<std::string> origins;
  for (const std::string& d : dirs) {
    origins.push_back((std::filesystem::path(d) / "results.json").string());
    shards.push_back(read_json(origins.back()));
  }
  Table t = merge_tables(shards, origins);
  for (const Front& f : pareto_fronts()) mark_front(t, f);
  make_output_dir(out_dir);
  SweepSummary s;
  s.merged = true;
  s.points = t.rows.size();
  s.points_total = t.rows.size();
  s.written = write_outputs(t, out_dir, plots, html, s.warnings);
  s.seconds = seconds_since(t0);
  return s;
}

std::vector<std::string> write_outputs(const Table& table, const std::string& dir, bool plots,
                                       bool html, std::vector<std::string>& warnings) {
  const auto path = [&](const char* f) { return (std::filesystem::path(dir) / f).string(); };
  std::vector<std::string> written = {path("results.csv"), path("results.json")};
  write_csv(table, written[0]);
  write_json(table, written[1]);
  if (plots) {
    const std::vector<std::string> p = write_plots(table, dir, warnings);
    written.insert(written.end(), p.begin(), p.end());
  }
  if (html) {
    written.push_back(path("sweep.html"));
    write_text_file(written.back(), sweep_page(table));
  }
  return written;
}

void print_sweep_summary(std::ostream& os, const SweepSummary& s) {
  os << std::fixed << std::setprecision(1);
  if (s.truth_only)
    os << "truths   " << s.truth_images << " image" << (s.truth_images == 1 ? "" : "s")
       << " for the " << s.points_total << " points in " << s.seconds << " s (" << s.truth_renders
       << " rendered, " << s.truth_images - s.truth_renders << " already in the cache)\n";
  else if (s.merged)
    os << "merged   " << s.points << " points in " << s.seconds << " s\n";
  else
    os << "points   " << s.points << " of " << s.points_total << " in " << s.seconds << " s ("
       << s.truth_renders << " truth image" << (s.truth_renders == 1 ? "" : "s") << " rendered"
       << (s.points_resumed > 0 ? ", " + std::to_string(s.points_resumed) + " resumed" : "")
       << ")\n";
  for (const std::string& w : s.warnings) std::cerr << "voxcast: warning: " << w << "\n";
  for (const std::string& w : s.written) os << "wrote    " << w << "\n";
}

}  // namespace voxcast::cosim::sweep
