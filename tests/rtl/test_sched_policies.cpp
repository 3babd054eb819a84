// The row-activate schedulers beyond the baseline (rtl_model/sched/):
//  (a) every policy, on random request streams with refresh, never puts an
//      illegal command on the bus (the Dimm is the referee and throws) and
//      serves every request exactly once; on a pure open-row stream every
//      policy reaches the streaming closed form of docs/sdram.md §5;
//  (b) FR-FCFS serves row hits inside its window ahead of an older
//      conflict, and bypasses the oldest request exactly starvation_limit
//      times before serving it;
//  (c) look-ahead activation on a stream of segments alternating between
//      two banks hides tRP and tRCD: each row change costs one command-bus
//      cycle per row command instead of tRP + tRCD (closed forms below).
// Bit-exactness of whole frames for every policy is in test_rtl_engine.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "refmodel/error.hpp"
#include "rtl_model/sched/fr_fcfs.hpp"
#include "rtl_model/sched/registry.hpp"
#include "rtl_model/sdram/controller.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast::rtl;
using namespace voxcast::rtl::sdram;

Controller make(const std::string& scheduler, SchedulerParams params = {},
                ControllerConfig cc = {}, DimmConfig dimm = {}) {
  return Controller(dimm, sched::make_scheduler(scheduler, params),
                    sched::make_refresh_policy("eager"), cc);
}

// Feeds `addresses` (ids 0, 1, ...) as fast as the queue takes them, pops
// every completion at once, and returns the completions in data order.
std::vector<Completion> serve(Controller& ctl, const std::vector<Address>& addresses,
                              Cycle& now, Cycle limit = 10'000'000) {
  std::vector<Completion> done;
  std::size_t next = 0;
  while (done.size() < addresses.size()) {
    while (next < addresses.size() && ctl.ready()) {
      ctl.push(Request{.id = next, .kind = RequestKind::kRead, .address = addresses[next],
                       .arrival = now});
      ++next;
    }
    ctl.tick(now++);
    while (ctl.completions().valid()) done.push_back(ctl.completions().pop());
    if (now > limit) ADD_FAILURE() << "no progress";
    if (now > limit) break;
  }
  return done;
}

std::vector<std::uint64_t> ids(const std::vector<Completion>& c) {
  std::vector<std::uint64_t> v;
  for (const Completion& x : c) v.push_back(x.request.id);
  return v;
}

// ---- (a) Legal commands, every request once, streaming closed form ------------------------
TEST(SchedPolicies, EveryPolicyIsLegalAndServesEveryRequestOnce) {
  for (const std::string& name : sched::scheduler_names()) {
    for (int window : {1, 3, 8}) {
      SCOPED_TRACE(name + ", window " + std::to_string(window));
      Controller ctl = make(name, SchedulerParams{.reorder_window = window, .starvation_limit = 5});
      const Cycle refi = ctl.dimm().timing().tREFI;
      // Runs of hits in random banks and rows, mixed with conflicts and
      // misses; long enough for several refreshes.
      std::mt19937 rng(77);
      std::vector<Address> a;
      while (a.size() < 12'000) {
        const Address base{static_cast<std::uint32_t>(rng() % 4), static_cast<std::uint32_t>(rng() % 6),
                           static_cast<std::uint32_t>(rng() % 256)};
        const std::size_t run = 1 + rng() % 12;
        for (std::size_t k = 0; k < run; ++k)
          a.push_back({base.bank, base.row, static_cast<std::uint32_t>((base.column + k) % 512)});
      }
      Cycle now = 0;
      std::vector<Completion> done;
      ASSERT_NO_THROW(done = serve(ctl, a, now));  // the Dimm throws on any illegal command
      std::vector<std::uint64_t> got = ids(done);
      std::sort(got.begin(), got.end());
      for (std::size_t i = 0; i < got.size(); ++i) ASSERT_EQ(got[i], i);
      EXPECT_GT(ctl.dimm().stats().refreshes, static_cast<std::uint64_t>(now / refi) - 1);
      EXPECT_NO_THROW(ctl.expect_drained());
    }
  }
}

TEST(SchedPolicies, EveryPolicyStreamsAnOpenRowAtTheClosedForm) {
  for (const std::string& name : sched::scheduler_names()) {
    SCOPED_TRACE(name);
    Controller ctl = make(name);
    const TimingCycles& t = ctl.dimm().timing();
    std::vector<Address> a;
    for (std::uint32_t i = 0; i < 40 * t.tREFI; ++i) a.push_back({1, 9, i % 512});
    Cycle now = 0;
    const std::vector<Completion> done = serve(ctl, a, now);
    // One read per clock but tRP + tRFC + tRCD per refresh (docs/sdram.md §5).
    const double closed = 1.0 - static_cast<double>(t.tRP + t.tRFC + t.tRCD) /
                                    static_cast<double>(t.tREFI);
    const double measured = static_cast<double>(done.size()) / static_cast<double>(now);
    EXPECT_LT(std::abs(measured - closed) / closed, 0.005) << measured << " vs " << closed;
  }
}

