// The simulation core (rtl_model/sim/): clock domains and the one place of
// time/cycle conversion; the bounded valid/ready FIFO.
//  (a) closed forms of the conversions at 100 MHz, 133 MHz and 33 MHz PCI,
//      including the exact-boundary cases the integer picoseconds guarantee;
//  (b) several domains advanced together in time order;
//  (c) the FIFO: order, wrap-around, occupancy statistics, and the protocol
//      errors (push when full, pop when empty, data left at the end), each
//      naming the FIFO.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "refmodel/error.hpp"
#include "rtl_model/sim/clock.hpp"
#include "rtl_model/sim/fifo.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast::rtl::sim;
using voxcast::Error;

// Expects `fn` to throw voxcast::Error with every one of `parts` in what().
template <typename Fn>
void expect_error(Fn&& fn, const std::vector<std::string>& parts) {
  try {
    fn();
    ADD_FAILURE() << "no voxcast::Error thrown";
  } catch (const Error& e) {
    const std::string what = e.what();
    for (const std::string& p : parts) EXPECT_NE(what.find(p), std::string::npos) << what;
  }
}

// ---- (a) Conversions ---------------------------------------------------------------------
TEST(ClockDomain, PresetsHaveTheirPeriods) {
  EXPECT_EQ(clocks::pc100().period_ps(), 10'000);
  EXPECT_EQ(clocks::pc133().period_ps(), 7'500);
  EXPECT_EQ(clocks::pci33().period_ps(), 30'000);
  EXPECT_DOUBLE_EQ(clocks::pc100().frequency_mhz(), 100.0);
  EXPECT_NEAR(clocks::pc133().frequency_mhz(), 133.333, 1e-3);
  EXPECT_NEAR(clocks::pci33().frequency_mhz(), 33.333, 1e-3);
  // 133 MHz from a frequency rounds to 7519 ps: PC133 must use its period.
  EXPECT_EQ(ClockDomain::from_mhz("x", 133.0).period_ps(), 7'519);
  EXPECT_EQ(ClockDomain::from_mhz("x", 100.0), ClockDomain("x", 10'000));
}

TEST(ClockDomain, MinimumDelaysRoundUpMaximumIntervalsDown) {
  const ClockDomain c100 = clocks::pc100();
  const ClockDomain c133 = clocks::pc133();
  struct Case {
    double ns;
    Cycle up100, down100, up133, down133;  // ceil/floor(ns / 10), ceil/floor(ns / 7.5)
  };
  const Case cases[] = {
      {0, 0, 0, 0, 0},   {7.5, 1, 0, 1, 1},
      {10, 1, 1, 2, 1},  {15, 2, 1, 2, 2},
      {20, 2, 2, 3, 2},  {20.001, 3, 2, 3, 2},
      {44, 5, 4, 6, 5},  {66, 7, 6, 9, 8},
      {70, 7, 7, 10, 9}, {15625, 1563, 1562, 2084, 2083},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.ns);
    const Picoseconds ps = ps_from_ns(k.ns);
    EXPECT_EQ(c100.cycles_at_least(ps), k.up100);
    EXPECT_EQ(c100.cycles_at_most(ps), k.down100);
    EXPECT_EQ(c133.cycles_at_least(ps), k.up133);
    EXPECT_EQ(c133.cycles_at_most(ps), k.down133);
  }
}

TEST(ClockDomain, CrossesBetweenDomainsAtEdges) {
  const ClockDomain sdram = clocks::pc100();
  const ClockDomain pci = clocks::pci33();
  // PCI edge 3 is at 90 ns: SDRAM edge 9 coincides.
  EXPECT_EQ(sdram.edge_at_or_after(3, pci), 9);
  // SDRAM edge 10 (100 ns) is first seen at PCI edge 4 (120 ns).
  EXPECT_EQ(pci.edge_at_or_after(10, sdram), 4);
  EXPECT_EQ(pci.edge_at_or_after(9, sdram), 3);
  // 3 PCI cycles last 9 SDRAM cycles; 4 SDRAM cycles need 2 PCI cycles.
  EXPECT_EQ(sdram.cycles_covering(3, pci), 9);
  EXPECT_EQ(pci.cycles_covering(4, sdram), 2);
  EXPECT_EQ(sdram.time_of(7), 70'000);
}

TEST(ClockDomain, RejectsNonsense) {
  expect_error([] { ClockDomain("bad", 0); }, {"bad", "not positive"});
  expect_error([] { ClockDomain::from_mhz("bad", -1.0); }, {"bad"});
  expect_error([] { ps_from_ns(-1.0); }, {"-1"});
}

// ---- (b) Several domains -----------------------------------------------------------------
TEST(MultiClock, AdvancesDomainsInTimeOrderWithCoincidentEdgesTogether) {
  MultiClock clock;
  const std::size_t sdram = clock.add(clocks::pc100());
  const std::size_t pci = clock.add(clocks::pci33());
  std::vector<Picoseconds> times;
  for (int i = 0; i < 7; ++i) {
    const MultiClock::Tick t = clock.advance();
    times.push_back(t.time);
    const bool pci_edge = t.time % 30'000 == 0;
    ASSERT_EQ(t.edges.size(), pci_edge ? 2u : 1u) << "at " << t.time;
    EXPECT_EQ(t.edges[0].domain, sdram);
    EXPECT_EQ(t.edges[0].cycle, t.time / 10'000);
    if (pci_edge) {
      EXPECT_EQ(t.edges[1].domain, pci);
    }
  }
  EXPECT_EQ(times, (std::vector<Picoseconds>{0, 10'000, 20'000, 30'000, 40'000, 50'000, 60'000}));
  EXPECT_EQ(clock.edges_seen(sdram), 7);
  EXPECT_EQ(clock.edges_seen(pci), 3);
  EXPECT_THROW(MultiClock{}.advance(), Error);
}

// ---- (c) FIFO ----------------------------------------------------------------------------
TEST(Fifo, KeepsOrderAcrossWrapAround) {
  Fifo<int> f("wrap", 3);
  int next_in = 0;
  int next_out = 0;
  for (int round = 0; round < 10; ++round) {
    while (f.ready()) f.push(next_in++);
    EXPECT_TRUE(f.full());
    f.sample();
    EXPECT_EQ(f.pop(), next_out++);
    EXPECT_EQ(f.pop(), next_out++);
  }
  while (f.valid()) EXPECT_EQ(f.pop(), next_out++);
  EXPECT_EQ(next_in, next_out);
  EXPECT_TRUE(f.drained());
  EXPECT_EQ(f.stats().pushes, static_cast<std::uint64_t>(next_in));
  EXPECT_EQ(f.stats().max_occupancy, 3u);
}

// The collapsing queue of row-hit issue: taking an entry from the middle keeps
// the order of the rest, across the wrap-around of the ring.
TEST(Fifo, TakeFromTheMiddleKeepsTheOrderOfTheRest) {
  Fifo<int> f("collapse", 4);
  for (int v = 0; v < 3; ++v) f.push(v);
  EXPECT_EQ(f.pop(), 0);
  f.push(3);
  f.push(4);  // the ring now wraps: 1 2 3 4
  ASSERT_TRUE(f.full());
  EXPECT_EQ(f.at(2), 3);
  EXPECT_EQ(f.take(2), 3);  // 1 2 4
  EXPECT_EQ(f.size(), 3u);
  f.push(5);  // 1 2 4 5
  EXPECT_EQ(f.take(0), 1);
  EXPECT_EQ(f.take(2), 5);
  EXPECT_EQ(f.pop(), 2);
  EXPECT_EQ(f.pop(), 4);
  EXPECT_TRUE(f.empty());
  EXPECT_EQ(f.stats().pushes, f.stats().pops);
  expect_error([&f] { f.take(0); }, {"collapse", "take() past the last entry"});
  f.push(7);
  expect_error([&f] { (void)f.at(1); }, {"collapse", "at() past the last entry"});
}

TEST(Fifo, OccupancyStatisticsAreMemberCounters) {
  Fifo<int> f("stats", 4);
  // Occupancy 0, 1, 2, 3, 4 over five sampled cycles: mean 2, one full, one empty.
  for (int i = 0; i < 5; ++i) {
    f.sample();
    if (f.ready()) f.push(i);
  }
  EXPECT_EQ(f.stats().sampled_cycles, 5u);
  EXPECT_EQ(f.stats().occupancy_sum, 0u + 1 + 2 + 3 + 4);
  EXPECT_DOUBLE_EQ(f.stats().mean_occupancy(), 2.0);
  EXPECT_EQ(f.stats().full_cycles, 1u);
  EXPECT_EQ(f.stats().empty_cycles, 1u);
}

// Sampling on change (the pipeline's FIFOs) gives the statistics of sampling
// every clock: a fixed-seed stream of pushes, pops and takes, with idle
// stretches, into two FIFOs, one sampled at the end of every cycle and one
// told the cycle.
// The lazy FIFO starts with entries, at a clock other than 0, is read out
// half-way (sample_until goes on accounting from there), and builds and
// drops entries in place (emplace, discard) and by copy (push_copy) as well
// as by value.
TEST(Fifo, SamplingOnChangeEqualsSamplingEveryCycle) {
  Fifo<int> every("every", 5), lazy("lazy", 5);
  for (int v : {7, 8}) {
    every.push(v);
    lazy.push(v);
  }
  const std::int64_t start = 100;
  std::int64_t now = start;
  lazy.sample_on_change(&now, start);
  std::uint32_t seed = 12345;
  auto rnd = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return seed >> 16;
  };
  for (now = start; now < 20000; ++now) {
    const unsigned moves = (now / 500) % 3 == 2 ? 0 : rnd() % 3;  // idle stretches too
    for (unsigned m = 0; m < moves; ++m) {
      const unsigned op = rnd() % 6;
      const int v = static_cast<int>(rnd() % 1000);
      if (op == 0 && every.ready()) {
        every.push(v);
        lazy.push(v);
      } else if (op == 1 && every.valid()) {
        ASSERT_EQ(lazy.pop(), every.pop());
      } else if (op == 2 && every.size() > 1) {
        ASSERT_EQ(lazy.take(1), every.take(1));
      } else if (op == 3 && every.ready()) {
        every.push(v);
        lazy.emplace() = v;
      } else if (op == 4 && every.valid()) {
        ASSERT_EQ(lazy.front(), every.front());
        every.pop();
        lazy.discard();
      } else if (op == 5 && every.ready()) {
        every.push(v);
        lazy.push_copy(v);
      }
    }
    every.sample();
    // A producer that samples on its own ticks (a memory port) counts
    // nothing more: the owner's clock accounts every cycle.
    if (rnd() % 4 == 0) lazy.sample();
    if (now == 9999) lazy.sample_until(now + 1);  // a read-out half-way
  }
  lazy.sample_until(now);
  const FifoStats& a = every.stats();
  const FifoStats& b = lazy.stats();
  EXPECT_EQ(b.sampled_cycles, a.sampled_cycles);
  EXPECT_EQ(b.occupancy_sum, a.occupancy_sum);
  EXPECT_EQ(b.full_cycles, a.full_cycles);
  EXPECT_EQ(b.empty_cycles, a.empty_cycles);
  EXPECT_EQ(b.max_occupancy, a.max_occupancy);
  EXPECT_EQ(b.pushes, a.pushes);
  EXPECT_EQ(b.pops, a.pops);
  EXPECT_GT(a.full_cycles, 0u);
  EXPECT_GT(a.empty_cycles, 0u);
}

TEST(Fifo, OverflowAndUnderflowAreErrorsNamingTheFifo) {
  Fifo<int> f("sdram.return", 2);
  expect_error([&] { f.pop(); }, {"FIFO 'sdram.return'", "depth 2", "pop while empty"});
  expect_error([&] { (void)f.front(); }, {"sdram.return", "empty"});
  f.push(1);
  f.push(2);
  expect_error([&] { f.push(3); }, {"FIFO 'sdram.return'", "push while full"});
  expect_error([&] { f.emplace() = 3; }, {"FIFO 'sdram.return'", "push while full"});
  expect_error([&] { f.push_copy(3); }, {"FIFO 'sdram.return'", "push while full"});
  EXPECT_EQ(f.size(), 2u);  // the failed pushes changed nothing
  EXPECT_FALSE(f.drained());
  expect_error([&] { f.expect_drained(); }, {"sdram.return", "2 entries at the end"});
  f.pop();
  f.discard();
  EXPECT_NO_THROW(f.expect_drained());
  expect_error([&] { f.discard(); }, {"FIFO 'sdram.return'", "pop while empty"});
  expect_error([] { Fifo<int>("zero", 0); }, {"zero", "depth 0"});
}

}  // namespace
