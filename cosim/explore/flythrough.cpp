#include "cosim/explore/flythrough.hpp"
#include "cosim/reports/progress.hpp"
#include "cosim/reports/files.hpp"

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cosim/engines/engines.hpp"
#include "cosim/reports/image_io.hpp"
#include "cosim/engines/truth.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/error.hpp"
#include "refmodel/parallel.hpp"
#include "refmodel/render/raycaster.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/scene_config.hpp"

namespace voxcast::cosim {
namespace {

constexpr int kDefaultFrames = 24;
// The image read back per frame: one RGBA8 word per pixel.
constexpr int kReadbackBytesPerPixel = 4;

int frame_count(const ref::Scene& scene, const FlythroughOptions& options) {
  if (options.frames < 0 || options.frames == 1)
    throw Error("flythrough: --frames " + std::to_string(options.frames) +
                " (a flythrough needs at least 2 frames; 0 takes the scene's render.frames)");
  if (options.frames > 0) return options.frames;
  return scene.render.frames > 1 ? scene.render.frames : kDefaultFrames;
}

std::string frame_name(int f) {
  std::ostringstream os;
  os << "frame_" << std::setw(4) << std::setfill('0') << f << ".png";
  return os.str();
}

void write_csv(const std::string& path, const std::vector<FlythroughFrame>& frames,
               const std::vector<rtl::pci::FrameReadback>& readback) {
  std::ofstream out(path);
  if (!out) throw Error(path + ": cannot write");
  out << "frame,eye_x,eye_y,eye_z,center_x,center_y,center_z,cycles,fps,ns_per_sample,"
         "samples,samples_issued,rays,rays_hit,rays_ert,row_hit_rate,activates,refreshes,"
         "readback_ms,stall_ms,readback_hidden\n";
  out << std::setprecision(10);
  for (const FlythroughFrame& f : frames) {
    const auto& s = f.stats;
    const rtl::pci::FrameReadback& rb = readback[static_cast<std::size_t>(f.index)];
    out << f.index << ',' << f.pose.eye.x << ',' << f.pose.eye.y << ',' << f.pose.eye.z << ','
        << f.pose.center.x << ',' << f.pose.center.y << ',' << f.pose.center.z << ',' << s.cycles
        << ',' << s.fps() << ',' << s.ns_per_sample() << ',' << s.samples << ','
        << s.samples_issued << ',' << s.rays << ',' << s.rays_hit << ',' << s.rays_ert << ','
        << s.row_hit_rate() << ',' << s.activates() << ',' << s.refreshes() << ','
        << 1e3 * rb.readback_s << ',' << 1e3 * rb.stall_s << ',' << (rb.hidden ? 1 : 0) << '\n';
  }
}

struct FpsSummary {
  double min = 0.0, mean = 0.0, max = 0.0;
  int at_least_20 = 0;  // frames at or above the paper's "well above 20 frames/s"
};

FpsSummary summarise(const std::vector<FlythroughFrame>& frames) {
  FpsSummary s;
  s.min = frames.front().stats.fps();
  for (const FlythroughFrame& f : frames) {
    const double fps = f.stats.fps();
    s.min = std::min(s.min, fps);
    s.max = std::max(s.max, fps);
    s.mean += fps;
    if (fps >= 20.0) ++s.at_least_20;
  }
  s.mean /= static_cast<double>(frames.size());
  return s;
}

// Frame f against frame f - 1, in output LSBs (TemporalStability).
TemporalStability frame_stability(const ref::QuantImage& prev, const ref::QuantImage& cur,
                                  const ref::Image* truth_prev, const ref::Image* truth_cur) {
  TemporalStability s;
  const double top = cur.full_scale();
  std::size_t count = 0;
  for (int y = 0; y < cur.height; ++y)
    for (int x = 0; x < cur.width; ++x)
      for (int c = 0; c < 4; ++c) {
        const auto ch = static_cast<std::size_t>(c);
        const double d = static_cast<double>(cur.at(x, y)[ch]) - static_cast<double>(prev.at(x, y)[ch]);
        s.change_max = std::max(s.change_max, std::abs(d));
        s.change_mean += std::abs(d);
        if (truth_prev) {
          const double t = (truth_cur->at(x, y)[c] - truth_prev->at(x, y)[c]) * top;
          s.flicker_max = std::max(s.flicker_max, std::abs(d - t));
          s.flicker_mean += std::abs(d - t);
        }
        ++count;
      }
  s.change_mean /= static_cast<double>(std::max<std::size_t>(count, 1));
  s.flicker_mean /= static_cast<double>(std::max<std::size_t>(count, 1));
  return s;
}

TemporalStability flight_stability(const std::vector<FlythroughFrame>& frames) {
  TemporalStability s;
  for (std::size_t f = 1; f < frames.size(); ++f) {
    const TemporalStability& t = frames[f].stability;
    s.change_max = std::max(s.change_max, t.change_max);
    s.flicker_max = std::max(s.flicker_max, t.flicker_max);
    s.change_mean += t.change_mean;
    s.flicker_mean += t.flicker_mean;
  }
  const double n = static_cast<double>(std::max<std::size_t>(frames.size(), 2) - 1);
  s.change_mean /= n;
  s.flicker_mean /= n;
  return s;
}

nlohmann::json stability_json(const TemporalStability& t, bool truth) {
  nlohmann::json j = {{"change_max_lsb", t.change_max}, {"change_mean_lsb", t.change_mean}};
  j["flicker_max_lsb"] = truth ? nlohmann::json(t.flicker_max) : nlohmann::json(nullptr);
  j["flicker_mean_lsb"] = truth ? nlohmann::json(t.flicker_mean) : nlohmann::json(nullptr);
  return j;
}

nlohmann::json pci_json(const rtl::pci::PciStats& s) {
  return {{"bytes", s.bytes}, {"seconds", s.seconds}, {"mb_per_second", s.mb_per_second()}};
}

void write_json(const std::string& path, const ref::Scene& scene, const FlythroughResult& r) {
  nlohmann::json j;
  j["scene"] = scene.origin;
  j["profile"] = scene.precision_name;
  j["image"] = {{"width", scene.render.width}, {"height", scene.render.height},
                {"oversampling", scene.render.oversampling},
                {"ert_threshold", scene.render.ert_threshold},
                {"partial_segments", scene.render.partial_segments},
                {"classification", ref::to_string(scene.render.classification)}};
  j["temporal_stability"] = stability_json(r.stability, r.has_truth);
  const FpsSummary fps = summarise(r.frames);
  j["fps"] = {{"min", fps.min}, {"mean", fps.mean}, {"max", fps.max},
              {"frames_at_least_20", fps.at_least_20}};
  j["host"] = {{"volume_upload", pci_json(r.host.volume)},
               {"tables", pci_json(r.host.tables)},
               {"image_readback", pci_json(r.host.image)}};
  nlohmann::json frames = nlohmann::json::array();
  for (const FlythroughFrame& f : r.frames) {
    const rtl::pci::FrameReadback& rb = r.readback[static_cast<std::size_t>(f.index)];
    frames.push_back({{"frame", f.index},
                      {"eye", {f.pose.eye.x, f.pose.eye.y, f.pose.eye.z}},
                      {"center", {f.pose.center.x, f.pose.center.y, f.pose.center.z}},
                      {"cycles", f.stats.cycles},
                      {"fps", f.stats.fps()},
                      {"ns_per_sample", f.stats.ns_per_sample()},
                      {"samples", f.stats.samples},
                      {"rays_ert", f.stats.rays_ert},
                      {"row_hit_rate", f.stats.row_hit_rate()},
                      {"readback_ms", 1e3 * rb.readback_s},
                      {"stall_ms", 1e3 * rb.stall_s},
                      {"readback_hidden", rb.hidden},
                      {"temporal_stability", stability_json(f.stability, r.has_truth)},
                      {"image", f.image}});
  }
  j["frames"] = frames;
  write_json_file(path, j);
}

// One frame's readback on the clocked PCI model: the frame buffer's RGBA8
// words, one per core clock, across the asynchronous FIFO to the DMA engine.
rtl::pci::PciStats clocked_readback(const ref::Scene& scene, const rtl::RtlConfig& config) {
  const auto words = static_cast<std::size_t>(scene.render.width) *
                     static_cast<std::size_t>(scene.render.height) * kReadbackBytesPerPixel / 4;
  std::vector<std::uint32_t> frame(words);
  for (std::size_t i = 0; i < words; ++i) frame[i] = static_cast<std::uint32_t>(i);
  return rtl::pci::run_clocked_transfer(rtl::pci::PciConfig{}, config.pipeline.dimm.clock,
                                        rtl::pci::Direction::kCardToHost, frame)
      .pci;
}

}  // namespace

FlythroughResult run_flythrough(const ref::Scene& scene, const FlythroughOptions& options) {
  if (scene.camera.path.size() < 2)
    throw Error(scene.origin + ": camera.path has " + std::to_string(scene.camera.path.size()) +
                " keyframe(s); a flythrough needs at least 2");
  const int n = frame_count(scene, options);
  if (options.out_dir.empty()) throw Error("flythrough: --out is empty");
  const std::filesystem::path dir(options.out_dir);
  make_output_dir(dir.string());

  const auto t0 = std::chrono::steady_clock::now();
  const SceneVolume sv = load_scene_volume(scene);
  check_fixed_point(scene, sv, /*hls=*/true);
  const bittrue::VoxelMemory memory =
      bittrue::make_voxel_memory(scene.precision, sv.volume, sv.gradients);
  const rtl::RtlConfig config = rtl::rtl_config(scene.rtl);
  const std::vector<ref::CameraPose> poses = ref::frame_poses(scene.camera, n);

  // Frames are independent: one simulation per worker, each single-threaded
  // and deterministic, written to its own slot.
  FlythroughResult r;
  r.frames.resize(poses.size());
  std::vector<ref::Image> images(poses.size());
  std::vector<ref::QuantImage> quantized(poses.size(), ref::QuantImage(1, 1, scene.precision.out_bits));
  // The truth of each frame for the temporal stability (cosim/engines/truth.hpp).
  r.has_truth = options.truth_oversampling > 0.0;
  std::vector<ref::Image> truths(r.has_truth ? poses.size() : 0);
  const TruthSettings truth_settings{options.truth_oversampling > 0.0 ? options.truth_oversampling
                                                                      : 16.0};
  if (r.has_truth) check_truth_settings(truth_settings, scene);
  const ref::Scene truth = truth_scene(scene, truth_settings);
  Progress progress("flythrough", poses.size());
  ref::parallel_for(
      static_cast<int>(poses.size()),
      [&](int f) {
        const ref::RenderInputs in =
            ref::make_render_inputs(scene, sv.volume, sv.gradients, poses[f]);
        const bittrue::FrameSetup setup = bittrue::make_frame_setup(scene.precision, scene, in);
        rtl::RtlResult frame = rtl::rtl_render(setup, memory, config);
        FlythroughFrame& out = r.frames[static_cast<std::size_t>(f)];
        out.index = f;
        out.pose = poses[f];
        out.stats = frame.stats;
        out.image = (dir / frame_name(f)).string();
        images[static_cast<std::size_t>(f)] = frame.image.to_image();
        quantized[static_cast<std::size_t>(f)] = std::move(frame.image);
        if (r.has_truth)
          truths[static_cast<std::size_t>(f)] = ref::render_image(
              ref::make_render_inputs(truth, sv.volume, sv.gradients, poses[f]), 1);
        progress.step();
      },
      scene.render.threads);
  for (std::size_t f = 1; f < poses.size(); ++f)
    r.frames[f].stability = frame_stability(quantized[f - 1], quantized[f],
                                            r.has_truth ? &truths[f - 1] : nullptr,
                                            r.has_truth ? &truths[f] : nullptr);
  r.stability = flight_stability(r.frames);
  r.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  for (std::size_t f = 0; f < images.size(); ++f)
    write_image(r.frames[f].image, images[f], scene.render.background);
  r.animation = (dir / "flythrough.gif").string();
  write_animation(r.animation, images, scene.render.background, options.animation_fps);

  const auto& d = sv.volume.dims;
  r.host = rtl::pci::vizard2_host_transfers(
      rtl::pci::PciBus{},
      static_cast<std::uint64_t>(d[0]) * static_cast<std::uint64_t>(d[1]) *
          static_cast<std::uint64_t>(d[2]),
      rtl::pci::UploadFormat::kRawVoxels, scene.render.width, scene.render.height,
      kReadbackBytesPerPixel);
  r.clocked_readback = clocked_readback(scene, config);
  std::vector<rtl::sim::Cycle> cycles;
  for (const FlythroughFrame& f : r.frames) cycles.push_back(static_cast<rtl::sim::Cycle>(f.stats.cycles));
  r.readback = rtl::pci::double_buffered_readback(cycles, config.pipeline.dimm.clock, r.clocked_readback);
  r.csv = (dir / "frames.csv").string();
  write_csv(r.csv, r.frames, r.readback);
  r.json = (dir / "frames.json").string();
  write_json(r.json, scene, r);
  return r;
}

void print_flythrough(std::ostream& os, const ref::Scene& scene, const FlythroughResult& r) {
  const FpsSummary fps = summarise(r.frames);
  os << std::fixed << std::setprecision(2);
  os << "scene    " << scene.origin << ", " << r.frames.size() << " frames along "
     << scene.camera.path.size() << " keyframes, " << scene.render.width << "x"
     << scene.render.height << ", oversampling " << scene.render.oversampling << ", ERT "
     << scene.render.ert_threshold << ", profile " << scene.precision_name << "\n";
  os << "frame    cycles      frames/s  ns/sample  M samples  ERT rays  row hits  readback\n";
  for (const FlythroughFrame& f : r.frames) {
    const auto& s = f.stats;
    const rtl::pci::FrameReadback& rb = r.readback[static_cast<std::size_t>(f.index)];
    const double rays = static_cast<double>(std::max<std::uint64_t>(s.rays, 1));
    os << std::setw(5) << f.index << "  " << std::setw(10) << s.cycles << "  " << std::setw(8)
       << s.fps() << "  " << std::setw(9) << s.ns_per_sample() << "  " << std::setw(9)
       << static_cast<double>(s.samples) / 1e6 << "  " << std::setw(7)
       << 100.0 * static_cast<double>(s.rays_ert) / rays << "%  " << std::setw(7)
       << 100.0 * s.row_hit_rate() << "%  " << 1e3 * rb.readback_s << " ms "
       << (rb.hidden ? "hidden" : f.index + 1 == static_cast<int>(r.frames.size()) ? "last" : "NOT hidden");
    if (rb.stall_s > 0.0) os << ", frame waited " << 1e3 * rb.stall_s << " ms";
    os << "\n";
  }
  os << "card     " << fps.min << " / " << fps.mean << " / " << fps.max
     << " frames/s (min / mean / max), " << fps.at_least_20 << " of " << r.frames.size()
     << " frames at >= 20 frames/s\n"
     << "pci      volume upload " << r.host.volume.seconds << " s once; image readback "
     << 1e3 * r.host.image.seconds << " ms per frame (closed form; clocked "
     << 1e3 * r.clocked_readback.seconds << " ms, double-buffered behind the next frame)\n"
     << "stable   frame-to-frame change " << r.stability.change_max << " LSB max, "
     << r.stability.change_mean << " LSB mean";
  if (r.has_truth)
    os << "; flicker against the truth's change " << r.stability.flicker_max << " LSB max, "
       << r.stability.flicker_mean << " LSB mean";
  os << (scene.render.partial_segments ? " (partial segments)" : "") << "\n"
     << "host     " << r.wall_seconds << " s to simulate\n"
     << "wrote    " << r.animation << ", " << r.csv << ", " << r.json << ", frame_*.png\n";
}

}  // namespace voxcast::cosim