// Every access a row conflict in one bank (alternating rows): a policy that
// serves this bank in order (in-order; look-ahead, which prepares only other
// banks; FR-FCFS with a window of 1) overlaps nothing and must reach the
// row-cycle closed form of docs/sdram.md §5: one BL-1 read per
// T = max(tRC, max(tRAS, tRCD + BL) + tRP) clocks, less L clocks per
// refresh, L in [tRFC, tRFC + tRAS + tRP]. FR-FCFS with a window of 8 pairs
// up the requests to each row instead: at least 3 of every 4 become hits.
TEST(SchedPolicies, RowConflictStreamAtTheClosedForm) {
  struct Case {
    std::string name;
    int window;
  };
  for (const Case& k : {Case{"in-order", 8}, Case{"lookahead", 8}, Case{"fr-fcfs", 1},
                        Case{"fr-fcfs", 8}}) {
    SCOPED_TRACE(k.name + ", window " + std::to_string(k.window));
    Controller ctl = make(k.name, SchedulerParams{.reorder_window = k.window});
    const TimingCycles& t = ctl.dimm().timing();
    std::vector<Address> a;
    for (std::uint32_t i = 0; i < 30 * t.tREFI / 7; ++i) a.push_back({2, 100 + (i & 1), i % 512});
    Cycle now = 0;
    const std::vector<Completion> done = serve(ctl, a, now);
    const Cycle period = std::max(t.tRC, std::max(t.tRAS, t.tRCD + t.BL) + t.tRP);
    const auto rate = [&](double loss) {
      return 1.0 / static_cast<double>(period) * (1.0 - loss / static_cast<double>(t.tREFI));
    };
    const double measured = static_cast<double>(done.size()) / static_cast<double>(now);
    if (k.window == 8 && k.name == "fr-fcfs") {
      EXPECT_GE(ctl.stats().row_hits * 4, ctl.stats().requests * 3) << ctl.stats();
      EXPECT_GT(measured, 2.0 * rate(static_cast<double>(t.tRFC)));
      continue;
    }
    EXPECT_GE(measured, rate(static_cast<double>(t.tRFC + t.tRAS + t.tRP)) * 0.995);
    EXPECT_LE(measured, rate(static_cast<double>(t.tRFC)) * 1.005);
    EXPECT_EQ(ctl.stats().row_hits, 0u);
  }
}

// ---- (b) FR-FCFS --------------------------------------------------------------------------
TEST(FrFcfs, HitsInsideTheWindowOvertakeAnOlderConflict) {
  for (int window : {1, 3}) {
    SCOPED_TRACE("window " + std::to_string(window));
    Controller ctl = make("fr-fcfs", SchedulerParams{.reorder_window = window});
    Cycle now = 0;
    serve(ctl, {{0, 0, 0}}, now);  // opens row 0 of bank 0
    // 0: a conflict (row 1), then two hits to the open row.
    const std::vector<Completion> done = serve(ctl, {{0, 1, 0}, {0, 0, 1}, {0, 0, 2}}, now);
    if (window == 1) {  // in order: the conflict first, the hits become conflicts
      EXPECT_EQ(ids(done), (std::vector<std::uint64_t>{0, 1, 2}));
      EXPECT_EQ(ctl.stats().row_conflicts, 2u);
    } else {
      EXPECT_EQ(ids(done), (std::vector<std::uint64_t>{1, 2, 0}));
      EXPECT_EQ(ctl.stats().row_hits, 2u);
      EXPECT_EQ(ctl.stats().row_conflicts, 1u);
    }
  }
}

TEST(FrFcfs, TheOldestIsBypassedExactlyStarvationLimitTimes) {
  for (int limit : {0, 1, 5, 40}) {
    SCOPED_TRACE("limit " + std::to_string(limit));
    Controller ctl = make("fr-fcfs", SchedulerParams{.reorder_window = 8, .starvation_limit = limit});
    Cycle now = 0;
    serve(ctl, {{0, 0, 0}}, now);
    // The oldest: a conflict in bank 0; behind it an endless supply of hits
    // to bank 0's open row, which FR-FCFS prefers.
    std::vector<Address> a{{0, 1, 0}};
    for (std::uint32_t i = 1; i < 200; ++i) a.push_back({0, 0, i % 512});
    const std::vector<Completion> done = serve(ctl, a, now);
    const auto it = std::find_if(done.begin(), done.end(),
                                 [](const Completion& c) { return c.request.id == 0; });
    ASSERT_NE(it, done.end());
    EXPECT_EQ(it - done.begin(), limit);
  }
}

// ---- (c) Look-ahead activation ------------------------------------------------------------
// Segments of S reads, segment k to bank k % 2, row k: segment 1 starts with
// a miss, every later segment with a conflict. The request source is always
// ahead (the queue is full), so the closed forms hold with the first read
// at tRCD:
//   in order:   last RD = tRCD + (N S - 1) + tRCD + (N - 2)(tRP + tRCD)
//   look-ahead: last RD = tRCD + (N S - 1) + 1    + (N - 2) 2
// (one stolen command-bus cycle for the ACT of segment 1, two for the PRE and
// ACT of each later segment; tRP and tRCD elapse under the stream). S is long
// enough that tRAS, tRC and tRRD never bind, and the run ends before the
// first refresh falls due.
const std::map<std::string, TimingNs> kPc100Grades{{"pc100-cl2", presets::pc100_cl2()},
                                                   {"pc100-cl3", presets::pc100_cl3()}};

