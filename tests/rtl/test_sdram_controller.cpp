// The reference controller (rtl_model/sdram/controller.hpp) with the in-order
// open-page scheduler and eager refresh, the VIZARD II baseline:
//  (a) latency of single requests: hit CL, miss tRCD + CL, conflict
//      tRP + tRCD + CL (70 ns at PC100 CL3), and their classification;
//  (b) streaming bandwidth (sequential columns of an open row) within 0.5% of
//      the closed form W f (1 - (tRP + tRFC + tRCD) / tREFI), refresh
//      included, and within 2% of the 800 MB/s peak at 100 MHz;
//  (c) random-access bandwidth with every access a row conflict within 1% of
//      the closed form W BL f / T (1 - L / tREFI), T the row-cycle period,
//      and inside the exact bracket L in [tRFC, tRFC + tRAS + tRP];
//  (d) refresh over a long run: the k-th REF between k tREFI and
//      k tREFI + refresh_entry_bound, never overdue;
//  (e) back-pressure on the return FIFO, draining, and a scheduler that
//      breaks its contract;
//  (f) the pending-request queue keeps arrival order through any erase, and
//      the refresh tracker's due and overdue cycles are its owed() counts.
// docs/sdram.md §5 derives the closed forms and lists the measured figures.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <random>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "refmodel/error.hpp"
#include "rtl_model/sched/in_order.hpp"
#include "rtl_model/sched/refresh_eager.hpp"
#include "rtl_model/sdram/controller.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast::rtl;
using namespace voxcast::rtl::sdram;
using voxcast::Error;

struct Grade {
  TimingNs preset;
  sim::ClockDomain clock;
};

std::vector<Grade> grades() {
  return {{presets::pc100_cl2(), sim::clocks::pc100()},
          {presets::pc100_cl3(), sim::clocks::pc100()},
          {presets::pc133_cl3(), sim::clocks::pc133()}};
}

DimmConfig dimm_config(const Grade& g, int burst_length) {
  DimmConfig c;
  c.timing = g.preset;
  c.clock = g.clock;
  c.burst_length = burst_length;
  return c;
}

Controller baseline(const DimmConfig& c, ControllerConfig cc = {}) {
  return Controller(c, std::make_unique<sched::InOrderOpenPage>(),
                    std::make_unique<sched::EagerRefresh>(), cc);
}

// ---- (a) Single-request latency ----------------------------------------------------------
// Pushes one read at `now`, ticks until it completes, returns the completion.
Completion read_once(Controller& ctl, const Address& a, Cycle& now) {
  static std::uint64_t id = 0;
  ctl.push(Request{.id = ++id, .kind = RequestKind::kRead, .address = a, .arrival = now});
  while (!ctl.completions().valid()) ctl.tick(now++);
  return ctl.completions().pop();
}

