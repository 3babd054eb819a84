#include "cosim/explore/sweep_plot.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "refmodel/error.hpp"

namespace voxcast::cosim::sweep {
namespace {

bool is_number(const std::string& s, double& v) {
  std::istringstream in(s);
  in >> v;
  return !in.fail() && in.eof() && std::isfinite(v);
}

// A file name from a scene key: "precision.weight_bits" -> "precision_weight_bits".
std::string file_stem(const std::string& key) {
  std::string s;
  for (char c : key) s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return s;
}

struct PlotPoint {
  double x, y;
  bool front;
  std::string label;  // the point's configuration (point_label)
};

// A label as a gnuplot data string: double-quoted, no quote or backslash inside.
std::string quoted(std::string label) {
  for (char& c : label)
    if (c == '"' || c == '\\' || c == '\n') c = '\'';
  return "\"" + label + "\"";
}

// x y "label" per line: `using 1:2` draws the points, `using 1:2:3 with labels` names them.
void write_dat(const std::string& path, const std::vector<PlotPoint>& pts, bool front_only) {
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot write");
  out.precision(17);
  for (const PlotPoint& p : pts)
    if (!front_only || p.front) out << p.x << " " << p.y << " " << quoted(p.label) << "\n";
}

// Every point named by its configuration, beside it.
std::string labels_layer(const std::string& dat) {
  return ", \\\n     '" + dat + "' using 1:2:3 with labels offset char 0.6,0.6 left font ',7' notitle";
}

}  // namespace

bool on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::istringstream dirs(path);
  for (std::string d; std::getline(dirs, d, ':');)
    if (!d.empty() && access((std::filesystem::path(d) / program).c_str(), X_OK) == 0) return true;
  return false;
}

