// The DIMM device model (rtl_model/sdram/dimm.hpp):
//  (a) every row of the constraint table, for every preset and burst length,
//      generated from the table: the later command is illegal one cycle early
//      and legal exactly on time, and the error names the parameter;
//  (b) command sequences issued at their earliest cycles: a row hit (tCCD /
//      BL apart, seamless data), a row miss on an idle bank (ACT -> RD:
//      tRCD + CL to data) and a row conflict (PRE -> ACT -> RD:
//      tRP + tRCD + CL to data);
//  (c) everything else issue() rejects: bank state, address range, the
//      command bus, overdue refresh; the error names command, bank, cycle
//      and rule;
//  (d) statistics and printing.
#include <gtest/gtest.h>

#include <array>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "dimm_checks.hpp"
#include "refmodel/error.hpp"
#include "rtl_model/sdram/dimm.hpp"

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

DimmConfig config(const Grade& g, int burst_length) {
  DimmConfig c;
  c.timing = g.preset;
  c.clock = g.clock;
  c.burst_length = burst_length;
  return c;
}

using dimm_checks::at;
using dimm_checks::Banks;

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

// ---- (a) Every constraint, generated from the table --------------------------------------
std::vector<Banks> banks_for(const Constraint& c) {
  switch (c.scope) {
    case Scope::kSameBank:
      return {{1, 1}};
    case Scope::kOtherBank:
      return {{1, 2}};
    case Scope::kAnyBank:
      return {{1, 1}, {1, 2}};
    case Scope::kSameBankGroup:  // DDR4 only (tests/rtl/test_sdram_ddr4.cpp)
    case Scope::kOtherBankGroup:
      return {};
  }
  return {};
}