TEST(ControllerLatency, HitMissAndConflictAtTheirClosedForms) {
  for (const Grade& g : grades()) {
    SCOPED_TRACE(g.preset.name);
    Controller ctl = baseline(dimm_config(g, 1));
    const TimingCycles& t = ctl.dimm().timing();
    Cycle now = 0;
    const Completion miss = read_once(ctl, Address{0, 5, 0}, now);
    EXPECT_EQ(miss.outcome, RowOutcome::kMiss);
    EXPECT_EQ(miss.latency(), t.tRCD + t.CL);
    now += 20;
    const Completion hit = read_once(ctl, Address{0, 5, 9}, now);
    EXPECT_EQ(hit.outcome, RowOutcome::kHit);
    EXPECT_EQ(hit.latency(), t.CL);
    now += 20;
    const Completion conflict = read_once(ctl, Address{0, 6, 0}, now);
    EXPECT_EQ(conflict.outcome, RowOutcome::kConflict);
    EXPECT_EQ(conflict.latency(), t.tRP + t.tRCD + t.CL);
    EXPECT_EQ(conflict.column_command - conflict.first_command, t.tRP + t.tRCD);
    const ControllerStats& s = ctl.stats();
    EXPECT_EQ(s.row_hits, 1u);
    EXPECT_EQ(s.row_misses, 1u);
    EXPECT_EQ(s.row_conflicts, 1u);
    EXPECT_EQ(s.latency_max, t.tRP + t.tRCD + t.CL);
    if (g.preset.name == "PC100 CL3") {
      // VIZARD II: "70 ns for a pre-charge and row activate".
      EXPECT_EQ(g.clock.time_of(conflict.latency()), 70'000);
    }
    EXPECT_NO_THROW(ctl.expect_drained());
  }
}

// ---- Streams -----------------------------------------------------------------------------
struct RunResult {
  ControllerStats stats;
  DimmStats dimm;
  std::vector<Cycle> refreshes;  // cycle of every REF
  double mb_per_s = 0;
};

// Runs `cycles` clocks, keeping the request queue full from `next_address`
// and popping every completion as it arrives.
RunResult run(Controller& ctl, Cycle cycles,
              const std::function<Address(std::uint64_t)>& next_address) {
  RunResult r;
  std::uint64_t id = 0;
  for (Cycle now = 0; now < cycles; ++now) {
    while (ctl.ready()) {
      ctl.push(Request{
          .id = id, .kind = RequestKind::kRead, .address = next_address(id), .arrival = now});
      ++id;
    }
    const std::int64_t refreshes_before = ctl.dimm().refresh().issued();
    ctl.tick(now);
    if (ctl.dimm().refresh().issued() != refreshes_before) r.refreshes.push_back(now);
    while (ctl.completions().valid()) ctl.completions().pop();
  }
  r.stats = ctl.stats();
  r.dimm = ctl.dimm().stats();
  const sim::ClockDomain& clock = ctl.dimm().config().clock;
  // bytes / (cycles x period): bytes x 1e6 / (cycles x ps) is MB/s.
  r.mb_per_s =
      static_cast<double>(r.stats.bytes) * 1e6 / static_cast<double>(cycles * clock.period_ps());
  return r;
}

double relative_error(double measured, double expected) {
  return std::abs(measured - expected) / expected;
}

// ---- (b) Streaming bandwidth -------------------------------------------------------------
TEST(ControllerBandwidth, StreamingOpenRowMatchesPeakMinusRefresh) {
  for (const Grade& g : grades()) {
    for (int bl : {1, 4, 8}) {
      SCOPED_TRACE(g.preset.name + " BL " + std::to_string(bl));
      Controller ctl = baseline(dimm_config(g, bl));
      const TimingCycles& t = ctl.dimm().timing();
      const Geometry& geo = ctl.dimm().geometry();
      const Cycle cycles = 50 * t.tREFI + t.tREFI / 2;
      // Sequential bursts through the columns of one open row.
      const RunResult r = run(ctl, cycles, [&](std::uint64_t i) {
        return Address{0, 3, static_cast<std::uint32_t>(i * t.BL % geo.columns)};
      });
      // Closed form: one beat of W bytes per clock, except tRP + tRFC + tRCD
      // clocks per refresh (PREA in the next burst's slot, REF tRP later, ACT
      // tRFC later, the next RD tRCD later).
      const double peak = geo.bytes_per_beat() * g.clock.frequency_mhz();
      const double closed = peak * (1.0 - static_cast<double>(t.tRP + t.tRFC + t.tRCD) /
                                              static_cast<double>(t.tREFI));
      const std::string key = g.preset.name + " BL" + std::to_string(bl) + " stream MB/s";
      RecordProperty(key + " measured", std::to_string(r.mb_per_s));
      RecordProperty(key + " closed form", std::to_string(closed));
      EXPECT_LT(relative_error(r.mb_per_s, closed), 0.005)
          << "measured " << r.mb_per_s << " MB/s, closed form " << closed << " MB/s; " << r.stats;
      if (g.clock == sim::clocks::pc100()) {
        EXPECT_NEAR(peak, 800.0, 1e-9);
        EXPECT_LT(relative_error(r.mb_per_s, 800.0), 0.02);
      }
      EXPECT_EQ(r.stats.row_conflicts, 0u);
      EXPECT_EQ(r.dimm.refreshes, static_cast<std::uint64_t>(cycles / t.tREFI));
    }
  }
}

// ---- (c) Random access, every access a row conflict --------------------------------------
TEST(ControllerBandwidth, RowConflictStreamMatchesRowCycleClosedForm) {
  for (const Grade& g : grades()) {
    for (int bl : {1, 4, 8}) {
      SCOPED_TRACE(g.preset.name + " BL " + std::to_string(bl));
      Controller ctl = baseline(dimm_config(g, bl));
      const TimingCycles& t = ctl.dimm().timing();
      const Geometry& geo = ctl.dimm().geometry();
      const Cycle cycles = 100 * t.tREFI;
      // One bank, alternating rows, random columns (fixed seed).
      std::mt19937 rng(1234);
      std::uniform_int_distribution<std::uint32_t> column(0, geo.columns - 1);
      const RunResult r = run(ctl, cycles, [&](std::uint64_t i) {
        return Address{2, static_cast<std::uint32_t>(100 + (i & 1)), column(rng)};
      });
      // Closed form. Per access: ACT at a, RD at a + tRCD, PRE at a + P with
      // P = max(tRAS, tRCD + BL), next ACT at a + T with T = max(tRC, P + tRP):
      // B(L) = W BL / T f (1 - L / tREFI), L the clocks a refresh costs. L is
      // tRFC when the REF falls due after the access's RD, and
      // tRFC + tRAS + tRP when it falls due in the tRCD clocks between an ACT
      // and its RD (eager refresh closes the row unread; it is reopened).
      // Where refreshes land on the T-clock access grid depends on
      // tREFI mod T; spread evenly, L = tRFC + (tRCD / T)(tRAS + tRP).
      const Cycle p = std::max(t.tRAS, t.tRCD + t.BL);
      const Cycle period = std::max(t.tRC, p + t.tRP);
      auto bandwidth = [&](double loss) {
        return static_cast<double>(geo.bytes_per_beat() * t.BL) / static_cast<double>(period) *
               g.clock.frequency_mhz() * (1.0 - loss / static_cast<double>(t.tREFI));
      };
      const double l_min = static_cast<double>(t.tRFC);
      const double l_max = static_cast<double>(t.tRFC + t.tRAS + t.tRP);
      const double l_even = l_min + static_cast<double>(t.tRCD) / static_cast<double>(period) *
                                        static_cast<double>(t.tRAS + t.tRP);
      const double closed = bandwidth(l_even);
      const std::string key = g.preset.name + " BL" + std::to_string(bl) + " conflict MB/s";
      RecordProperty(key + " measured", std::to_string(r.mb_per_s));
      RecordProperty(key + " closed form", std::to_string(closed));
      EXPECT_LT(relative_error(r.mb_per_s, closed), 0.01)
          << "measured " << r.mb_per_s << " MB/s, closed form " << closed << " MB/s; " << r.stats;
      // The exact bracket, widened by 0.05% for the partial access at the end.
      EXPECT_GE(r.mb_per_s, bandwidth(l_max) * 0.9995) << r.stats;
      EXPECT_LE(r.mb_per_s, bandwidth(l_min) * 1.0005) << r.stats;
      EXPECT_LE(r.stats.row_misses, r.dimm.refreshes + 1);  // first access, and after each REF
      EXPECT_EQ(r.stats.row_hits, 0u);
    }
  }
}

// ---- (d) Refresh over a long run ---------------------------------------------------------
TEST(ControllerRefresh, EveryRefreshLandsWithinTheEntryBoundOfItsDueTime) {
  for (const Grade& g : grades()) {
    SCOPED_TRACE(g.preset.name);
    Controller ctl = baseline(dimm_config(g, 4));
    const TimingCycles& t = ctl.dimm().timing();
    const Cycle cycles = 200 * t.tREFI + t.tREFI / 2;
    // A mixed stream: mostly row hits, a conflict every 64 requests.
    const RunResult r = run(ctl, cycles, [](std::uint64_t i) {
      return Address{static_cast<std::uint32_t>(i / 64 % 4), static_cast<std::uint32_t>(i / 256),
                     static_cast<std::uint32_t>(i % 64 * 4)};
    });
    ASSERT_EQ(r.refreshes.size(), static_cast<std::size_t>(cycles / t.tREFI));
    for (std::size_t k = 0; k < r.refreshes.size(); ++k) {
      const Cycle due = static_cast<Cycle>(k + 1) * t.tREFI;
      EXPECT_GE(r.refreshes[k], due) << "REF " << k + 1;
      EXPECT_LE(r.refreshes[k], due + refresh_entry_bound(t)) << "REF " << k + 1;
      EXPECT_LT(r.refreshes[k], due + t.tREFI) << "REF " << k + 1;  // before the next is due
    }
    EXPECT_FALSE(ctl.dimm().refresh().overdue(cycles));
    EXPECT_GT(r.stats.row_conflicts, 0u);
  }
}

TEST(ControllerRefresh, IdleControllerStillRefreshes) {
  Controller ctl = baseline(DimmConfig{});
  const Cycle refi = ctl.dimm().timing().tREFI;
  for (Cycle now = 0; now < 10 * refi; ++now) ctl.tick(now);
  EXPECT_EQ(ctl.dimm().stats().refreshes, 9u);
  EXPECT_EQ(ctl.dimm().refresh().last_refresh(), 9 * refi);  // banks idle: REF on the due cycle
  EXPECT_EQ(ctl.dimm().stats().precharge_alls, 0u);
}

// ---- (e) Back-pressure, draining, contract -----------------------------------------------
TEST(ControllerFlow, ReturnFifoBackPressureStallsReadsWithoutLoss) {
  Controller ctl = baseline(DimmConfig{}, ControllerConfig{.queue_depth = 4, .return_depth = 2});
  Cycle now = 0;
  for (std::uint64_t id = 0; id < 4; ++id) {
    ctl.push(Request{.id = id,
                     .kind = RequestKind::kRead,
                     .address = Address{0, 1, static_cast<std::uint32_t>(id)},
                     .arrival = 0});
  }
  EXPECT_FALSE(ctl.ready());
  EXPECT_THROW(ctl.push(Request{}), Error);
  // Nobody pops: two reads fill the FIFO's two slots, the other two wait.
  for (; now < 40; ++now) ctl.tick(now);
  EXPECT_EQ(ctl.completions().size(), 2u);
  EXPECT_EQ(ctl.pending(), 2u);
  EXPECT_THROW(ctl.expect_drained(), Error);
  std::vector<std::uint64_t> order;
  while (!ctl.idle()) {
    while (ctl.completions().valid()) order.push_back(ctl.completions().pop().request.id);
    ctl.tick(now++);
  }
  EXPECT_EQ(order, (std::vector<std::uint64_t>{0, 1, 2, 3}));
  EXPECT_NO_THROW(ctl.expect_drained());
  EXPECT_EQ(ctl.completions().stats().max_occupancy, 2u);
}

TEST(ControllerFlow, WritesCompleteWithTheirDataWindow) {
  Controller ctl = baseline(dimm_config(grades()[0], 4));
  Cycle now = 0;
  ctl.push(
      Request{.id = 1, .kind = RequestKind::kWrite, .address = Address{1, 2, 8}, .arrival = 0});
  ctl.push(
      Request{.id = 2, .kind = RequestKind::kRead, .address = Address{1, 2, 16}, .arrival = 0});
  std::vector<Completion> done;
  while (done.size() < 2) {
    ctl.tick(now++);
    while (ctl.completions().valid()) done.push_back(ctl.completions().pop());
  }
  const TimingCycles& t = ctl.dimm().timing();
  EXPECT_EQ(done[0].request.id, 1u);
  EXPECT_EQ(done[0].data.first, t.tRCD);  // write data with the WRITE
  EXPECT_EQ(done[1].column_command - done[0].column_command, t.write_to_read());
  EXPECT_EQ(ctl.stats().writes, 1u);
  EXPECT_EQ(ctl.stats().reads, 1u);
  std::ostringstream os;
  os << done[1] << "\n" << ctl.stats();
  EXPECT_NE(os.str().find("row hit"), std::string::npos) << os.str();
}

// Breaks the contract: reads whatever the bank state.
class Reckless final : public CommandScheduler {
 public:
  std::string_view name() const override { return "reckless"; }
  std::optional<Decision> pick(const SchedulerView& view) override {
    if (view.pending.empty()) return std::nullopt;
    return Decision{
        .command = Command::kRd, .address = view.pending.front().request.address, .request = 0};
  }
};

TEST(ControllerFlow, ASchedulerBreakingItsContractIsAnError) {
  Controller ctl(DimmConfig{}, std::make_unique<Reckless>(),
                 std::make_unique<sched::EagerRefresh>());
  ctl.push(Request{.id = 7, .kind = RequestKind::kRead, .address = Address{3, 4, 5}, .arrival = 0});
  try {
    ctl.tick(0);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("scheduler 'reckless'"), std::string::npos) << what;
    EXPECT_NE(what.find("ACT to bank 3 row 4"), std::string::npos) << what;
  }
  EXPECT_THROW(baseline(DimmConfig{}).push(Request{.address = Address{9, 0, 0}}), Error);
  EXPECT_THROW(Controller(DimmConfig{}, nullptr, std::make_unique<sched::EagerRefresh>()), Error);
}

