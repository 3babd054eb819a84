// voxcast: the command-line tool. Each subcommand is a thin shell over a
// function in cosim/commands.hpp; every failure is one line on stderr and a
// non-zero exit code.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cosim/commands.hpp"
#include "cosim/bench.hpp"
#include "cosim/constraints.hpp"
#include "cosim/synth_script.hpp"
#include "cosim/cosim.hpp"
#include "cosim/flythrough.hpp"
#include "cosim/paper.hpp"
#include "cosim/regress.hpp"
#include "cosim/scene_fuzz.hpp"
#include "cosim/report.hpp"
#include "cosim/sweep.hpp"
#include "cosim/tune.hpp"
#include "refmodel/error.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/board/board.hpp"

namespace {

using voxcast::ref::Overrides;

// The exit statuses (README, "Exit status"): 0 success; 1 an error in the
// input (a scene, a volume, an option's value); 2 an internal error; 3 the
// engines differ; 4 regress / constraints: golden files differ; 5 tune: no point meets the target; 6 --strict: precision
// hazards; 7 fuzz-scenes: findings; 64 a malformed command line (EX_USAGE).
constexpr int kUsageError = 64;

// "unknown subcommand 'renderr'; did you mean 'render'?" when the first word
// is no subcommand (empty when it is one, or an option).
std::string unknown_subcommand(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return "";
  const std::string word = argv[1];
  std::string nearest;
  std::size_t best = std::string::npos;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (sub->get_name() == word) return "";
    const std::size_t d = voxcast::ref::edit_distance(word, sub->get_name());
    if (d < best) best = d, nearest = sub->get_name();
  }
  std::string msg = "unknown subcommand '" + word + "'";
  if (best <= std::max<std::size_t>(2, word.size() / 3)) msg += "; did you mean '" + nearest + "'?";
  return msg + " (voxcast --help lists the subcommands)";
}

// A command-line error as every other error: one line naming what is wrong,
// and where help is.
int usage_error(const CLI::App& app, const CLI::ParseError& e) {
  std::string where = "voxcast";
  for (const CLI::App* sub : app.get_subcommands()) where += " " + sub->get_name();
  std::string what = e.what();
  std::replace(what.begin(), what.end(), '\n', ' ');
  while (!what.empty() && what.back() == ' ') what.pop_back();
  std::cerr << "voxcast: " << what << " (" << where << " --help)\n";
  return kUsageError;
}

// A finite number above 0 (CLI::Range lets NaN through: it compares).
const CLI::Validator kPositiveFinite(
    [](std::string& text) -> std::string {
      try {
        std::size_t used = 0;
        const double v = std::stod(text, &used);
        if (used == text.size() && std::isfinite(v) && v > 0.0) return "";
      } catch (const std::exception&) {
      }
      return "must be a finite number above 0, not '" + text + "'";
    },
    "NUMBER > 0");

