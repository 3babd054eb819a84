// voxcast synth-script SCENE --board BOARD --tool vitis --out DIR.
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/hardware/synth_script.hpp"
#include "rtl_model/board/board.hpp"

namespace voxcast::cosim::commands {

Subcommand add_synth_script(CLI::App& voxcast) {
  struct Args {
    std::string scene, board = "vizard2_pci", tool = "vitis", out, root = default_source_root();
    ref::Overrides sets;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand(
      "synth-script", "Write a vendor HLS script per top-level kernel for a scene and a board");
  cmd->add_option("scene", a->scene, "Scene file (TOML): its precision profile")->required();
  cmd->add_option("--board", a->board, "Shipped board name or a board .toml")->capture_default_str();
  cmd->add_option("--tool", a->tool, "vitis (Vitis HLS Tcl)")->capture_default_str();
  cmd->add_option("--out", a->out, "Output folder")->required();
  cmd->add_option("--source-dir", a->root, "The voxcast source tree the scripts name")
      ->capture_default_str();
  add_set_option(*cmd, a->sets);
  return {cmd, [a] {
            const auto scene = ref::load_scene_file(a->scene, a->sets);
            const auto board = rtl::board::load_board(a->board);
            for (const auto& path :
                 write_synth_scripts(scene, a->scene, board, a->tool, a->out, a->root))
              std::cout << "wrote " << path << "\n";
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
