// voxcast report SCENE [--part NAME] [--json FILE] [--md FILE]: operators,
// FPGA resources and latency of the units the scene elaborates; on a DDR4
// board (rtl.board = "alveo_u250") also the card's N pipelines, caches and
// controllers against the part (cosim/hardware/card_price.cpp).
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/hardware/report.hpp"
#include "cosim/reports/files.hpp"

namespace voxcast::cosim::commands {

Subcommand add_report(CLI::App& voxcast) {
  struct Args {
    std::string scene, part, json, md;
    ref::Overrides sets;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand(
      "report", "Operators per unit, FPGA resources and latency of the design the scene needs");
  cmd->add_option("scene", a->scene, "Scene file (TOML)")->required();
  cmd->add_option("--part", a->part,
                  "xcv1000e, xc2v3000, xc7a200t, xc7k325t or xcu250 (default: the board's part "
                  "for a DDR4 board, else xc7a200t)");
  cmd->add_option("--json", a->json, "Write the report as JSON here");
  cmd->add_option("--md", a->md, "Write the report as Markdown here (default: stdout)");
  add_set_option(*cmd, a->sets);
  return {cmd, [a] {
            const auto scene = ref::load_scene_file(a->scene, a->sets);
            // A DDR4 board's report prices the card on the board's own part
            // unless --part asks for another.
            const std::string part = a->part.empty() ? default_part(scene) : a->part;
            const auto r = estimate_resources(scene, find_part(part));
            const std::string md = report_markdown(r);
            if (!a->md.empty()) {
              write_text_file(a->md, md);
            } else {
              std::cout << md;
            }
            if (!a->json.empty()) write_text_file(a->json, report_json(r) + "\n");
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
