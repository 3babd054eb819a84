#include "rtl_model/pci/pci_bus.hpp"

#include <ostream>

#include "refmodel/error.hpp"

namespace voxcast::rtl::pci {

std::ostream& operator<<(std::ostream& os, const PciConfig& c) {
  return os << "PCI " << c.clock.frequency_mhz() << " MHz x " << 8 * c.bus_bytes << " bits, bursts of "
            << c.burst_data_phases << " data phases, arbitration " << c.arbitration << ", address "
            << c.address << ", read turnaround " << c.read_turnaround << ", initial latency "
            << c.read_initial_latency << " (read) / " << c.write_initial_latency
            << " (write), idle " << c.idle;
}

double PciStats::mb_per_second() const {
  return seconds <= 0.0 ? 0.0 : static_cast<double>(bytes) * 1e-6 / seconds;
}
double PciStats::efficiency() const {
  return cycles == 0 ? 0.0 : static_cast<double>(data_cycles) / static_cast<double>(cycles);
}

std::ostream& operator<<(std::ostream& os, const PciStats& s) {
  return os << s.bytes << " bytes in " << s.transactions << " transactions, " << s.cycles
            << " PCI clocks (" << s.data_cycles << " data, " << s.overhead_cycles
            << " overhead) = " << s.seconds * 1e3 << " ms, " << s.mb_per_second() << " MB/s";
}

PciBus::PciBus(PciConfig config) : config_(config) {
  const PciConfig& c = config_;
  if (c.bus_bytes < 1 || c.burst_data_phases < 1)
    throw Error("PCI: bus width and burst length must be positive");
  if (c.arbitration < 0 || c.address < 0 || c.read_turnaround < 0 || c.read_initial_latency < 0 ||
      c.write_initial_latency < 0 || c.idle < 0)
    throw Error("PCI: phase lengths must not be negative");
}

Cycle PciBus::transaction_cycles(int data_phases, Direction direction) const {
  const PciConfig& c = config_;
  const bool read = direction == Direction::kHostToCard;
  return c.arbitration + c.address + (read ? c.read_turnaround : 0) +
         (read ? c.read_initial_latency : c.write_initial_latency) + data_phases + c.idle;
}

PciStats PciBus::transfer(std::uint64_t bytes, Direction direction) const {
  PciStats s;
  s.bytes = bytes;
  const auto width = static_cast<std::uint64_t>(config_.bus_bytes);
  std::uint64_t phases = (bytes + width - 1) / width;
  // Transaction by transaction: every full burst, then the remainder.
  while (phases > 0) {
    const auto n = static_cast<int>(
        std::min<std::uint64_t>(phases, static_cast<std::uint64_t>(config_.burst_data_phases)));
    const Cycle t = transaction_cycles(n, direction);
    s.cycles += t;
    s.data_cycles += n;
    s.overhead_cycles += t - n;
    ++s.transactions;
    phases -= static_cast<std::uint64_t>(n);
  }
  s.seconds = static_cast<double>(config_.clock.time_of(s.cycles)) * 1e-12;
  return s;
}

const char* to_string(UploadFormat f) {
  switch (f) {
    case UploadFormat::kRawVoxels: return "raw voxels";
    case UploadFormat::kVoxelWords: return "32-bit voxel words";
    case UploadFormat::kDimmImage: return "replicated DIMM image";
  }
  return "?";
}

std::uint64_t upload_bytes(std::uint64_t voxels, int bytes_per_stored_voxel, UploadFormat f) {
  switch (f) {
    case UploadFormat::kRawVoxels: return voxels * static_cast<std::uint64_t>(bytes_per_stored_voxel);
    case UploadFormat::kVoxelWords: return voxels * 4u;
    case UploadFormat::kDimmImage: return voxels * 8u;
  }
  return 0;
}

HostTransfers vizard2_host_transfers(const PciBus& bus, std::uint64_t voxels, UploadFormat format,
                                     int width, int height, int bytes_per_pixel) {
  HostTransfers t;
  t.volume = bus.transfer(upload_bytes(voxels, 1, format), Direction::kHostToCard);
  // VIZARD II §2.1: classification table about 2 KB, reflectance maps 3 KB.
  t.tables = bus.transfer(2048 + 3072, Direction::kHostToCard);
  t.image = bus.transfer(static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height) *
                             static_cast<std::uint64_t>(bytes_per_pixel),
                         Direction::kCardToHost);
  return t;
}

}  // namespace voxcast::rtl::pci
