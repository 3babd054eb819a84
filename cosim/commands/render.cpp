// voxcast render SCENE -o OUT: one scene on one engine, images and a report.
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/engines/render.hpp"

namespace voxcast::cosim::commands {

Subcommand add_render(CLI::App& voxcast) {
  struct Args {
    std::string scene;
    ref::Overrides sets;
    RenderOptions options;
    std::string engine = "ref";
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand("render", "Render a scene file with the reference ray caster");
  cmd->add_option("scene", a->scene, "Scene file (TOML, see docs/scenes.md)")->required();
  cmd->add_option("-o,--output", a->options.outputs, "Output image(s): .png and/or .exr")->required();
  cmd->add_option("--report", a->options.report_json, "Write a JSON report here");
  cmd->add_flag("--strict", a->options.strict,
                "Refuse a scene with precision hazards (exit status 6) instead of warning");
  cmd->add_option("--engine", a->engine,
                  "ref (double), bittrue (bit-true reference), hls, or rtl (cycle model)")
      ->capture_default_str();
  cmd->add_option("--vcd", a->options.vcd_path,
                  "rtl engine: write a VCD trace (FIFO handshakes, SDRAM commands) of each frame "
                  "(a stereo pair or path: one file per view, named like the images)");
  cmd->add_option("--vcd-window", a->options.vcd_window,
                  "rtl engine: cycles START:END (inclusive) the VCD covers");
  add_set_option(*cmd, a->sets);
  return {cmd, [a] {
            const auto scene = ref::load_scene_file(a->scene, a->sets);
            a->options.engine = parse_engine(a->engine);
            print_summary(std::cout, scene, run_render(scene, a->options));
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
