// `voxcast sweep` and `voxcast sweep-merge` (docs/sweep.md): the speed and
// accuracy of the design over the cartesian product of scene settings.
//
// Each point: accuracy against the truth (cosim/engines/truth.hpp) through the hls
// engine if the profile is compiled in, else the bit-true engine (bit-exact
// with hls; the `engine` column says which), and the cycle model's frames/s,
// ns per sample and cycles where the rtl engine runs (compiled presets only;
// elsewhere not available, with the reason). Rows come out in point order for
// any --jobs; shards merge to the single run's table.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "cosim/engines/engines.hpp"
#include "cosim/explore/sweep_plan.hpp"
#include "cosim/explore/sweep_table.hpp"
#include "refmodel/bittrue/raycaster.hpp"

namespace voxcast::cosim::sweep {

struct SweepOptions {
  std::string out_dir;
  int jobs = 1;           // points in parallel
  Shard shard;            // 0/1: the whole sweep
  bool progress = false;  // force the progress bar (it is on when stderr is a TTY)
  bool plots = true;      // PNG and SVG through gnuplot
  bool html = false;      // DIR/sweep.html (cosim/explore/pages.hpp); not for a shard
  // --resume: keep the finished points of DIR/points (the same sweep, checked)
  // and compute only the others; without it a run starts afresh.
  bool resume = false;
  // --truth-cache: the folder of truths on disk (TruthCache), shared by the
  // shards and later runs of a sweep; empty = DIR/truth.
  std::string truth_cache = {};
  // --truth-only: render the truth of every point into the truth cache and
  // nothing else (a cluster run's truth job); no journal, no table.
  bool truth_only = false;
  // --truth-from-cache: read every truth from the cache, never render one (a
  // cluster run's shards); a missing truth ends the run with an error.
  bool truth_from_cache = false;
  // --resume-if-started: --resume when OUT holds a journal, else a fresh run
  // (a cluster's shard, which may run again after a failure).
  bool resume_if_started = false;
};

// What a column group sees of one point, after the design's image is rendered.
struct PointContext {
  const ref::Scene& scene;
  const SceneVolume& volume;
  const bittrue::FrameSetup& setup;
  const bittrue::VoxelMemory& memory;
  const ref::QuantImage& design;  // the accuracy engine's image
  bool design_is_hls;             // else bit-true
  const ref::Image& truth;
  const std::string& part;  // the plan's part (resource columns)
};

// A group of columns measured per point. EXTENSION POINT: a further group (the
// resource model of `voxcast report`: LUTs, DSPs, block RAM of the point's
// profile) is one ColumnGroup appended to column_groups() in sweep.cpp, and its
// Pareto front (accuracy against a resource) one Front in pareto_fronts().
struct ColumnGroup {
  std::string name;
  std::vector<Column> columns;
  // Returns exactly columns.size() cells; a cell it cannot measure is
  // Cell::na(reason), never a made-up number.
  std::function<std::vector<Cell>(const PointContext&)> measure;
};
const std::vector<ColumnGroup>& column_groups();
const std::vector<Front>& pareto_fronts();

struct SweepSummary {
  std::size_t points = 0;         // points of this run (computed or resumed)
  std::size_t points_resumed = 0; // of those, read back from DIR/points (--resume)
  std::size_t points_total = 0;   // points of the whole sweep
  std::size_t truth_renders = 0;  // distinct truth images rendered (sweep; 0 for a merge)
  std::size_t truth_images = 0;   // distinct truth images the points need (--truth-only)
  bool truth_only = false;
  bool merged = false;
  double seconds = 0.0;
  std::vector<std::string> written;
  std::vector<std::string> warnings;  // e.g. plots skipped
};

// The journal: each point is written to DIR/points/NNNNNN.json the moment it
// finishes (atomically: files.hpp write_file_atomically), after
// DIR/points/sweep.json records which sweep they belong to. SIGINT and
// SIGTERM (Ctrl-C; Slurm's preemption and time limit) end the run at once,
// after one line saying how many points were kept, with status 128 + the
// signal; `--resume` goes on from there, and its results.csv and
// results.json are byte-identical to an uninterrupted run's.
SweepSummary run_sweep(const Plan& plan, const SweepOptions& options);

// Reads DIR/results.json of each input, joins them (merge_tables), marks the
// fronts over all points and writes results.csv, results.json and the plots.
SweepSummary run_sweep_merge(const std::vector<std::string>& dirs, const std::string& out_dir,
                             bool plots = true, bool html = false);

void print_sweep_summary(std::ostream& os, const SweepSummary& s);

// The table's files: results.csv, results.json; with plots, the gnuplot
// script, its data and PNG + SVG (skipped with a warning when gnuplot is
// missing); with html, sweep.html. Returns the paths written.
std::vector<std::string> write_outputs(const Table& table, const std::string& dir, bool plots,
                                       bool html, std::vector<std::string>& warnings);

}  // namespace voxcast::cosim::sweep
