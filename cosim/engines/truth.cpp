#include "cosim/engines/truth.hpp"
#include "cosim/reports/files.hpp"
#include "cosim/reports/progress.hpp"

#include <toml++/toml.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
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
  // The truth is post-classified (issue 25): pre-integration is an
  // approximation of the same integral, measured against the same image.
  s.render.classification = ref::ClassificationMode::Post;
  return s;
}

std::string truth_key(const ref::Scene& scene, const TruthSettings& t) {
  toml::table root = toml::parse(ref::scene_to_toml(scene));
  root.erase("precision");
  root.erase("rtl");
  if (toml::table* render = root["render"].as_table())
    for (const char* k : {"oversampling", "ert_threshold", "threads", "jitter", "space_leaping",
                          "leap_block", "partial_segments", "classification"})
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
      const std::string path = dir_.empty() ? std::string() : truth_file(dir_, key);
      std::optional<ref::Image> image;
      if (!path.empty()) image = read_truth_file(path, key);
      if (!image && !render_missing_)
        throw TruthMissingError(
            "the truth " + (path.empty() ? std::string("image") : path) +
            " is not in the truth cache, and this run only reads it (--truth-from-cache; on a "
            "cluster the truth job renders it: did it finish?)");
      if (!image) {
        image = render_truth(scene, sv, t);
        {
          const std::lock_guard lock(mutex_);
          ++renders_;
        }
        if (!path.empty()) {
          // The disk copy saves later runs a render; without it this run
          // loses nothing, so a folder that cannot be written is a warning.
          try {
            make_parent_dir(path);
            write_truth_file(path, key, *image);
          } catch (const Error& e) {
            std::cerr << "voxcast: warning: the truth is not kept on disk: " << e.what() << "\n";
          }
        }
      }
      promise.set_value(std::make_shared<const ref::Image>(std::move(*image)));
    } catch (...) {
      promise.set_exception(std::current_exception());
    }
  }
  return future.get();
}

std::size_t TruthCache::renders() const {
  const std::lock_guard lock(mutex_);
  return renders_;
}

std::size_t TruthCache::images() const {
  const std::lock_guard lock(mutex_);
  return images_.size();
}

namespace {

constexpr char kTruthMagic[] = "voxcast truth 1\n";

std::uint64_t fnv1a64(const std::string& text) {
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

std::string truth_file(const std::string& dir, const std::string& key) {
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.truth",
                static_cast<unsigned long long>(fnv1a64(key)));
  return (std::filesystem::path(dir) / name).string();
}

// Layout: the magic line, the key's length and bytes, width and height (int32),
// then width x height x 4 doubles (r, g, b, alpha), all in the machine's byte order.
std::optional<ref::Image> read_truth_file(const std::string& path, const std::string& key) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::string magic(sizeof kTruthMagic - 1, '\0');
  std::uint64_t key_size = 0;
  in.read(magic.data(), static_cast<std::streamsize>(magic.size()));
  in.read(reinterpret_cast<char*>(&key_size), sizeof key_size);
  if (!in || magic != kTruthMagic || key_size != key.size()) return std::nullopt;
  std::string stored(key_size, '\0');
  std::int32_t w = 0, h = 0;
  in.read(stored.data(), static_cast<std::streamsize>(key_size));
  in.read(reinterpret_cast<char*>(&w), sizeof w);
  in.read(reinterpret_cast<char*>(&h), sizeof h);
  if (!in || stored != key || w <= 0 || h <= 0) return std::nullopt;
  ref::Image image(w, h);
  in.read(reinterpret_cast<char*>(image.pixels.data()),
          static_cast<std::streamsize>(image.pixels.size() * sizeof(glm::dvec4)));
  if (!in || in.peek() != std::char_traits<char>::eof()) return std::nullopt;
  return image;
}

void write_truth_file(const std::string& path, const std::string& key, const ref::Image& image) {
  std::string bytes = kTruthMagic;
  const std::uint64_t key_size = key.size();
  const std::int32_t w = image.width, h = image.height;
  bytes.append(reinterpret_cast<const char*>(&key_size), sizeof key_size);
  bytes += key;
  bytes.append(reinterpret_cast<const char*>(&w), sizeof w);
  bytes.append(reinterpret_cast<const char*>(&h), sizeof h);
  bytes.append(reinterpret_cast<const char*>(image.pixels.data()),
               image.pixels.size() * sizeof(glm::dvec4));
  write_file_atomically(path, bytes);
}

}  // namespace voxcast::cosim
