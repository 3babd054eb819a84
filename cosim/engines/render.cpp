#include "cosim/engines/render.hpp"
#include "cosim/reports/files.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
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
#include "refmodel/bittrue/raycaster.hpp"
#include "cosim/reports/rtl_json.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/scene_config.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/error.hpp"
#include "refmodel/parallel.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::cosim {
namespace {


struct View {
  ref::CameraPose pose;
  std::string suffix;
};

std::vector<View> views_of(const ref::Scene& scene) {
  const std::vector<ref::CameraPose> poses = ref::frame_poses(scene.camera, scene.render.frames);
  std::vector<View> views;
  for (std::size_t f = 0; f < poses.size(); ++f) {
    std::ostringstream frame;
    if (poses.size() > 1) frame << '_' << std::setw(4) << std::setfill('0') << f;
    if (scene.camera.stereo_deg > 0.0) {
      const double half = 0.5 * scene.camera.stereo_deg;
      views.push_back({ref::rotate_about_up(poses[f], -half), frame.str() + "_left"});
      views.push_back({ref::rotate_about_up(poses[f], +half), frame.str() + "_right"});
    } else {
      views.push_back({poses[f], frame.str()});
    }
  }
  return views;
}

void write_report(const std::string& path, const ref::Scene& scene, const RenderSummary& s) {
  nlohmann::json j;
  j["scene"] = scene.origin;
  j["engine"] = to_string(s.engine);
  if (s.engine != Engine::Ref) {
    j["profile"] = scene.precision_name;
    j["hazards"] = hazards_json(s.hazards);
  }
  j["volume"] = {{"source", s.volume_source}, {"dims", s.dims}, {"bits", s.bits}};
  j["image"] = {{"width", scene.render.width}, {"height", scene.render.height},
                {"mode", ref::to_string(scene.render.mode)},
                {"projection", ref::to_string(scene.camera.projection)},
                {"oversampling", scene.render.oversampling},
                {"ert_threshold", scene.render.ert_threshold}};
  // The counts of ref::FrameStats (docs/pipeline.md §9); a MIP frame has no
  // early ray termination: null, not 0.
  j["stats"] = {{"rays", s.stats.rays},
                {"rays_hit", s.stats.rays_hit},
                {"rays_terminated_early", scene.render.mode == ref::RenderMode::Mip
                                              ? nlohmann::json(nullptr)
                                              : nlohmann::json(s.stats.rays_terminated_early)},
                {"samples", s.stats.samples},
                {"samples_skipped", s.stats.samples_skipped}};
  j["timing"] = {{"load_seconds", s.load_seconds}, {"render_seconds", s.render_seconds},
                 {"threads", s.threads}};
  if (s.engine == Engine::Rtl)
    j["rtl"] = {{"cycles", s.rtl_cycles}, {"fps", s.rtl_fps},
                {"ns_per_sample", s.rtl_ns_per_sample}, {"row_hit_rate", s.rtl_row_hit_rate},
                {"config", rtl_desc_json(scene.rtl)}};
  if (s.engine == Engine::Rtl && s.vcd_commands > 0) j["rtl"]["vcd_commands"] = s.vcd_commands;
  if (s.engine == Engine::Rtl && s.rtl_pipelines > 0)
    j["rtl"]["ddr4_card"] = {{"pipelines", s.rtl_pipelines},
                             {"clock_mhz", s.rtl_clock_mhz},
                             {"samples_per_second", s.rtl_samples_per_second},
                             {"bandwidth_gb_s", s.rtl_bandwidth_gbs},
                             {"bandwidth_share", s.rtl_bandwidth_share},
                             {"cache_hit_rate", s.rtl_cache_hit_rate},
                             {"bound", s.rtl_bound},
                             {"samples_issued", s.rtl_samples_issued},
                             {"pipeline_busy", s.rtl_pipeline_busy},
                             {"channel_busy", s.rtl_channel_busy}};
  j["written"] = s.written;
  write_json_file(path, j);
}

// One view with the chosen engine; the fixed-point engines' output is scaled
// back to [0, 1] for writing.
ref::Image render_view(const ref::Scene& scene, const ref::Volume& volume,
                       const ref::GradientField& gradients, const ref::CameraPose& pose,
                       Engine engine, const bittrue::VoxelMemory* memory, ref::FrameStats& fs,
                       RenderSummary& summary, const rtl::trace::TraceOptions* trace) {
  const ref::RenderInputs in = ref::make_render_inputs(scene, volume, gradients, pose);
  if (engine == Engine::Ref) return ref::render_image(in, scene.render.threads, &fs);
  const bittrue::FrameSetup setup = bittrue::make_frame_setup(scene.precision, scene, in);
  if (engine == Engine::BitTrue)
    return bittrue::bt_render_image(setup, *memory, scene.render.threads, &fs).to_image();
  if (engine == Engine::Rtl) {
    const rtl::RtlResult r = rtl::rtl_render(setup, *memory, rtl::rtl_config(scene.rtl), trace);
    summary.vcd_commands += r.traced_commands;
    fs = rtl::frame_stats(r.stats);
    summary.rtl_cycles += static_cast<double>(r.stats.cycles);
    summary.rtl_ns_per_sample = r.stats.ns_per_sample();
    summary.rtl_fps = r.stats.fps();
    summary.rtl_row_hit_rate = r.stats.row_hit_rate();
    summary.rtl_clock_mhz = r.stats.clock_mhz;
    summary.rtl_pipelines = r.stats.card.pipelines;
    if (r.stats.card.pipelines > 0) {
      summary.rtl_samples_per_second = r.stats.samples_per_second();
      summary.rtl_bandwidth_gbs = r.stats.bandwidth_mb_s() * 1e-3;
      summary.rtl_bandwidth_share = r.stats.bandwidth_utilisation();
      summary.rtl_cache_hit_rate = r.stats.card.cache_hit_rate();
      summary.rtl_bound = r.stats.card.bound(r.stats.cycles);
      summary.rtl_samples_issued = r.stats.samples_issued;
      summary.rtl_pipeline_busy = r.stats.card.pipeline_utilisation(r.stats.cycles);
      summary.rtl_channel_busy = r.stats.card.channel_utilisation();
    }
    return r.image.to_image();
  }
  return hls_render_image(setup, *memory, scene.render.threads, &fs).to_image();
}

}  // namespace

