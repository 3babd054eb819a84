// The keys of the scene's [rtl] table (docs/scenes.md) in one list: the
// schema's accepted names (scene_toml.cpp), the scene writer's [rtl] section
// (scene_to_toml) and the reports' "rtl" object (cosim/reports/rtl_json.hpp) all
// visit this list, so a key added to RtlDesc is added here once.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "refmodel/scene/scene.hpp"

namespace voxcast::ref {

// Calls f(name, value) for every [rtl] key, in the documented order. `d` may
// be const or not (f may then assign the value).
template <typename Desc, typename F>
void for_each_rtl_key(Desc& d, F&& f) {
  f(std::string_view("board"), d.board);
  f(std::string_view("scheduler"), d.scheduler);
  f(std::string_view("reorder_window"), d.reorder_window);
  f(std::string_view("starvation_limit"), d.starvation_limit);
  f(std::string_view("refresh"), d.refresh);
  f(std::string_view("refresh_postpone"), d.refresh_postpone);
  f(std::string_view("sdram"), d.sdram);
  f(std::string_view("layout"), d.layout);
  f(std::string_view("brick"), d.brick);
  f(std::string_view("traversal"), d.traversal);
  f(std::string_view("tile"), d.tile);
  f(std::string_view("ray_slots"), d.ray_slots);
  f(std::string_view("issue"), d.issue);
  f(std::string_view("issue_burst"), d.issue_burst);
  f(std::string_view("issue_bypass_limit"), d.issue_bypass_limit);
  f(std::string_view("sample_buffer"), d.sample_buffer);
  f(std::string_view("queue_depth"), d.queue_depth);
  f(std::string_view("return_depth"), d.return_depth);
  f(std::string_view("auto_precharge"), d.auto_precharge);
  f(std::string_view("pipelines"), d.pipelines);
}

// The names alone.
inline std::vector<std::string> rtl_key_names() {
  std::vector<std::string> names;
  const RtlDesc d;
  for_each_rtl_key(d, [&](std::string_view k, const auto&) { names.emplace_back(k); });
  return names;
}

}  // namespace voxcast::ref
