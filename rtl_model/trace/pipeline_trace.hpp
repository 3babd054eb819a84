// The VCD trace of a frame (`voxcast render --engine rtl --vcd FILE`): the
// valid/ready handshakes of the pipeline's FIFOs and the commands on each
// DIMM's command bus, inside a window of SDRAM cycles.
//
// Signals (scope card): pipeline.<fifo>_valid / _ready for each pipeline
// FIFO (valid: the consumer may pop, ready: the producer may push, sampled
// at the end of every cycle); dimmD.request_* and dimmD.completions_* for
// the FIFOs around each DIMM's controller; dimmD.cmd, the command on the
// bus in that cycle (kCommandCodes below; 0 = NOP), dimmD.bank and
// dimmD.row, the address of the last bank command. The trace observes the
// model and changes nothing in it; a frame without a trace pays one
// null-pointer test per SDRAM command and per cycle.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "rtl_model/sdram/geometry.hpp"
#include "rtl_model/sdram/observer.hpp"
#include "rtl_model/trace/vcd_writer.hpp"

namespace voxcast::rtl::trace {

// What to trace: the output stream and the window of cycles, inclusive.
struct TraceOptions {
  std::ostream* out = nullptr;
  Cycle first = 0;
  Cycle last = std::numeric_limits<Cycle>::max() / 4;
};

// Parses "START:END" (cycles, inclusive; END may be empty for "to the end").
// Throws voxcast::Error naming `what` for anything else.
TraceOptions parse_window(const std::string& text, const std::string& what);

// dimmD.cmd's values: the sdram::Command enumerators (NOP 0, ACT 1, RD 2,
// WR 3, PRE 4, PREA 5, REF 6), written into the VCD's $comment.
inline constexpr const char* kCommandCodes = "cmd: 0 NOP, 1 ACT, 2 RD, 3 WR, 4 PRE, 5 PREA, 6 REF, 7 RDA";

class PipelineTrace {
 public:
  PipelineTrace(const TraceOptions& options, std::int64_t cycle_ps, const sdram::Geometry& g,
                int dimms);
  ~PipelineTrace();
  PipelineTrace(const PipelineTrace&) = delete;
  PipelineTrace& operator=(const PipelineTrace&) = delete;

  // A FIFO's handshake pair, in scope card.<scope>; before begin().
  int add_fifo(const std::string& scope, const std::string& name);
  void begin();

  void fifo(int index, bool valid, bool ready, Cycle now) {
    Fifo& f = fifos_[static_cast<std::size_t>(index)];
    if (valid != f.valid) vcd_.set(f.valid_id, valid, now), f.valid = valid;
    if (ready != f.ready) vcd_.set(f.ready_id, ready, now), f.ready = ready;
  }
  sdram::CommandObserver* dimm(int d);
  void finish(Cycle now);

  // Commands (NOP excluded) issued inside the window, over every DIMM.
  std::uint64_t commands_in_window() const { return commands_; }

 private:
  struct Fifo {
    int valid_id = 0, ready_id = 0;
    bool valid = false, ready = true;
  };
  class Dimm;
  void command(int d, sdram::Command cmd, const sdram::Address& a, Cycle now);

  VcdWriter vcd_;
  std::vector<Fifo> fifos_;
  std::vector<std::unique_ptr<Dimm>> dimms_;
  std::uint64_t commands_ = 0;
};

}  // namespace voxcast::rtl::trace
