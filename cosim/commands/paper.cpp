// voxcast paper vizard2 --out DIR: the VIZARD II paper's oversampling experiment;
// voxcast paper engel2001 SCENE --out DIR: pre-integration's error budget.
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/explore/paper.hpp"
#include "cosim/explore/paper_engel2001.hpp"
#include "refmodel/error.hpp"

namespace voxcast::cosim::commands {

Subcommand add_paper(CLI::App& voxcast) {
  struct Args {
    std::string experiment, scene;
    paper::Vizard2Options options;
    ref::Overrides sets;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand(
      "paper",
      "Reproduce a paper's experiment as a Markdown report (vizard2: oversampling; "
      "engel2001: pre-integration's error budget on a scene)");
  cmd->add_option("experiment", a->experiment, "vizard2 or engel2001")->required();
  cmd->add_option("scene", a->scene, "engel2001: the scene file (TOML)");
  cmd->add_option("--out", a->options.out_dir, "Output folder (report.md, results.json, images)")
      ->required();
  cmd->add_option("--size", a->options.image_size, "Image width and height in pixels")
      ->capture_default_str();
  cmd->add_option("--volume-size", a->options.volume_size, "Tube phantom voxels per side")
      ->capture_default_str();
  cmd->add_option("--profile", a->options.profile, "Precision preset of the card")
      ->capture_default_str();
  cmd->add_option("--truth-oversampling", a->options.truth.oversampling,
                  "Oversampling of the truth (the float reference)")
      ->capture_default_str();
  add_set_option(*cmd, a->sets);
  return {cmd, [a] {
            if (a->experiment == "vizard2") {
              if (!a->scene.empty() || !a->sets.empty())
                throw Error("paper vizard2: the experiment has its own scene (no SCENE, no --set)");
              paper::print_vizard2_summary(std::cout, paper::run_vizard2(a->options));
              return 0;
            }
            if (a->experiment == "engel2001") {
              if (a->scene.empty()) throw Error("paper engel2001: a SCENE file is required");
              paper::Engel2001Options o;
              o.scene_file = a->scene;
              o.out_dir = a->options.out_dir;
              o.sets = a->sets;
              o.truth = a->options.truth;
              paper::print_engel2001_summary(std::cout, paper::run_engel2001(o));
              return 0;
            }
            throw Error("paper: unknown experiment \"" + a->experiment + "\" (vizard2, engel2001)");
          }};
}

}  // namespace voxcast::cosim::commands