Engine parse_engine(const std::string& name) {
  if (name == "ref") return Engine::Ref;
  if (name == "bittrue") return Engine::BitTrue;
  if (name == "hls") return Engine::Hls;
  if (name == "rtl") return Engine::Rtl;
  throw Error("unknown engine \"" + name + "\" (ref, bittrue, hls, rtl)");
}

const char* to_string(Engine e) {
  switch (e) {
    case Engine::Ref: return "refmodel (double precision)";
    case Engine::BitTrue: return "bit-true reference";
    case Engine::Hls: return "hls kernels";
    case Engine::Rtl: return "rtl cycle model";
  }
  return "?";
}

RenderSummary run_render(const ref::Scene& scene, const RenderOptions& options) {
  if (scene.algorithm == ref::Algorithm::Heidelberg) return run_render_heidelberg(scene, options);
  RenderSummary s;
  // Every argument before any work: the outputs' types and folders, the views.
  for (const std::string& out : options.outputs) check_image_path(out);
  if (scene.render.frames > 1 && scene.camera.path.size() < 2)
    throw Error(scene.origin + ": render.frames = " + std::to_string(scene.render.frames) +
                " renders a camera path, but camera.path has " +
                std::to_string(scene.camera.path.size()) + " keyframe(s); a path needs at least 2");
  for (const std::string& out : options.outputs) make_parent_dir(out);
  if (!options.report_json.empty()) make_parent_dir(options.report_json);
  const auto t_load = StopwatchClock::now();
  const SceneVolume sv = load_scene_volume(scene);
  const ref::Volume& volume = sv.volume;
  const ref::GradientField& gradients = sv.gradients;
  s.load_seconds = seconds_since(t_load);
  s.volume_source = volume.source;
  s.dims = volume.dims;
  s.bits = volume.bits;
  s.threads = ref::worker_count(scene.render.threads);
  s.engine = options.engine;
  if ((!options.vcd_path.empty() || !options.vcd_window.empty()) && options.engine != Engine::Rtl)
    throw Error("--vcd and --vcd-window need --engine rtl (the trace is the cycle model's)");
  if (!options.vcd_window.empty() && options.vcd_path.empty())
    throw Error("--vcd-window needs --vcd FILE");
  if (!options.vcd_window.empty()) rtl::trace::parse_window(options.vcd_window, "--vcd-window");
  // The fixed-point engines hold the volume as voxel words in 8 banks.
  std::optional<bittrue::VoxelMemory> memory;
  if (options.engine != Engine::Ref) {
    check_fixed_point(scene, sv, options.engine == Engine::Hls || options.engine == Engine::Rtl);
    s.hazards = precision_hazards(scene, volume);
    report_hazards(s.hazards, options.strict, std::cerr);
    memory = bittrue::make_voxel_memory(scene.precision, volume, gradients);
  }

  // The VCD trace: one file per view (a trace is one frame's cycles), named
  // like the images: trace.vcd, or trace_L.vcd / trace_0003.vcd for the views
  // of a stereo pair or a camera path.
  rtl::trace::TraceOptions trace;
  if (!options.vcd_path.empty()) {
    if (!options.vcd_window.empty()) trace = rtl::trace::parse_window(options.vcd_window, "--vcd-window");
    make_parent_dir(options.vcd_path);
  }
  const auto t_render = StopwatchClock::now();
  for (const View& view : views_of(scene)) {
    ref::FrameStats fs;
    std::ofstream vcd;
    const std::string vcd_path =
        options.vcd_path.empty() ? std::string() : with_suffix(options.vcd_path, view.suffix);
    if (!vcd_path.empty()) {
      vcd.open(vcd_path);
      if (!vcd) throw Error(vcd_path + ": cannot write the VCD trace");
      trace.out = &vcd;
    }
    const ref::Image img = render_view(scene, volume, gradients, view.pose, options.engine,
                                       memory ? &*memory : nullptr, fs, s,
                                       vcd_path.empty() ? nullptr : &trace);
    if (!vcd_path.empty()) {
      vcd.close();
      if (!vcd) throw Error(vcd_path + ": error writing the VCD trace");
      s.written.push_back(vcd_path);
      trace.out = nullptr;
    }
    s.stats += fs;
    for (const std::string& out : options.outputs) {
      const std::string path = with_suffix(out, view.suffix);
      write_image(path, img, scene.render.background);
      s.written.push_back(path);
    }
  }
  s.render_seconds = seconds_since(t_render);
  if (!options.report_json.empty()) {
    write_report(options.report_json, scene, s);
    s.written.push_back(options.report_json);
  }
  return s;
}

