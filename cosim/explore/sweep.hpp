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
  std::size_t points = 0;         // points this run computed
  std::size_t points_total = 0;   // points of the whole sweep
  std::size_t truth_renders = 0;  // distinct truth images rendered (sweep; 0 for a merge)
  bool merged = false;
  double seconds = 0.0;
  std::vector<std::string> written;
  std::vector<std::string> warnings;  // e.g. plots skipped
};

SweepSummary run_sweep(const Plan& plan, const SweepOptions& options);

// Reads DIR/results.json of each input, joins them (merge_tables), marks the
// fronts over all points and writes results.csv, results.json and the plots.
SweepSummary run_sweep_merge(const std::vector<std::string>& dirs, const std::string& out_dir,
                             bool plots = true);

void print_sweep_summary(std::ostream& os, const SweepSummary& s);

// The table's files: results.csv, results.json; with plots, the gnuplot
// script, its data and PNG + SVG (skipped with a warning when gnuplot is
// missing). Returns the paths written.
std::vector<std::string> write_outputs(const Table& table, const std::string& dir, bool plots,
                                       std::vector<std::string>& warnings);

}  // namespace voxcast::cosim::sweep
