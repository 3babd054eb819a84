// voxcast cosim SCENE --out DIR: every engine on one scene, their agreement
// proven and their error against the truth measured.
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/engines/cosim.hpp"
#include "cosim/explore/pages.hpp"
#include "cosim/reports/files.hpp"
#include "cosim/reports/junit.hpp"

namespace voxcast::cosim::commands {

Subcommand add_cosim(CLI::App& voxcast) {
  struct Args {
    std::string scene, out, junit;
    ref::Overrides sets;
    TruthSettings truth;
    bool strict = false, html = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand(
      "cosim", "Run float, bit-true and hls engines; prove hls == bit-true; measure the error");
  cmd->add_option("scene", a->scene, "Scene file (TOML)")->required();
  cmd->add_option("--out", a->out, "Output folder (report.json, layers.exr, PNGs)")->required();
  cmd->add_option("--junit", a->junit,
                  "Write the engine pairs' verdicts as JUnit XML here (Jenkins, GitLab)");
  cmd->add_flag("--html", a->html,
                "Write OUT/cosim.html: images, error histogram, divergence trace, cycles, resources");
  add_set_option(*cmd, a->sets);
  cmd->add_flag("--strict", a->strict,
                "Refuse a scene with precision hazards (exit status 6) instead of warning");
  cmd->add_option("--truth-oversampling", a->truth.oversampling,
                  "Oversampling of the truth (the float reference) for report.json's truth section")
      ->capture_default_str();
  return {cmd, [a] {
            const auto scene = ref::load_scene_file(a->scene, a->sets);
            if (!a->junit.empty()) make_parent_dir(a->junit);  // before the work, not after
            const auto r = run_cosim(scene, a->out, a->truth, a->strict);
            print_cosim_summary(std::cout, scene, r);
            if (!a->junit.empty()) write_junit_file(a->junit, cosim_junit(scene, r));
            if (a->html) {
              const std::string page = (std::filesystem::path(a->out) / "cosim.html").string();
              write_text_file(page, cosim_page(scene, r, a->out));
              std::cout << "wrote      " << page << "\n";
            }
            if (!r.bit_exact) {
              std::cerr << "voxcast: " << r.mismatch.engine << " differs from "
                        << (r.mismatch.engine == "rtl" ? "hls" : "bit-true") << " at pixel ("
                        << r.mismatch.x << ", " << r.mismatch.y << "), sample "
                        << r.mismatch.sample << ", first in the "
                        << bittrue::to_string(r.mismatch.unit) << "; reproducer "
                        << r.mismatch.reproducer << "\n";
              return 3;
            }
            if (r.not_run.empty()) return 0;
            // The engines that ran agree; the ones named did not run.
            std::cerr << "voxcast: cosim: not every engine ran:";
            for (std::size_t i = 0; i < r.not_run.size(); ++i)
              std::cerr << (i ? "; " : " ") << r.not_run[i].engine << " (" << r.not_run[i].reason
                        << ")";
            std::cerr << "\n";
            return 8;
          }};
}

}  // namespace voxcast::cosim::commands
