// The card's host interface: 32-bit PCI at 33 MHz (VIZARD II, 2001 paper
// §2.3: "a 256^3 volume is uploaded in about 0.15 s"), as bus-master burst
// transactions of the card's DMA engine, counted clock by clock.
//
// One transaction (PCI Local Bus Specification Rev. 2.2, §3.3-3.5):
//   arbitration  REQ#/GNT# before FRAME# (0 when the bus is parked on the
//                card or arbitration is hidden behind the previous transfer)
//   address      1 clock (FRAME# asserted, address on AD)
//   turnaround   1 clock on reads only (AD changes driver, §3.3.1)
//   initial      target initial latency, address to first data (the spec's
//                limit is 16 clocks, §3.5.1.1): host-bridge reads of main
//                memory take several clocks, posted writes few
//   data         one data phase per 4 bytes, no wait states after the first
//   idle         1 clock after the last data phase (bus turnaround, §3.3.1)
// A burst is cut after burst_data_phases data phases (the master's latency
// timer, §3.5.4, and the bridge's prefetch buffer limit long bursts).
//
// The per-transaction numbers are our assumptions for a 2001 PC chipset
// (host-bridge memory-read initial latency 8 clocks, posted-write latency
// 2 clocks, 64-phase bursts = 256 bytes, parked bus); they are parameters.
// With them, the upload of 16 MB (one byte per voxel: the card computes the
// gradients and the replicated DIMM words itself, our reading of the paper's
// 0.15 s, see docs/performance.md) takes 0.150 s.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>

#include "rtl_model/sim/clock.hpp"

namespace voxcast::rtl::pci {

using sim::Cycle;

enum class Direction : std::uint8_t {
  kHostToCard,  // the card reads host memory (Memory Read Multiple): upload
  kCardToHost,  // the card writes host memory (Memory Write, posted): readback
};

struct PciConfig {
  sim::ClockDomain clock = sim::clocks::pci33();
  int bus_bytes = 4;            // 32-bit AD bus
  int burst_data_phases = 64;   // data phases per transaction at most
  int arbitration = 0;          // clocks of REQ#/GNT# per transaction
  int address = 1;
  int read_turnaround = 1;
  int read_initial_latency = 8;   // target (host bridge) initial latency, reads
  int write_initial_latency = 2;  // posted writes
  int idle = 1;                   // after each transaction
};

std::ostream& operator<<(std::ostream& os, const PciConfig& c);

struct PciStats {
  std::uint64_t bytes = 0;
  std::uint64_t transactions = 0;
  Cycle cycles = 0;           // PCI clocks for the whole transfer
  Cycle data_cycles = 0;      // clocks with a data phase
  Cycle overhead_cycles = 0;  // everything else
  double seconds = 0.0;

  double mb_per_second() const;    // 10^6 bytes per second
  double efficiency() const;       // data_cycles / cycles
};

std::ostream& operator<<(std::ostream& os, const PciStats& s);

class PciBus {
 public:
  // Throws voxcast::Error for non-positive widths or bursts, negative latencies.
  explicit PciBus(PciConfig config = {});
  const PciConfig& config() const { return config_; }

  // One DMA transfer of `bytes`, transaction by transaction, phase by phase.
  PciStats transfer(std::uint64_t bytes, Direction direction) const;
  // Clocks of one transaction with `data_phases` data phases.
  Cycle transaction_cycles(int data_phases, Direction direction) const;

 private:
  PciConfig config_;
};

// What the host sends for a volume of `voxels` voxels.
enum class UploadFormat : std::uint8_t {
  kRawVoxels,   // the stored values, 1 or 2 bytes each; the card derives the words
  kVoxelWords,  // 4-byte packed voxel words (value + gradient); the card replicates
  kDimmImage,   // the four DIMM images as stored: 8 bytes per voxel pair, 2 x kVoxelWords
};

const char* to_string(UploadFormat f);
std::uint64_t upload_bytes(std::uint64_t voxels, int bytes_per_stored_voxel, UploadFormat f);

struct HostTransfers {
  PciStats volume;      // upload of the volume
  PciStats tables;      // classification table (2 KB) + reflectance maps (3 KB)
  PciStats image;       // readback of one frame
};

// The VIZARD II numbers: a dims^3 volume of one-byte voxels in `format`, the
// 2 KB + 3 KB tables, a width x height image of `bytes_per_pixel`.
HostTransfers vizard2_host_transfers(const PciBus& bus, std::uint64_t voxels, UploadFormat format,
                                     int width, int height, int bytes_per_pixel);

}  // namespace voxcast::rtl::pci
