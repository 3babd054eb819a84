// The scene's [rtl] table in the reports (report.json of `voxcast cosim` and
// `voxcast render --engine rtl`): the keys as docs/scenes.md names them, so a
// sweep can read back what it set with --set rtl.KEY=VALUE. The key list is
// the scene's own (refmodel/scene/rtl_keys.hpp).
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "refmodel/scene/rtl_keys.hpp"
#include "refmodel/scene/scene.hpp"

namespace voxcast::cosim {

inline nlohmann::json rtl_desc_json(const ref::RtlDesc& d) {
  nlohmann::json j = nlohmann::json::object();
  ref::for_each_rtl_key(d, [&j](std::string_view key, const auto& value) { j[std::string(key)] = value; });
  return j;
}

}  // namespace voxcast::cosim
