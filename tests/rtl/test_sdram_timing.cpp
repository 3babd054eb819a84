// SDRAM timing as data (rtl_model/sdram/timing.hpp):
//  (a) ns -> cycles: the one conversion, closed forms at 100 MHz and 133 MHz;
//  (b) every preset converted: the hand-derived cycle counts of docs/sdram.md
//      §2, and every parameter equal to ceil (minimum) / floor (maximum) of
//      ns over the period computed independently in integer picoseconds;
//  (c) VIZARD II's "70 ns for a precharge and row activate" in both readings;
//  (d) the constraint table: every row equals its named formula, and the
//      grades refuse clocks they are not rated for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include "refmodel/error.hpp"
#include "rtl_model/sdram/timing.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast::rtl;
using namespace voxcast::rtl::sdram;
using voxcast::Error;

// ---- (a) The one conversion --------------------------------------------------------------
TEST(NsToCycles, ClosedFormsAt100And133MHz) {
  const sim::ClockDomain c100 = sim::clocks::pc100();
  const sim::ClockDomain c133 = sim::clocks::pc133();
  // ceil(ns / 10) and ceil(ns / 7.5) for the datasheet values in the presets.
  const std::map<double, std::pair<Cycle, Cycle>> up = {
      {15, {2, 2}}, {20, {2, 3}},  {44, {5, 6}},  {50, {5, 7}},
      {66, {7, 9}}, {70, {7, 10}}, {7.5, {1, 1}}, {8, {1, 2}},
  };
  for (const auto& [ns, expected] : up) {
    SCOPED_TRACE(ns);
    EXPECT_EQ(ns_to_cycles(ns, c100), expected.first);
    EXPECT_EQ(ns_to_cycles(ns, c133), expected.second);
  }
  // Maximum intervals round down: tREFI = 64 ms / 4096 = 15.625 us, tRAS(max) = 120 us.
  EXPECT_EQ(ns_to_cycles(15'625, c100, Rounding::kDownForMaximum), 1562);
  EXPECT_EQ(ns_to_cycles(15'625, c133, Rounding::kDownForMaximum), 2083);
  EXPECT_EQ(ns_to_cycles(120'000, c100, Rounding::kDownForMaximum), 12'000);
  EXPECT_EQ(ns_to_cycles(120'000, c133, Rounding::kDownForMaximum), 16'000);
}

// ---- (b) Presets -------------------------------------------------------------------------
struct Expected {
  TimingNs preset;
  sim::ClockDomain clock;
  Cycle CL, tRCD, tRP, tRAS, tRAS_max, tRC, tRRD, tWR, tRFC, tREFI;
};

TEST(Presets, ConvertToTheHandDerivedCycleCounts) {
  const Expected table[] = {
      {presets::pc100_cl2(), sim::clocks::pc100(), 2, 2, 2, 5, 12'000, 7, 2, 2, 7, 1562},
      {presets::pc100_cl3(), sim::clocks::pc100(), 3, 2, 2, 5, 12'000, 7, 2, 2, 7, 1562},
      {presets::pc133_cl3(), sim::clocks::pc133(), 3, 3, 3, 6, 16'000, 9, 2, 2, 9, 2083},
      {presets::pc133_cl3(), sim::clocks::pc100(), 3, 2, 2, 5, 12'000, 7, 2, 2, 7, 1562},
  };
  for (const Expected& e : table) {
    SCOPED_TRACE(e.preset.name + " at " + e.clock.name());
    const TimingCycles t = to_cycles(e.preset, e.clock, 4);
    EXPECT_EQ(t.CL, e.CL);
    EXPECT_EQ(t.BL, 4);
    EXPECT_EQ(t.tRCD, e.tRCD);
    EXPECT_EQ(t.tRP, e.tRP);
    EXPECT_EQ(t.tRAS, e.tRAS);
    EXPECT_EQ(t.tRAS_max, e.tRAS_max);
    EXPECT_EQ(t.tRC, e.tRC);
    EXPECT_EQ(t.tRRD, e.tRRD);
    EXPECT_EQ(t.tWR, e.tWR);
    EXPECT_EQ(t.tRFC, e.tRFC);
    EXPECT_EQ(t.tREFI, e.tREFI);
    EXPECT_EQ(t.tCCD, 1);
    EXPECT_EQ(t.tCDL, 1);
  }
}

// ceil / floor of ns over the period, computed here without the library.
Cycle ceil_div_ps(double ns, const sim::ClockDomain& c) {
  const long long ps = std::llround(ns * 1000.0);
  return (ps + c.period_ps() - 1) / c.period_ps();
}
Cycle floor_div_ps(double ns, const sim::ClockDomain& c) {
  return std::llround(ns * 1000.0) / c.period_ps();
}

TEST(Presets, EveryParameterIsTheDatasheetValueRoundedOnce) {
  for (const TimingNs& p : presets::all()) {
    for (const sim::ClockDomain& clock : {sim::clocks::pc100(), sim::clocks::pc133()}) {
      if (clock.period_ps() < std::llround(p.tCK_min_ns * 1000.0)) continue;
      for (int bl : {1, 2, 4, 8}) {
        SCOPED_TRACE(p.name + " at " + clock.name() + " BL " + std::to_string(bl));
        const TimingCycles t = to_cycles(p, clock, bl);
        EXPECT_EQ(t.tRCD, ceil_div_ps(p.tRCD_ns, clock));
        EXPECT_EQ(t.tRP, ceil_div_ps(p.tRP_ns, clock));
        EXPECT_EQ(t.tRAS, ceil_div_ps(p.tRAS_ns, clock));
        EXPECT_EQ(t.tRC, ceil_div_ps(p.tRC_ns, clock));
        EXPECT_EQ(t.tRRD, ceil_div_ps(p.tRRD_ns, clock));
        EXPECT_EQ(t.tWR, ceil_div_ps(p.tWR_ns, clock));
        EXPECT_EQ(t.tRFC, ceil_div_ps(p.tRFC_ns, clock));
        EXPECT_EQ(t.tRAS_max, floor_div_ps(p.tRAS_max_ns, clock));
        EXPECT_EQ(t.tREFI, floor_div_ps(p.tREF_ms * 1e6 / p.refresh_count, clock));
        EXPECT_EQ(t.CL, p.cas_latency);
        EXPECT_EQ(t.BL, bl);
      }
    }
  }
}

TEST(Presets, CiteTheirDatasheet) {
  for (const TimingNs& p : presets::all()) {
    SCOPED_TRACE(p.name);
    EXPECT_NE(p.part.find("Micron MT48LC8M16A2"), std::string::npos);
    EXPECT_NE(p.source.find("128Mb"), std::string::npos);
    EXPECT_NE(p.source.find("Rev. E"), std::string::npos);
    EXPECT_NE(p.source.find("p. 34"), std::string::npos);
    EXPECT_DOUBLE_EQ(p.tREFI_ns(), 15'625.0);
    std::ostringstream os;
    os << p;
    EXPECT_NE(os.str().find("tRCD 20"), std::string::npos) << os.str();
  }
}

TEST(Presets, RefuseClocksAndBurstsTheyAreNotRatedFor) {
  // -8E: tCK(2) = 10 ns, tCK(3) = 8 ns: neither runs at 7.5 ns.
  EXPECT_THROW(to_cycles(presets::pc100_cl2(), sim::clocks::pc133(), 4), Error);
  EXPECT_THROW(to_cycles(presets::pc100_cl3(), sim::clocks::pc133(), 4), Error);
  EXPECT_NO_THROW(to_cycles(presets::pc133_cl3(), sim::clocks::pc133(), 4));
  for (int bl : {0, 3, 16}) {
    EXPECT_THROW(to_cycles(presets::pc100_cl2(), sim::clocks::pc100(), bl), Error) << bl;
  }
  try {
    to_cycles(presets::pc100_cl2(), sim::clocks::pc133(), 4);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("tCK(2) = 10 ns"), std::string::npos) << e.what();
  }
}

// ---- (c) VIZARD II's 70 ns ---------------------------------------------------------------
TEST(Presets, ReproduceVizard2SeventyNanosecondsPrechargeAndActivate) {
  const sim::ClockDomain clock = sim::clocks::pc100();
  const TimingCycles cl2 = to_cycles(presets::pc100_cl2(), clock, 1);
  const TimingCycles cl3 = to_cycles(presets::pc100_cl3(), clock, 1);
  // Reading 1: the row cycle, ACT to ACT in one bank, = tRAS + tRP.
  EXPECT_EQ(clock.time_of(cl2.tRC), 70'000);
  EXPECT_EQ(cl2.tRC, cl2.tRAS + cl2.tRP);
  // Reading 2: PRE -> ACT -> RD -> first data at CL3.
  EXPECT_EQ(clock.time_of(cl3.tRP + cl3.tRCD + cl3.CL), 70'000);
  EXPECT_EQ(clock.time_of(cl2.tRP + cl2.tRCD + cl2.CL), 60'000);
}

// ---- (d) The constraint table ------------------------------------------------------------
TEST(ConstraintTable, EveryRowIsItsNamedFormula) {
  for (const TimingNs& p : presets::all()) {
    for (int bl : {1, 2, 4, 8}) {
      const TimingCycles t = to_cycles(p, sim::clocks::pc100(), bl);
      SCOPED_TRACE(p.name + " BL " + std::to_string(bl));
      const std::map<std::string, Cycle> formula = {
          {"tRC", t.tRC},
          {"tRCD", t.tRCD},
          {"tRAS", t.tRAS},
          {"tRP", t.tRP},
          {"tRRD", t.tRRD},
          {"tRFC", t.tRFC},
          {"BL", t.BL},
          {"BL-1+tWR", t.BL - 1 + t.tWR},
          {"max(tCCD,BL)", std::max(t.tCCD, t.BL)},
          {"CL+BL+1", t.CL + t.BL + 1},
          {"BL-1+tCDL", t.BL - 1 + t.tCDL},
          // READ with auto precharge: the READ's rows and its internal
          // PRECHARGE's, BL clocks after it.
          {"max(tRCD,tRAS-BL)", std::max(t.tRCD, t.tRAS - t.BL)},
          {"BL+tRP", t.BL + t.tRP},
          {"max(BL-1+tCDL,tWR-1)", std::max(t.BL - 1 + t.tCDL, t.tWR - 1)},
      };
      const ConstraintTable table(t);
      EXPECT_EQ(table.rows().size(), 33u);
      for (const Constraint& c : table.rows()) {
        const auto it = formula.find(std::string(c.parameter));
        ASSERT_NE(it, formula.end()) << c;
        EXPECT_EQ(c.cycles, it->second) << c;
      }
      // rows_before(next) partitions the table.
      std::size_t indexed = 0;
      for (Command next : kAllCommands) {
        for (std::size_t i : table.rows_before(next)) {
          EXPECT_EQ(table.rows()[i].next, next);
          ++indexed;
        }
      }
      EXPECT_EQ(indexed, table.rows().size());
    }
  }
}

TEST(ConstraintTable, CoversTheRulesOfDocsSdram) {
  const TimingCycles t = to_cycles(presets::pc100_cl2(), sim::clocks::pc100(), 4);
  const ConstraintTable table(t);
  auto find = [&](Command prev, Command next, Scope scope) -> const Constraint* {
    for (const Constraint& c : table.rows()) {
      if (c.prev == prev && c.next == next && c.scope == scope) return &c;
    }
    return nullptr;
  };
  using C = Command;
  using S = Scope;
  ASSERT_NE(find(C::kAct, C::kRd, S::kSameBank), nullptr);
  EXPECT_EQ(find(C::kAct, C::kRd, S::kSameBank)->cycles, 2);    // tRCD
  EXPECT_EQ(find(C::kAct, C::kAct, S::kSameBank)->cycles, 7);   // tRC
  EXPECT_EQ(find(C::kAct, C::kAct, S::kOtherBank)->cycles, 2);  // tRRD
  EXPECT_EQ(find(C::kRd, C::kRd, S::kAnyBank)->cycles, 4);      // one BL-4 burst
  EXPECT_EQ(find(C::kRd, C::kWr, S::kAnyBank)->cycles, 2 + 4 + 1);
  EXPECT_EQ(find(C::kWr, C::kPre, S::kSameBank)->cycles, 4 - 1 + 2);
  EXPECT_EQ(find(C::kRef, C::kAct, S::kAnyBank)->cycles, 7);  // tRFC
  EXPECT_EQ(find(C::kRd, C::kAct, S::kSameBank), nullptr);    // state, not timing
  std::ostringstream os;
  os << table;
  EXPECT_NE(os.str().find("ACT -> RD (same bank): 2 cycles (tRCD)"), std::string::npos) << os.str();
}

}  // namespace
