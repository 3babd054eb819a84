#include "rtl_model/bench/calibration.hpp"

#include <chrono>
#include <ctime>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/error.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "refmodel/volume/gradients.hpp"
#include "refmodel/volume/loaders.hpp"
#include "rtl_model/scene_config.hpp"

namespace voxcast::rtl::bench {
namespace {

// The default scene's view (scenes/default.toml, 128^3: eye (63.5, -150, 260),
// centre the volume centre) scaled to an n^3 phantom seen in n x n pixels: the
// eye at centre + (0, -427.5, 392.5) n/256, so every size sees the same share
// of the volume and each pixel covers the same share of a voxel; the whole
// volume, 1 sample per voxel, no ERT. n = 256 is the documented calibration.
ref::Scene baseline(int n, const ref::Overrides& more) {
  const double c = (n - 1) / 2.0, k = n / 256.0;
  const std::string size = std::to_string(n), last = std::to_string(n - 1);
  ref::Overrides o = {"precision.profile=vizard2",
                      "volume.source=phantom:shepp-logan?size=" + size,
                      "volume.crop.lo=[0, 0, 0]",
                      "volume.crop.hi=[" + last + ", " + last + ", " + last + "]",
                      "camera.eye=[" + std::to_string(c) + ", " + std::to_string(c - 427.5 * k) +
                          ", " + std::to_string(c + 392.5 * k) + "]",
                      "camera.center=[" + std::to_string(c) + ", " + std::to_string(c) + ", " +
                          std::to_string(c) + "]",
                      "render.width=" + size,
                      "render.height=" + size,
                      "render.oversampling=1",
                      "render.ert_threshold=1"};
  o.insert(o.end(), more.begin(), more.end());
  return ref::default_scene(o);
}

// Parallel, view height n, the eye 427.5 n/256 before the centre on `axis`.
ref::Overrides parallel_along(int n, int axis) {
  const double c = (n - 1) / 2.0;
  std::string eye[3];
  for (int a = 0; a < 3; ++a) {
    std::string p[3] = {std::to_string(c), std::to_string(c), std::to_string(c)};
    p[a] = std::to_string(c - 427.5 * n / 256.0);
    eye[a] = "camera.eye=[" + p[0] + ", " + p[1] + ", " + p[2] + "]";
  }
  return {"camera.projection=parallel", "camera.height=" + std::to_string(n), eye[axis],
          axis == 2 ? "camera.up=[0.0, 1.0, 0.0]" : "camera.up=[0.0, 0.0, 1.0]"};
}

ref::Scene endoscopy(double oversampling) {
  return ref::load_scene_file(VOXCAST_RTL_SOURCE_DIR "/scenes/endoscopy.toml",
                              {"precision.profile=vizard2",
                               "render.oversampling=" + std::to_string(oversampling)});
}

}  // namespace

std::vector<CalibrationPoint> baseline_points(int size) {
  if (size < 2) throw Error("calibration: baseline frames need a volume of at least 2^3");
  const std::string n = std::to_string(size), pre = "baseline-" + n + "-";
  return {
      {pre + "perspective",
       size == 256 ? "paper: 256^3 at one sample per voxel, 5 fps, 12.7 ns per sample"
                   : "as baseline-256-perspective at " + n + "^3, " + n + "x" + n + " pixels",
       baseline(size, {})},
      {pre + "x", "as baseline, parallel along +x", baseline(size, parallel_along(size, 0))},
      {pre + "y", "as baseline, parallel along +y", baseline(size, parallel_along(size, 1))},
      {pre + "z", "as baseline, parallel along +z", baseline(size, parallel_along(size, 2))},
  };
}

std::vector<CalibrationPoint> calibration_points() {
  std::vector<CalibrationPoint> points = baseline_points(256);
  points.push_back({"endoscopy-ert-1x", "paper: opaque endoscopic views with ERT well above 20 fps",
                    endoscopy(1.0)});
  points.push_back({"endoscopy-ert-4x", "paper: with 4x oversampling about 5 fps", endoscopy(4.0)});
  return points;
}

CalibrationPoint calibration_point(const std::string& name) {
  std::string known;
  for (CalibrationPoint& p : calibration_points()) {
    if (p.name == name) return p;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  throw Error("unknown calibration point '" + name + "' (known: " + known + ")");
}

RtlConfig row_hit_goal_config() {
  return rtl_config(ref::default_scene({"rtl.issue=row-hit", "rtl.issue_bypass_limit=4096",
                                        "rtl.ray_slots=32", "rtl.traversal=tiles", "rtl.tile=4",
                                        "rtl.layout=bricked-swizzled", "rtl.scheduler=lookahead",
                                        "rtl.auto_precharge=true"})
                        .rtl);
}

double CalibrationResult::samples_per_host_second() const {
  return simulate_seconds <= 0.0 ? 0.0 : static_cast<double>(stats.samples) / simulate_seconds;
}

CalibrationResult run_calibration(const CalibrationPoint& point, const RtlConfig& config) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const ref::Scene& s = point.scene;
  const ref::Volume volume =
      ref::load_volume(s.volume.source, s.base_dir, s.volume.raw ? &*s.volume.raw : nullptr,
                       {.resample = s.volume.resample});
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
