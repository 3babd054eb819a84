// voxcast tune SCENE --target-psnr DB: the cheapest precision meeting a target.
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/explore/tune.hpp"

namespace voxcast::cosim::commands {

Subcommand add_tune(CLI::App& voxcast) {
  // A finite number above 0 (CLI::Range lets NaN through: it compares).
  static const CLI::Validator positive_finite(
      [](std::string& text) -> std::string {
        try {
          std::size_t used = 0;
          const double v = std::stod(text, &used);
          if (used == text.size() && std::isfinite(v) && v > 0.0) return "";
        } catch (const std::exception&) {
        }
        return "must be a finite number above 0, not '" + text + "'";
      },
      "NUMBER > 0");
  struct Args {
    std::string scene;
    std::vector<std::string> vary;
    TuneOptions options;
    ref::Overrides sets;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand(
      "tune", "Cheapest precision widths (resource model) meeting a PSNR target (bit-true engine)");
  cmd->add_option("scene", a->scene, "Scene file (TOML)")->required();
  cmd->add_option("--target-psnr", a->options.target_psnr_db,
                  "Target PSNR in dB against the truth (exit status 5 when no point meets it)")
      ->required()
      ->check(positive_finite);
  cmd->add_option("--truth-oversampling", a->options.truth.oversampling,
                  "Oversampling of the truth (the float reference)")
      ->capture_default_str();
  cmd->add_option("--part", a->options.part, "Part whose capacity prices the resources")
      ->capture_default_str();
  cmd->add_option("--vary", a->vary,
                  "Search axis FIELD=LO..HI (repeatable; default: docs/resources.md)");
  cmd->add_flag("--prune", a->options.prune,
                "Skip points below per-axis floors (assumes accuracy monotone in each width; "
                "the answer may then not be the cheapest)");
  add_set_option(*cmd, a->sets);
  return {cmd, [a] {
            const auto scene = ref::load_scene_file(a->scene, a->sets);
            for (const std::string& v : a->vary) a->options.axes.push_back(parse_tune_axis(v));
            const auto r = run_tune(scene, a->options);
            print_tune(std::cout, scene, a->options, r);
            return r.found ? 0 : 5;
          }};
}

}  // namespace voxcast::cosim::commands