namespace {

// The "image" and "engine" lines of a VIRIM scene: its view cube and
// interpolation instead of the ray caster's camera, its own profile.
void print_heidelberg_setup(std::ostream& os, const ref::Scene& scene, const RenderSummary& s) {
  const ref::HeidelbergDesc& h = scene.heidelberg;
  os << "image    " << scene.render.width << "x" << scene.render.height
     << " Heidelberg model (VIRIM), view cube depth "
     << (h.depth > 0 ? std::to_string(h.depth) : std::string("= largest volume edge")) << ", "
     << (h.interpolation == ref::HeidelbergInterpolation::Gaussian ? "Gaussian mask" : "trilinear")
     << ", " << h.weight_bits << " weight bits, "
     << (h.perspective > 0.0 ? "perspective" : "parallel") << (h.stereo_deg > 0.0 ? ", stereo" : "")
     << "\n"
     << "engine   " << to_string(s.engine) << (s.engine == Engine::Ref ? "" : ", profile virim")
     << ", " << s.threads << " threads, " << s.render_seconds << " s\n";
  if (s.engine == Engine::Rtl)
    os << std::setprecision(0) << "card     VIRIM, " << h.modules << " module(s): " << s.rtl_cycles
       << std::setprecision(2) << " cycles at " << h.rotator_mhz << " MHz (rotator): " << s.rtl_fps
       << " frames/s, " << s.rtl_ns_per_sample << " ns/voxel; rtl == hls on every pixel\n";
}

// A count as printed: exact below a million, else in millions to 0.1 M.
std::string sample_count(std::uint64_t n) {
  if (n < 1000000) return std::to_string(n);
  std::ostringstream os;
  os << std::fixed << std::setprecision(1) << static_cast<double>(n) / 1e6 << " M";
  return os.str();
}

void print_raycast_setup(std::ostream& os, const ref::Scene& scene, const RenderSummary& s) {
  const double rays = static_cast<double>(std::max<std::uint64_t>(s.stats.rays, 1));
  os << "image    " << scene.render.width << "x" << scene.render.height << " "
     << ref::to_string(scene.render.mode) << ", " << ref::to_string(scene.camera.projection)
     << ", oversampling " << scene.render.oversampling << ", ERT " << scene.render.ert_threshold
     << "\n"
     << "engine   " << to_string(s.engine)
     << (s.engine == Engine::Ref ? "" : ", profile " + scene.precision_name) << ", " << s.threads
     << " threads, " << s.render_seconds << " s\n"
     << "rays     " << 100.0 * static_cast<double>(s.stats.rays_hit) / rays << "% hit the volume, ";
  // ref::FrameStats' counts (docs/pipeline.md §9); MIP has no early ray
  // termination and never leaps.
  const bool mip = scene.render.mode == ref::RenderMode::Mip;
  if (mip)
    os << "no early termination (MIP), ";
  else
    os << 100.0 * static_cast<double>(s.stats.rays_terminated_early) / rays << "% terminated early, ";
  os << sample_count(s.stats.samples) << " samples";
  if (scene.render.space_leaping && !mip)
    os << ", " << sample_count(s.stats.samples_skipped) << " skipped by space leaping";
  os << "\n" << std::setprecision(2);
  if (s.engine == Engine::Rtl && s.rtl_pipelines > 0) {
    os << std::setprecision(0) << "card     " << s.rtl_cycles << std::setprecision(2)
       << " cycles at " << s.rtl_clock_mhz << " MHz: " << s.rtl_fps << " frames/s, "
       << std::setprecision(3) << s.rtl_ns_per_sample << " ns/sample, "
       << s.rtl_samples_per_second * 1e-9 << " G samples/s (" << s.rtl_samples_issued
       << " issued, those beyond an early termination included)\n"
       << std::setprecision(2) << "         DDR4 card, " << s.rtl_pipelines << " pipeline(s), "
       << scene.rtl.ray_slots << " ray slots each: channels " << s.rtl_bandwidth_gbs << " GB/s ("
       << 100.0 * s.rtl_bandwidth_share << "% of peak), row hit rate " << 100.0 * s.rtl_row_hit_rate
       << "%, brick cache hit rate " << 100.0 * s.rtl_cache_hit_rate << "%; bound: " << s.rtl_bound
       << " (busiest pipeline issuing " << 100.0 * s.rtl_pipeline_busy
       << "% of clocks, busiest channel's data bus " << 100.0 * s.rtl_channel_busy << "% busy)\n"
       << "         " << scene.rtl.scheduler << " scheduler, " << scene.rtl.traversal
       << " traversal\n";
  } else if (s.engine == Engine::Rtl) {
    os << std::setprecision(0) << "card     " << s.rtl_cycles << std::setprecision(2)
       << " cycles at 100 MHz: " << s.rtl_fps << " frames/s, " << s.rtl_ns_per_sample
       << " ns/sample, row hit rate " << 100.0 * s.rtl_row_hit_rate << "%\n"
       << "         " << scene.rtl.scheduler << " scheduler, " << scene.rtl.layout << " layout, "
       << scene.rtl.traversal << " traversal, " << scene.rtl.ray_slots << " ray slots\n";
  }
}

}  // namespace

void print_summary(std::ostream& os, const ref::Scene& scene, const RenderSummary& s) {
  os << std::fixed << std::setprecision(2);
  os << "scene    " << scene.origin << "\n"
     << "volume   " << s.volume_source << "  " << s.dims[0] << "x" << s.dims[1] << "x" << s.dims[2]
     << ", " << s.bits << "-bit voxels (loaded in " << s.load_seconds << " s)\n";
  if (scene.algorithm == ref::Algorithm::Heidelberg)
    print_heidelberg_setup(os, scene, s);
  else
    print_raycast_setup(os, scene, s);
  if (s.engine == Engine::Rtl && s.vcd_commands > 0)
    os << "vcd      " << s.vcd_commands << " SDRAM commands inside the window\n";
  for (const std::string& w : s.written) os << "wrote    " << w << "\n";
}

std::string with_suffix(const std::string& path, const std::string& suffix) {
  const std::filesystem::path p(path);
  return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

}  // namespace voxcast::cosim
