// Timing constraints of a board (voxcast constraints BOARD --format xdc|sdc):
// Vivado XDC or Synopsys/Quartus SDC with the board's clocks, the I/O delays
// of the SDRAM and PCI pins from their datasheets and the board traces, the
// asynchronous clock groups and the clock-domain crossings, each number with
// its source (docs/constraints.md).
#pragma once

#include "cosim/reports/files.hpp"

#include <iosfwd>
#include <string>
#include <vector>

#include "rtl_model/board/board.hpp"

namespace voxcast::cosim {

enum class ConstraintFormat { kXdc, kSdc };
// "xdc" | "sdc"; throws voxcast::Error otherwise.
ConstraintFormat parse_constraint_format(const std::string& name);

// One set_input_delay / set_output_delay pair (max and min) on a group of ports.
struct IoDelay {
  std::string group;  // "sdram write", "pci bused in", ...
  std::string ports;  // Tcl list of port patterns, "dimm0_dq[*]"
  std::string clock;  // the clock the delay refers to
  bool input = false;
  double max_ns = 0;
  double min_ns = 0;
  std::string formula;  // both formulas with the numbers put in, for the comment
};

// The I/O delays of a board, DIMM by DIMM and for the host bus (empty for a
// vendor PHY or a hard block). Formulas (t_clk / t_data: board traces):
//   SDRAM, FPGA -> SDRAM (relative to the forwarded clock at the FPGA pin):
//     output max = t_data,max + tIS - t_clk,min     output min = t_data,min - tIH - t_clk,max
//   SDRAM, SDRAM -> FPGA (read data, launched by the SDRAM on the same clock):
//     input max  = t_clk,max + tAC + t_data,max     input min  = t_clk,min + tOH + t_data,min
//   PCI component at its pins (PCI 2.2 §4.2.3.2; the bus's Tprop and skew
//   are the spec's budget outside the component):
//     input max  = Tcyc - Tsu      input min  = Th
//     output max = Tcyc - Tval,max output min = -Tval,min
std::vector<IoDelay> io_delays(const rtl::board::Board& board);

// The DIMM clocks the FPGA forwards (one generated clock per DIMM, "dimm0_ck").
std::vector<std::string> forwarded_clock_names(const rtl::board::Board& board);

// The whole constraint file. Deterministic: the same board gives the same text.
std::string generate_constraints(const rtl::board::Board& board, ConstraintFormat format);

// Nanoseconds with three decimals, as the constraints and the synthesis
// scripts print periods and delays ("10.000"; never "-0.000").
std::string ns3(double ns);

}  // namespace voxcast::cosim

namespace voxcast::cosim {

// The golden constraint files (tests/golden/constraints/BOARD.xdc|.sdc) of
// every shipped board: compared (returns the number of files that differ,
// each reported on `log` with its first differing line) or, with bless,
// rewritten (returns 0).
// Writes text to path; throws voxcast::Error naming the path on failure.
int check_constraint_goldens(const std::string& golden_dir, bool bless, std::ostream& log);

}  // namespace voxcast::cosim
