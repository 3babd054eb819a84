#include "cosim/explore/bench.hpp"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <functional>
#include <iomanip>

#include <nlohmann/json.hpp>

#include "cosim/engines/render.hpp"
#include "cosim/engines/engines.hpp"
#include "cosim/engines/heidelberg.hpp"
#include "cosim/reports/progress.hpp"
#include "cosim/reports/stopwatch.hpp"
#include "refmodel/error.hpp"
#include "refmodel/parallel.hpp"
#include "refmodel/render/heidelberg/heidelberg.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/scene_config.hpp"
#include "rtl_model/virim/engine.hpp"

namespace voxcast::cosim {
namespace {

// What one frame did: its samples, and its simulated card cycles (rtl engine).
struct FrameWork {
  std::uint64_t samples = 0;
  std::uint64_t cycles = 0;
};

// The process's CPU time (every thread's), in seconds.
double cpu_seconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Median and minimum wall time, and median CPU time, of `repeats` runs of
// `frame` after one warm-up.
void time_frames(const std::function<FrameWork()>& frame, int repeats, BenchResult& r) {
  Progress progress("bench " + r.engine, static_cast<std::size_t>(repeats) + 1);
  const FrameWork warm = frame();  // warm-up (caches, page faults); also the counts
  r.samples = warm.samples;
  r.cycles = warm.cycles;
  progress.step();
  std::vector<double> wall, cpu;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = StopwatchClock::now();
    const double c0 = cpu_seconds();
    frame();
    cpu.push_back(cpu_seconds() - c0);
    wall.push_back(seconds_since(t0));
    progress.step();
  }
  r.median_seconds = median(wall);
  r.min_seconds = *std::min_element(wall.begin(), wall.end());
  r.median_cpu_seconds = median(cpu);
}

// VIRIM: voxels rotated and traced per host second; the rtl engine's are
// simulated voxels (its modules on the scene's threads).
std::vector<BenchResult> run_bench_heidelberg(const ref::Scene& scene,
                                              const std::vector<std::string>& engines, int repeats) {
  const SceneVolume sv = load_scene_volume(scene);
  const HeidelbergProfile profile = bittrue::heidelberg_profile(scene);
  const double eye = ref::heidelberg::eye_offsets(scene.heidelberg).front();
  const bittrue::VirimSetup setup = bittrue::make_virim_setup(profile, scene, sv.volume, eye);
  const bittrue::VirimMemory memory = bittrue::make_virim_memory(sv.volume);
  const std::uint64_t voxels = static_cast<std::uint64_t>(setup.W) *
                               static_cast<std::uint64_t>(setup.D) *
                               static_cast<std::uint64_t>(setup.H);
  const int threads = scene.render.threads;
  const rtl::virim::VirimRtlConfig rtl_config = rtl::virim::virim_rtl_config(scene.heidelberg);
  std::vector<BenchResult> out;
  for (const std::string& name : engines) {
    const Engine e = parse_engine(name);
    BenchResult r;
    r.engine = name;
    time_frames([&] {
      if (e == Engine::Ref) {
        ref::heidelberg::render(scene, sv.volume, eye, threads);
      } else if (e == Engine::BitTrue) {
        bittrue::bt_render_heidelberg(setup, memory, threads);
      } else if (e == Engine::Hls) {
        hls_render_heidelberg(setup, memory, threads);
      } else {
        return FrameWork{voxels,
                         rtl::virim::virim_rtl_render(setup, memory, rtl_config, threads).stats.cycles};
      }
      return FrameWork{voxels, 0};
    }, repeats, r);
    out.push_back(r);
  }
  return out;
}

}  // namespace