// PendingQueue against a std::vector doing the same pushes and erases: the
// same entries in the same order after every step, through the compactions
// that the queue's advancing start forces.
TEST(ControllerQueues, PendingQueueKeepsArrivalOrderThroughAnyErase) {
  std::mt19937 rng(7);
  for (const std::size_t depth : {std::size_t{1}, std::size_t{2}, std::size_t{8}}) {
    PendingQueue queue(depth);
    std::vector<PendingRequest> model;
    std::uint64_t next_id = 0;
    for (int step = 0; step < 5000; ++step) {
      const bool push = model.empty() || (model.size() < depth && rng() % 2 == 0);
      if (push) {
        PendingRequest p;
        p.request.id = next_id++;
        queue.push_back(p);
        model.push_back(p);
      } else {
        // Mostly the oldest, as a row-hit stream serves them.
        const std::size_t i = rng() % 3 == 0 ? rng() % model.size() : 0;
        queue.erase(i);
        model.erase(model.begin() + static_cast<std::ptrdiff_t>(i));
      }
      ASSERT_EQ(queue.size(), model.size());
      const std::span<const PendingRequest> view = queue.span();
      for (std::size_t k = 0; k < model.size(); ++k)
        ASSERT_EQ(view[k].request.id, model[k].request.id) << "step " << step << ", entry " << k;
    }
  }
}

// due() and overdue() compare with cached cycles; the contract states them
// as owed(now) >= 1 and owed(now) > 1 + postpone limit.
TEST(ControllerRefresh, DueAndOverdueAreTheOwedCounts) {
  for (const int limit : {0, 1, 5}) {
    RefreshTracker t(97, limit);
    for (Cycle now = -200; now < 3000; ++now) {
      ASSERT_EQ(t.due(now), t.owed(now) >= 1) << now;
      ASSERT_EQ(t.overdue(now), t.owed(now) > 1 + limit) << now;
      if (now > 0 && now % 150 == 0) t.on_refresh(now);
    }
  }
}

}  // namespace