int run_in(const std::string& dir, const std::vector<std::string>& argv) {
  // Everything the child needs is made before fork: between fork and exec it
  // calls only async-signal-safe functions (other threads may hold malloc's lock).
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    // The child: quiet, in `dir`, then the program.
    const int devnull = open("/dev/null", O_WRONLY);
    if (devnull >= 0) {
      dup2(devnull, STDOUT_FILENO);
      dup2(devnull, STDERR_FILENO);
    }
    if (chdir(dir.c_str()) != 0) _exit(127);
    execvp(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<std::string> write_plots(const Table& t, const std::string& dir,
                                     std::vector<std::string>& warnings) {
  namespace fs = std::filesystem;
  const auto path = [&](const std::string& f) { return (fs::path(dir) / f).string(); };
  const std::size_t status = t.column("status");
  const auto ok = [&](const Row& r) { return r.cells[status].text == "ok"; };

  std::vector<std::string> plots;  // stems
  std::ostringstream gp;
  gp << "# voxcast sweep plots: gnuplot plots.gp (in this folder) redraws them.\n"
     << "set grid\nset key below\n";
  std::vector<std::pair<std::string, std::string>> bodies;  // stem, plot commands

  // A figure of merit (PSNR, frames/s) against a cost or speed column, its
  // Pareto front as a line. Labels are gnuplot single-quoted strings: no
  // apostrophes in them.
  const auto front_plot = [&](const std::string& stem, const std::string& x_column,
                              const std::string& y_column, const std::string& front_column,
                              const std::string& xlabel, const std::string& ylabel) {
    const std::size_t xc = t.column(x_column), yc = t.column(y_column),
                      front = t.column(front_column);
    std::vector<PlotPoint> pf;
    for (const Row& r : t.rows) {
      const auto x = r.cells[xc].value(), y = r.cells[yc].value();
      if (ok(r) && x && y && std::isfinite(*y))
        pf.push_back({*x, *y, r.cells[front].text == "yes", point_label(t, r)});
    }
    std::sort(pf.begin(), pf.end(),
              [](const PlotPoint& a, const PlotPoint& b) { return a.x < b.x; });
    if (pf.empty()) {
      // Only PSNR plots warn: a sweep without rtl figures (a profile the rtl
      // engine is not compiled for) has no frames/s front to draw.
      if (y_column == "psnr_db")
        warnings.push_back("no point has both a finite PSNR and " + x_column + ": " + stem +
                           " not plotted");
      return;
    }
    write_dat(path(stem + ".dat"), pf, false);
    write_dat(path(stem + "_front.dat"), pf, true);
    bodies.push_back({stem, "set xlabel '" + xlabel + "'\nset ylabel '" + ylabel + "'\n" +
                                "plot '" + stem + ".dat' using 1:2 with points pt 7 title 'points', \\\n"
                                "     '" + stem + "_front.dat' using 1:2 with linespoints lw 2 pt 6 "
                                "ps 2 title 'Pareto front'" + labels_layer(stem + ".dat") + "\n"});
  };
  const std::string psnr_label = "PSNR against the truth (dB)";
  const std::string part = t.meta.value("part", std::string("xc7a200t"));
  front_plot("psnr_vs_fps", "rtl_fps", "psnr_db", "pareto_psnr_fps",
             "rtl frames/s (cycle model, at the core clock of the board)", psnr_label);
  front_plot("psnr_vs_resources", "part_pct", "psnr_db", "pareto_psnr_resources",
             "share of the " + part + " used (report cost: sum of LUT, FF, DSP, RAM shares, %)",
             psnr_label);
  front_plot("fps_vs_resources", "part_max_pct", "rtl_fps", "pareto_fps_resources",
             "share of the " + part + " taken by its scarcest resource (%)",
             "rtl frames/s (cycle model, at the core clock of the board)");
  // PSNR against each numeric axis.
  const std::size_t axes = t.meta.at("axes").size();
  for (std::size_t a = 0; a < axes; ++a) {
    const std::string key = t.columns[a].name;
    std::vector<PlotPoint> pts;
    bool numeric = true;
    for (const Row& r : t.rows) {
      double x = 0;
      if (!is_number(r.cells[a].text, x)) numeric = false;
      const auto y = r.cells[t.column("psnr_db")].value();
      if (numeric && ok(r) && y && std::isfinite(*y)) pts.push_back({x, *y, false, point_label(t, r)});
    }
    if (!numeric || pts.empty()) continue;
    const std::string stem = "psnr_vs_" + file_stem(key);
    write_dat(path(stem + ".dat"), pts, false);
    bodies.push_back({stem, "set xlabel '" + key +
                                "'\nset ylabel 'PSNR against the truth (dB)'\n"
                                "plot '" +
                                stem + ".dat' using 1:2 with points pt 7 title 'points'" +
                                labels_layer(stem + ".dat") + "\n"});
  }
  for (const char* term : {"pngcairo size 800,600", "svg size 800,600"})
    for (const auto& [stem, body] : bodies) {
      const std::string ext = std::string(term).rfind("png", 0) == 0 ? ".png" : ".svg";
      gp << "\nset terminal " << term << "\nset output '" << stem << ext << "'\n" << body;
      plots.push_back(stem + ext);
    }
  gp << "\nset output\n";
  {
    std::ofstream out(path("plots.gp"));
    if (!out) throw Error(path("plots.gp") + ": cannot write");
    out << gp.str();
  }
  std::vector<std::string> written = {path("plots.gp")};
  if (bodies.empty()) return written;
  if (!on_path("gnuplot")) {
    warnings.push_back("gnuplot is not installed (Debian: gnuplot-nox): plots skipped; " +
                       path("plots.gp") + " draws them");
    return written;
  }
  if (const int rc = run_in(dir, {"gnuplot", "plots.gp"}); rc != 0) {
    warnings.push_back("gnuplot failed (exit " + std::to_string(rc) + ") on " + path("plots.gp") +
                       ": plots skipped");
    return written;
  }
  for (const std::string& p : plots) written.push_back(path(p));
  return written;
}

}  // namespace voxcast::cosim::sweep
