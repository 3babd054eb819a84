#include "cosim/engines/cosim.hpp"
#include "cosim/reports/files.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cosim/engines/engines.hpp"
#include "cosim/engines/heidelberg.hpp"
#include "cosim/reports/image_io.hpp"
#include "cosim/engines/warnings.hpp"
#include "cosim/reports/stopwatch.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "refmodel/volume/loaders.hpp"
#include "cosim/reports/rtl_json.hpp"
#include "rtl_model/layout/address_mapping.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/scene_config.hpp"

namespace voxcast::cosim {
namespace {

// Signed difference hls - float, per channel, in [−1, 1] of full scale.
ref::Image difference(const ref::Image& a, const ref::Image& b) {
  ref::Image d(a.width, a.height);
  for (std::size_t i = 0; i < d.pixels.size(); ++i) d.pixels[i] = a.pixels[i] - b.pixels[i];
  return d;
}

}  // namespace

void write_cosim_images(const std::string& out_dir, const ref::Scene& scene,
                        const ref::Image& float_image, const ref::QuantImage& bittrue_image,
                        const ref::QuantImage& hls_image, bool hls_ran,
                        const ref::Image* truth_image, std::vector<std::string>& written) {
  const auto path = [&](const char* name) { return (std::filesystem::path(out_dir) / name).string(); };
  const ref::Image hls_img = hls_image.to_image();
  const ref::Image diff = difference(hls_img, float_image);
  write_exr_layers(path("layers.exr"), {{"float", &float_image}, {"hls", &hls_img}, {"diff", &diff}});
  write_image(path("float.png"), float_image, scene.render.background);
  if (hls_ran) write_image(path("hls.png"), hls_img, scene.render.background);
  write_image(path("bittrue.png"), bittrue_image.to_image(), scene.render.background);
  write_image(path("diff.png"), error_heat_map(hls_image, float_image, 4.0), glm::dvec3(0.0));
  if (truth_image) write_image(path("truth.png"), *truth_image, scene.render.background);
  for (const char* f : {"layers.exr", "float.png", "hls.png", "bittrue.png", "diff.png", "truth.png"})
    if ((hls_ran || std::string(f) != "hls.png") && (truth_image || std::string(f) != "truth.png"))
      written.push_back(path(f));
}

bool first_difference(const ref::QuantImage& a, const ref::QuantImage& b, int& x, int& y) {
  for (y = 0; y < a.height; ++y)
    for (x = 0; x < a.width; ++x)
      if (a.at(x, y) != b.at(x, y)) return true;
  return false;
}

namespace {

// A scene that reproduces a mismatch: the scene as run, with a comment naming
// the pixel, sample and unit. tests/regress/ holds the ones worth keeping.
std::string write_reproducer(const std::string& dir, const ref::Scene& scene, const Mismatch& m) {
  const std::string path = (std::filesystem::path(dir) / "reproducer.toml").string();
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot write the reproducer");
  out << "# voxcast cosim reproducer: hls and bit-true differ at pixel (" << m.x << ", " << m.y
      << "), sample " << m.sample << ", first in the " << bittrue::to_string(m.unit) << ".\n"
      << "# Run: voxcast cosim " << path << " --out DIR\n"
      << ref::scene_to_toml(scene);
  return path;
}

}  // namespace

CosimResult run_cosim(const ref::Scene& scene, const std::string& out_dir,
                      const TruthSettings& truth_settings, bool strict) {
  if (scene.algorithm == ref::Algorithm::Heidelberg) return run_cosim_heidelberg(scene, out_dir, strict);
  CosimResult r;
  r.truth = truth_settings;
  check_truth_settings(truth_settings, scene);
  make_output_dir(out_dir);
  const SceneVolume sv = load_scene_volume(scene);
  // A profile the hls engine is not compiled for is still measured, through
  // the bit-true engine (which takes any profile at run time); bit-exactness
  // is then not established and the report says so.
  r.hls_ran = hls_supports(scene.precision);
  check_fixed_point(scene, sv, false);
  r.hazards = precision_hazards(scene, sv.volume);
  report_hazards(r.hazards, strict, std::cerr);
  const ref::Volume& volume = sv.volume;
  const ref::GradientField& gradients = sv.gradients;

  // One frame: the camera pose (a path's first keyframe), mono.
  const ref::CameraPose pose = ref::frame_poses(scene.camera, 1).front();
  const ref::RenderInputs inputs = ref::make_render_inputs(scene, volume, gradients, pose);
  const int threads = scene.render.threads;

  ref::FrameStats fs_float, fs_hls;
  auto t0 = StopwatchClock::now();
  const ref::Image truth = ref::render_image(inputs, threads, &fs_float);
  r.seconds_float = seconds_since(t0);

  const bittrue::FrameSetup setup = bittrue::make_frame_setup(scene.precision, scene, inputs);
  const bittrue::VoxelMemory memory = bittrue::make_voxel_memory(scene.precision, volume, gradients);
  t0 = StopwatchClock::now();
  const ref::QuantImage bt = bittrue::bt_render_image(setup, memory, threads);
  r.seconds_bittrue = seconds_since(t0);
  ref::QuantImage hls = bt;
  if (r.hls_ran) {
    t0 = StopwatchClock::now();
    hls = hls_render_image(setup, memory, threads, &fs_hls);
    r.seconds_hls = seconds_since(t0);
  }
  r.samples_float = fs_float.samples;
  r.samples_hls = fs_hls.samples;

  r.bit_exact = !r.hls_ran || hls.pixels == bt.pixels;
  // The cycle model: the same pixels as hls, and how many cycles they take.
  rtl::RtlResult rtl_result;
  if (!r.hls_ran) {
    r.not_run.push_back({"hls", "the hls kernels are not compiled for profile " +
                                    scene.precision_name + " (" + hls_supported_profiles() + ")"});
    r.not_run.push_back({"rtl", "it runs the hls kernels' profiles only"});
  } else {
    t0 = StopwatchClock::now();
    try {
      rtl_result = rtl::rtl_render(setup, memory, rtl::rtl_config(scene.rtl));
      r.rtl_ran = true;
    } catch (const rtl::layout::CapacityError& e) {
      // The volume is larger than the card's memory: the other engines have
      // no such limit, so their agreement is still proven (issue 22).
      r.not_run.push_back({"rtl", std::string("the volume does not fit the card's memory: ") +
                                      e.what()});
    }
    r.seconds_rtl = seconds_since(t0);
  }
  if (r.rtl_ran) {
    r.rtl_exact = rtl_result.image.pixels == hls.pixels;
    r.rtl_cycles = rtl_result.stats.cycles;
    r.rtl_fps = rtl_result.stats.fps();
    r.rtl_ns_per_sample = rtl_result.stats.ns_per_sample();
    r.rtl_clock_mhz = rtl_result.stats.clock_mhz;
    r.rtl_pipelines = rtl_result.stats.card.pipelines;
    r.bit_exact = r.bit_exact && r.rtl_exact;
  }
  if (!r.bit_exact && !r.rtl_exact && hls.pixels == bt.pixels) {
    // hls agrees with bit-true: the cycle model is the one that differs.
    Mismatch& m = r.mismatch;
    first_difference(rtl_result.image, hls, m.x, m.y);
    m.unit = bittrue::Unit::Output;
    m.engine = "rtl";
    m.reproducer = write_reproducer(out_dir, scene, m);
    r.written.push_back(m.reproducer);
  } else if (!r.bit_exact) {
    Mismatch& m = r.mismatch;
    first_difference(hls, bt, m.x, m.y);
    bittrue::bt_cast_ray(setup, memory, m.x, m.y, &m.bt_trace);
    m.hls_trace = hls_trace_ray(setup, memory, m.x, m.y);
    const bittrue::Divergence d = bittrue::first_divergence(m.hls_trace, m.bt_trace);
    m.sample = d.sample;
    m.unit = d.unit;
    m.reproducer = write_reproducer(out_dir, scene, m);
    r.written.push_back(m.reproducer);
  }
  r.accuracy = measure_accuracy(hls, truth);
  t0 = StopwatchClock::now();
  const ref::Image high = render_truth_with_progress(scene, sv, truth_settings);
  r.seconds_truth = seconds_since(t0);
  r.truth_accuracy = measure_accuracy(hls, high);
  r.truth_histogram = error_histogram(hls, high);

  write_cosim_images(out_dir, scene, truth, bt, hls, r.hls_ran, &high, r.written);
  const auto path = [&](const char* name) { return (std::filesystem::path(out_dir) / name).string(); };

  nlohmann::json j;
  j["scene"] = scene.origin;
  j["bit_exact"] = r.hls_ran ? nlohmann::json(r.bit_exact) : nlohmann::json(nullptr);
  j["engines"] = r.rtl_ran   ? nlohmann::json{"float", "bittrue", "hls", "rtl"}
                 : r.hls_ran ? nlohmann::json{"float", "bittrue", "hls"}
                             : nlohmann::json{"float", "bittrue"};
  if (!r.not_run.empty()) {
    j["not_run"] = nlohmann::json::array();
    for (const EngineNotRun& n : r.not_run)
      j["not_run"].push_back({{"engine", n.engine}, {"reason", n.reason}});
  }
  if (r.rtl_ran) {
    const rtl::RtlStats& st = rtl_result.stats;
    j["rtl_bit_exact"] = r.rtl_exact;
    j["cycles"] = st.cycles;
    j["fps"] = st.fps();
    j["ns_per_sample"] = st.ns_per_sample();
    j["samples"] = st.samples;
    // Up to each ray's end, as `samples` (docs/pipeline.md §9, docs/leaping.md).
    if (st.leaps > 0) j["samples_skipped"] = rtl::frame_stats(st).samples_skipped;
    if (st.issue_bypasses > 0) j["issue_bypasses"] = st.issue_bypasses;  // docs/performance.md §7
    j["row_hit_rate"] = st.row_hit_rate();
    j["stalls"] = {{"issue_no_ray", st.stalls.issue_no_ray},
                   {"issue_buffer_full", st.stalls.issue_buffer_full},
                   {"issue_memory_full", st.stalls.issue_memory_full},
                   {"issue_idle", st.stalls.issue_idle},
                   {"interp_wait_memory", st.stalls.interp_wait_memory},
                   {"interp_blocked", st.stalls.interp_blocked},
                   {"setup_no_slot", st.stalls.setup_no_slot},
                   {"composite_blocked", st.stalls.composite_blocked}};
    j["rtl_config"] = rtl_desc_json(scene.rtl);
    std::ostringstream config;
    config << rtl::rtl_config(scene.rtl);
    j["rtl_description"] = config.str();
  }
  if (!r.hls_ran)
    j["note"] = "the hls engine is not compiled for this profile (" + hls_supported_profiles() +
                "); the accuracy figures are the bit-true engine's";
  j["profile"] = scene.precision_name;
  j["hazards"] = hazards_json(r.hazards);
  j["profile_widths"] = nlohmann::json::object();
  for (const ProfileField& f : profile_fields()) j["profile_widths"][f.name] = scene.precision.*f.member;
  const nlohmann::json acc = accuracy_json(r.accuracy);
  for (auto it = acc.begin(); it != acc.end(); ++it) j[it.key()] = it.value();
  j["diff_heat_map_full_scale_lsb"] = 4.0;
  j["truth"] = accuracy_json(r.truth_accuracy);
  j["truth"]["engine"] = r.hls_ran ? "hls" : "bittrue";
  j["truth"]["reference"] = "float";
  j["truth"]["oversampling"] = truth_settings.oversampling;
  j["truth"]["ert_threshold"] = kTruthErtThreshold;
  if (!r.bit_exact)
    j["mismatch"] = {{"engine", r.mismatch.engine},
                     {"pixel", {r.mismatch.x, r.mismatch.y}},
                     {"sample", r.mismatch.sample},
                     {"unit", bittrue::to_string(r.mismatch.unit)},
                     {"reproducer", r.mismatch.reproducer}};
  j["samples_by_engine"] = {{"float", r.samples_float}, {"hls", r.samples_hls}};
  j["seconds"] = {{"float", r.seconds_float}, {"bittrue", r.seconds_bittrue}, {"hls", r.seconds_hls},
                  {"rtl", r.seconds_rtl}, {"truth", r.seconds_truth}};
  j["image"] = {{"width", scene.render.width}, {"height", scene.render.height},
                {"mode", ref::to_string(scene.render.mode)},
                {"oversampling", scene.render.oversampling}};
  write_json_file(path("report.json"), j);
  r.written.push_back(path("report.json"));
  return r;
}

namespace {
// "none ...", or "N (worst case X LSB): key key ..." (the precision guard, cosim/engines/warnings.hpp).
std::string hazard_summary(const std::vector<Hazard>& hazards) {
  if (hazards.empty()) return "none predicted by the precision guard";
  std::ostringstream os;
  os << hazards.size() << " (worst case " << std::setprecision(3) << largest_worst_lsb(hazards)
     << " LSB): " << hazard_keys(hazards);
  return os.str();
}
}  // namespace

void print_cosim_summary(std::ostream& os, const ref::Scene& scene, const CosimResult& r) {
  if (scene.algorithm == ref::Algorithm::Heidelberg)
    return print_cosim_summary_heidelberg(os, scene, r);
  const Accuracy& a = r.accuracy;
  const auto rate = [](std::uint64_t n, double s) {
    return s > 0 ? static_cast<double>(n) / s / 1e6 : 0.0;
  };
  os << std::fixed << std::setprecision(2);
  os << "scene      " << scene.origin << " (" << scene.render.width << "x" << scene.render.height
     << " " << ref::to_string(scene.render.mode) << ", oversampling " << scene.render.oversampling
     << ")\n"
     << "profile    " << scene.precision_name << "\n"
     << "bit-exact  "
     << (!r.hls_ran    ? "not checked: the hls engine is not compiled for this profile"
         : !r.bit_exact ? "NO"
         : r.rtl_ran    ? "yes: hls == bit-true == rtl on every pixel"
                        : "yes: hls == bit-true on every pixel (rtl not run)")
     << "\n"
     << "accuracy   " << (r.hls_ran ? "hls" : "bit-true") << " vs float: PSNR " << a.psnr_db << " dB, max " << a.max_abs_err_lsb
     << " LSB, rms " << std::setprecision(3) << a.rms_err_lsb << " LSB, " << std::setprecision(2)
     << a.pct_within_1lsb << "% of pixels within 1 LSB\n"
     << "hazards    " << hazard_summary(r.hazards) << "\n"
     << "truth      " << (r.hls_ran ? "hls" : "bit-true") << " vs float at " << r.truth.oversampling
     << "x oversampling, ERT at 1 - 2^-20: PSNR " << r.truth_accuracy.psnr_db << " dB, max "
     << r.truth_accuracy.max_abs_err_lsb << " LSB, " << r.truth_accuracy.pct_within_1lsb
     << "% within 1 LSB, SSIM " << std::setprecision(4) << r.truth_accuracy.ssim
     << std::setprecision(2) << "\n"
     << "speed      float " << rate(r.samples_float, r.seconds_float) << " M samples/s, hls "
     << rate(r.samples_hls, r.seconds_hls) << " M samples/s, bit-true "
     << rate(r.samples_float, r.seconds_bittrue) << " M samples/s (float's sample count)\n";
  for (const EngineNotRun& n : r.not_run) os << "not run    " << n.engine << ": " << n.reason << "\n";
  if (r.rtl_ran && r.rtl_pipelines > 0)
    os << "card       rtl model (DDR4 card, " << r.rtl_pipelines << " pipeline(s), "
       << scene.rtl.scheduler << " scheduler, " << scene.rtl.traversal
       << " traversal): " << r.rtl_cycles << " cycles, " << r.rtl_fps << " frames/s at "
       << r.rtl_clock_mhz << " MHz, " << r.rtl_ns_per_sample << " ns/sample\n";
  else if (r.rtl_ran)
    os << "card       rtl model (" << scene.rtl.scheduler << " scheduler, " << scene.rtl.layout
       << " layout, " << scene.rtl.traversal << " traversal): " << r.rtl_cycles << " cycles, "
       << r.rtl_fps << " frames/s at 100 MHz, " << r.rtl_ns_per_sample << " ns/sample\n";
  for (const std::string& w : r.written) os << "wrote      " << w << "\n";
}

JUnitSuite cosim_junit(const ref::Scene& scene, const CosimResult& r) {
  const std::string classname =
      "cosim." + std::filesystem::path(scene.origin).stem().string();
  const auto not_run = [&r](const std::string& engine) -> const EngineNotRun* {
    for (const EngineNotRun& n : r.not_run)
      if (n.engine == engine) return &n;
    return nullptr;
  };
  const auto pair = [&](const std::string& name, const std::string& engine,
                        const std::string& other, double seconds) {
    JUnitCase c{classname, name, seconds};
    if (const EngineNotRun* n = not_run(engine)) {
      c.outcome = JUnitCase::Outcome::Skipped;
      c.message = engine + " not run: " + n->reason;
    } else if (!r.bit_exact && r.mismatch.engine == engine) {
      const Mismatch& m = r.mismatch;
      std::ostringstream msg;
      msg << engine << " differs from " << other << " at pixel (" << m.x << ", " << m.y
          << "), sample " << m.sample << ", first in the " << bittrue::to_string(m.unit);
      c.outcome = JUnitCase::Outcome::Failed;
      c.type = "MISMATCH";
      c.message = msg.str();
      c.details = "reproducer: " + m.reproducer;
    }
    return c;
  };
  JUnitSuite suite{"voxcast cosim", {}};
  suite.cases.push_back(pair("hls == bit-true", "hls", "bit-true", r.seconds_hls + r.seconds_bittrue));
  suite.cases.push_back(pair("rtl == hls", "rtl", "hls", r.seconds_rtl));
  return suite;
}

}  // namespace voxcast::cosim
