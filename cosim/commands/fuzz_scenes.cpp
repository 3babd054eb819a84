// voxcast fuzz-scenes --seed S --scenes N [--size PX] [--out DIR].
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/verify/scene_fuzz.hpp"

namespace voxcast::cosim::commands {

Subcommand add_fuzz_scenes(CLI::App& voxcast) {
  auto options = std::make_shared<SceneFuzzOptions>();
  CLI::App* cmd = voxcast.add_subcommand(
      "fuzz-scenes", "Random valid scenes through float, bit-true and hls: engines must agree, and "
                     "the error must stay within the precision guard's bound (exit 7 on findings)");
  cmd->add_option("--seed", options->seed, "Seed of the scene stream")->capture_default_str();
  cmd->add_option("--scenes", options->scenes, "Scenes to run")->capture_default_str();
  cmd->add_option("--size", options->image_size, "Image width and height in pixels")
      ->capture_default_str();
  cmd->add_option("--out", options->out_dir, "Folder for the findings' scene files");
  return {cmd, [options] {
            const auto r = run_scene_fuzz(*options);
            print_scene_fuzz(std::cout, *options, r);
            return r.findings.empty() ? 0 : 7;
          }};
}

}  // namespace voxcast::cosim::commands
