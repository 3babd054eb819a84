#include "cosim/engines/heidelberg.hpp"
#include "cosim/reports/files.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/engines/engines.hpp"
#include "cosim/reports/image_io.hpp"
#include "cosim/reports/metrics.hpp"
#include "cosim/reports/stopwatch.hpp"
#include "cosim/engines/warnings.hpp"
#include "hls/virim/host.hpp"
#include "refmodel/error.hpp"
#include "refmodel/parallel.hpp"
#include "refmodel/render/heidelberg/heidelberg.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/virim/engine.hpp"

namespace voxcast::cosim {
namespace {

template <class HP>
ref::QuantImage render_hls(const bittrue::VirimSetup& s, const bittrue::VirimMemory& m,
                           int threads, hls::virim::MemoryStats* stats) {
  const auto frame = hls::virim::host::load_virim_frame<HP>(s);
  const std::uint16_t* banks[16];
  hls::virim::host::bank_pointers(m, banks);
  ref::QuantImage img(s.W, s.H, HP::out_bits);
  const auto full = static_cast<std::uint32_t>(img.full_scale());
  std::vector<hls::virim::MemoryStats> line_stats(static_cast<std::size_t>(s.H));
  ref::parallel_for(
      s.H,
      [&](int k) {
        std::vector<std::uint32_t> level(static_cast<std::size_t>(s.W));
        std::unique_ptr<bool[]> bg(new bool[static_cast<std::size_t>(s.W)]);
        hls::virim::virim_frame<HP>(frame.get(), banks, k, k + 1, level.data(), bg.get(),
                                    &line_stats[static_cast<std::size_t>(k)]);
        for (int x = 0; x < s.W; ++x) {
          const std::uint32_t v = level[static_cast<std::size_t>(x)];
          img.at(x, s.H - 1 - k) = bg[static_cast<std::size_t>(x)]
                                       ? std::array<std::uint32_t, 4>{0, 0, 0, 0}
                                       : std::array<std::uint32_t, 4>{v, v, v, full};
        }
      },
      threads);
  if (stats) {
    *stats = {};
    for (const auto& l : line_stats) {
      stats->accesses += l.accesses;
      stats->suppressed += l.suppressed;
      stats->out_of_bounds += l.out_of_bounds;
      stats->bank_reads[0] += l.bank_reads[0];
      stats->bank_reads[1] += l.bank_reads[1];
    }
  }
  return img;
}


void check_hls(const HeidelbergProfile& p) {
  if (!hls_supports_heidelberg(p))
    throw Error("heidelberg.weight_bits = " + std::to_string(p.weight_bits) +
                " is not compiled into the hls engine (compiled: " +
                hls::virim::host::kCompiledHeidelbergProfiles + "); use the bittrue engine");
}

rtl::virim::VirimRtlResult run_rtl(const ref::Scene& scene, const bittrue::VirimSetup& setup,
                                   const bittrue::VirimMemory& memory) {
  return rtl::virim::virim_rtl_render(setup, memory,
                                      rtl::virim::virim_rtl_config(scene.heidelberg),
                                      scene.render.threads);
}

}  // namespace

nlohmann::json virim_rtl_json(const ref::Scene& scene, const rtl::virim::VirimRtlStats& st) {
  const ref::HeidelbergDesc& h = scene.heidelberg;
  return {{"cycles", st.cycles},
          {"fps", st.fps()},
          {"frame_ms", st.frame_ns * 1e-6},
          {"ns_per_voxel", st.ns_per_voxel()},
          {"ns_per_sample", st.ns_per_voxel()},
          {"voxels", st.voxels},
          {"voxels_per_second", st.voxels_per_second()},
          {"rotation_rate", st.rotation_rate()},
          {"peak_rotation_rate", st.peak_rotation_rate()},
          {"mean_access_ns", st.mean_access_ns()},
          {"dsp_utilisation", st.dsp_utilisation()},
          {"memory",
           {{"unit_reads", st.unit_reads},
            {"ram_reads", st.ram_reads},
            {"suppressed", st.suppressed},
            {"out_of_range", st.out_of_range},
            {"bank_reads", {st.bank_reads[0], st.bank_reads[1]}}}},
          {"stalls",
           {{"rotator_bank_busy", st.stalls.rotator_bank_busy},
            {"rotator_bus_full", st.stalls.rotator_bus_full},
            {"bus_dsp_fifo_full", st.stalls.bus_dsp_fifo_full},
            {"dsp_starved", st.stalls.dsp_starved}}},
          {"config",
           {{"modules", h.modules},
            {"rotator_mhz", h.rotator_mhz},
            {"dsp_mhz", h.dsp_mhz},
            {"bus_mhz", h.bus_mhz}}}};
}

void check_rtl_matches_hls(const ref::QuantImage& rtl_img, const ref::QuantImage& hls_img) {
  int x = 0, y = 0;
  if (first_difference(rtl_img, hls_img, x, y))
    throw Error("rtl engine: the VIRIM cycle model differs from the hls kernels at pixel (" +
                std::to_string(x) + ", " + std::to_string(y) + ")");
}

bool hls_supports_heidelberg(const HeidelbergProfile& p) {
  return hls::virim::host::dispatch_heidelberg_profile(p, []<class>() {});
}

ref::QuantImage hls_render_heidelberg(const bittrue::VirimSetup& setup,
                                      const bittrue::VirimMemory& memory, int threads,
                                      hls::virim::MemoryStats* stats) {
  check_hls(setup.profile);
  ref::QuantImage img;
  hls::virim::host::dispatch_heidelberg_profile(setup.profile, [&]<class HP>() {
    img = render_hls<HP>(setup, memory, threads, stats);
  });
  return img;
}

RenderSummary run_render_heidelberg(const ref::Scene& scene, const RenderOptions& options) {
  if (!options.vcd_path.empty() || !options.vcd_window.empty())
    throw Error("--vcd and --vcd-window trace the ray caster's card; VIRIM's cycle model "
                "(render.algorithm = \"heidelberg\") writes no trace");
  RenderSummary s;
  for (const std::string& out : options.outputs) check_image_path(out);
  const auto t_load = StopwatchClock::now();
  const SceneVolume sv = load_scene_volume(scene);
  s.load_seconds = seconds_since(t_load);
  s.volume_source = sv.volume.source;
  s.dims = sv.volume.dims;
  s.bits = sv.volume.bits;
  s.threads = ref::worker_count(scene.render.threads);
  s.engine = options.engine;
  const HeidelbergProfile profile = bittrue::heidelberg_profile(scene);
  if (options.engine == Engine::Hls || options.engine == Engine::Rtl) check_hls(profile);
  if (options.engine != Engine::Ref) {
    s.hazards = precision_hazards(scene, sv.volume);
    report_hazards(s.hazards, options.strict, std::cerr);
  }
  const bittrue::VirimMemory memory = bittrue::make_virim_memory(sv.volume);
  for (const std::string& out : options.outputs) make_parent_dir(out);
  const std::vector<double> eyes = ref::heidelberg::eye_offsets(scene.heidelberg);
  const auto t_render = StopwatchClock::now();
  rtl::virim::VirimRtlStats rtl_stats;  // the last eye's
  for (std::size_t e = 0; e < eyes.size(); ++e) {
    ref::Image img;
    if (options.engine == Engine::Ref) {
      img = ref::heidelberg::render(scene, sv.volume, eyes[e], scene.render.threads);
    } else {
      const bittrue::VirimSetup setup =
          bittrue::make_virim_setup(profile, scene, sv.volume, eyes[e]);
      if (options.engine == Engine::Rtl) {
        // The cycle model, held to the hls kernels' pixels on every run.
        const rtl::virim::VirimRtlResult r = run_rtl(scene, setup, memory);
        check_rtl_matches_hls(r.image, hls_render_heidelberg(setup, memory, scene.render.threads));
        rtl_stats = r.stats;
        s.rtl_cycles += static_cast<double>(r.stats.cycles);
        s.rtl_fps = r.stats.fps();
        s.rtl_ns_per_sample = r.stats.ns_per_voxel();
        img = r.image.to_image();
      } else {
        img = (options.engine == Engine::Hls
                   ? hls_render_heidelberg(setup, memory, scene.render.threads)
                   : bittrue::bt_render_heidelberg(setup, memory, scene.render.threads))
                  .to_image();
      }
    }
    // The Heidelberg model computes every pixel through the rotated view cube:
    // it has no ray set-up with a hit test, no early termination and no
    // leaping, so only `rays` (the pixels) is counted, and the summary prints
    // none of the ray caster's counts.
    s.stats.rays += static_cast<std::uint64_t>(img.width) * static_cast<std::uint64_t>(img.height);
    const std::string suffix = eyes.size() == 1 ? "" : (e == 0 ? "_left" : "_right");
    for (const std::string& out : options.outputs) {
      const std::string path = with_suffix(out, suffix);
      write_image(path, img, scene.render.background);
      s.written.push_back(path);
    }
  }
  s.render_seconds = seconds_since(t_render);
  if (!options.report_json.empty()) {
    nlohmann::json j;
    j["scene"] = scene.origin;
    j["algorithm"] = "heidelberg";
    j["engine"] = to_string(s.engine);
    j["volume"] = {{"source", s.volume_source}, {"dims", s.dims}, {"bits", s.bits}};
    j["image"] = {{"width", scene.render.width}, {"height", scene.render.height}};
    j["timing"] = {{"load_seconds", s.load_seconds}, {"render_seconds", s.render_seconds},
                   {"threads", s.threads}};
    if (s.engine == Engine::Rtl) j["rtl"] = virim_rtl_json(scene, rtl_stats);
    j["written"] = s.written;
    write_json_file(options.report_json, j);
    s.written.push_back(options.report_json);
  }
  return s;
}

CosimResult run_cosim_heidelberg(const ref::Scene& scene, const std::string& out_dir,
                                 bool strict) {
  CosimResult r;
  make_output_dir(out_dir);
  const SceneVolume sv = load_scene_volume(scene);
  r.hazards = precision_hazards(scene, sv.volume);
  report_hazards(r.hazards, strict, std::cerr);
  const HeidelbergProfile profile = bittrue::heidelberg_profile(scene);
  r.hls_ran = hls_supports_heidelberg(profile);
  const int threads = scene.render.threads;
  const double eye = ref::heidelberg::eye_offsets(scene.heidelberg).front();

  auto t0 = StopwatchClock::now();
  const ref::Image truth = ref::heidelberg::render(scene, sv.volume, eye, threads);
  r.seconds_float = seconds_since(t0);
  const bittrue::VirimSetup setup = bittrue::make_virim_setup(profile, scene, sv.volume, eye);
  const bittrue::VirimMemory memory = bittrue::make_virim_memory(sv.volume);
  t0 = StopwatchClock::now();
  const ref::QuantImage bt = bittrue::bt_render_heidelberg(setup, memory, threads);
  r.seconds_bittrue = seconds_since(t0);
  ref::QuantImage hls = bt;
  hls::virim::MemoryStats ms;
  if (r.hls_ran) {
    t0 = StopwatchClock::now();
    hls = hls_render_heidelberg(setup, memory, threads, &ms);
    r.seconds_hls = seconds_since(t0);
  }
  // The cycle model: the hls kernels' pixels, and the card's cycles.
  rtl::virim::VirimRtlResult rtl_result;
  if (!r.hls_ran) {
    r.not_run.push_back({"hls", "the hls kernels are not compiled for VIRIM's widths"});
    r.not_run.push_back({"rtl", "it runs the hls kernels' widths only"});
  } else {
    t0 = StopwatchClock::now();
    rtl_result = run_rtl(scene, setup, memory);
    r.rtl_ran = true;
    r.seconds_rtl = seconds_since(t0);
    r.rtl_exact = rtl_result.image.pixels == hls.pixels;
    r.rtl_cycles = rtl_result.stats.cycles;
    r.rtl_fps = rtl_result.stats.fps();
    r.rtl_ns_per_sample = rtl_result.stats.ns_per_voxel();
  }
  const std::uint64_t voxels = static_cast<std::uint64_t>(setup.W) * static_cast<std::uint64_t>(setup.D) *
                               static_cast<std::uint64_t>(setup.H);
  r.samples_float = r.samples_hls = voxels;
  const bool hls_exact = !r.hls_ran || hls.pixels == bt.pixels;
  r.bit_exact = hls_exact && r.rtl_exact;
  if (!r.bit_exact) {
    // As for the ray caster: when hls agrees with bit-true, the cycle model is
    // the one that differs.
    Mismatch& m = r.mismatch;
    m.engine = hls_exact ? "rtl" : "hls";
    first_difference(hls_exact ? rtl_result.image : hls, hls_exact ? hls : bt, m.x, m.y);
    m.reproducer = (std::filesystem::path(out_dir) / "reproducer.toml").string();
    std::ofstream out(m.reproducer);
    out << "# voxcast cosim reproducer: " << m.engine << " and "
        << (hls_exact ? "hls" : "bit-true") << " differ at pixel (" << m.x << ", " << m.y
        << ") of the Heidelberg path.\n"
        << ref::scene_to_toml(scene);
    r.written.push_back(m.reproducer);
  }
  r.accuracy = measure_accuracy(hls, truth);

  write_cosim_images(out_dir, scene, truth, bt, hls, r.hls_ran, nullptr, r.written);
  const auto path = [&](const char* name) { return (std::filesystem::path(out_dir) / name).string(); };

  nlohmann::json j;
  j["scene"] = scene.origin;
  j["algorithm"] = "heidelberg";
  j["hazards"] = hazards_json(r.hazards);
  j["bit_exact"] = r.hls_ran ? nlohmann::json(r.bit_exact) : nlohmann::json(nullptr);
  j["engines"] = r.hls_ran ? nlohmann::json{"float", "bittrue", "hls", "rtl"}
                           : nlohmann::json{"float", "bittrue"};
  if (r.hls_ran) {
    j["rtl_bit_exact"] = r.rtl_exact;
    const nlohmann::json rj = virim_rtl_json(scene, rtl_result.stats);
    for (const char* key : {"cycles", "fps", "ns_per_voxel", "ns_per_sample", "stalls"})
      j[key] = rj[key];
    j["rtl"] = rj;
  }
  j["weight_bits"] = profile.weight_bits;
  j["psnr_db"] = std::isfinite(r.accuracy.psnr_db) ? nlohmann::json(r.accuracy.psnr_db)
                                                   : nlohmann::json("inf");
  j["max_abs_err_lsb"] = r.accuracy.max_abs_err_lsb;
  j["mean_abs_err_lsb"] = r.accuracy.mean_abs_err_lsb;
  j["rms_err_lsb"] = r.accuracy.rms_err_lsb;
  j["pct_within_1lsb"] = r.accuracy.pct_within_1lsb;
  j["worst_pixel"] = {r.accuracy.worst_x, r.accuracy.worst_y};
  if (r.hls_ran)
    j["memory"] = {{"accesses", ms.accesses}, {"suppressed", ms.suppressed},
                   {"out_of_bounds", ms.out_of_bounds},
                   {"bank_reads", {ms.bank_reads[0], ms.bank_reads[1]}}};
  if (!r.bit_exact)
    j["mismatch"] = {{"engine", r.mismatch.engine},
                     {"pixel", {r.mismatch.x, r.mismatch.y}},
                     {"reproducer", r.mismatch.reproducer}};
  j["seconds"] = {{"float", r.seconds_float}, {"bittrue", r.seconds_bittrue}, {"hls", r.seconds_hls},
                  {"rtl", r.seconds_rtl}};
  write_json_file(path("report.json"), j);
  r.written.push_back(path("report.json"));
  return r;
}

void print_cosim_summary_heidelberg(std::ostream& os, const ref::Scene& scene,
                                    const CosimResult& r) {
  const Accuracy& a = r.accuracy;
  os << std::fixed << std::setprecision(2);
  os << "scene      " << scene.origin << " (Heidelberg model, " << scene.render.width << "x"
     << scene.render.height << ", weight_bits " << scene.heidelberg.weight_bits << ")\n"
     << "bit-exact  "
     << (!r.hls_ran ? "not checked: the hls engine is not compiled for this profile"
                    : r.bit_exact ? "yes: rtl == hls == bit-true on every pixel"
                                  : "NO")
     << "\n"
     << "accuracy   " << (r.hls_ran ? "hls" : "bit-true") << " vs float: PSNR " << a.psnr_db
     << " dB, max " << a.max_abs_err_lsb << " LSB, rms " << std::setprecision(3) << a.rms_err_lsb
     << " LSB, " << std::setprecision(2) << a.pct_within_1lsb << "% of pixels within 1 LSB\n"
     << "seconds    float " << r.seconds_float << ", bit-true " << r.seconds_bittrue << ", hls "
     << r.seconds_hls << ", rtl " << r.seconds_rtl << "\n";
  if (r.hls_ran)
    os << "card       " << r.rtl_cycles << " rotator cycles: " << r.rtl_fps << " frames/s, "
       << r.rtl_ns_per_sample << " ns/voxel (" << scene.heidelberg.modules << " modules, rotator "
       << scene.heidelberg.rotator_mhz << " MHz, DSP " << scene.heidelberg.dsp_mhz << " MHz)\n";
  for (const std::string& w : r.written) os << "wrote      " << w << "\n";
}

}  // namespace voxcast::cosim
