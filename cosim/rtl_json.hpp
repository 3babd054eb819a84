// The scene's [rtl] table in the reports (report.json of `voxcast cosim` and
// `voxcast render --engine rtl`): the keys as docs/scenes.md names them, so a
// sweep can read back what it set with --set rtl.KEY=VALUE.
#pragma once

#include <nlohmann/json.hpp>

#include "refmodel/scene/scene.hpp"

namespace voxcast::cosim {

inline nlohmann::json rtl_desc_json(const ref::RtlDesc& d) {
  return {{"board", d.board},
          {"scheduler", d.scheduler},
          {"reorder_window", d.reorder_window},
          {"starvation_limit", d.starvation_limit},
          {"refresh", d.refresh},
          {"refresh_postpone", d.refresh_postpone},
          {"sdram", d.sdram},
          {"layout", d.layout},
          {"brick", d.brick},
          {"traversal", d.traversal},
          {"tile", d.tile},
          {"ray_slots", d.ray_slots},
          {"issue_burst", d.issue_burst},
          {"sample_buffer", d.sample_buffer},
          {"queue_depth", d.queue_depth},
          {"return_depth", d.return_depth}};
}

}  // namespace voxcast::cosim
