// The card's PCI DMA engine as a clocked unit in the PCI domain (33 MHz),
// with the clock-domain crossing to the core: the transaction phases of
// pci_bus.hpp stepped clock by clock, each data phase moving one 32-bit word
// through an asynchronous FIFO (sim/async_fifo.hpp) to or from the core.
//
//   readback (card to host): the core writes the frame buffer's words into
//     the FIFO; a data phase pops one; with the FIFO empty the master holds
//     IRDY# (a wait state, PCI 2.2 §3.2.1) and the phase waits.
//   upload (host to card): a data phase pushes the host's word into the FIFO,
//     the core pops it; with the FIFO full the master holds IRDY#.
//
// With the core keeping up (it moves a word per core clock, three per PCI
// clock at 100 MHz), no wait state occurs and the clocked transfer takes
// exactly PciBus::transfer's clocks (tests/rtl/test_rtl_pci_clocked.cpp).
#pragma once

#include <cstdint>
#include <vector>

#include "rtl_model/pci/pci_bus.hpp"
#include "rtl_model/sim/async_fifo.hpp"
#include "rtl_model/sim/clock.hpp"

namespace voxcast::rtl::pci {

// One DMA transfer, one PCI clock per clock().
class PciDmaEngine {
 public:
  // Throws voxcast::Error as PciBus does for a bad configuration.
  PciDmaEngine(const PciConfig& config, Direction direction, std::uint64_t bytes);

  // One PCI clock. Readback: `fifo` is read (core to PCI); upload: written.
  // `host` supplies upload words / receives readback words.
  void clock(sim::AsyncFifo<std::uint32_t>& fifo, std::vector<std::uint32_t>& host);
  bool done() const { return phase_ == Phase::kDone; }
  // Clocks until done (data, overhead and wait states) and the rest of
  // PciStats; `seconds` from the PCI clock.
  PciStats stats() const;
  Cycle wait_cycles() const { return waits_; }

 private:
  enum class Phase : std::uint8_t { kArbitration, kAddress, kTurnaround, kInitial, kData, kIdle, kDone };
  int length(Phase p) const;
  void enter(Phase p);
  void start_transaction();

  PciConfig config_;
  bool read_;                    // host to card (the card reads host memory)
  std::uint64_t phases_left_;    // data phases of the whole transfer
  std::uint64_t host_index_ = 0; // next host word (upload)
  int burst_left_ = 0;
  Phase phase_ = Phase::kDone;
  int left_ = 0;                 // clocks left in the current phase (not kData)
  PciStats stats_;
  Cycle waits_ = 0;
};

// A whole transfer across the crossing: the PCI domain (config.clock) and
// the core domain (`core`) advanced edge by edge in time order (at equal
// times the core first), the core moving one word every `core_interval`
// core clocks, through an AsyncFifo of `fifo_depth`.
struct ClockedTransfer {
  PciStats pci;                      // cycles include wait states
  Cycle wait_cycles = 0;             // PCI clocks the master waited on the FIFO
  Cycle core_cycles = 0;             // core clocks from the start to the last word moved
  std::vector<std::uint32_t> words;  // readback: what the host received; upload: what the core got
};

ClockedTransfer run_clocked_transfer(const PciConfig& config, const sim::ClockDomain& core,
                                     Direction direction, const std::vector<std::uint32_t>& words,
                                     int core_interval = 1, std::size_t fifo_depth = 16);

// A multi-frame run with a double-buffered frame buffer: frame k renders
// into buffer k mod 2 while the DMA engine reads frame k-1 back from the
// other. Frame k starts when frame k-1 has rendered and the readback of
// frame k-2 (its buffer) has ended; the readback of frame k starts when
// frame k has rendered and the readback of frame k-1 has ended (one DMA
// engine). A readback is hidden when it ends before the next frame has
// rendered, so that no frame waits for a buffer; the last frame's readback
// has no next frame to hide behind.
struct FrameReadback {
  Cycle render_cycles = 0;       // core clocks of the frame's rendering
  double render_start_s = 0.0;   // when the frame starts rendering
  double render_end_s = 0.0;
  double readback_start_s = 0.0;
  double readback_end_s = 0.0;
  double readback_s = 0.0;       // the readback's duration (the clocked transfer)
  double stall_s = 0.0;          // the frame waited this long for its buffer
  bool hidden = false;
};

// `render_cycles` per frame in `core` clocks; `readback` the clocked
// transfer of one frame (run_clocked_transfer).
std::vector<FrameReadback> double_buffered_readback(const std::vector<Cycle>& render_cycles,
                                                    const sim::ClockDomain& core,
                                                    const PciStats& readback);

}  // namespace voxcast::rtl::pci
