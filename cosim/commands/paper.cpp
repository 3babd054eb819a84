// voxcast paper vizard2 --out DIR: the paper's oversampling experiment.
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/explore/paper.hpp"
#include "refmodel/error.hpp"

namespace voxcast::cosim::commands {

Subcommand add_paper(CLI::App& voxcast) {
  struct Args {
    std::string experiment;
    paper::Vizard2Options options;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand(
      "paper", "Reproduce a paper's experiment as a Markdown report (vizard2: oversampling)");
  cmd->add_option("experiment", a->experiment, "vizard2")->required();
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
  return {cmd, [a] {
            if (a->experiment != "vizard2")
              throw Error("paper: unknown experiment \"" + a->experiment + "\" (vizard2)");
            paper::print_vizard2_summary(std::cout, paper::run_vizard2(a->options));
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
