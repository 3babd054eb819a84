// The sweep's plots, drawn by gnuplot (Debian's gnuplot-nox): the table's
// data as gnuplot data files, one script (plots.gp, kept beside them so a plot
// can be restyled and redrawn by hand), run once for PNG and SVG.
#pragma once

#include <string>
#include <vector>

#include "cosim/explore/sweep_table.hpp"

namespace voxcast::cosim::sweep {

// Writes DIR/plots.gp, its .dat files and DIR/<plot>.png and .svg:
//   psnr_vs_fps, psnr_vs_resources: every feasible point with both figures, the
//     Pareto front as a line;
//   psnr_vs_<key>: PSNR against each varied key whose values are all numbers.
// Without gnuplot on PATH (or if it fails), the plots are skipped and a
// warning says why; the data and the script are still written.
std::vector<std::string> write_plots(const Table& table, const std::string& dir,
                                     std::vector<std::string>& warnings);

// Runs `program args...` in folder `dir`; the exit status, or -1 if it cannot start.
int run_in(const std::string& dir, const std::vector<std::string>& argv);
bool on_path(const std::string& program);

}  // namespace voxcast::cosim::sweep
