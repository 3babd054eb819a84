#include "rtl_model/scene_config.hpp"

#include <algorithm>

#include "refmodel/error.hpp"
#include "rtl_model/board/board.hpp"
#include "rtl_model/board/board_config.hpp"
#include "rtl_model/sched/registry.hpp"

namespace voxcast::rtl {
namespace {

std::string join(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

const std::string& known(const char* key, const std::string& value,
                         const std::vector<std::string>& names) {
  if (std::find(names.begin(), names.end(), value) == names.end())
    throw Error(std::string("rtl.") + key + " = \"" + value + "\" is not known (known: " +
                join(names) + ")");
  return value;
}

// The card of the scene's board description: clocks, DIMMs and SDRAM timing.
RtlConfig board_config(const std::string& name_or_path) {
  try {
    return rtl_config_for_board(board::load_board(name_or_path));
  } catch (const Error& e) {
    throw Error(std::string("rtl.board = \"") + name_or_path + "\": " + e.what());
  }
}

// The SDRAM grades the card can run at its 100 MHz clock (sdram/timing.hpp),
// overriding the board's datasheet timing.
sdram::TimingNs sdram_preset(const std::string& name) {
  known("sdram", name, {"board", "pc100-cl2", "pc100-cl3"});
  return name == "pc100-cl2" ? sdram::presets::pc100_cl2() : sdram::presets::pc100_cl3();
}

// The DDR4 card's keys; those of the SDR card's word layout and issue
// variants do not apply to it (an error naming the key, not a silent
// default).
RtlConfig ddr4_card(const ref::RtlDesc& d, RtlConfig c) {
  const std::string board = " on the DDR4 board \"" + d.board + "\"";
  if (d.pipelines < 1 || d.pipelines > 64)
    throw Error("rtl.pipelines = " + std::to_string(d.pipelines) + " is out of range 1..64");
  if (d.sdram != "board")
    throw Error("rtl.sdram = \"" + d.sdram + "\" is an SDR preset; it does not apply" + board);
  if (d.layout != "linear")
    throw Error("rtl.layout = \"" + d.layout +
                "\" orders SDR words; the DDR4 card's bursts are 4x2x2-skewed-blocks" + board);
  if (d.brick != ref::RtlDesc{}.brick)
    throw Error("rtl.brick: bricks of SDR words; the DDR4 card's bursts are 4x2x2-skewed-blocks" +
                board);
  if (d.issue != "oldest" || d.issue_burst != 0)
    throw Error("rtl.issue = \"" + d.issue +
                "\", rtl.issue_burst = " + std::to_string(d.issue_burst) +
                ": the DDR4 card issues from the oldest ray to its end (\"oldest\", 0)" + board);
  c.card.pipelines = d.pipelines;
  return c;
}

}  // namespace

RtlConfig rtl_config(const ref::RtlDesc& d) {
  RtlConfig c = board_config(d.board);
  c.scheduler = known("scheduler", d.scheduler, sched::scheduler_names());
  c.refresh = known("refresh", d.refresh, sched::refresh_policy_names());
  c.mapping.name = known("layout", d.layout, layout::mapping_names());
  for (std::size_t i = 0; i < 3; ++i) {
    if (d.brick[i] < 1) throw Error("rtl.brick: edges must be at least 1");
    c.mapping.brick[i] = static_cast<std::uint32_t>(d.brick[i]);
  }
  pipeline::PipelineConfig& p = c.pipeline;
  p.traversal = pipeline::parse_traversal(known("traversal", d.traversal, {"scanline", "tiles"}));
  p.tile = d.tile;
  p.ray_slots = d.ray_slots;
  p.issue_burst = d.issue_burst;
  p.issue = pipeline::parse_issue_policy(known("issue", d.issue, pipeline::issue_policy_names()));
  p.issue_bypass_limit = d.issue_bypass_limit;
  p.sample_buffer = d.sample_buffer;
  if (d.queue_depth < 1 || d.return_depth < 1)
    throw Error("rtl.queue_depth and rtl.return_depth must be at least 1");
  p.controller.queue_depth = static_cast<std::size_t>(d.queue_depth);
  p.controller.return_depth = static_cast<std::size_t>(d.return_depth);
  p.controller.auto_precharge = d.auto_precharge;
  p.scheduler_params.reorder_window = d.reorder_window;
  p.scheduler_params.starvation_limit = d.starvation_limit;
  p.dimm.refresh_postpone_limit = d.refresh_postpone;
  if (c.card.enabled) return ddr4_card(d, c);
  if (d.pipelines != 1)
    throw Error("rtl.pipelines = " + std::to_string(d.pipelines) +
                ": the SDR card (rtl.board = \"" + d.board +
                "\") has one pipeline; more run on a DDR4 board");
  if (d.sdram != "board") p.dimm.timing = sdram_preset(d.sdram);
  return c;
}

}  // namespace voxcast::rtl
