// One DDR4 channel of the card as the pipelines see it (docs/sdram.md §10):
//
//   core clock   | memory clock (the DRAM command clock)
//   requests --> [async FIFO] --> controller (rtl_model/sdram, the Dimm as
//                                 referee of every command)
//   returns  <-- [async FIFO] <-- completions, in data order
//
// The two crossings are clocked asynchronous FIFOs (sim::AsyncFifo, Gray-code
// pointers through sync_stages flops), as between PCI and the core. A request
// names a burst (its DDR4 address) and carries the id of the core side's miss
// register (MSHR) that waits for it; the return carries the id back, and the
// core side reads the burst's 64 bytes from the memory image (the data the
// DRAM holds at that address: burst_card.hpp). The controller runs one tick
// per memory edge when it can act (Controller::next_event), so an idle
// channel costs the simulation two synchroniser shifts per edge.
#pragma once

#include <cstdint>
#include <string>

#include "rtl_model/pipeline/burst_config.hpp"
#include "rtl_model/sdram/controller.hpp"
#include "rtl_model/sim/async_fifo.hpp"

namespace voxcast::rtl::pipeline {

struct BurstRequest {
  std::uint32_t mshr = 0;  // the core side's miss register
  sdram::Address address;  // the burst's bank (group x banks + bank), row, first column
};

struct BurstReturn {
  std::uint32_t mshr = 0;
};

class BurstChannel {
 public:
  // Throws voxcast::Error for an unknown scheduler or refresh policy, or a bad
  // FIFO depth.
  BurstChannel(int index, const sdram::DimmConfig& dimm, const std::string& scheduler,
               const sdram::SchedulerParams& params, const std::string& refresh,
               const sdram::ControllerConfig& controller, const BurstCardConfig& card);

  // ---- Core clock domain: at each core edge, core_clock() first ----
  void core_clock();
  bool can_send() const { return requests_.ready(); }
  void send(const BurstRequest& r) { requests_.push(r); }
  bool has_return() const { return returns_.valid(); }
  BurstReturn take_return() { return returns_.pop(); }

  // ---- Memory clock domain: one edge, cycles strictly increasing ----
  void memory_clock(sdram::Cycle m);

  // Nothing in either FIFO or the controller.
  bool idle() const;
  // Throws voxcast::Error naming what is left.
  void expect_drained() const;
  const sdram::Controller& controller() const { return controller_; }
  std::string state() const;

 private:
  int index_;
  sim::AsyncFifo<BurstRequest> requests_;
  sim::AsyncFifo<BurstReturn> returns_;
  sdram::Controller controller_;
  sdram::Cycle wake_ = 0;  // the controller's next tick that can change something
};

}  // namespace voxcast::rtl::pipeline
