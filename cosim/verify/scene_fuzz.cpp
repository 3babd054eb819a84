#include "cosim/verify/scene_fuzz.hpp"
#include "cosim/reports/files.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <ostream>

#include "cosim/engines/engines.hpp"
#include "cosim/engines/warnings.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/geometry.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/presets.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace voxcast::cosim {
namespace {

// splitmix64: a fixed stream of 64-bit words per (seed, index).
class FuzzStream {
 public:
  FuzzStream(std::uint64_t seed, int index)
      : state_(seed * 0x9E3779B97F4A7C15ull + static_cast<std::uint64_t>(index) + 1) {}
  std::uint64_t next() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  double unit() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }  // [0, 1)
  double range(double lo, double hi) { return lo + (hi - lo) * unit(); }
  int pick(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
  bool chance(double p) { return unit() < p; }

 private:
  std::uint64_t state_;
};

// A transfer function over 8-bit phantom values: a transparent floor, one to
// three materials, sometimes a feature narrower than a table entry (a spike
// of width below one value) or a faint material.
std::vector<ref::TfPoint> random_tf(FuzzStream& s) {
  std::vector<ref::TfPoint> pts{{0.0, {1.0, 1.0, 1.0}, 0.0}};
  double v = s.range(5.0, 60.0);
  const int materials = 1 + s.pick(3);
  for (int m = 0; m < materials && v < 250.0; ++m) {
    const glm::dvec3 c{s.range(0.2, 1.0), s.range(0.2, 1.0), s.range(0.2, 1.0)};
    const int kind = s.pick(4);
    const double alpha = kind == 0 ? s.range(0.001, 0.05)   // faint
                         : kind == 1 ? s.range(0.5, 1.0)    // opaque
                                     : s.range(0.02, 0.5);
    if (kind == 3) {  // a spike narrower than one value
      const double w = s.range(0.1, 0.9);
      pts.push_back({v, c, 0.0});
      pts.push_back({v + w / 2, c, alpha});
      pts.push_back({v + w, c, 0.0});
      v += w + s.range(5.0, 60.0);
    } else {
      pts.push_back({v, c, alpha});
      v += s.range(5.0, 80.0);
    }
  }
  return pts;
}

// One width of a preset moved within its documented range (docs/scenes.md).
void vary_one_width(FuzzStream& s, PrecisionProfile& p) {
  switch (s.pick(5)) {
    case 0: p.alpha_bits = 6 + s.pick(11); break;       // 6..16
    case 1: p.tf_addr_bits = 6 + s.pick(7); break;      // 6..12
    case 2: p.rm_int_bits = s.pick(3); break;           // 0..2
    case 3: p.acc_bits = 8 + s.pick(13); break;         // 8..20
    default: p.sample_frac_bits = s.pick(9); break;     // 0..8
  }
}

double fuzz_percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size()))) - 1;
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

}  // namespace

ref::Scene random_scene(std::uint64_t seed, int index, int image_size) {
  FuzzStream s(seed, index);
  ref::Scene scene = ref::default_scene();
  scene.origin = "scene-fuzz seed " + std::to_string(seed) + " index " + std::to_string(index);
  static const char* const phantoms[] = {"shepp-logan", "shells", "tube", "box"};
  const int n = 12 + 4 * s.pick(4);  // 12..24 voxels per side
  scene.volume.source = std::string("phantom:") + phantoms[s.pick(4)] + "?size=" + std::to_string(n);
  scene.volume.crop.reset();
  scene.tf_points = random_tf(s);
  scene.tf_interpolation = s.chance(0.8) ? ref::TfInterpolation::Ramp : ref::TfInterpolation::Binary;
  scene.material = {s.range(0.0, 0.4), s.range(0.2, 0.9), s.range(0.0, 0.6), s.range(2.0, 60.0)};
  scene.lights.clear();
  const int lights = 1 + s.pick(3);
  for (int l = 0; l < lights; ++l) {
    ref::Light light;
    if (s.chance(0.5)) {
      light.type = ref::LightType::Directional;
      light.direction = {s.range(-1.0, 1.0), s.range(-1.0, 1.0), s.range(0.1, 1.0)};
    }
    light.intensity = s.range(0.2, 1.6);
    scene.lights.push_back(light);
  }
  const std::vector<std::string> presets = preset_names();
  scene.precision_name = presets[static_cast<std::size_t>(s.pick(static_cast<int>(presets.size())))];
  scene.precision = preset_profile(scene.precision_name);
  if (s.chance(0.3)) {
    vary_one_width(s, scene.precision);
    scene.precision_name += "+varied";
  }
  static const double oversamplings[] = {1.0, 2.0, 4.0, 8.0, 16.0};
  scene.render.oversampling = oversamplings[s.pick(5)];
  const int mode = s.pick(10);
  scene.render.mode = mode < 6 ? ref::RenderMode::Shaded
                      : mode < 9 ? ref::RenderMode::Unshaded
                                 : ref::RenderMode::Mip;
  scene.render.ert_threshold = s.chance(0.5) ? 1.0 : s.range(0.8, 1.0);
  scene.render.width = scene.render.height = image_size;
  scene.render.frames = 1;
  // The camera on a sphere around the volume's centre, looking at it.
  const double c = (n - 1) / 2.0;
  const double theta = s.range(0.0, 6.283185307179586), z = s.range(-0.8, 0.8);
  const double r = std::sqrt(1.0 - z * z), dist = s.range(1.6, 3.0) * n;
  scene.camera.path.clear();
  scene.camera.stereo_deg = 0.0;
  scene.camera.pose = {{c + dist * r * std::cos(theta), c + dist * r * std::sin(theta), c + dist * z},
                       {c, c, c},
                       {0.0, 0.0, 1.0}};
  if (s.chance(0.4)) {
    scene.camera.projection = ref::Projection::Parallel;
    scene.camera.height = 1.2 * n;
  } else {
    scene.camera.projection = ref::Projection::Perspective;
    scene.camera.fov_deg = 2.0 * std::atan(0.75 * n / dist) * 57.29577951308232;
  }
  return scene;
}

