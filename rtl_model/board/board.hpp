// The board description: one TOML file per card (constraints/boards/*.toml)
// that the cycle model, the generated timing constraints and the vendor
// synthesis scripts all read, so the three cannot disagree
// (docs/constraints.md lists every key).
//
//   clocks   every clock of the card: a port clock (create_clock) or a clock
//            the design derives from another (create_generated_clock)
//   fpga     the part on the card and the part today's vendor tools target
//   memory   the DIMMs: geometry, the datasheet timing the model converts to
//            cycles, and the I/O timing of their pins
//   host     the host interface (PCI or PCIe) and its I/O timing
//
// Every table that holds numbers carries a `source` string (datasheet, page,
// table, or "assumption: ..."); the constraints cite it beside each number.
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "rtl_model/sdram/geometry.hpp"
#include "rtl_model/sdram/timing.hpp"
#include "rtl_model/sim/clock.hpp"

namespace voxcast::rtl::board {

struct Clock {
  std::string name;                // the key under [clocks]: also the constraint's clock name
  sim::Picoseconds period_ps = 0;  // derived for a generated clock
  std::string port;                // a port clock: its top-level port
  std::string from;                // a generated clock: its master clock
  int multiply = 1;                // generated: period = master * divide / multiply
  int divide = 1;
  std::string pin;  // generated: the clock generator's output pin
  std::string source;
  int line = 0;  // where it is defined, for messages

  bool generated() const { return !from.empty(); }
  double period_ns() const { return static_cast<double>(period_ps) / 1000.0; }
  sim::ClockDomain domain() const { return sim::ClockDomain(name, period_ps); }
};

struct Fpga {
  std::string part;       // the part on the card
  std::string tool_part;  // the part Vivado / Vitis HLS target for this board
  std::string source;
};

// A min/max pair of board trace delays, in ns.
struct Window {
  double min_ns = 0;
  double max_ns = 0;
};

// I/O timing of the SDRAM pins (system-synchronous SDR: the FPGA forwards the
// clock to the DIMM and launches and captures on it), from the SDRAM datasheet
// and the board traces.
struct SdramIo {
  // "system_synchronous": the constraints carry set_input/output_delay from
  // the numbers below; "vendor_phy": a memory-controller IP closes its own
  // I/O timing (DDR3/DDR4), the constraints list the interface only.
  std::string interface;
  double tAC_ns = 0;  // access time from CLK at the CAS latency (max)
  double tOH_ns = 0;  // data-out hold time after the next CLK (min)
  double tIS_ns = 0;  // input setup: max of tAS, tCMS, tDS
  double tIH_ns = 0;  // input hold: max of tAH, tCMH, tDH
  std::string source;
  Window clock_trace;  // FPGA clock pin to DIMM clock pin
  Window data_trace;   // FPGA pin to DIMM pin (address, command, DQ)
  std::string trace_source;
};

struct Memory {
  std::string type;      // "sdr" (the cycle model's device) or "ddr4"
  std::string clock;     // name of the memory clock (clocks table)
  int dimms = 0;         // independent channels, one controller each
  int burst_length = 1;  // mode-register burst length the design uses
  std::string ports;     // port-name prefix with {i} for the DIMM index, "dimm{i}"
  std::string source;    // why this many DIMMs, this burst length
  sdram::Geometry geometry;
  sdram::TimingNs timing;
  SdramIo io;
};

// I/O timing of the host bus pins: PCI Local Bus Specification Rev. 2.2,
// §4.2.3.2 (Table 4-6) for 33 MHz.
struct PciIo {
  // "pci_component": set_input/output_delay from the numbers below;
  // "hard_block": a PCIe hard block (serial lanes, no delays to constrain).
  std::string interface;
  double tval_min_ns = 0;      // CLK to signal valid, bused signals (min)
  double tval_max_ns = 0;      // ... (max)
  double tval_ptp_max_ns = 0;  // CLK to REQ# valid (point to point, max)
  double tsu_ns = 0;           // input setup to CLK, bused signals
  double tsu_ptp_ns = 0;       // input setup to CLK, GNT# (point to point)
  double th_ns = 0;            // input hold from CLK
  std::string source;
};

struct Host {
  std::string interface;  // "pci" (the cycle model's bus) or "pcie"
  std::string clock;      // name of the host clock
  int bus_bits = 0;       // PCI AD width (32 or 64); PCIe: lanes x 1
  int lanes = 0;          // PCIe lanes (0 for PCI)
  std::string ports;      // port-name prefix: "pci" gives pci_ad[*], pci_frame_n ...
  std::string source;
  PciIo io;
};

struct Board {
  std::string name;
  std::string description;
  std::string origin;  // file path or "shipped:NAME"
  Fpga fpga;
  std::vector<Clock> clocks;
  std::string core_clock;  // the clock of the ray-casting pipeline
  std::string core_source;
  Memory memory;
  Host host;

  // Throws voxcast::Error naming the board when there is no such clock.
  const Clock& clock(const std::string& name) const;
  const Clock& memory_clock() const { return clock(memory.clock); }
  const Clock& core() const { return clock(core_clock); }
  const Clock& host_clock() const { return clock(host.clock); }
};

std::ostream& operator<<(std::ostream& os, const Board& b);

// Reads a board description. Errors are one line naming the file, line and
// key: "vizard2_pci.toml:40: memory.timing.tRCD_ns = -1 is outside [0.1, 1e+06]".
// Unknown keys, missing keys, wrong types, non-physical values (periods,
// delays, a generated clock whose master is missing or itself derived from
// it) are all errors.
Board parse_board(const std::string& toml_text, const std::string& origin);
Board load_board_file(const std::string& path);

// The boards compiled into the binary (constraints/boards/*.toml).
std::vector<std::string> shipped_board_names();
// Throws voxcast::Error naming the shipped boards when there is none of that name.
const std::string& shipped_board_text(const std::string& name);
Board shipped_board(const std::string& name);
// A shipped board's name, or else a path to a board file.
Board load_board(const std::string& name_or_path);

// Every key the parser accepts, dotted ("memory.timing.tRCD_ns",
// "clocks.*.period_ns"); docs/constraints.md documents each (a test checks).
std::vector<std::string> known_board_keys();

}  // namespace voxcast::rtl::board
