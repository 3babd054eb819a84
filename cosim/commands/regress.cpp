// voxcast regress: every scene x preset against the golden hashes.
#include <iostream>
#include <memory>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/verify/regress.hpp"

namespace voxcast::cosim::commands {

Subcommand add_regress(CLI::App& voxcast) {
  auto options = std::make_shared<RegressOptions>(
      RegressOptions{"scenes", "tests/golden/regress", {"vizard2", "balanced", "precise"}, false, {}});
  CLI::App* cmd = voxcast.add_subcommand(
      "regress", "Bit-accuracy regression: every scene x preset, hls == bit-true == golden hash");
  cmd->add_option("--scenes", options->scenes_dir, "Folder of scenes")->capture_default_str();
  cmd->add_option("--golden", options->golden_dir, "Folder of golden files")->capture_default_str();
  cmd->add_option("--profiles", options->profiles, "Presets to run")->delimiter(',');
  cmd->add_flag("--bless", options->bless,
                "Measure accuracy against the float reference and (re)write the golden files "
                "of the cases that meet their floor");
  cmd->add_option("--junit", options->junit_path,
                  "Write the cases as JUnit XML here (Jenkins, GitLab): one per scene x preset");
  add_set_option(*cmd, options->overrides);
  return {cmd, [options] {
            const int failed = run_regress(*options, std::cout);
            if (failed == 0) return 0;
            std::cerr << "voxcast: regress: " << failed << " case(s) failed\n";
            return 4;
          }};
}

}  // namespace voxcast::cosim::commands
