// voxcast burst-study SCENE: the volume's layouts in 64-byte DDR4 bursts on a
// four-channel card, measured on the scene's samples (cosim/explore/burst_study.hpp).
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/explore/burst_study.hpp"

namespace voxcast::cosim::commands {

Subcommand add_burst_study(CLI::App& voxcast) {
  struct Args {
    std::string scene;
    BurstStudyOptions options;
    ref::Overrides sets;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand(
      "burst-study",
      "Bursts per sample of each layout of the volume in 64-byte DDR4 bursts on four channels "
      "(brick shape, bank groups, reuse), from the scene's own samples");
  cmd->add_option("scene", a->scene, "Scene file (TOML)")->required();
  cmd->add_option("--cache-lines", a->options.cache_lines,
                  "Lines per channel of the direct-mapped brick cache (a power of two)")
      ->check(CLI::Range(1u, 1u << 24))
      ->capture_default_str();
  cmd->add_option("--json", a->options.json, "Write the results as JSON here too");
  add_set_option(*cmd, a->sets);
  return {cmd, [a] {
            const auto scene = ref::load_scene_file(a->scene, a->sets);
            print_burst_study(std::cout, run_burst_study(scene, a->options));
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
