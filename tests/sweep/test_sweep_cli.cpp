// `voxcast sweep`, `sweep-merge` and cosim's truth section through the command
// line: the sweep measures what cosim measures, shards merge to the single
// run, bad input is one line.
#include <gtest/gtest.h>

#include "cli.hpp"

namespace VOXCAST_UNITY_ID {

using namespace sweep_test;
namespace fs = std::filesystem;

// The row of results.json whose varied values are `values`.
const nlohmann::json& row_with(const nlohmann::json& results, const std::vector<std::string>& keys,
                               const std::vector<std::string>& values) {
  for (const auto& r : results.at("rows")) {
    bool match = true;
    for (std::size_t k = 0; k < keys.size(); ++k)
      match = match && r.at("cells").at(keys[k]) == values[k];
    if (match) return r;
  }
  throw std::runtime_error("no such row");
}

TEST(CosimTruth, ReportHasTheTruthSection) {
  const auto d = temp_dir("cosim_truth");
  const Command r =
      run("cosim " + tiny_scene() + " --out " + d.string() + " --truth-oversampling 8");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = json_of(d / "report.json");
  const nlohmann::json& t = j.at("truth");
  for (const char* k : {"psnr_db", "max_abs_err_lsb", "pct_within_1lsb", "ssim", "rms_err_lsb"})
    EXPECT_TRUE(t.at(k).is_number()) << k;
  EXPECT_EQ(t.at("oversampling"), 8.0);
  EXPECT_EQ(t.at("engine"), "hls");
  // The existing keys (error against the float reference at the same settings) stay.
  EXPECT_TRUE(j.at("psnr_db").is_number());
  EXPECT_TRUE(fs::exists(d / "truth.png"));
  EXPECT_LE(t.at("ssim").get<double>(), 1.0);
}

// The sweep's accuracy and speed figures are cosim's for the same point, for a
// compiled preset (hls, rtl) and for a profile only bit-true runs.
TEST(Sweep, AccuracyFiguresEqualCosimsForTheSamePoint) {
  const auto d = temp_dir("equal");
  const Command s = run("sweep " + tiny_scene() + " --out " + (d / "sweep").string() +
                        " --vary precision.profile=vizard2,balanced --vary "
                        "precision.weight_bits=6,7 --no-plots --jobs 2");
  ASSERT_EQ(s.status, 0) << s.output;
  const nlohmann::json results = json_of(d / "sweep" / "results.json");
  struct Point {
    const char* profile;
    const char* weight_bits;
    const char* engine;
  };
  for (const Point& p : {Point{"vizard2", "6", "hls"}, Point{"balanced", "7", "bittrue"}}) {
    const fs::path out = d / (std::string(p.profile) + p.weight_bits);
    const Command c = run("cosim " + tiny_scene() + " --out " + out.string() +
                          " --set precision.profile=" + p.profile +
                          " --set precision.weight_bits=" + p.weight_bits);
    // A profile the hls kernels are not compiled for: the bit-true engine
    // measures it, and cosim says not every engine ran (exit status 8).
    ASSERT_EQ(c.status, std::string(p.engine) == "hls" ? 0 : 8) << c.output;
    const nlohmann::json truth = json_of(out / "report.json").at("truth");
    const nlohmann::json& row = row_with(results, {"precision.profile", "precision.weight_bits"},
                                         {p.profile, p.weight_bits})
                                    .at("cells");
    EXPECT_EQ(row.at("engine"), p.engine);
    EXPECT_EQ(truth.at("engine"), p.engine);
    EXPECT_EQ(row.at("psnr_db"), truth.at("psnr_db"));
    EXPECT_EQ(row.at("max_err_lsb"), truth.at("max_abs_err_lsb"));
    EXPECT_EQ(row.at("mean_err_lsb"), truth.at("mean_abs_err_lsb"));
    EXPECT_EQ(row.at("rms_err_lsb"), truth.at("rms_err_lsb"));
    EXPECT_EQ(row.at("pct_within_1lsb"), truth.at("pct_within_1lsb"));
    EXPECT_EQ(row.at("ssim"), truth.at("ssim"));
    if (std::string(p.engine) == "hls") {
      const nlohmann::json report = json_of(out / "report.json");
      EXPECT_EQ(row.at("rtl_fps"), report.at("fps"));
      EXPECT_EQ(row.at("rtl_ns_per_sample"), report.at("ns_per_sample"));
      EXPECT_EQ(row.at("rtl_cycles").get<double>(), report.at("cycles").get<double>());
    }
  }
  // A profile the rtl engine does not run: not available, with the reason.
  const nlohmann::json& bt =
      row_with(results, {"precision.profile", "precision.weight_bits"}, {"balanced", "7"});
  EXPECT_TRUE(bt.at("cells").at("rtl_fps").is_null());
  EXPECT_NE(bt.at("not_available").at("rtl_fps").get<std::string>().find("compiled presets"),
            std::string::npos);
  // One truth image for the whole sweep: precision is not truth-relevant.
  EXPECT_NE(s.output.find("(1 truth image rendered)"), std::string::npos) << s.output;
}

TEST(Sweep, ShardsMergedEqualASingleRun) {
  const auto d = temp_dir("shards");
  const std::string args = "sweep " + tiny_scene() +
                           " --vary render.oversampling=1,2 --vary precision.profile=vizard2,"
                           "balanced --vary render.ert_threshold=0.9,1 --no-plots";
  ASSERT_EQ(run(args + " --jobs 2 --out " + (d / "single").string()).status, 0);
  for (const char* i : {"0", "1", "2"}) {
    const fs::path out = d / (std::string("s") + i);
    const Command r = run(args + " --shard " + i + "/3 --out " + out.string());
    ASSERT_EQ(r.status, 0) << r.output;
  }
  const std::string shards =
      (d / "s2").string() + " " + (d / "s0").string() + " " + (d / "s1").string();
  const Command m = run("sweep-merge " + shards + " --no-plots --out " + (d / "merged").string());
  ASSERT_EQ(m.status, 0) << m.output;
  for (const char* f : {"results.csv", "results.json"}) {
    const std::string single = text_of(d / "single" / f);
    EXPECT_FALSE(single.empty());
    EXPECT_EQ(text_of(d / "merged" / f), single) << f;
  }
  // The Pareto front is marked over all points, not per shard.
  const nlohmann::json merged = json_of(d / "merged" / "results.json");
  int on_front = 0;
  for (const auto& r : merged.at("rows")) on_front += r.at("cells").at("pareto_psnr_fps") == "yes";
  EXPECT_GE(on_front, 1);
  // A missing or repeated shard is a one-line error.
  for (const std::string& bad : {(d / "s0").string() + " " + (d / "s1").string(),
                                 (d / "s0").string() + " " + (d / "s0").string() + " " +
                                     (d / "s1").string() + " " + (d / "s2").string()}) {
    const Command r = run("sweep-merge " + bad + " --out " + (d / "bad").string());
    EXPECT_EQ(r.status, 1) << r.output;
    EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << r.output;
  }
}

TEST(Sweep, BadVaryAndUnknownKeysAreOneLineErrors) {
  const auto d = temp_dir("bad");
  const std::string base = "sweep " + tiny_scene() + " --out " + d.string() + " ";
  const struct {
    std::string args, message;
  } cases[] = {
      {"--vary precision.wieght_bits=3",
       "voxcast: --vary precision.wieght_bits=3: unknown key precision.wieght_bits (did you mean "
       "precision.weight_bits?)\n"},
      {"--vary precision.weight_bits=8..3",
       "voxcast: --vary precision.weight_bits=8..3: range 8..3 is empty (A > B)\n"},
      {"--vary render.oversampling=1,2 --shard 2/2", "voxcast: --shard 2/2: i must be in [0, 1]"},
      {"--vary render.oversampling=1 --truth-oversampling 100",
       "voxcast: truth oversampling 100 is outside [1, 64]\n"},
  };
  for (const auto& c : cases) {
    const Command r = run(base + c.args);
    EXPECT_EQ(r.status, 1) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "not one line: " << r.output;
  }
}

// A width that cannot hold the volume makes its point infeasible, with the
// reason; the other points run. Progress goes to stderr when asked; the plots
// are drawn when gnuplot is there.
TEST(Sweep, InfeasiblePointsProgressAndPlots) {
  const auto d = temp_dir("infeasible");
  const Command r = run("sweep " + tiny_scene() + " --set precision.profile=vizard2 --progress " +
                        "--vary precision.value_bits=4,8 " +
                        "--vary render.oversampling=1,2 --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("sweep [##############################] 4/4 100%"), std::string::npos)
      << r.output;
  const nlohmann::json j = json_of(d / "results.json");
  ASSERT_EQ(j.at("rows").size(), 4u);
  const auto& bad = j.at("rows")[0];
  EXPECT_NE(bad.at("cells").at("status").get<std::string>().find(
                "infeasible: precision.value_bits = 4 cannot hold"),
            std::string::npos);
  EXPECT_TRUE(bad.at("cells").at("psnr_db").is_null());
  EXPECT_EQ(j.at("rows")[2].at("cells").at("status"), "ok");
  const std::string csv = text_of(d / "results.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "precision.value_bits,render.oversampling,status,engine,psnr_db,max_err_lsb,"
            "mean_err_lsb,rms_err_lsb,pct_within_1lsb,ssim,hazards,hazard_worst_lsb,hazard_keys,"
            "rtl_fps,rtl_ns_per_sample,rtl_cycles,"
            "part,luts,ffs,dsps,brams,urams,part_pct,part_max_pct,pareto_psnr_fps,"
            "pareto_psnr_resources,pareto_fps_resources,notes");
  if (std::system("command -v gnuplot > /dev/null 2>&1") == 0) {
    for (const char* f : {"psnr_vs_fps.png", "psnr_vs_fps.svg", "psnr_vs_render_oversampling.png",
                          "psnr_vs_render_oversampling.svg"})
      EXPECT_GT(fs::file_size(d / f), 1000u) << f;
  }
}

// Without gnuplot the results are written all the same and one warning says
// the plots were skipped.
TEST(Sweep, WithoutGnuplotThePlotsAreSkippedWithAWarning) {
  const auto d = temp_dir("no_gnuplot");
  const Command r = run("sweep " + tiny_scene() + " --set precision.profile=vizard2 " +
                            "--vary render.oversampling=1 --out " + d.string(),
                        "env PATH=/nonexistent");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("voxcast: warning: gnuplot is not installed (Debian: gnuplot-nox): "
                          "plots skipped"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(d / "results.csv"));
  EXPECT_TRUE(fs::exists(d / "plots.gp"));
  EXPECT_FALSE(fs::exists(d / "psnr_vs_fps.png"));
}

}  // namespace

namespace VOXCAST_UNITY_ID {

// --part chooses the part of the resource columns: every point's LUT, FF, DSP
// and RAM figures are `voxcast report`'s totals for that part and part_pct is
// report's cost (the sum of the four shares of the part's capacity, in %);
// the CSV's part column and results.json's sweep.part name it. An unknown
// part is one line listing the known ones.
TEST(Sweep, PartSelectsTheResourceColumnsPart) {
  const auto d = temp_dir("part");
  for (const char* part : {"xc2v3000", "xc7k325t"}) {
    const fs::path out = d / part;
    const Command s = run("sweep " + tiny_scene() + " --set precision.profile=vizard2 --vary " +
                          "precision.weight_bits=6 --no-plots --part " + part + " --out " +
                          out.string());
    ASSERT_EQ(s.status, 0) << s.output;
    const nlohmann::json results = json_of(out / "results.json");
    EXPECT_EQ(results.at("sweep").at("part"), part);
    for (const auto& row : results.at("rows")) {
      const nlohmann::json& c = row.at("cells");
      EXPECT_EQ(c.at("part"), part);
      const Command r = run("report " + tiny_scene() + " --set precision.profile=vizard2 " +
                            "--set precision.weight_bits=" +
                            c.at("precision.weight_bits").get<std::string>() + " --part " + part +
                            " --json " + (out / "report.json").string());
      ASSERT_EQ(r.status, 0) << r.output;
      const nlohmann::json rep = json_of(out / "report.json");
      const nlohmann::json& total = rep.at("total");
      const nlohmann::json& cap = rep.at("part");
      EXPECT_EQ(c.at("luts"), total.at("lut"));
      EXPECT_EQ(c.at("ffs"), total.at("ff"));
      EXPECT_EQ(c.at("dsps"), total.at("dsp"));
      EXPECT_EQ(c.at("brams"), total.at("bram"));
      double share = 0.0;
      for (const char* k : {"lut", "ff", "dsp", "bram"})
        if (cap.at(k).get<double>() > 0)
          share += total.at(k).get<double>() / cap.at(k).get<double>();
      EXPECT_NEAR(c.at("part_pct").get<double>(), 100.0 * share, 1e-9);
    }
    const std::string csv = text_of(out / "results.csv");
    const std::string second = csv.substr(csv.find('\n') + 1);
    EXPECT_NE(second.find(std::string(",") + part + ","), std::string::npos) << csv;
  }
  // Virtex-II counts 4-input LUTs and MULT18X18s, 7-series 6-input LUTs and
  // DSP48E1s: the part changes the resource figures, not only the share.
  const nlohmann::json v2 = json_of(d / "xc2v3000" / "results.json");
  const nlohmann::json k7 = json_of(d / "xc7k325t" / "results.json");
  EXPECT_GT(v2.at("rows")[0].at("cells").at("luts").get<double>(),
            k7.at("rows")[0].at("cells").at("luts").get<double>());
  // Results for different parts are different sweeps: they do not merge.
  const Command merge = run("sweep-merge " + (d / "xc2v3000").string() + " " +
                            (d / "xc7k325t").string() + " --no-plots --out " +
                            (d / "merged").string());
  EXPECT_EQ(merge.status, 1);
  EXPECT_NE(merge.output.find("(scene, --set, --vary, truth or --part differ)"),
            std::string::npos)
      << merge.output;
  const Command bad = run("sweep " + tiny_scene() + " --vary precision.weight_bits=5 --part " +
                          "xc9999 --out " + (d / "bad").string());
  EXPECT_EQ(bad.status, 1);
  EXPECT_EQ(bad.output, "voxcast: sweep: --part: unknown part \"xc9999\" (known: xcv1000e, "
                        "xc2v3000, xc7a200t, xc7k325t, xcu250)\n");
}

}  // namespace