std::vector<BenchResult> run_bench(const ref::Scene& scene, const std::vector<std::string>& engines,
                                   int repeats) {
  if (repeats < 1) throw Error("bench: --repeat must be at least 1");
  if (scene.algorithm == ref::Algorithm::Heidelberg) return run_bench_heidelberg(scene, engines, repeats);
  const SceneVolume sv = load_scene_volume(scene);
  const ref::CameraPose pose = ref::frame_poses(scene.camera, 1).front();
  const ref::RenderInputs in = ref::make_render_inputs(scene, sv.volume, sv.gradients, pose);
  const int threads = scene.render.threads;
  std::vector<BenchResult> out;
  for (const std::string& name : engines) {
    const Engine e = parse_engine(name);
    BenchResult r;
    r.engine = name;
    if (e == Engine::Ref) {
      time_frames([&] {
        ref::FrameStats fs;
        ref::render_image(in, threads, &fs);
        return FrameWork{fs.samples, 0};
      }, repeats, r);
    } else {
      check_fixed_point(scene, sv, e != Engine::BitTrue);
      const bittrue::FrameSetup setup = bittrue::make_frame_setup(scene.precision, scene, in);
      const bittrue::VoxelMemory memory =
          bittrue::make_voxel_memory(scene.precision, sv.volume, sv.gradients);
      time_frames([&] {
        ref::FrameStats fs;
        if (e == Engine::Hls) {
          hls_render_image(setup, memory, threads, &fs);
        } else if (e == Engine::Rtl) {
          // Simulated samples and card cycles (the simulation is one thread).
          const rtl::RtlStats st = rtl::rtl_render(setup, memory, rtl::rtl_config(scene.rtl)).stats;
          return FrameWork{st.samples, static_cast<std::uint64_t>(st.cycles)};
        } else {
          bittrue::bt_render_image(setup, memory, threads, &fs);
        }
        return FrameWork{fs.samples, 0};
      }, repeats, r);
    }
    out.push_back(r);
  }
  return out;
}

void print_bench(std::ostream& os, const ref::Scene& scene, const std::vector<BenchResult>& rs) {
  // VIRIM's unit of work is a rotated and traced voxel; its widths are its own profile.
  const bool voxels = scene.algorithm == ref::Algorithm::Heidelberg;
  os << "scene    " << scene.origin << " (" << scene.render.width << "x" << scene.render.height << " ";
  if (voxels)
    os << "Heidelberg model, profile virim";
  else
    os << ref::to_string(scene.render.mode) << ", oversampling " << scene.render.oversampling
       << ", profile " << scene.precision_name;
  os << ", " << ref::worker_count(scene.render.threads) << " threads)\n";
  os << std::left << std::setw(10) << "engine" << std::right << std::setw(14)
     << (voxels ? "voxels" : "samples") << std::setw(12) << "median s" << std::setw(12) << "min s"
     << std::setw(12) << "CPU s" << std::setw(14) << (voxels ? "M voxels/s" : "M samples/s")
     << std::setw(12) << (voxels ? "ns/voxel" : "ns/sample") << std::setw(10) << "vs ref\n";
  double ref_rate = 0.0;
  for (const BenchResult& r : rs)
    if (r.engine == "ref") ref_rate = r.samples_per_second();
  os << std::fixed;
  for (const BenchResult& r : rs) {
    const double rate = r.samples_per_second();
    os << std::left << std::setw(10) << r.engine << std::right << std::setw(14) << r.samples
       << std::setprecision(3) << std::setw(12) << r.median_seconds << std::setw(12)
       << r.min_seconds << std::setw(12) << r.median_cpu_seconds << std::setprecision(2)
       << std::setw(14) << rate / 1e6 << std::setw(12) << (rate > 0 ? 1e9 / rate : 0.0);
    // Without the ref engine in the run there is nothing to compare with.
    if (ref_rate > 0)
      os << std::setw(9) << rate / ref_rate << "x\n";
    else
      os << std::setw(10) << "-" << "\n";
  }
  // The cycle model's own measure: what it simulates per CPU second.
  for (const BenchResult& r : rs)
    if (r.cycles > 0)
      os << r.engine << " simulates " << std::setprecision(2) << r.samples_per_cpu_second() / 1e6
         << " M " << (voxels ? "voxels" : "samples") << " and " << r.cycles_per_cpu_second() / 1e6
         << " M card cycles per CPU second (" << r.cycles << " cycles per frame)\n";
  os.unsetf(std::ios::fixed);
}

nlohmann::json bench_json(const ref::Scene& scene, const std::vector<BenchResult>& rs) {
  nlohmann::json engines = nlohmann::json::array();
  for (const BenchResult& r : rs)
    engines.push_back({{"engine", r.engine},
                       {"samples", r.samples},
                       {"cycles", r.cycles},
                       {"median_seconds", r.median_seconds},
                       {"min_seconds", r.min_seconds},
                       {"median_cpu_seconds", r.median_cpu_seconds},
                       {"samples_per_second", r.samples_per_second()},
                       {"samples_per_cpu_second", r.samples_per_cpu_second()},
                       {"cycles_per_cpu_second", r.cycles_per_cpu_second()}});
  return {{"scene", scene.origin},
          {"width", scene.render.width},
          {"height", scene.render.height},
          {"threads", ref::worker_count(scene.render.threads)},
          {"unit", scene.algorithm == ref::Algorithm::Heidelberg ? "voxels" : "samples"},
          {"engines", engines}};
}

}  // namespace voxcast::cosim