TEST(DimmConstraints, EveryRowIllegalOneCycleEarlyAndLegalOnTime) {
  std::size_t checked = 0;
  for (const Grade& g : grades()) {
    for (int bl : {1, 2, 4, 8}) {
      const DimmConfig cfg = config(g, bl);
      const ConstraintTable table = Dimm(cfg).constraints();
      for (const Constraint& c : table.rows()) {
        for (Banks b : banks_for(c)) {
          std::ostringstream trace;
          trace << g.preset.name << " BL " << bl << ": " << c << ", banks " << b.prev << " -> "
                << b.next;
          SCOPED_TRACE(trace.str());
          dimm_checks::check_constraint(cfg, c, b, {.spacing = 10, .t0 = 100});
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 3u * 4u * (33u + 17u));  // 17 any-bank rows run with both bank pairings
}

// ---- (b) Command sequences ---------------------------------------------------------------
// Issues `cmd` at its earliest cycle at or after `now`.
Issued issue_asap(Dimm& d, Command cmd, const Address& a, Cycle now) {
  return d.issue(cmd, a, d.earliest(cmd, a.bank, now));
}

TEST(DimmSequences, RowHitsStreamSeamlessBursts) {
  for (const Grade& g : grades()) {
    for (int bl : {1, 2, 4, 8}) {
      SCOPED_TRACE(g.preset.name + " BL " + std::to_string(bl));
      Dimm d(config(g, bl));
      const TimingCycles& t = d.timing();
      issue_asap(d, Command::kAct, at(0), 0);
      Issued prev = issue_asap(d, Command::kRd, at(0, 0), 1);
      for (std::uint32_t col = 1; col < 8; ++col) {
        const Issued next = issue_asap(d, Command::kRd, at(0, col * 8), prev.cycle + 1);
        EXPECT_EQ(next.cycle - prev.cycle, std::max(t.tCCD, t.BL));
        EXPECT_EQ(next.data->first, prev.data->last + 1);  // no gap on the data bus
        prev = next;
      }
    }
  }
}

TEST(DimmSequences, RowMissOnIdleBankIsTrcdPlusCl) {
  for (const Grade& g : grades()) {
    SCOPED_TRACE(g.preset.name);
    Dimm d(config(g, 4));
    const TimingCycles& t = d.timing();
    const Issued act = issue_asap(d, Command::kAct, at(2), 50);
    const Issued rd = issue_asap(d, Command::kRd, at(2, 4), act.cycle + 1);
    EXPECT_EQ(rd.cycle - act.cycle, t.tRCD);
    EXPECT_EQ(rd.data->first - act.cycle, t.tRCD + t.CL);
    EXPECT_EQ(rd.data->last - rd.data->first, t.BL - 1);
  }
}

TEST(DimmSequences, RowConflictIsTrpPlusTrcdPlusCl) {
  for (const Grade& g : grades()) {
    for (int bl : {1, 4, 8}) {
      SCOPED_TRACE(g.preset.name + " BL " + std::to_string(bl));
      Dimm d(config(g, bl));
      const TimingCycles& t = d.timing();
      const Address row_a{1, 100, 0};
      const Address row_b{1, 200, 0};
      const Issued act_a = issue_asap(d, Command::kAct, row_a, 0);
      const Issued rd_a = issue_asap(d, Command::kRd, row_a, 1);
      const Issued pre = issue_asap(d, Command::kPre, row_b, rd_a.cycle + 1);
      // The row closes after tRAS and after the burst: max(tRAS, tRCD + BL).
      EXPECT_EQ(pre.cycle - act_a.cycle, std::max(t.tRAS, t.tRCD + t.BL));
      const Issued act_b = issue_asap(d, Command::kAct, row_b, pre.cycle + 1);
      const Issued rd_b = issue_asap(d, Command::kRd, row_b, act_b.cycle + 1);
      EXPECT_EQ(act_b.cycle - pre.cycle, std::max(t.tRP, t.tRC - (pre.cycle - act_a.cycle)));
      EXPECT_EQ(rd_b.data->first - pre.cycle, t.tRP + t.tRCD + t.CL);
      EXPECT_EQ(d.row_outcome(row_b), RowOutcome::kHit);
      EXPECT_EQ(d.row_outcome(row_a), RowOutcome::kConflict);
      EXPECT_EQ(d.row_outcome(Address{0, 5, 0}), RowOutcome::kMiss);
    }
  }
}

// READ with auto precharge: data as a READ's, the bank idle right after it
// (a column command to the row is a state error, an ACT waits BL + tRP), the
// row's open time ending where the internal PRECHARGE starts.
TEST(DimmSequences, ReadWithAutoPrechargeClosesTheRowItself) {
  Dimm d(DimmConfig{});
  const TimingCycles& t = d.timing();
  d.issue(Command::kAct, at(1), 10);
  const Cycle rda = 10 + std::max(t.tRCD, t.tRAS - t.BL);
  EXPECT_FALSE(d.can_issue(Command::kRda, at(1), rda - 1));
  const Issued i = d.issue(Command::kRda, at(1), rda);
  ASSERT_TRUE(i.data.has_value());
  EXPECT_EQ(i.data->first, rda + t.CL);
  EXPECT_EQ(i.data->last, rda + t.CL + t.BL - 1);
  EXPECT_EQ(d.bank(1).state, BankState::kIdle);
  expect_error([&] { d.issue(Command::kRd, at(1), rda + 1); }, {"RD to bank 1", "is idle"});
  EXPECT_EQ(d.earliest(Command::kAct, 1, rda + 1), rda + t.BL + t.tRP);
  const BankStats& b = d.stats().banks[1];
  EXPECT_EQ(b.reads, 1u);
  EXPECT_EQ(b.auto_precharges, 1u);
  EXPECT_EQ(b.precharges, 1u);
  EXPECT_EQ(b.open_cycles, rda + t.BL - 10);
  d.issue(Command::kAct, at(1), rda + t.BL + t.tRP);
}

TEST(DimmSequences, NextCommandIsTheRequestsPrerequisite) {
  Dimm d(DimmConfig{});
  EXPECT_EQ(d.next_command(Command::kRd, at(0)), Command::kAct);
  d.issue(Command::kAct, at(0), 0);
  EXPECT_EQ(d.next_command(Command::kRd, at(0)), Command::kRd);
  EXPECT_EQ(d.next_command(Command::kWr, at(0)), Command::kWr);
  EXPECT_EQ(d.next_command(Command::kRd, Address{0, 99, 0}), Command::kPre);
  EXPECT_THROW(d.next_command(Command::kAct, at(0)), Error);
}

TEST(DimmSequences, DataWindowsFollowClAndWriteLatencyZero) {
  for (int bl : {1, 2, 4, 8}) {
    Dimm d(config(grades()[1], bl));  // CL3
    d.issue(Command::kAct, at(0), 0);
    const Issued rd = d.issue(Command::kRd, at(0), 10);
    EXPECT_EQ(rd.data->first, 13);
    EXPECT_EQ(rd.data->last, 13 + bl - 1);
    const Issued wr = d.issue(Command::kWr, at(0), 10 + 3 + bl + 1);
    EXPECT_EQ(wr.data->first, wr.cycle);
    EXPECT_EQ(wr.data->last, wr.cycle + bl - 1);
    EXPECT_GT(wr.data->first, rd.data->last + 1);  // one idle clock to turn the bus
  }
}

// ---- (c) Everything issue() rejects ------------------------------------------------------
TEST(DimmErrors, TimingViolationNamesCommandBankCycleAndParameter) {
  Dimm d(DimmConfig{});  // PC100 CL2: tRCD = 2
  d.issue(Command::kAct, Address{2, 7, 0}, 103);
  expect_error(
      [&] {
        d.issue(Command::kRd, Address{2, 7, 12}, 104);
      },
      {"RD to bank 2 row 7 col 12", "at cycle 104", "violates tRCD", "ACT to bank 2 at cycle 103",
       "needs 2 cycles", "earliest cycle 105"});
  EXPECT_NO_THROW(d.issue(Command::kRd, Address{2, 7, 12}, 105));
}

TEST(DimmErrors, StateAddressBusAndRefreshViolations) {
  Dimm d(DimmConfig{});
  expect_error([&] { d.issue(Command::kRd, at(1), 10); }, {"RD to bank 1", "idle"});
  expect_error([&] { d.issue(Command::kAct, Address{4, 0, 0}, 10); }, {"no such bank"});
  expect_error([&] { d.issue(Command::kAct, Address{0, 4096, 0}, 10); }, {"no such row"});
  d.issue(Command::kAct, at(1), 10);
  expect_error([&] { d.issue(Command::kAct, at(1), 30); }, {"ACT to bank 1", "already has row 11"});
  expect_error([&] { d.issue(Command::kRd, Address{1, 12, 0}, 30); }, {"row 11 open, not row 12"});
  expect_error([&] { d.issue(Command::kRd, Address{1, 11, 512}, 30); }, {"no such column"});
  expect_error([&] { d.issue(Command::kRef, Address{}, 30); }, {"REF", "bank 1 has row 11 open"});
  expect_error([&] { d.issue(Command::kAct, at(2), 10); }, {"command bus", "cycle 10"});
  expect_error([&] { d.issue(Command::kAct, at(2), 9); }, {"command bus"});
  EXPECT_NO_THROW(d.issue(Command::kNop, Address{}, 10));  // NOP is always legal
  // Refresh: the REF due at tREFI must come before 2 tREFI.
  const Cycle refi = d.timing().tREFI;
  EXPECT_FALSE(d.refresh().due(refi - 1));
  EXPECT_TRUE(d.refresh().due(refi));
  EXPECT_FALSE(d.refresh().overdue(2 * refi - 1));
  expect_error([&] { d.issue(Command::kPrea, Address{}, 2 * refi); },
               {"PREA", "refresh overdue", "deadline was cycle " + std::to_string(2 * refi)});
  d.issue(Command::kPrea, Address{}, 2 * refi - 3);
  d.issue(Command::kRef, Address{}, 2 * refi - 1);
  EXPECT_EQ(d.refresh().deadline(), 3 * refi);
  // A failed issue changed nothing.
  EXPECT_EQ(d.stats().refreshes, 1u);
  EXPECT_EQ(d.last_command_cycle(), 2 * refi - 1);
}

TEST(DimmErrors, PostponementMayNotKeepARowOpenBeyondTrasMax) {
  DimmConfig c;
  c.refresh_postpone_limit = 5;  // 7 x 1562 <= 12000 cycles
  EXPECT_NO_THROW(Dimm{c});
  c.refresh_postpone_limit = 6;  // 8 x 1562 > 12000
  expect_error([&] { Dimm{c}; }, {"tRAS(max)"});
  c.refresh_postpone_limit = 9;
  expect_error([&] { Dimm{c}; }, {"[0, 8]"});
}

// ---- (d) Statistics and printing ---------------------------------------------------------
TEST(DimmStats, CountsCommandsPerBankAndBusyCycles) {
  Dimm d(config(grades()[0], 4));
  d.issue(Command::kAct, at(0), 0);
  d.issue(Command::kAct, at(3), 2);
  d.issue(Command::kRd, at(0), 4);
  d.issue(Command::kRd, at(3), 8);
  d.issue(Command::kWr, at(3), 8 + 2 + 4 + 1);
  d.issue(Command::kPre, at(0), 20);
  d.issue(Command::kPrea, Address{}, 40);
  d.issue(Command::kRef, Address{}, 42);
  const DimmStats& s = d.stats();
  EXPECT_EQ(s.banks[0].activates, 1u);
  EXPECT_EQ(s.banks[0].reads, 1u);
  EXPECT_EQ(s.banks[0].precharges, 1u);
  EXPECT_EQ(s.banks[0].open_cycles, 20);
  EXPECT_EQ(s.banks[3].reads, 1u);
  EXPECT_EQ(s.banks[3].writes, 1u);
  EXPECT_EQ(s.banks[3].precharges, 1u);  // closed by PREA
  EXPECT_EQ(s.banks[3].open_cycles, 38);
  EXPECT_EQ(s.total().activates, 2u);
  EXPECT_EQ(s.commands, 8u);
  EXPECT_EQ(s.precharge_alls, 1u);
  EXPECT_EQ(s.refreshes, 1u);
  EXPECT_EQ(s.data_bus_busy_cycles, 3 * 4);
  EXPECT_EQ(s.refresh_busy_cycles, 7);
  std::ostringstream os;
  os << s << "\n" << d.bank(0) << "\n" << d.refresh() << "\n" << d.config();
  EXPECT_NE(os.str().find("bank 3: 1 ACT, 1 RD, 1 WR, 1 closed"), std::string::npos) << os.str();
  EXPECT_NE(os.str().find("MT4LSDT864A"), std::string::npos) << os.str();
  EXPECT_NE(os.str().find("64 MB"), std::string::npos) << os.str();
}

TEST(DimmGeometry, Mt4lsdt864aIs64MBytes) {
  const Geometry g = geometries::mt4lsdt864a();
  EXPECT_EQ(g.bytes(), 64ull << 20);
  EXPECT_EQ(g.bytes_per_beat(), 8u);
  EXPECT_EQ(g.bytes_per_row(), 4096u);
  // VIZARD II: 256^3 voxels, 32 bits each plus the replicated 32 bits, over four DIMMs.
  EXPECT_GE(g.bytes(), 256ull * 256 * 256 * 8 / 4);
}

}  // namespace

namespace VOXCAST_UNITY_ID {

// Dimm::earliest answers from the table compiled as commands issue; gate()
// scans every row against the last command of each kind. On a random legal
// command sequence (every command kind, every bank, writes and refresh
// included) both give the same cycle for every command and bank, every cycle.
TEST(DimmConstraints, CompiledEarliestEqualsTheTableScan) {
  for (const auto& grade : {presets::pc100_cl2(), presets::pc100_cl3()}) {
    DimmConfig config;
    config.timing = grade;
    config.burst_length = 2;
    Dimm dimm(config);
    const std::array kinds{Command::kAct, Command::kRd,   Command::kWr,
                           Command::kPre, Command::kPrea, Command::kRef};
    const std::uint64_t issued = dimm_checks::run_random_sequence(dimm, kinds, kinds, 3000, 11);
    EXPECT_GT(issued, 500u);
    EXPECT_GE(dimm.stats().refreshes, 1u);
    EXPECT_GT(dimm.stats().total().writes, 50u);
  }
}

}  // namespace
