#include "rtl_model/pci/pci_dma.hpp"

#include <algorithm>

#include "refmodel/error.hpp"

namespace voxcast::rtl::pci {

PciDmaEngine::PciDmaEngine(const PciConfig& config, Direction direction, std::uint64_t bytes)
    : config_(PciBus(config).config()),  // PciBus validates
      read_(direction == Direction::kHostToCard),
      phases_left_((bytes + static_cast<std::uint64_t>(config.bus_bytes) - 1) /
                   static_cast<std::uint64_t>(config.bus_bytes)) {
  stats_.bytes = bytes;
  if (phases_left_ > 0) start_transaction();
}

// pci_bus.hpp's phases; a phase of length 0 is skipped.
int PciDmaEngine::length(Phase p) const {
  const PciConfig& c = config_;
  switch (p) {
    case Phase::kArbitration: return c.arbitration;
    case Phase::kAddress: return c.address;
    case Phase::kTurnaround: return read_ ? c.read_turnaround : 0;
    case Phase::kInitial: return read_ ? c.read_initial_latency : c.write_initial_latency;
    case Phase::kData: return burst_left_;
    case Phase::kIdle: return c.idle;
    case Phase::kDone: return 0;
  }
  return 0;
}

void PciDmaEngine::enter(Phase p) {
  while (p != Phase::kDone && length(p) == 0) {
    if (p == Phase::kIdle) {  // the transaction is over
      if (phases_left_ == 0) {
        p = Phase::kDone;
        break;
      }
      start_transaction();
      return;
    }
    p = static_cast<Phase>(static_cast<int>(p) + 1);
  }
  phase_ = p;
  left_ = length(p);
}

void PciDmaEngine::start_transaction() {
  burst_left_ = static_cast<int>(
      std::min<std::uint64_t>(phases_left_, static_cast<std::uint64_t>(config_.burst_data_phases)));
  ++stats_.transactions;
  enter(Phase::kArbitration);
}

void PciDmaEngine::clock(sim::AsyncFifo<std::uint32_t>& fifo, std::vector<std::uint32_t>& host) {
  if (phase_ == Phase::kDone) return;
  ++stats_.cycles;
  if (phase_ == Phase::kData) {
    const bool can = read_ ? fifo.ready() : fifo.valid();
    if (!can) {  // IRDY# held: a wait state
      ++waits_;
      ++stats_.overhead_cycles;
      return;
    }
    if (read_)
      fifo.push(host.at(host_index_++));
    else
      host.push_back(fifo.pop());
    ++stats_.data_cycles;
    --phases_left_;
    if (--burst_left_ == 0) enter(Phase::kIdle);
    return;
  }
  ++stats_.overhead_cycles;
  if (--left_ == 0) {
    if (phase_ == Phase::kIdle) {
      if (phases_left_ == 0)
        phase_ = Phase::kDone;
      else
        start_transaction();
    } else {
      enter(static_cast<Phase>(static_cast<int>(phase_) + 1));
    }
  }
}

PciStats PciDmaEngine::stats() const {
  PciStats s = stats_;
  s.seconds = static_cast<double>(config_.clock.time_of(s.cycles)) * 1e-12;
  return s;
}

ClockedTransfer run_clocked_transfer(const PciConfig& config, const sim::ClockDomain& core,
                                     Direction direction, const std::vector<std::uint32_t>& words,
                                     int core_interval, std::size_t fifo_depth) {
  if (core_interval < 1) throw Error("clocked PCI transfer: core interval must be at least 1");
  const bool upload = direction == Direction::kHostToCard;
  const auto bytes = static_cast<std::uint64_t>(words.size()) * static_cast<std::uint64_t>(config.bus_bytes);
  PciDmaEngine dma(config, direction, bytes);
  sim::AsyncFifo<std::uint32_t> fifo(upload ? "pci->core" : "core->pci", fifo_depth);
  ClockedTransfer r;
  // Upload: the host's words feed the DMA; the core collects. Readback: the
  // core feeds the FIFO from `words`; the DMA hands them to the host.
  std::vector<std::uint32_t> host = upload ? words : std::vector<std::uint32_t>{};
  std::size_t core_index = 0;
  Cycle pci_edge = 0, core_edge = 0;
  while (!dma.done() || (upload && core_index < words.size())) {
    const sim::Picoseconds t_core = core.time_of(core_edge), t_pci = config.clock.time_of(pci_edge);
    if (t_core <= t_pci) {  // a core edge (first at equal times)
      if (upload) fifo.read_clock(); else fifo.write_clock();
      if (core_edge % core_interval == 0) {
        if (upload && fifo.valid()) {
          r.words.push_back(fifo.pop());
          ++core_index;
          r.core_cycles = core_edge + 1;
        } else if (!upload && core_index < words.size() && fifo.ready()) {
          fifo.push(words[core_index++]);
          r.core_cycles = core_edge + 1;
        }
      }
      ++core_edge;
    } else {
      if (upload) fifo.write_clock(); else fifo.read_clock();
      dma.clock(fifo, host);
      ++pci_edge;
    }
  }
  fifo.expect_drained();
  if (!upload) r.words = std::move(host);
  r.pci = dma.stats();
  r.wait_cycles = dma.wait_cycles();
  return r;
}

std::vector<FrameReadback> double_buffered_readback(const std::vector<Cycle>& render_cycles,
                                                    const sim::ClockDomain& core,
                                                    const PciStats& readback) {
  std::vector<FrameReadback> f(render_cycles.size());
  for (std::size_t k = 0; k < f.size(); ++k) {
    FrameReadback& x = f[k];
    x.render_cycles = render_cycles[k];
    const double previous_render_end = k >= 1 ? f[k - 1].render_end_s : 0.0;
    const double buffer_free = k >= 2 ? f[k - 2].readback_end_s : 0.0;
    x.render_start_s = std::max(previous_render_end, buffer_free);
    x.stall_s = x.render_start_s - previous_render_end;
    x.render_end_s =
        x.render_start_s + static_cast<double>(core.time_of(render_cycles[k])) * 1e-12;
    x.readback_s = readback.seconds;
    x.readback_start_s = std::max(x.render_end_s, k >= 1 ? f[k - 1].readback_end_s : 0.0);
    x.readback_end_s = x.readback_start_s + readback.seconds;
  }
  for (std::size_t k = 0; k + 1 < f.size(); ++k)
    f[k].hidden = f[k].readback_end_s <= f[k + 1].render_end_s;
  return f;
}

}  // namespace voxcast::rtl::pci