void add_set_option(CLI::App& cmd, Overrides& overrides) {
  cmd.add_option("--set", overrides,
                 "Override a scene key, e.g. --set render.oversampling=4 (repeatable)")
      ->take_all()
      ->allow_extra_args(false);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"voxcast: VIRIM and VIZARD II hardware volume renderers — reference model, "
               "fixed-point design and cycle model"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "voxcast 0.1.0");

  // render SCENE -o OUT
  std::string scene_path;
  Overrides render_sets;
  voxcast::cosim::RenderOptions render_opts;
  CLI::App* render = app.add_subcommand("render", "Render a scene file with the reference ray caster");
  render->add_option("scene", scene_path, "Scene file (TOML, see docs/scenes.md)")->required();
  render->add_option("-o,--output", render_opts.outputs, "Output image(s): .png and/or .exr")
      ->required();
  render->add_option("--report", render_opts.report_json, "Write a JSON report here");
  std::string engine_name = "ref";
  render->add_flag("--strict", render_opts.strict,
                   "Refuse a scene with precision hazards (exit status 6) instead of warning");
  render->add_option("--engine", engine_name,
                     "ref (double), bittrue (bit-true reference), hls, or rtl (cycle model)")
      ->capture_default_str();
  render->add_option("--vcd", render_opts.vcd_path,
                     "rtl engine: write a VCD trace (FIFO handshakes, SDRAM commands) of each frame "
                     "(a stereo pair or path: one file per view, named like the images)");
  render->add_option("--vcd-window", render_opts.vcd_window,
                     "rtl engine: cycles START:END (inclusive) the VCD covers");
  add_set_option(*render, render_sets);

  // cosim SCENE --out DIR
  std::string cosim_scene, cosim_out;
  Overrides cosim_sets;
  CLI::App* cosim = app.add_subcommand(
      "cosim", "Run float, bit-true and hls engines; prove hls == bit-true; measure the error");
  cosim->add_option("scene", cosim_scene, "Scene file (TOML)")->required();
  cosim->add_option("--out", cosim_out, "Output folder (report.json, layers.exr, PNGs)")->required();
  add_set_option(*cosim, cosim_sets);
  voxcast::cosim::TruthSettings cosim_truth;
  bool cosim_strict = false;
  cosim->add_flag("--strict", cosim_strict,
                  "Refuse a scene with precision hazards (exit status 6) instead of warning");
  cosim->add_option("--truth-oversampling", cosim_truth.oversampling,
                    "Oversampling of the truth (the float reference) for report.json's truth section")
      ->capture_default_str();

  // sweep SCENE --vary KEY=V1,V2,... --out DIR ; sweep-merge DIR... --out DIR (docs/sweep.md)
  std::string sweep_scene, sweep_shard = "0/1";
  std::vector<std::string> sweep_vary;
  Overrides sweep_sets;
  voxcast::cosim::TruthSettings sweep_truth;
  voxcast::cosim::sweep::SweepOptions sweep_opts;
  bool sweep_no_plots = false;
  CLI::App* sweep = app.add_subcommand(
      "sweep", "Accuracy against the truth and modelled speed over a product of scene settings");
  sweep->add_option("scene", sweep_scene, "Scene file (TOML)")->required();
  sweep->add_option("--vary", sweep_vary,
                    "KEY=V1,V2,... or KEY=A..B (integers); repeat for a product")
      ->take_all()
      ->allow_extra_args(false)
      ->required();
  sweep->add_option("--out", sweep_opts.out_dir, "Output folder (results.csv, results.json, plots)")
      ->required();
  sweep->add_option("--jobs", sweep_opts.jobs, "Points in parallel")->capture_default_str();
  sweep->add_option("--shard", sweep_shard, "Compute only the points with index % n == i (i/n)")
      ->capture_default_str();
  sweep->add_flag("--progress", sweep_opts.progress, "Progress on stderr even when not a TTY");
  sweep->add_flag("--no-plots", sweep_no_plots, "Do not run gnuplot");
  std::string sweep_part = "xc7a200t";
  sweep->add_option("--part", sweep_part, "Part of the resource columns (voxcast report's parts)")
      ->capture_default_str();
  sweep->add_option("--truth-oversampling", sweep_truth.oversampling,
                    "Oversampling of the truth (the float reference)")
      ->capture_default_str();
  add_set_option(*sweep, sweep_sets);
  std::vector<std::string> merge_dirs;
  std::string merge_out;
  bool merge_no_plots = false;
  CLI::App* sweep_merge = app.add_subcommand(
      "sweep-merge", "Join the outputs of sweep --shard i/n runs into the single run's results");
  sweep_merge->add_option("dirs", merge_dirs, "Output folders of the shards")->required();
  sweep_merge->add_option("--out", merge_out, "Output folder")->required();
  sweep_merge->add_flag("--no-plots", merge_no_plots, "Do not run gnuplot");

  // regress
  voxcast::cosim::RegressOptions regress_opts{"scenes", "tests/golden/regress",
                                              {"vizard2", "balanced", "precise"}, false, {}};
  CLI::App* regress = app.add_subcommand(
      "regress", "Bit-accuracy regression: every scene x preset, hls == bit-true == golden hash");
  regress->add_option("--scenes", regress_opts.scenes_dir, "Folder of scenes")->capture_default_str();
  regress->add_option("--golden", regress_opts.golden_dir, "Folder of golden files")
      ->capture_default_str();
  regress->add_option("--profiles", regress_opts.profiles, "Presets to run")->delimiter(',');
  regress->add_flag("--bless", regress_opts.bless,
                    "Measure accuracy against the float reference and (re)write the golden files "
                    "of the cases that meet their floor");
  add_set_option(*regress, regress_opts.overrides);

  // paper vizard2 --out DIR
  std::string paper_name;
  voxcast::cosim::paper::Vizard2Options paper_opts;
  CLI::App* paper = app.add_subcommand(
      "paper", "Reproduce a paper's experiment as a Markdown report (vizard2: oversampling)");
  paper->add_option("experiment", paper_name, "vizard2")->required();
  paper->add_option("--out", paper_opts.out_dir, "Output folder (report.md, results.json, images)")
      ->required();
  paper->add_option("--size", paper_opts.image_size, "Image width and height in pixels")
      ->capture_default_str();
  paper->add_option("--volume-size", paper_opts.volume_size, "Tube phantom voxels per side")
      ->capture_default_str();
  paper->add_option("--profile", paper_opts.profile, "Precision preset of the card")
      ->capture_default_str();
  paper->add_option("--truth-oversampling", paper_opts.truth.oversampling,
                    "Oversampling of the truth (the float reference)")
      ->capture_default_str();

  // bench SCENE
  std::string bench_scene;
  std::vector<std::string> bench_engines{"ref", "bittrue", "hls", "rtl"};
  int bench_repeats = 5;
  Overrides bench_sets;
  CLI::App* bench = app.add_subcommand(
      "bench", "Measure samples per second of the engines on one scene (median of repeats)");
  bench->add_option("scene", bench_scene, "Scene file (TOML)")->required();
  bench->add_option("--engines", bench_engines, "Engines to time")->delimiter(',')
      ->capture_default_str();
  bench->add_option("--repeat", bench_repeats, "Timed frames per engine")->capture_default_str();
  add_set_option(*bench, bench_sets);

  // flythrough SCENE --out DIR
  std::string fly_scene;
  voxcast::cosim::FlythroughOptions fly_opts;
  Overrides fly_sets;
  CLI::App* fly = app.add_subcommand(
      "flythrough",
      "Fly along the scene's camera.path on the cycle model: frames, GIF, modelled frames/s");
  fly->add_option("scene", fly_scene, "Scene file with a camera.path (TOML)")->required();
  fly->add_option("--out", fly_opts.out_dir, "Output folder")->required();
  fly->add_option("--frames", fly_opts.frames,
                  "Frames along the path (default: render.frames if > 1, else 24)");
  fly->add_option("--gif-fps", fly_opts.animation_fps, "Playback rate of the GIF (1..100)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  fly->add_option("--truth-oversampling", fly_opts.truth_oversampling,
                  "Oversampling of the truth the temporal stability is measured against "
                  "(0: no truth, the rendered frame-to-frame change only)")
      ->capture_default_str();
  add_set_option(*fly, fly_sets);

  // demo
  Overrides demo_sets;
  std::string demo_out = "out/demo";
  CLI::App* demo = app.add_subcommand("demo", "Render the embedded default scene (no file needed)");
  demo->add_option("-o,--output", demo_out,
                   "Output path without extension; writes OUT.png, OUT.exr and OUT.json")
      ->capture_default_str();
  add_set_option(*demo, demo_sets);

  // constraints BOARD --format xdc|sdc --out FILE   (or --golden DIR [--bless])
  std::string constraints_board, constraints_format = "xdc", constraints_out, constraints_golden;
  bool constraints_bless = false;
  CLI::App* constraints = app.add_subcommand(
      "constraints", "Write the timing constraints (Vivado XDC or SDC) of a board description");
  constraints->add_option("board", constraints_board,
                          "Shipped board name (vizard2_pci, alveo_u250) or a board .toml");
  constraints->add_option("--format", constraints_format, "xdc or sdc")->capture_default_str();
  constraints->add_option("--out", constraints_out, "Output file");
  constraints->add_option("--golden", constraints_golden,
                          "Compare every shipped board's constraints with the golden files here");
  constraints->add_flag("--bless", constraints_bless, "With --golden: rewrite the golden files");

  // synth-script SCENE --board BOARD --tool vitis --out DIR
  std::string synth_scene, synth_board = "vizard2_pci", synth_tool = "vitis", synth_out,
                           synth_root = voxcast::cosim::default_source_root();
  Overrides synth_sets;
  CLI::App* synth = app.add_subcommand(
      "synth-script", "Write a vendor HLS script per top-level kernel for a scene and a board");
  synth->add_option("scene", synth_scene, "Scene file (TOML): its precision profile")->required();
  synth->add_option("--board", synth_board, "Shipped board name or a board .toml")
      ->capture_default_str();
  synth->add_option("--tool", synth_tool, "vitis (Vitis HLS Tcl)")->capture_default_str();
  synth->add_option("--out", synth_out, "Output folder")->required();
  synth->add_option("--source-dir", synth_root, "The voxcast source tree the scripts name")
      ->capture_default_str();
  add_set_option(*synth, synth_sets);
  // report SCENE [--part NAME] [--json FILE] [--md FILE]
  std::string report_scene, report_part = "xc7a200t", report_json_path, report_md_path;
  Overrides report_sets;
  CLI::App* report = app.add_subcommand(
      "report", "Operators per unit, FPGA resources and latency of the design the scene needs");
  report->add_option("scene", report_scene, "Scene file (TOML)")->required();
  report->add_option("--part", report_part, "xcv1000e, xc2v3000, xc7a200t or xc7k325t")
      ->capture_default_str();
  report->add_option("--json", report_json_path, "Write the report as JSON here");
  report->add_option("--md", report_md_path, "Write the report as Markdown here (default: stdout)");
  add_set_option(*report, report_sets);

  // fuzz-scenes --seed S --scenes N [--size PX] [--out DIR]
  voxcast::cosim::SceneFuzzOptions fuzz_opts;
  CLI::App* fuzz_scenes = app.add_subcommand(
      "fuzz-scenes", "Random valid scenes through float, bit-true and hls: engines must agree, and "
                     "the error must stay within the precision guard's bound (exit 7 on findings)");
  fuzz_scenes->add_option("--seed", fuzz_opts.seed, "Seed of the scene stream")->capture_default_str();
  fuzz_scenes->add_option("--scenes", fuzz_opts.scenes, "Scenes to run")->capture_default_str();
  fuzz_scenes->add_option("--size", fuzz_opts.image_size, "Image width and height in pixels")
      ->capture_default_str();
  fuzz_scenes->add_option("--out", fuzz_opts.out_dir, "Folder for the findings' scene files");

  // tune SCENE --target-psnr DB
  std::string tune_scene;
  std::vector<std::string> tune_vary;
  voxcast::cosim::TuneOptions tune_opts;
  Overrides tune_sets;
  CLI::App* tune = app.add_subcommand(
      "tune", "Cheapest precision widths (resource model) meeting a PSNR target (bit-true engine)");
  tune->add_option("scene", tune_scene, "Scene file (TOML)")->required();
  tune->add_option("--target-psnr", tune_opts.target_psnr_db, "Target PSNR in dB against the "
                   "truth (exit status 5 when no point meets it)")
      ->required()
      ->check(kPositiveFinite);
  tune->add_option("--truth-oversampling", tune_opts.truth.oversampling,
                   "Oversampling of the truth (the float reference)")
      ->capture_default_str();
  tune->add_option("--part", tune_opts.part, "Part whose capacity prices the resources")
      ->capture_default_str();
  tune->add_option("--vary", tune_vary, "Search axis FIELD=LO..HI (repeatable; default: "
                   "docs/resources.md)");
  tune->add_flag("--prune", tune_opts.prune,
                 "Skip points below per-axis floors (assumes accuracy monotone in each width; "
                 "the answer may then not be the cheapest)");
  add_set_option(*tune, tune_sets);

  if (const std::string word = unknown_subcommand(app, argc, argv); !word.empty()) {
    std::cerr << "voxcast: " << word << "\n";
    return kUsageError;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --help-all, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return usage_error(app, e);
  }

  try {
    if (*render) {
      const auto scene = voxcast::ref::load_scene_file(scene_path, render_sets);
      render_opts.engine = voxcast::cosim::parse_engine(engine_name);
      const auto summary = voxcast::cosim::run_render(scene, render_opts);
      voxcast::cosim::print_summary(std::cout, scene, summary);
    } else if (*cosim) {
      const auto scene = voxcast::ref::load_scene_file(cosim_scene, cosim_sets);
      const auto r = voxcast::cosim::run_cosim(scene, cosim_out, cosim_truth, cosim_strict);
      voxcast::cosim::print_cosim_summary(std::cout, scene, r);
      if (!r.bit_exact) {
        std::cerr << "voxcast: " << r.mismatch.engine << " differs from "
                  << (r.mismatch.engine == "rtl" ? "hls" : "bit-true") << " at pixel ("
                  << r.mismatch.x << ", " << r.mismatch.y << "), sample " << r.mismatch.sample
                  << ", first in the " << voxcast::bittrue::to_string(r.mismatch.unit)
                  << "; reproducer " << r.mismatch.reproducer << "\n";
        return 3;
      }
    } else if (*sweep) {
      namespace sw = voxcast::cosim::sweep;
      sweep_opts.shard = sw::parse_shard(sweep_shard);
      sweep_opts.plots = !sweep_no_plots;
      sw::Plan plan = sw::make_plan(sweep_scene, sweep_sets, sweep_vary, sweep_truth);
      plan.part = sweep_part;
      sw::print_sweep_summary(std::cout, sw::run_sweep(plan, sweep_opts));
    } else if (*sweep_merge) {
      namespace sw = voxcast::cosim::sweep;
      sw::print_sweep_summary(std::cout, sw::run_sweep_merge(merge_dirs, merge_out, !merge_no_plots));
    } else if (*paper) {
      if (paper_name != "vizard2")
        throw voxcast::Error("paper: unknown experiment \"" + paper_name + "\" (vizard2)");
      voxcast::cosim::paper::print_vizard2_summary(
          std::cout, voxcast::cosim::paper::run_vizard2(paper_opts));
    } else if (*bench) {
      const auto scene = voxcast::ref::load_scene_file(bench_scene, bench_sets);
      voxcast::cosim::print_bench(std::cout, scene,
                                  voxcast::cosim::run_bench(scene, bench_engines, bench_repeats));
    } else if (*fly) {
      const auto scene = voxcast::ref::load_scene_file(fly_scene, fly_sets);
      voxcast::cosim::print_flythrough(std::cout, scene,
                                       voxcast::cosim::run_flythrough(scene, fly_opts));
    } else if (*regress) {
      const int failed = voxcast::cosim::run_regress(regress_opts, std::cout);
      if (failed > 0) {
        std::cerr << "voxcast: regress: " << failed << " case(s) failed\n";
        return 4;
      }
    } else if (*constraints) {
      if (!constraints_golden.empty()) {
        const int differ = voxcast::cosim::check_constraint_goldens(constraints_golden,
                                                                    constraints_bless, std::cout);
        if (differ > 0) {
          std::cerr << "voxcast: constraints: " << differ << " golden file(s) differ\n";
          return 4;
        }
      } else {
        if (constraints_board.empty() || constraints_out.empty())
          throw voxcast::Error("constraints: give BOARD and --out FILE (or --golden DIR)");
        const auto board = voxcast::rtl::board::load_board(constraints_board);
        const auto format = voxcast::cosim::parse_constraint_format(constraints_format);
        voxcast::cosim::write_text_file(constraints_out,
                                        voxcast::cosim::generate_constraints(board, format));
        std::cout << "wrote " << constraints_out << " (" << board << ")\n";
      }
    } else if (*synth) {
      const auto scene = voxcast::ref::load_scene_file(synth_scene, synth_sets);
      const auto board = voxcast::rtl::board::load_board(synth_board);
      for (const auto& path : voxcast::cosim::write_synth_scripts(scene, synth_scene, board,
                                                                  synth_tool, synth_out, synth_root))
        std::cout << "wrote " << path << "\n";
    } else if (*report) {
      const auto scene = voxcast::ref::load_scene_file(report_scene, report_sets);
      const auto r = voxcast::cosim::estimate_resources(scene,
                                                        voxcast::cosim::find_part(report_part));
      const std::string md = voxcast::cosim::report_markdown(r);
      if (!report_md_path.empty()) {
        voxcast::cosim::write_text_file(report_md_path, md);
      } else {
        std::cout << md;
      }
      if (!report_json_path.empty())
        voxcast::cosim::write_text_file(report_json_path, voxcast::cosim::report_json(r) + "\n");
    } else if (*tune) {
      const auto scene = voxcast::ref::load_scene_file(tune_scene, tune_sets);
      for (const std::string& v : tune_vary)
        tune_opts.axes.push_back(voxcast::cosim::parse_tune_axis(v));
      const auto r = voxcast::cosim::run_tune(scene, tune_opts);
      voxcast::cosim::print_tune(std::cout, scene, tune_opts, r);
      if (!r.found) return 5;
    } else if (*fuzz_scenes) {
      const auto r = voxcast::cosim::run_scene_fuzz(fuzz_opts);
      voxcast::cosim::print_scene_fuzz(std::cout, fuzz_opts, r);
      if (!r.findings.empty()) return 7;
    } else if (*demo) {
      const auto scene = voxcast::ref::default_scene(demo_sets);
      voxcast::cosim::RenderOptions opts{{demo_out + ".png", demo_out + ".exr"}, demo_out + ".json"};
      const auto summary = voxcast::cosim::run_render(scene, opts);
      voxcast::cosim::print_summary(std::cout, scene, summary);
    }
  } catch (const voxcast::cosim::PrecisionHazardError& e) {
    std::cerr << "voxcast: " << e.what() << "\n";
    return 6;
  } catch (const voxcast::Error& e) {
    std::cerr << "voxcast: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "voxcast: internal error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
