#include "rtl_model/bench/calibration.hpp"

#include <chrono>
#include <ctime>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/error.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "refmodel/volume/gradients.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::rtl::bench {
namespace {

// The 256^3 view of the default scene (scenes/default.toml, eye and centre
// scaled from its 128^3 phantom), the whole volume, 1 sample per voxel, no ERT.
ref::Scene baseline(const ref::Overrides& more) {
  ref::Overrides o = {"precision.profile=vizard2",
                      "volume.source=phantom:shepp-logan?size=256",
                      "volume.crop.lo=[0, 0, 0]",
                      "volume.crop.hi=[255, 255, 255]",
                      "camera.eye=[127.5, -300.0, 520.0]",
                      "camera.center=[127.5, 127.5, 127.5]",
                      "render.width=256",
                      "render.height=256",
                      "render.oversampling=1",
                      "render.ert_threshold=1"};
  o.insert(o.end(), more.begin(), more.end());
  return ref::default_scene(o);
}

ref::Overrides parallel_along(int axis) {
  const char* eye[3] = {"camera.eye=[-300.0, 127.5, 127.5]", "camera.eye=[127.5, -300.0, 127.5]",
                        "camera.eye=[127.5, 127.5, -300.0]"};
  return {"camera.projection=parallel", "camera.height=256", eye[axis],
          axis == 2 ? "camera.up=[0.0, 1.0, 0.0]" : "camera.up=[0.0, 0.0, 1.0]"};
}

ref::Scene endoscopy(double oversampling) {
  return ref::load_scene_file(VOXCAST_RTL_SOURCE_DIR "/scenes/endoscopy.toml",
                              {"precision.profile=vizard2",
                               "render.oversampling=" + std::to_string(oversampling)});
}

}  // namespace

std::vector<CalibrationPoint> calibration_points() {
  return {
      {"baseline-256-perspective",
       "paper: 256^3 at one sample per voxel, 5 fps, 12.7 ns per sample", baseline({})},
      {"baseline-256-x", "as baseline, parallel along +x", baseline(parallel_along(0))},
      {"baseline-256-y", "as baseline, parallel along +y", baseline(parallel_along(1))},
      {"baseline-256-z", "as baseline, parallel along +z", baseline(parallel_along(2))},
      {"endoscopy-ert-1x", "paper: opaque endoscopic views with ERT well above 20 fps",
       endoscopy(1.0)},
      {"endoscopy-ert-4x", "paper: with 4x oversampling about 5 fps", endoscopy(4.0)},
  };
}

CalibrationPoint calibration_point(const std::string& name) {
  std::string known;
  for (CalibrationPoint& p : calibration_points()) {
    if (p.name == name) return p;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  throw Error("unknown calibration point '" + name + "' (known: " + known + ")");
}

double CalibrationResult::samples_per_host_second() const {
  return simulate_seconds <= 0.0 ? 0.0 : static_cast<double>(stats.samples) / simulate_seconds;
}

CalibrationResult run_calibration(const CalibrationPoint& point, const RtlConfig& config) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const ref::Scene& s = point.scene;
  const ref::Volume volume = ref::load_volume(s.volume.source, s.base_dir,
                                              s.volume.raw ? &*s.volume.raw : nullptr);
  const ref::GradientField gradients = ref::compute_gradients(volume, s.volume.gradient);
  const ref::RenderInputs in = ref::make_render_inputs(s, volume, gradients, s.camera.pose);
  const bittrue::FrameSetup setup = bittrue::make_frame_setup(s.precision, s, in);
  const bittrue::VoxelMemory memory = bittrue::make_voxel_memory(s.precision, volume, gradients);
  const auto t1 = Clock::now();
  const std::clock_t c1 = std::clock();
  CalibrationResult r;
  r.name = point.name;
  r.stats = rtl_render(setup, memory, config).stats;
  const std::clock_t c2 = std::clock();
  const auto t2 = Clock::now();
  r.simulate_cpu_seconds = static_cast<double>(c2 - c1) / CLOCKS_PER_SEC;
  r.setup_seconds = std::chrono::duration<double>(t1 - t0).count();
  r.simulate_seconds = std::chrono::duration<double>(t2 - t1).count();
  return r;
}

}  // namespace voxcast::rtl::bench
