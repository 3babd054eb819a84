// voxcast constraints BOARD --format xdc|sdc --out FILE (or --golden DIR [--bless]).
#include <iostream>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/hardware/constraints.hpp"
#include "cosim/reports/files.hpp"
#include "refmodel/error.hpp"
#include "rtl_model/board/board.hpp"

namespace voxcast::cosim::commands {

Subcommand add_constraints(CLI::App& voxcast) {
  struct Args {
    std::string board, format = "xdc", out, golden;
    bool bless = false;
  };
  auto a = std::make_shared<Args>();
  CLI::App* cmd = voxcast.add_subcommand(
      "constraints", "Write the timing constraints (Vivado XDC or SDC) of a board description");
  cmd->add_option("board", a->board,
                  "Shipped board name (vizard2_pci, alveo_u250) or a board .toml");
  cmd->add_option("--format", a->format, "xdc or sdc")->capture_default_str();
  cmd->add_option("--out", a->out, "Output file");
  cmd->add_option("--golden", a->golden,
                  "Compare every shipped board's constraints with the golden files here");
  cmd->add_flag("--bless", a->bless, "With --golden: rewrite the golden files");
  return {cmd, [a] {
            if (!a->golden.empty()) {
              const int differ = check_constraint_goldens(a->golden, a->bless, std::cout);
              if (differ == 0) return 0;
              std::cerr << "voxcast: constraints: " << differ << " golden file(s) differ\n";
              return 4;
            }
            if (a->board.empty() || a->out.empty())
              throw Error("constraints: give BOARD and --out FILE (or --golden DIR)");
            const auto board = rtl::board::load_board(a->board);
            const auto format = parse_constraint_format(a->format);
            write_text_file(a->out, generate_constraints(board, format));
            std::cout << "wrote " << a->out << " (" << board << ")\n";
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
