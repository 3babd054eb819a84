// The pipeline's port to one DIMM: a request queue, a controller and its
// completions, behind one interface with three implementations:
//
//   ReferencePort    the reference sdram::Controller with any scheduler and
//                    refresh policy, the Dimm as referee of every command
//                    (reference_port.hpp).
//   FastInOrderPort  the in-order open-page scheduler with eager refresh,
//                    event-driven: the same decisions, commands, cycles and
//                    statistics as the reference with those two policies,
//                    ten times faster (fast_in_order_port.hpp).
//   FastLookAheadPort the look-ahead activation scheduler with eager refresh,
//                    open page or auto precharge (the row-hit goal
//                    configuration), event-driven in the same way
//                    (fast_lookahead_port.hpp).
// The two event-driven ports share their queue, banks, refresh sequence and
// statistics in EventDrivenPort (event_driven_port.hpp).
// tests/rtl compare the fast ports with the reference command by command on
// random request streams and statistic by statistic on whole frames.
//
// Contract (a memory port), per SDRAM cycle `now`, strictly increasing:
//   - push(r) (when ready()) before tick(now) enqueues r with arrival now;
//   - tick(now) runs the controller's cycle: refresh, one command, retire
//     (sdram/controller.hpp), filling completions();
//   - the consumer pops completions() after tick(now) and calls popped(now);
//   - wake() is a cycle before which tick() would change nothing but the
//     controller's tick counters: the pipeline may skip ahead to it, and
//     need not call tick() before it (a port that cannot tell keeps 0).
//   - activity() counts the commands issued and accesses completed so far
//     (ControllerStats::command_cycles + completed): the pipeline's test of
//     progress, asked every cycle.
// wake() and activity() are plain members of the interface, not virtual:
// the pipeline asks them for four ports in every simulated cycle.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "rtl_model/sdram/controller.hpp"
#include "rtl_model/sdram/dimm.hpp"
#include "rtl_model/sim/fifo.hpp"

namespace voxcast::rtl::pipeline {

class MemoryPort {
 public:
  virtual ~MemoryPort() = default;
  virtual bool ready() const = 0;
  virtual void push(const sdram::Request& r) = 0;
  virtual void tick(sim::Cycle now) = 0;
  virtual sim::Fifo<sdram::Completion>& completions() = 0;
  virtual const sim::Fifo<sdram::Completion>& completions() const = 0;
  virtual void popped(sim::Cycle now) = 0;
  sim::Cycle wake() const { return wake_; }
  std::uint64_t activity() const { return activity_; }
  // Tells `o` of every command the port puts on the DIMM's bus (a trace).
  virtual void set_observer(sdram::CommandObserver* o) = 0;

  virtual std::size_t pending() const = 0;
  virtual std::size_t in_flight() const = 0;
  virtual bool idle() const = 0;
  virtual void expect_drained() const = 0;
  // ControllerStats::cycles counts the ticks a port ran, which differ
  // between implementations; everything else is equal. The pipeline reports
  // the frame's cycles instead (the card clocks its controllers in every
  // cycle) and samples the completions FIFO on its own clock
  // (sim::Fifo::sample_on_change), so its statistics do not depend on the
  // port.
  virtual const sdram::ControllerStats& controller_stats() const = 0;
  virtual const sdram::DimmStats& dimm_stats() const = 0;

 protected:
  sim::Cycle wake_ = 0;
  std::uint64_t activity_ = 0;
};

// The memory model of a run.
enum class MemoryModel : std::uint8_t {
  kAuto,       // FastInOrderPort for in-order + eager + open page, FastLookAheadPort for
               // lookahead + eager, ReferencePort otherwise
  kReference,  // always the reference controller
};

// Throws voxcast::Error for unknown policy names.
std::unique_ptr<MemoryPort> make_memory_port(MemoryModel model, const std::string& scheduler,
                                             const std::string& refresh,
                                             const sdram::DimmConfig& dimm,
                                             const sdram::ControllerConfig& controller,
                                             bool skip_idle_ticks,
                                             const sdram::SchedulerParams& params = {});

}  // namespace voxcast::rtl::pipeline
