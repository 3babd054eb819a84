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
    std::string reuse = "cache";
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
  cmd->add_option("--channel-run", a->options.channel_layout,
                  "Run this layout's fetches (e.g. 4x2x2-skewed-blocks) through the board's DDR4 "
                  "channels for each number of pipelines");
  cmd->add_option("--reuse", a->reuse, "The channel run's reuse scheme: none, ray or cache")
      ->check(CLI::IsMember({"none", "ray", "cache"}))
      ->capture_default_str();
  cmd->add_option("--pipelines", a->options.pipelines,
                  "The channel run's numbers of pipelines (one sample a core clock each)")
      ->check(CLI::Range(1, 64))
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--core-mhz", a->options.core_mhz, "The pipelines' clock")
      ->check(CLI::Range(1.0, 2000.0))
      ->capture_default_str();
  cmd->add_option("--board", a->options.board,
                  "The channel run's board: a shipped name or a board .toml")
      ->capture_default_str();
  cmd->add_option("--queue", a->options.queue_depth, "The channel run's controller queue depth")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  add_set_option(*cmd, a->sets);
  return {cmd, [a] {
            a->options.channel_reuse = a->reuse == "none"  ? rtl::layout::Reuse::kNone
                                       : a->reuse == "ray" ? rtl::layout::Reuse::kRay
                                                           : rtl::layout::Reuse::kCache;
            const auto scene = ref::load_scene_file(a->scene, a->sets);
            print_burst_study(std::cout, run_burst_study(scene, a->options));
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
