// The points of `voxcast sweep`: the cartesian product of --vary axes, applied
// to a scene through the same `--set` overrides the other commands take
// (refmodel/scene/scene_toml.hpp), so every scene key can be swept.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "cosim/engines/truth.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace voxcast::cosim::sweep {

// One --vary: a scene key and its values, each as text for `--set KEY=VALUE`.
struct Axis {
  std::string key;
  std::vector<std::string> values;
};

// "KEY=V1,V2,..." where each Vi is a value or an integer range A..B (A <= B,
// both ends included). Commas inside [...] or "..." belong to the value
// (camera.eye=[1,2,3],[4,5,6] is two values). Throws voxcast::Error, one line,
// naming the spec: "--vary precision.weight_bits=8..3: range 8..3 is empty".
Axis parse_axis(const std::string& spec);

// --shard i/n: this run computes the points whose index % n == i (0 <= i < n);
// sweep-merge joins the n outputs. Round robin, so slow and fast regions of
// the product spread over the shards.
struct Shard {
  int index = 0;
  int count = 1;
  bool owns(std::size_t point) const {
    return point % static_cast<std::size_t>(count) == static_cast<std::size_t>(index);
  }
};
Shard parse_shard(const std::string& spec);

struct Plan {
  std::string scene_path;
  ref::Overrides sets;     // fixed --set overrides, applied before the axes
  std::vector<Axis> axes;  // the first varies slowest
  TruthSettings truth;
  std::string part = "xc7a200t";  // the part of the resource columns (--part; cosim/hardware/report.hpp)

  std::size_t size() const;  // the number of points (product of the axes' sizes)
  // Point `index` (0 <= index < size()): the value of each axis, in axis order.
  std::vector<std::string> values(std::size_t index) const;
  ref::Overrides overrides(std::size_t index) const;  // sets, then KEY=VALUE per axis
  ref::Scene scene(std::size_t index) const;          // the point's scene
};

// Checks the axes (at least one, no key twice, none also given by --set, at
// most kMaxPoints points) and parses every point's scene, so an unknown key or
// an out-of-range value is a one-line error before anything renders
// ("--vary precision.wieght_bits=3: unknown key precision.wieght_bits (did you
// mean precision.weight_bits?)").
Plan make_plan(const std::string& scene_path, const ref::Overrides& sets,
               const std::vector<std::string>& vary_specs, const TruthSettings& truth);

inline constexpr std::size_t kMaxPoints = 100000;

}  // namespace voxcast::cosim::sweep
