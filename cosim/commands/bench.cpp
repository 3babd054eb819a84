// voxcast bench SCENE: samples per second of each engine.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/explore/bench.hpp"
#include "cosim/reports/files.hpp"

namespace voxcast::cosim::commands {

Subcommand add_bench(CLI::App& voxcast) {
  struct Args {
    std::string scene;
    std::vector<std::string> engines{"ref", "bittrue", "hls", "rtl"};
    int repeats = 5;
    std::string json;
    ref::Overrides sets;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand(
      "bench", "Measure samples per second of the engines on one scene (median of repeats)");
  cmd->add_option("scene", a->scene, "Scene file (TOML)")->required();
  cmd->add_option("--engines", a->engines, "Engines to time")->delimiter(',')->capture_default_str();
  cmd->add_option("--repeat", a->repeats, "Timed frames per engine")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--json", a->json, "Write the measurements as JSON here too");
  add_set_option(*cmd, a->sets);
  return {cmd, [a] {
            const auto scene = ref::load_scene_file(a->scene, a->sets);
            if (!a->json.empty()) make_parent_dir(a->json);  // before the work, not after
            const auto results = run_bench(scene, a->engines, a->repeats);
            print_bench(std::cout, scene, results);
            if (!a->json.empty()) write_json_file(a->json, bench_json(scene, results));
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
