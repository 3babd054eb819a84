#include "cosim/engines/truth.hpp"
#include "cosim/reports/progress.hpp"

#include <toml++/toml.h>

#include <sstream>

#include "refmodel/error.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace voxcast::cosim {
namespace {

std::string fmt(double v) {
  std::ostringstream os;
  os.precision(17);
  os << v;
  return os.str();
}

}  // namespace

void check_truth_settings(const TruthSettings& t, const ref::Scene& scene) {
  if (!(t.oversampling >= 1.0 && t.oversampling <= 64.0))
    throw Error("truth oversampling " + fmt(t.oversampling) + " is outside [1, 64]");
  if (t.oversampling < scene.render.oversampling)
    throw Error("truth oversampling " + fmt(t.oversampling) + " is below the scene's " +
                "render.oversampling " + fmt(scene.render.oversampling) +
                ": the truth must sample at least as densely as the image it judges");
}

ref::Scene truth_scene(const ref::Scene& scene, const TruthSettings& t) {
  ref::Scene s = scene;
  s.render.oversampling = t.oversampling;
  s.render.ert_threshold = kTruthErtThreshold;
  // The truth samples every ray from its entry (no jitter); space leaping
  // would not change it (docs/leaping.md) and is left off.
  s.render.jitter = false;
  s.render.space_leaping = false;
  // One truth for a scene with and without render.partial_segments (so the two
  // are measured against the same image, docs/accuracy.md): whole steps from
  // the entry, as before the key existed; at the truth's oversampling its own
  // end segments are 1/oversampling of a scene step.
  s.render.partial_segments = false;
  return s;
}

std::string truth_key(const ref::Scene& scene, const TruthSettings& t) {
  toml::table root = toml::parse(ref::scene_to_toml(scene));
  root.erase("precision");
  root.erase("rtl");
  if (toml::table* render = root["render"].as_table())
    for (const char* k : {"oversampling", "ert_threshold", "threads", "jitter", "space_leaping",
                          "leap_block", "partial_segments"})
      render->erase(k);
  std::ostringstream os;
  os << root << "\n# truth oversampling " << fmt(t.oversampling) << ", ERT "
     << fmt(kTruthErtThreshold) << "\n";
  return os.str();
}

ref::Image render_truth(const ref::Scene& scene, const SceneVolume& sv, const TruthSettings& t,
                        const std::function<void()>& row_done) {
  check_truth_settings(t, scene);
  const ref::Scene ts = truth_scene(scene, t);
  const ref::CameraPose pose = ref::frame_poses(ts.camera, 1).front();
  const ref::RenderInputs in = ref::make_render_inputs(ts, sv.volume, sv.gradients, pose);
  return ref::render_image(in, ts.render.threads, nullptr, row_done);
}

ref::Image render_truth_with_progress(const ref::Scene& scene, const SceneVolume& sv,
                                      const TruthSettings& t) {
  Progress progress("truth", static_cast<std::size_t>(scene.render.height));
  return render_truth(scene, sv, t, [&progress] { progress.step(); });
}

std::shared_ptr<const ref::Image> TruthCache::get(const ref::Scene& scene, const SceneVolume& sv,
                                                  const TruthSettings& t) {
  check_truth_settings(t, scene);
  const std::string key = truth_key(scene, t);
  std::promise<std::shared_ptr<const ref::Image>> promise;
  std::shared_future<std::shared_ptr<const ref::Image>> future;
  bool mine = false;
  {
    const std::lock_guard lock(mutex_);
    auto it = images_.find(key);
    if (it == images_.end()) {
      future = promise.get_future().share();
      images_.emplace(key, future);
      mine = true;
    } else {
      future = it->second;
    }
  }
  if (mine) {
    try {
      promise.set_value(std::make_shared<const ref::Image>(render_truth(scene, sv, t)));
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
  }
  return future.get();
}

std::size_t TruthCache::renders() const {
  const std::lock_guard lock(mutex_);
  return images_.size();
}

}  // namespace voxcast::cosim