// N segments of S reads each, segment k to row k of bank k mod 2.
std::vector<Address> alternating_bank_segments(Cycle S, Cycle N) {
  std::vector<Address> a;
  for (Cycle k = 0; k < N; ++k)
    for (Cycle i = 0; i < S; ++i)
      a.push_back({static_cast<std::uint32_t>(k % 2), static_cast<std::uint32_t>(k),
                   static_cast<std::uint32_t>(i)});
  return a;
}

TEST(LookAhead, HidesPrechargeAndActivateOnAlternatingBanks) {
  for (const auto& [grade, timing] : kPc100Grades) {
    DimmConfig dimm;
    dimm.timing = timing;
    const Cycle S = 16, N = 20;
    const std::vector<Address> a = alternating_bank_segments(S, N);
    std::map<std::string, Cycle> last_rd;
    for (const char* name : {"in-order", "lookahead"}) {
      SCOPED_TRACE(grade + " " + name);
      Controller ctl = make(name, {}, {}, dimm);
      Cycle now = 0;
      const std::vector<Completion> done = serve(ctl, a, now);
      ASSERT_EQ(done.size(), a.size());
      ASSERT_LT(now, ctl.dimm().timing().tREFI);
      EXPECT_EQ(ctl.dimm().stats().refreshes, 0u);
      last_rd[name] = done.back().column_command;
      // Data in order for both.
      for (std::size_t i = 0; i < done.size(); ++i) EXPECT_EQ(done[i].request.id, i);
    }
    const TimingCycles t = Dimm(dimm).timing();
    EXPECT_EQ(last_rd["in-order"], t.tRCD + (N * S - 1) + t.tRCD + (N - 2) * (t.tRP + t.tRCD))
        << grade;
    EXPECT_EQ(last_rd["lookahead"], t.tRCD + (N * S - 1) + 1 + (N - 2) * 2) << grade;
  }
}

// The same stream with the adaptive page policy (ControllerConfig::
// auto_precharge): the last READ of each segment finds no other request for
// its row in the queue and goes as READ with auto precharge, so each row
// change costs the ACT alone: one command-bus cycle with look-ahead (instead
// of two), tRCD in order (instead of tRP + tRCD: the bank closed itself under
// the other bank's segment).
TEST(AutoPrecharge, ARowChangeCostsTheActivateAlone) {
  for (const auto& [grade, timing] : kPc100Grades) {
    DimmConfig dimm;
    dimm.timing = timing;
    const Cycle S = 16, N = 20;
    const std::vector<Address> a = alternating_bank_segments(S, N);
    const TimingCycles t = Dimm(dimm).timing();
    const std::map<std::string, Cycle> expected{
        {"in-order", t.tRCD + (N * S - 1) + (N - 1) * t.tRCD},
        {"lookahead", t.tRCD + (N * S - 1) + 1 + (N - 2) * 1}};
    for (const auto& [name, last] : expected) {
      SCOPED_TRACE(grade + " " + name);
      Controller ctl = make(name, {}, {.auto_precharge = true}, dimm);
      Cycle now = 0;
      const std::vector<Completion> done = serve(ctl, a, now);
      ASSERT_EQ(done.size(), a.size());
      ASSERT_LT(now, t.tREFI);
      for (std::size_t i = 0; i < done.size(); ++i) EXPECT_EQ(done[i].request.id, i);
      EXPECT_EQ(done.back().column_command, last);
      // One RDA per segment (its last READ), no PRE at all.
      EXPECT_EQ(ctl.stats().auto_precharges, static_cast<std::uint64_t>(N));
      const BankStats b = ctl.dimm().stats().total();
      EXPECT_EQ(b.auto_precharges, static_cast<std::uint64_t>(N));
      EXPECT_EQ(b.precharges, static_cast<std::uint64_t>(N));
      EXPECT_EQ(b.activates, static_cast<std::uint64_t>(N));
      EXPECT_EQ(ctl.stats().command_cycles, static_cast<Cycle>(N * S + N));
      EXPECT_EQ(ctl.stats().row_conflicts, 0u);
    }
  }
}

TEST(SchedPolicies, RegistryRejectsUnknownNamesAndBadParameters) {
  EXPECT_THROW(sched::make_scheduler("fifo"), voxcast::Error);
  try {
    sched::make_scheduler("fifo");
  } catch (const voxcast::Error& e) {
    EXPECT_NE(std::string(e.what()).find("in-order, fr-fcfs, lookahead"), std::string::npos);
  }
  EXPECT_THROW(sched::make_scheduler("fr-fcfs", SchedulerParams{.reorder_window = 0}),
               voxcast::Error);
  EXPECT_THROW(sched::make_scheduler("fr-fcfs", SchedulerParams{.starvation_limit = -1}),
               voxcast::Error);
}

}  // namespace
