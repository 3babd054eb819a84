#include "cosim/bench.hpp"
#include "cosim/progress.hpp"

#include <algorithm>
#include <chrono>
#include <functional>
#include <iomanip>

#include "cosim/commands.hpp"
#include "cosim/engines.hpp"
#include "cosim/heidelberg.hpp"
#include "cosim/stopwatch.hpp"
#include "refmodel/error.hpp"
#include "refmodel/parallel.hpp"
#include "refmodel/render/heidelberg/heidelberg.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/scene_config.hpp"
#include "rtl_model/virim/engine.hpp"

namespace voxcast::cosim {
namespace {


// Median and minimum wall time of `repeats` runs of `frame` after one warm-up.
void time_frames(const std::function<std::uint64_t()>& frame, int repeats, BenchResult& r) {
  Progress progress("bench " + r.engine, static_cast<std::size_t>(repeats) + 1);
  r.samples = frame();  // warm-up (caches, page faults); also the sample count
  progress.step();
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = StopwatchClock::now();
    frame();
    t.push_back(seconds_since(t0));
    progress.step();
  }
  std::sort(t.begin(), t.end());
  r.median_seconds = t[t.size() / 2];
  r.min_seconds = t.front();
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
      if (e == Engine::Ref) ref::heidelberg::render(scene, sv.volume, eye, threads);
      else if (e == Engine::BitTrue) bittrue::bt_render_heidelberg(setup, memory, threads);
      else if (e == Engine::Hls) hls_render_heidelberg(setup, memory, threads);
      else rtl::virim::virim_rtl_render(setup, memory, rtl_config, threads);
      return voxels;
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
        return fs.samples;
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
          // Simulated samples per host second (the simulation is one thread).
          return rtl::rtl_render(setup, memory, rtl::rtl_config(scene.rtl)).stats.samples;
        } else {
          bittrue::bt_render_image(setup, memory, threads, &fs);
        }
        return fs.samples;
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
     << std::setw(14) << (voxels ? "M voxels/s" : "M samples/s") << std::setw(12)
     << (voxels ? "ns/voxel" : "ns/sample") << std::setw(10) << "vs ref\n";
  double ref_rate = 0.0;
  for (const BenchResult& r : rs)
    if (r.engine == "ref") ref_rate = r.samples_per_second();
  os << std::fixed;
  for (const BenchResult& r : rs) {
    const double rate = r.samples_per_second();
    os << std::left << std::setw(10) << r.engine << std::right << std::setw(14) << r.samples
       << std::setprecision(3) << std::setw(12) << r.median_seconds << std::setw(12)
       << r.min_seconds << std::setprecision(2) << std::setw(14) << rate / 1e6 << std::setw(12)
       << (rate > 0 ? 1e9 / rate : 0.0);
    // Without the ref engine in the run there is nothing to compare with.
    if (ref_rate > 0)
      os << std::setw(9) << rate / ref_rate << "x\n";
    else
      os << std::setw(10) << "-" << "\n";
  }
}

}  // namespace voxcast::cosim
