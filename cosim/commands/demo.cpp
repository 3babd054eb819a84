// voxcast demo: the embedded default scene, no file needed (README command 1).
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/engines/render.hpp"

namespace voxcast::cosim::commands {

Subcommand add_demo(CLI::App& voxcast) {
  struct Args {
    ref::Overrides sets;
    std::string out = "out/demo";
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand("demo", "Render the embedded default scene (no file needed)");
  cmd->add_option("-o,--output", a->out,
                  "Output path without extension; writes OUT.png, OUT.exr and OUT.json")
      ->capture_default_str();
  add_set_option(*cmd, a->sets);
  return {cmd, [a] {
            const auto scene = ref::default_scene(a->sets);
            const RenderOptions options{{a->out + ".png", a->out + ".exr"}, a->out + ".json"};
            print_summary(std::cout, scene, run_render(scene, options));
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
