// The PCI model against its closed form, and the VIZARD II figures: a 256^3
// volume of one-byte voxels uploads in about 0.15 s (2001 paper, §2.3).
#include <gtest/gtest.h>

#include "refmodel/error.hpp"
#include "rtl_model/pci/pci_bus.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

using rtl::pci::Direction;
using rtl::pci::PciBus;
using rtl::pci::PciConfig;
using rtl::pci::UploadFormat;

TEST(Pci, TransactionPhases) {
  const PciBus bus;
  // Read: address 1 + turnaround 1 + initial latency 8 + 64 data + idle 1.
  EXPECT_EQ(bus.transaction_cycles(64, Direction::kHostToCard), 75);
  // Posted write: address 1 + initial latency 2 + data + idle 1.
  EXPECT_EQ(bus.transaction_cycles(64, Direction::kCardToHost), 68);
  EXPECT_EQ(bus.transaction_cycles(1, Direction::kCardToHost), 5);
}

TEST(Pci, TransferIsBurstsPlusRemainder) {
  const PciBus bus;
  const auto s = bus.transfer(1000, Direction::kHostToCard);  // 250 phases: 3 x 64 + 58
  EXPECT_EQ(s.transactions, 4u);
  EXPECT_EQ(s.data_cycles, 250);
  EXPECT_EQ(s.cycles, 3 * 75 + (75 - 64 + 58));
  // Each transaction's address, turnaround, initial latency and idle clock.
  EXPECT_EQ(s.overhead_cycles, 4 * (1 + 1 + 8 + 1));
  EXPECT_DOUBLE_EQ(s.seconds, static_cast<double>(s.cycles) * 30e-9);
  const auto odd = bus.transfer(5, Direction::kCardToHost);  // two phases, the last partial
  EXPECT_EQ(odd.data_cycles, 2);
  EXPECT_EQ(bus.transfer(0, Direction::kCardToHost).cycles, 0);
}

TEST(Pci, PeakIs133MBPerSecond) {
  PciConfig ideal;
  ideal.address = ideal.read_turnaround = ideal.read_initial_latency = ideal.idle = 0;
  ideal.burst_data_phases = 1 << 30;
  const auto s = PciBus(ideal).transfer(std::uint64_t{1} << 24, Direction::kHostToCard);
  EXPECT_NEAR(s.mb_per_second(), 133.33, 0.01);
}

// Paper: "a 256^3 volume is uploaded in about 0.15 s". One byte per voxel with
// the default (assumed) chipset figures: 4,915,200 clocks = 0.147 s; the two
// alternatives the card might have used take 4x and 8x as long.
TEST(Pci, Vizard2UploadAndReadback) {
  const PciBus bus;
  const std::uint64_t voxels = std::uint64_t{256} * 256 * 256;
  const auto raw = rtl::pci::vizard2_host_transfers(bus, voxels, UploadFormat::kRawVoxels, 256, 256, 4);
  EXPECT_EQ(raw.volume.cycles, 65536 * 75);  // 2^22 data phases in 64-phase bursts
  EXPECT_NEAR(raw.volume.seconds, 0.15, 0.005);
  RecordProperty("upload_256_raw_ms", std::to_string(raw.volume.seconds * 1e3));
  const auto words = rtl::pci::vizard2_host_transfers(bus, voxels, UploadFormat::kVoxelWords, 256, 256, 4);
  EXPECT_NEAR(words.volume.seconds / raw.volume.seconds, 4.0, 1e-9);
  const auto image = rtl::pci::vizard2_host_transfers(bus, voxels, UploadFormat::kDimmImage, 256, 256, 4);
  EXPECT_NEAR(image.volume.seconds / raw.volume.seconds, 8.0, 1e-9);
  // Tables: 5 KB. Readback of a 256x256 RGBA8 image (256 KB): 4096 write bursts.
  EXPECT_EQ(raw.tables.bytes, 5120u);
  EXPECT_EQ(raw.image.transactions, 1024u);
  EXPECT_EQ(raw.image.cycles, 1024 * 68);
  EXPECT_NEAR(raw.image.seconds, 2.09e-3, 0.01e-3);
  // The paper's "about 65 KB" per image is one byte per pixel.
  const auto grey = rtl::pci::vizard2_host_transfers(bus, voxels, UploadFormat::kRawVoxels, 256, 256, 1);
  EXPECT_EQ(grey.image.bytes, 65536u);
  EXPECT_NEAR(grey.image.seconds, 0.52e-3, 0.01e-3);
}

TEST(Pci, RejectsNonsense) {
  PciConfig c;
  c.burst_data_phases = 0;
  EXPECT_THROW(PciBus{c}, Error);
  c = PciConfig{};
  c.idle = -1;
  EXPECT_THROW(PciBus{c}, Error);
}

}  // namespace
}  // namespace voxcast::test
