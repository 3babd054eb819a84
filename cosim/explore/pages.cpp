#include "cosim/explore/pages.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cosim/hardware/report.hpp"
#include "cosim/reports/html.hpp"
#include "cosim/reports/junit.hpp"
#include "cosim/reports/text.hpp"

namespace voxcast::cosim {
namespace {

namespace fs = std::filesystem;

std::string verdicts(const ref::Scene& scene, const CosimResult& r) {
  std::string out = "<h2>Verdict</h2>\n<table>\n<tr><th>engines</th><th>result</th><th>detail</th></tr>\n";
  for (const JUnitCase& c : cosim_junit(scene, r).cases) {
    const char* cls = c.outcome == JUnitCase::Outcome::Passed   ? "pass"
                      : c.outcome == JUnitCase::Outcome::Failed ? "fail"
                                                                : "skip";
    const char* word = c.outcome == JUnitCase::Outcome::Passed   ? "bit-exact"
                       : c.outcome == JUnitCase::Outcome::Failed ? "DIFFER"
                                                                 : "not run";
    out += "<tr><td>" + html::escape(c.name) + "</td><td class=\"" + cls + "\">" + word +
           "</td><td>" + html::escape(c.message) + "</td></tr>\n";
  }
  return out + "</table>\n";
}

std::string images(const ref::Scene& scene, const CosimResult& r, const std::string& out_dir) {
  const int w = scene.render.width, h = scene.render.height;
  const int scale = std::clamp(256 / std::max(1, std::max(w, h)), 1, 8);
  std::string out = "<h2>Images</h2>\n";
  const std::pair<const char*, std::string> shown[] = {
      {"float.png", "float reference (scene settings)"},
      {"bittrue.png", "bit-true reference"},
      {"hls.png", "hls kernels"},
      {"diff.png", "|hls - float| heat map (black 0, white 4 LSB)"},
      {"truth.png", "truth (float at " + fixed_text(r.truth.oversampling, 0) + "x oversampling)"}};
  for (const auto& [file, caption] : shown)
    if (fs::exists(fs::path(out_dir) / file)) out += html::figure(file, caption, w, h, scale);
  return out;
}

std::vector<std::string> accuracy_row(const std::string& what, const Accuracy& a) {
  return {what,
          fixed_text(a.psnr_db),
          fixed_text(a.ssim, 4),
          fixed_text(a.max_abs_err_lsb),
          fixed_text(a.rms_err_lsb, 3),
          fixed_text(a.pct_within_1lsb)};
}

std::string accuracy(const ref::Scene& scene, const CosimResult& r) {
  const std::string engine = r.hls_ran ? "hls" : "bit-true";
  std::vector<std::vector<std::string>> rows = {accuracy_row(engine + " vs float", r.accuracy)};
  if (scene.algorithm != ref::Algorithm::Heidelberg)
    rows.push_back(accuracy_row(engine + " vs truth", r.truth_accuracy));
  std::string out = "<h2>Accuracy</h2>\n" +
                    html::table({"", "PSNR (dB)", "SSIM", "max (LSB)", "rms (LSB)",
                                 "% within 1 LSB"},
                                rows);
  std::uint64_t total = 0;
  for (std::uint64_t c : r.truth_histogram.count) total += c;
  if (total > 0) {
    std::vector<std::string> labels;
    std::vector<double> values;
    for (int b = 0; b < ErrorHistogram::kBins; ++b) {
      labels.push_back(ErrorHistogram::label(b));
      values.push_back(static_cast<double>(r.truth_histogram.count[b]));
    }
    out += html::bar_chart("Pixels by their worst channel's error against the truth (LSB)",
                           labels, values, "pixels");
  }
  return out;
}

// The first divergence: both engines' unit outputs at the diverging sample
// and the one before it.
std::string divergence(const CosimResult& r) {
  if (r.bit_exact) return "";
  const Mismatch& m = r.mismatch;
  std::string out = "<h2>First divergence</h2>\n<p>" +
                    html::escape(m.engine + " differs at pixel (" + std::to_string(m.x) + ", " +
                                 std::to_string(m.y) + "), sample " + std::to_string(m.sample) +
                                 ", first in the " + bittrue::to_string(m.unit) +
                                 "; reproducer " + m.reproducer) +
                    "</p>\n";
  if (m.hls_trace.trace.empty() && m.bt_trace.trace.empty()) return out;
  std::vector<std::vector<std::string>> rows;
  const auto add = [&](const std::string& what, const std::string& a, const std::string& b) {
    rows.push_back({what, a, b, a == b ? "" : "differs"});
  };
  const auto vec = [](const auto& v) {
    std::string s;
    for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + fixed_text(v[i], 6);
    return s;
  };
  add("ray setup: p0", vec(m.hls_trace.p0), vec(m.bt_trace.p0));
  add("ray setup: step", vec(m.hls_trace.step), vec(m.bt_trace.step));
  const std::uint64_t first = m.sample > 0 ? m.sample - 1 : 0;
  for (std::uint64_t k = first; k <= m.sample; ++k) {
    if (k >= m.hls_trace.trace.size() || k >= m.bt_trace.trace.size()) break;
    const bittrue::SampleTrace& a = m.hls_trace.trace[k];
    const bittrue::SampleTrace& b = m.bt_trace.trace[k];
    const std::string s = "sample " + std::to_string(k) + ": ";
    add(s + "position (stepping)", vec(a.position), vec(b.position));
    add(s + "value (interpolation)", fixed_text(a.value, 6), fixed_text(b.value, 6));
    add(s + "gradient (interpolation)", vec(a.gradient), vec(b.gradient));
    add(s + "class address (classification)", std::to_string(a.class_address),
        std::to_string(b.class_address));
    add(s + "alpha (classification)", fixed_text(a.alpha, 6), fixed_text(b.alpha, 6));
    add(s + "diffuse, specular (reflectance map)",
        fixed_text(a.diffuse, 6) + ", " + fixed_text(a.specular, 6),
        fixed_text(b.diffuse, 6) + ", " + fixed_text(b.specular, 6));
    add(s + "shaded (shader)", vec(a.shaded), vec(b.shaded));
    add(s + "accumulator (compositor)", vec(a.accumulator), vec(b.accumulator));
  }
  return out + html::table({"unit output", "hls", "bit-true", ""}, rows);
}

std::string cycles(const std::string& out_dir) {
  std::ifstream in(fs::path(out_dir) / "report.json");
  if (!in) return "";
  nlohmann::json j;
  try {
    in >> j;
  } catch (const nlohmann::json::exception&) {
    return "";
  }
  if (!j.contains("cycles")) return "<h2>Cycle model</h2>\n<p>Not run.</p>\n";
  std::string out =
      "<h2>Cycle model</h2>\n" +
      html::table({"cycles", "frames/s", "ns/sample", "row-hit rate"},
                  {{std::to_string(j["cycles"].get<std::uint64_t>()),
                    fixed_text(j.value("fps", 0.0)), fixed_text(j.value("ns_per_sample", 0.0), 3),
                    fixed_text(100.0 * j.value("row_hit_rate", 0.0), 1) + " %"}});
  if (j.contains("stalls")) {
    std::vector<std::string> labels;
    std::vector<double> values;
    for (auto it = j["stalls"].begin(); it != j["stalls"].end(); ++it) {
      labels.push_back(it.key());
      values.push_back(it.value().get<double>());
    }
    out += html::bar_chart("Stall cycles by cause (rtl_model/pipeline/stats.hpp)", labels, values,
                           "cycles");
  }
  return out;
}

std::string resources(const ref::Scene& scene, const std::string& part) {
  const ResourceReport rep = estimate_resources(scene, find_part(part));
  std::vector<std::vector<std::string>> rows;
  for (const UnitResources& u : rep.units)
    rows.push_back({u.unit.name, fixed_text(u.res.luts, 0), fixed_text(u.res.ffs, 0),
                    fixed_text(u.res.dsps, 0), fixed_text(u.res.brams, 0),
                    std::to_string(u.unit.latency)});
  rows.push_back({"total", fixed_text(rep.total.luts, 0), fixed_text(rep.total.ffs, 0),
                  fixed_text(rep.total.dsps, 0), fixed_text(rep.total.brams, 0), ""});
  rows.push_back({rep.part.name + " capacity", std::to_string(rep.part.luts),
                  std::to_string(rep.part.ffs), std::to_string(rep.part.dsps),
                  std::to_string(rep.part.brams), ""});
  return "<h2>Resources (" + html::escape(rep.part.name) + ", voxcast report)</h2>\n" +
         html::table({"unit", "LUT", "FF", "DSP", "BRAM", "latency (cycles)"}, rows);
}

}  // namespace

std::string cosim_page(const ref::Scene& scene, const CosimResult& r, const std::string& out_dir,
                       const std::string& part) {
  std::string body = "<p>" + html::escape("scene " + scene.origin + ", profile " +
                                          scene.precision_name + ", " +
                                          std::to_string(scene.render.width) + "x" +
                                          std::to_string(scene.render.height)) +
                     "</p>\n";
  body += verdicts(scene, r) + images(scene, r, out_dir) + accuracy(scene, r) + divergence(r);
  if (scene.algorithm != ref::Algorithm::Heidelberg) body += cycles(out_dir) + resources(scene, part);
  return html::page("voxcast cosim: " + fs::path(scene.origin).filename().string(), body);
}

std::string sweep_page(const sweep::Table& t) {
  std::string body = "<p>" + html::escape("scene " + t.meta.value("scene", std::string()) + ", " +
                                          std::to_string(t.rows.size()) + " points") +
                     "</p>\n";
  const std::size_t status = t.column("status");
  struct Plot {
    const char* x_column;
    const char* y_column;
    const char* front_column;
    const char* x_label;
    const char* y_label;
    const char* what;  // the title: WHAT and X_LABEL
  };
  constexpr const char* kPsnr = "PSNR against the truth (dB)";
  for (const Plot& p :
       {Plot{"rtl_fps", "psnr_db", "pareto_psnr_fps", "rtl frames/s (cycle model)", kPsnr,
             "PSNR against the truth"},
        Plot{"part_pct", "psnr_db", "pareto_psnr_resources", "share of the part used (%)", kPsnr,
             "PSNR against the truth"},
        Plot{"part_max_pct", "rtl_fps", "pareto_fps_resources",
             "the scarcest resource's share of the part (%)", "rtl frames/s (cycle model)",
             "rtl frames/s"}}) {
    const std::size_t xc = t.column(p.x_column), yc = t.column(p.y_column),
                      front = t.column(p.front_column);
    std::vector<html::ScatterPoint> pts;
    for (const sweep::Row& r : t.rows) {
      const auto x = r.cells[xc].value(), y = r.cells[yc].value();
      if (r.cells[status].text == "ok" && x && y && std::isfinite(*y))
        pts.push_back({*x, *y, sweep::point_label(t, r), r.cells[front].text == "yes"});
    }
    body += html::scatter(std::string(p.what) + " and " + p.x_label, p.x_label, p.y_label, pts);
  }
  std::vector<std::string> head;
  for (const sweep::Column& c : t.columns) head.push_back(c.unit.empty() ? c.name : c.name + " (" + c.unit + ")");
  std::vector<std::vector<std::string>> rows;
  for (const sweep::Row& r : t.rows) {
    std::vector<std::string> cells;
    for (const sweep::Cell& c : r.cells)
      cells.push_back(c.kind == sweep::Cell::Kind::Number ? fixed_text(c.number, 3)
                      : c.kind == sweep::Cell::Kind::Text ? c.text
                                                          : "n/a");
    rows.push_back(cells);
  }
  body += "<h2>Points</h2>\n" + html::table(head, rows);
  return html::page("voxcast sweep: " + fs::path(t.meta.value("scene", std::string("sweep")))
                                            .filename()
                                            .string(),
                    body);
}

}  // namespace voxcast::cosim
