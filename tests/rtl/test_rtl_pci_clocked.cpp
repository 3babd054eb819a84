// The PCI bus as a clock domain (rtl_model/pci/pci_dma.hpp) and its
// crossing to the core (rtl_model/sim/async_fifo.hpp): the clocked DMA
// engine must reproduce the transaction-level closed forms of pci_bus.hpp
// (docs/performance.md §4) exactly when the core keeps up, move every word
// once and in order across the 33 MHz / 100 MHz crossing, and pay wait
// states, not lose data, when the core is slower than the bus.
#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <random>
#include <vector>

#include "refmodel/error.hpp"
#include "rtl_model/pci/pci_bus.hpp"
#include "rtl_model/pci/pci_dma.hpp"
#include "rtl_model/sim/async_fifo.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

using rtl::pci::Direction;

std::vector<std::uint32_t> counting(std::uint64_t n) {
  std::vector<std::uint32_t> w(n);
  std::iota(w.begin(), w.end(), 0x1000u);
  return w;
}

// A pushed entry is seen by the reader at its second read-clock edge after
// the push (two synchroniser flops), not at the first; the freed slot is
// seen by the writer at its second write-clock edge after the pop.
TEST(AsyncFifo, SynchroniserLatencyIsTwoEdgesOfTheOtherDomain) {
  rtl::sim::AsyncFifo<int> f("cdc", 2);
  f.write_clock();
  f.push(7);
  EXPECT_FALSE(f.valid());
  f.read_clock();
  EXPECT_FALSE(f.valid());
  f.read_clock();
  ASSERT_TRUE(f.valid());
  f.push(8);  // the writer still sees both slots as free
  EXPECT_FALSE(f.ready());
  EXPECT_EQ(f.pop(), 7);
  f.write_clock();
  EXPECT_FALSE(f.ready());
  f.write_clock();
  EXPECT_TRUE(f.ready());
  EXPECT_THROW(rtl::sim::AsyncFifo<int>("bad", 3), Error);
  EXPECT_THROW(rtl::sim::AsyncFifo<int>("bad", 4, 1), Error);
}

// Random pushes and pops at unrelated clocks (7.5 ns and 30 ns, and the
// reverse): every entry arrives once, in order; a push when not ready or a
// pop when not valid is refused by the FIFO itself.
TEST(AsyncFifo, NothingLostOrReorderedAcrossUnrelatedClocks) {
  for (auto [tw, tr] : {std::pair{7500, 30000}, std::pair{30000, 7500}, std::pair{10000, 10000}}) {
    rtl::sim::AsyncFifo<int> f("cdc", 4);
    std::mt19937 rng(3);
    int next = 0, expect = 0;
    std::int64_t w = 0, r = 0;
    while (expect < 3000) {
      if (w * tw <= r * tr) {
        f.write_clock();
        if (rng() % 2 && f.ready()) f.push(next++);
        ++w;
      } else {
        f.read_clock();
        if (rng() % 3 && f.valid()) {
          ASSERT_EQ(f.pop(), expect++);
        }
        ++r;
      }
    }
    EXPECT_LE(f.size(), 4u);
  }
  rtl::sim::AsyncFifo<int> f("cdc", 2);
  EXPECT_THROW(f.pop(), Error);
}

