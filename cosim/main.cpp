// voxcast: the command-line tool. Each subcommand lives in its own file in
// cosim/commands/ (its options and what it runs); main only dispatches: it
// checks the command line before any work starts, runs the chosen subcommand
// and turns every failure into one line on stderr and an exit status.
#include <algorithm>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/engines/warnings.hpp"
#include "refmodel/error.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace {

// The exit statuses (README, "Exit status"): 0 success; 1 an error in the
// input (a scene, a volume, an option's value); 2 an internal error; 3 the
// engines differ; 4 regress / constraints: golden files differ; 5 tune: no
// point meets the target; 6 --strict: precision hazards; 7 fuzz-scenes:
// findings; 8 cosim: not every engine ran; 64 a malformed command line
// (EX_USAGE). The subcommands return 0, 3, 4, 5, 7 and 8 themselves.
constexpr int kUsageError = 64;

// "unknown subcommand 'renderr'; did you mean 'render'?" when the first word
// is no subcommand (empty when it is one, or an option).
std::string unknown_subcommand(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return "";
  const std::string word = argv[1];
  std::string nearest;
  std::size_t best = std::string::npos;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (sub->get_name() == word) return "";
    const std::size_t d = voxcast::ref::edit_distance(word, sub->get_name());
    if (d < best) best = d, nearest = sub->get_name();
  }
  std::string msg = "unknown subcommand '" + word + "'";
  if (best <= std::max<std::size_t>(2, word.size() / 3)) msg += "; did you mean '" + nearest + "'?";
  return msg + " (voxcast --help lists the subcommands)";
}

// A command-line error as every other error: one line naming what is wrong,
// and where help is.
int usage_error(const CLI::App& app, const CLI::ParseError& e) {
  std::string where = "voxcast";
  for (const CLI::App* sub : app.get_subcommands()) where += " " + sub->get_name();
  std::string what = e.what();
  std::replace(what.begin(), what.end(), '\n', ' ');
  while (!what.empty() && what.back() == ' ') what.pop_back();
  std::cerr << "voxcast: " << what << " (" << where << " --help)\n";
  return kUsageError;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"voxcast: VIRIM and VIZARD II hardware volume renderers — reference model, "
               "fixed-point design and cycle model"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "voxcast 0.1.0");
  const std::vector<voxcast::cosim::commands::Subcommand> subcommands =
      voxcast::cosim::commands::add_all(app);

  if (const std::string word = unknown_subcommand(app, argc, argv); !word.empty()) {
    std::cerr << "voxcast: " << word << "\n";
    return kUsageError;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --help-all, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return usage_error(app, e);
  }

  try {
    for (const auto& sub : subcommands)
      if (*sub.app) return sub.run();
  } catch (const voxcast::cosim::PrecisionHazardError& e) {
    std::cerr << "voxcast: " << e.what() << "\n";
    return 6;
  } catch (const voxcast::Error& e) {
    std::cerr << "voxcast: " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "voxcast: internal error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