SceneVerdict judge_scene(const ref::Scene& scene, int threads) {
  SceneVerdict v;
  try {
    const SceneVolume sv = load_scene_volume(scene);
    v.hls_ran = hls_supports(scene.precision);
    check_fixed_point(scene, sv, v.hls_ran);
    const std::vector<Hazard> hazards = precision_hazards(scene, sv.volume);
    v.hazards = hazards.size();
    const double range = std::ldexp(1.0, scene.precision.out_bits) - 1.0;
    v.bound_lsb = kHazardFraction * range + largest_worst_lsb(hazards);
    const ref::RenderInputs in =
        ref::make_render_inputs(scene, sv.volume, sv.gradients, scene.camera.pose);
    const bittrue::FrameSetup setup = bittrue::make_frame_setup(scene.precision, scene, in);
    const bittrue::VoxelMemory memory =
        bittrue::make_voxel_memory(scene.precision, sv.volume, sv.gradients);
    const ref::Image truth = ref::render_image(in, threads);
    const ref::QuantImage bt = bittrue::bt_render_image(setup, memory, threads);
    if (v.hls_ran) v.bit_exact = hls_render_image(setup, memory, threads).pixels == bt.pixels;
    std::vector<double> errors;
    errors.reserve(bt.pixels.size() * 4);
    for (int y = 0; y < bt.height; ++y)
      for (int x = 0; x < bt.width; ++x) {
        // Geometry: a pixel whose fixed-point ray takes another number of
        // samples than the float ray (a grazing ray that hits in one engine
        // only, or a clip point on the other side of a sample) is bounded ray
        // by ray by the extremes suite, not by the guard.
        const auto seg = ref::clip(ref::primary_ray(in.camera, x, y), in.volume.world_box);
        const std::uint64_t n_float = seg ? ref::sample_count(*seg, in.settings.step) : 0;
        const bittrue::BtRay ray = bittrue::bt_ray_setup(setup, x, y);
        if ((ray.hit ? ray.n : 0) != n_float) {
          ++v.geometry_pixels;
          continue;
        }
        for (int ch = 0; ch < 4; ++ch)
          errors.push_back(std::abs(static_cast<double>(bt.at(x, y)[static_cast<std::size_t>(ch)]) -
                                    truth.at(x, y)[ch] * range));
      }
    v.error_lsb = fuzz_percentile(std::move(errors), 0.99);
  } catch (const Error& e) {
    v.feasible = false;
    v.refusal = e.what();
  }
  return v;
}

SceneFuzzResult run_scene_fuzz(const SceneFuzzOptions& o) {
  if (o.scenes < 1) throw Error("fuzz-scenes: --scenes must be at least 1");
  if (o.image_size < 1 || o.image_size > 256)
    throw Error("fuzz-scenes: --size must be in 1..256 (got " + std::to_string(o.image_size) + ")");
  SceneFuzzResult r;
  for (int i = 0; i < o.scenes; ++i) {
    const ref::Scene scene = random_scene(o.seed, i, o.image_size);
    const SceneVerdict v = judge_scene(scene, o.threads);
    ++r.scenes;
    if (!v.feasible) {
      ++r.infeasible;
      continue;
    }
    r.hazardous += v.hazards > 0;
    r.hls_ran += v.hls_ran;
    r.worst_ratio = std::max(r.worst_ratio, v.error_lsb / v.bound_lsb);
    if (!v.finding()) continue;
    SceneFuzzFinding f{i, {}, v};
    if (!o.out_dir.empty()) {
      make_output_dir(o.out_dir);
      f.scene_file = (std::filesystem::path(o.out_dir) /
                      ("scene_" + std::to_string(o.seed) + "_" + std::to_string(i) + ".toml"))
                         .string();
      std::ofstream out(f.scene_file);
      out << "# voxcast fuzz-scenes finding: seed " << o.seed << ", scene " << i << ": "
          << (v.bit_exact ? "" : "hls != bit-true; ") << "error " << v.error_lsb
          << " LSB (99th percentile) against the guard's bound " << v.bound_lsb << " LSB\n"
          << ref::scene_to_toml(scene);
      if (!out) throw Error("fuzz-scenes: cannot write " + f.scene_file);
    }
    r.findings.push_back(std::move(f));
  }
  return r;
}

void print_scene_fuzz(std::ostream& os, const SceneFuzzOptions& o, const SceneFuzzResult& r) {
  os << "fuzz-scenes: seed " << o.seed << ", " << r.scenes << " scenes of " << o.image_size << "x"
     << o.image_size << " pixels: " << r.infeasible << " refused by the widths, " << r.hazardous
     << " with precision hazards, " << r.hls_ran << " through the hls kernels; largest error / bound "
     << r.worst_ratio << "; " << r.findings.size() << " finding" << (r.findings.size() == 1 ? "" : "s")
     << "\n";
  for (const SceneFuzzFinding& f : r.findings)
    os << "  scene " << f.index << ": " << (f.verdict.bit_exact ? "" : "hls != bit-true; ")
       << "error " << f.verdict.error_lsb << " LSB > bound " << f.verdict.bound_lsb << " LSB"
       << (f.scene_file.empty() ? "" : " (" + f.scene_file + ")") << "\n";
}

}  // namespace voxcast::cosim