// With the core at 100 MHz moving a word per clock the bus never waits: the
// clocked transfers take exactly the closed-form clocks of §4 (upload of the
// 256^3 one-byte volume 147.5 ms, the 5 KB tables, the 256x256 RGBA8
// readback 2.09 ms), and the words arrive in order.
TEST(PciClocked, EqualsTheClosedFormsWhenTheCoreKeepsUp) {
  const rtl::pci::PciBus bus;
  const auto core = rtl::sim::clocks::pc100();
  struct Case {
    std::uint64_t bytes;
    Direction dir;
  };
  for (const Case c : {Case{std::uint64_t{256} * 256 * 256, Direction::kHostToCard},
                       Case{2048 + 3072, Direction::kHostToCard},
                       Case{256 * 256 * 4, Direction::kCardToHost},
                       Case{65536 + 12, Direction::kCardToHost}}) {
    SCOPED_TRACE(::testing::Message() << c.bytes << " bytes");
    const auto words = counting(c.bytes / 4);
    const rtl::pci::ClockedTransfer t = rtl::pci::run_clocked_transfer(bus.config(), core, c.dir, words);
    const rtl::pci::PciStats closed = bus.transfer(c.bytes, c.dir);
    EXPECT_EQ(t.pci.cycles, closed.cycles);
    EXPECT_EQ(t.pci.data_cycles, closed.data_cycles);
    EXPECT_EQ(t.pci.transactions, closed.transactions);
    EXPECT_EQ(t.wait_cycles, 0);
    EXPECT_DOUBLE_EQ(t.pci.seconds, closed.seconds);
    ASSERT_EQ(t.words, words);
  }
  const auto words = counting(std::uint64_t{256} * 256 * 256 / 4);
  EXPECT_NEAR(rtl::pci::run_clocked_transfer(bus.config(), core, Direction::kHostToCard, words)
                  .pci.seconds,
              0.1475, 0.0001);
}

// A core that moves a word only every 8th clock (12.5 M words/s, 50 MB/s,
// below the bus's 133 MB/s): the master waits, nothing is lost, and the
// readback takes the core's time (words x 80 ns) plus at most the closed
// form's per-transaction overhead.
TEST(PciClocked, ASlowCoreCostsWaitStatesNotData) {
  const rtl::pci::PciBus bus;
  const auto words = counting(4096);
  const auto t = rtl::pci::run_clocked_transfer(bus.config(), rtl::sim::clocks::pc100(),
                                                Direction::kCardToHost, words, 8);
  ASSERT_EQ(t.words, words);
  EXPECT_GT(t.wait_cycles, 0);
  const double core_s = 4096 * 80e-9;
  const rtl::pci::PciStats closed = bus.transfer(4096 * 4, Direction::kCardToHost);
  EXPECT_GE(t.pci.seconds, core_s);
  EXPECT_LE(t.pci.seconds, core_s + static_cast<double>(closed.overhead_cycles) * 30e-9 + 90e-9);
  EXPECT_EQ(t.pci.data_cycles, 4096);
}

}  // namespace
}  // namespace voxcast::test

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

// Double-buffered readback: frames of 5 ms with a 2.09 ms readback overlap
// completely (each readback ends 2.09 ms into the next frame); frames of
// 1 ms with a 2.09 ms readback cannot: from frame 2 on each frame waits for
// its buffer, and the schedule settles at one frame per readback.
TEST(PciClocked, DoubleBufferedReadbackHidesBehindLongFramesOnly) {
  const auto core = rtl::sim::clocks::pc100();
  rtl::pci::PciStats rb;
  rb.seconds = 2.09e-3;
  const auto slow = rtl::pci::double_buffered_readback({500000, 500000, 500000}, core, rb);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(slow[k].render_start_s, 5e-3 * static_cast<double>(k));
    EXPECT_DOUBLE_EQ(slow[k].readback_end_s, 5e-3 * static_cast<double>(k + 1) + 2.09e-3);
    EXPECT_EQ(slow[k].stall_s, 0.0);
  }
  EXPECT_TRUE(slow[0].hidden);
  EXPECT_TRUE(slow[1].hidden);
  EXPECT_FALSE(slow[2].hidden);  // the last frame: nothing to hide behind
  const auto fast = rtl::pci::double_buffered_readback({100000, 100000, 100000, 100000}, core, rb);
  EXPECT_FALSE(fast[0].hidden);
  EXPECT_EQ(fast[1].stall_s, 0.0);
  EXPECT_NEAR(fast[2].stall_s, 1e-3 + 2.09e-3 - 2e-3, 1e-12);  // frame 0's readback ends at 3.09 ms
  EXPECT_NEAR(fast[3].render_start_s - fast[2].render_start_s, 2.09e-3, 1e-12);
}

}  // namespace
}  // namespace voxcast::test
