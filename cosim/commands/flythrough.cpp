// voxcast flythrough SCENE --out DIR: the camera path on the cycle model.
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/explore/flythrough.hpp"

namespace voxcast::cosim::commands {

Subcommand add_flythrough(CLI::App& voxcast) {
  struct Args {
    std::string scene;
    FlythroughOptions options;
    ref::Overrides sets;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand(
      "flythrough",
      "Fly along the scene's camera.path on the cycle model: frames, GIF, modelled frames/s");
  cmd->add_option("scene", a->scene, "Scene file with a camera.path (TOML)")->required();
  cmd->add_option("--out", a->options.out_dir, "Output folder")->required();
  cmd->add_option("--frames", a->options.frames,
                  "Frames along the path (default: render.frames if > 1, else 24)");
  cmd->add_option("--gif-fps", a->options.animation_fps, "Playback rate of the GIF (1..100)")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_option("--truth-oversampling", a->options.truth_oversampling,
                  "Oversampling of the truth the temporal stability is measured against "
                  "(0: no truth, the rendered frame-to-frame change only)")
      ->capture_default_str();
  add_set_option(*cmd, a->sets);
  return {cmd, [a] {
            const auto scene = ref::load_scene_file(a->scene, a->sets);
            print_flythrough(std::cout, scene, run_flythrough(scene, a->options));
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
