// The truth every accuracy figure of the tool is measured against: the float
// (double-precision) reference at high oversampling with early ray
// termination practically off, at the scene's camera, image size and transfer
// function (docs/accuracy.md, "The truth").
//
// Oversampling, bit widths and ERT are then judged on one scale: a point of a
// sweep that changes render.oversampling or render.ert_threshold is compared
// with the same truth as one that changes a width.
#pragma once

#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "cosim/engines/engines.hpp"
#include "refmodel/error.hpp"
#include "refmodel/render/image.hpp"
#include "refmodel/scene/scene.hpp"

namespace voxcast::cosim {

struct TruthSettings {
  double oversampling = 16.0;  // samples per world unit along the ray
};

// The truth's termination threshold: once the accumulated opacity reaches it,
// what the rest of the ray could add is below 1 - threshold = 2^-20 of full
// scale (2.4e-4 LSB at 8 output bits), so the truth is ERT-free to well below
// an LSB while opaque rays still stop.
inline constexpr double kTruthErtThreshold = 1.0 - 0x1p-20;

// Throws voxcast::Error unless 1 <= oversampling <= 64 and the truth samples
// at least as densely as the scene ("truth oversampling 8 is below the
// scene's render.oversampling 16").
void check_truth_settings(const TruthSettings& t, const ref::Scene& scene);

// The scene as the truth renders it: render.oversampling = t.oversampling,
// render.ert_threshold = kTruthErtThreshold; nothing else changes.
ref::Scene truth_scene(const ref::Scene& scene, const TruthSettings& t);

// A text that is equal for two scenes iff their truths are equal: the scene as
// TOML without what the truth does not depend on ([precision], an [rtl] table,
// render.oversampling, render.ert_threshold, render.threads) plus the truth
// settings. Everything else is kept, so a new scene key can cost a cache miss
// but never a stale truth.
std::string truth_key(const ref::Scene& scene, const TruthSettings& t);

// Renders the truth of the scene's first frame (camera pose or the path's first
// keyframe, mono), as `voxcast cosim` does. `row_done` as ref::render_image's
// (render_truth_with_progress passes a progress line's step).
ref::Image render_truth(const ref::Scene& scene, const SceneVolume& sv, const TruthSettings& t,
                        const std::function<void()>& row_done = {});

// render_truth with a progress line "truth" (rows done) on a terminal: the
// truth is the longest single render of a cosim or a tune (16x the scene's
// samples by default).
ref::Image render_truth_with_progress(const ref::Scene& scene, const SceneVolume& sv,
                                      const TruthSettings& t);

// Truth images shared by the points of a sweep: each distinct truth_key is
// rendered once, by the first caller; concurrent callers wait for it.
//
// With a folder (sweep --truth-cache, default OUT/truth), each truth is also
// kept on disk under its content hash, FNV-1a 64 of its truth_key:
// DIR/HASH.truth holds the key and the image's doubles bit for bit, so a
// later run or another shard that shares the folder reads it instead of
// rendering it again (a file whose key differs, a hash collision, is not
// used). Files are written whole and renamed into place: a run stopped
// mid-write leaves no truncated truth.
//
// Reading only (render_missing = false; sweep --truth-from-cache, the shards of
// a cluster run after its truth job): a truth missing from the folder is a
// TruthMissingError instead of a render.
class TruthCache {
 public:
  TruthCache() = default;
  explicit TruthCache(std::string dir, bool render_missing = true)
      : dir_(std::move(dir)), render_missing_(render_missing) {}
  std::shared_ptr<const ref::Image> get(const ref::Scene& scene, const SceneVolume& sv,
                                        const TruthSettings& t);
  std::size_t renders() const;  // truths this cache rendered (not read from disk)
  std::size_t images() const;   // distinct truths asked for (rendered or read)

 private:
  std::string dir_;
  bool render_missing_ = true;
  mutable std::mutex mutex_;
  std::map<std::string, std::shared_future<std::shared_ptr<const ref::Image>>> images_;
  std::size_t renders_ = 0;
};

// A truth a read-only TruthCache does not hold: the run cannot go on without
// it (a sweep's point catches voxcast::Error as "infeasible"; not this).
class TruthMissingError : public Error {
 public:
  using Error::Error;
};

// The truth file of `key` in `dir` (DIR/HASH.truth), and its reading and
// writing; read_truth_file returns nothing when the file is absent, is not
// a truth file, or holds another key.
std::string truth_file(const std::string& dir, const std::string& key);
std::optional<ref::Image> read_truth_file(const std::string& path, const std::string& key);
void write_truth_file(const std::string& path, const std::string& key, const ref::Image& image);

}  // namespace voxcast::cosim
