// DDR4 in the device model (rtl_model/sdram, docs/sdram.md "DDR4"):
//  (a) the DDR4-2400 CL17 preset in cycles: every parameter equal to JEDEC's
//      rounding of ns over tCK computed independently in integer picoseconds,
//      max'ed with its clock floor, and equal to DRAMsim3's and Ramulator 2's
//      published DDR4-2400 x4 cycle counts where they agree with JEDEC;
//  (b) every row of the DDR4 constraint table, generated from the table, and
//      the four-activate window tFAW: the later command is illegal one cycle
//      early (Dimm::issue / can_issue, the error names the rule) and legal
//      exactly on time;
//  (c) bank-group sequences: column commands tCCD_S apart across groups and
//      tCCD_L within one, BL8 in BL/2 = 4 clocks, write data CWL after the
//      WRITE, a row conflict tRP + tRCD + CL to data;
//  (d) NotBefore (the compiled table, tFAW included) agrees with Dimm::gate on
//      random legal DDR4 command sequences.
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

DimmConfig ddr4_config(const TimingNs& timing = presets::ddr4_2400_cl17()) {
  DimmConfig c;
  c.geometry = geometries::mta18asf2g72pz();
  c.timing = timing;
  c.clock = sim::clocks::ddr4_2400();
  c.burst_length = 8;
  return c;
}

// ---- (a) The preset in cycles ------------------------------------------------------------
// JEDEC's DDR4 rounding, written out again in integers: ps * 1000 / tCK in
// thousandths of a clock, + 974 (the 2.5 % guard band), truncated.
Cycle jedec_clocks(std::int64_t ps, std::int64_t tck_ps) {
  return (ps * 1000 / tck_ps + 974) / 1000;
}
Cycle pair_clocks(int ck, std::int64_t ps, std::int64_t tck_ps) {
  return std::max<Cycle>(ck, jedec_clocks(ps, tck_ps));
}

TEST(Ddr4Timing, PresetIsJedecRoundingOfItsNanosecondsInIntegerPicoseconds) {
  const std::int64_t tck = 833;
  const TimingCycles t = to_cycles(presets::ddr4_2400_cl17(), sim::clocks::ddr4_2400(), 8);
  EXPECT_EQ(t.standard, Standard::kDdr4);
  EXPECT_EQ(t.CL, 17);
  EXPECT_EQ(t.CWL, 12);
  EXPECT_EQ(t.tRCD, jedec_clocks(14'160, tck));
  EXPECT_EQ(t.tRP, jedec_clocks(14'160, tck));
  EXPECT_EQ(t.tRAS, jedec_clocks(32'000, tck));
  EXPECT_EQ(t.tRC, jedec_clocks(46'160, tck));
  EXPECT_EQ(t.tWR, jedec_clocks(15'000, tck));
  EXPECT_EQ(t.tRFC, jedec_clocks(350'000, tck));
  EXPECT_EQ(t.tRRD_S, pair_clocks(4, 3'300, tck));
  EXPECT_EQ(t.tRRD_L, pair_clocks(4, 4'900, tck));
  EXPECT_EQ(t.tFAW, pair_clocks(16, 13'000, tck));
  EXPECT_EQ(t.tCCD_S, 4);
  EXPECT_EQ(t.tCCD_L, pair_clocks(5, 5'000, tck));
  EXPECT_EQ(t.tWTR_S, pair_clocks(2, 2'500, tck));
  EXPECT_EQ(t.tWTR_L, pair_clocks(4, 7'500, tck));
  EXPECT_EQ(t.tRTP, pair_clocks(4, 7'500, tck));
  // Maximum intervals round down: tREFI = 7.8 us, tRAS(max) = 9 tREFI.
  EXPECT_EQ(t.tREFI, 7'800'000 / tck);
  EXPECT_EQ(t.tRAS_max, 9 * 7'800'000 / tck);

  // The published counts (DRAMsim3 configs/DDR4_8Gb_x4_2400.ini; Ramulator 2
  // DDR4.cpp, preset DDR4_2400U and its x4 tables): every one equal.
  const std::vector<std::pair<Cycle, Cycle>> published = {
      {t.tRCD, 17},  {t.tRP, 17},   {t.tRAS, 39},         {t.tRC, 56},   {t.tWR, 18},
      {t.tRRD_S, 4}, {t.tRRD_L, 6}, {t.tFAW, 16},         {t.tCCD_L, 6}, {t.tWTR_S, 3},
      {t.tWTR_L, 9}, {t.tRTP, 9},   {t.burst_cycles(), 4}};
  for (const auto& [ours, theirs] : published) EXPECT_EQ(ours, theirs);
  // Where they differ (docs/sdram.md, DDR4): tRFC, 350 ns at 0.833 ns is 421
  // by JEDEC's rounding (DRAMsim3 420 at the exact 5/6 ns); tREFI 9363
  // (DRAMsim3 9360 at 5/6 ns, Ramulator 2 9364 rounding a maximum up).
  EXPECT_EQ(t.tRFC, 421);
  EXPECT_EQ(t.tREFI, 9363);

  // A plain ceil would be wrong at the truncated tCK: 5 ns is 6.0024 clocks.
  EXPECT_EQ(ns_to_cycles(5, sim::clocks::ddr4_2400()), 7);
  EXPECT_EQ(ns_to_cycles(5, sim::clocks::ddr4_2400(), Rounding::kJedecGuardBand), 6);

  // x8 components: 1 KB page, tFAW max(20nCK, 21ns) (Ramulator 2: nFAW 26).
  const TimingCycles x8 = to_cycles(presets::ddr4_2400_cl17_x8(), sim::clocks::ddr4_2400(), 8);
  EXPECT_EQ(x8.tFAW, pair_clocks(20, 21'000, tck));
  EXPECT_EQ(x8.tFAW, 26);
}

TEST(Ddr4Timing, DerivedDelaysAreJedecFormulas) {
  const TimingCycles t = to_cycles(presets::ddr4_2400_cl17(), sim::clocks::ddr4_2400(), 8);
  EXPECT_EQ(t.read_to_write(), t.CL + 4 + 2 - t.CWL);              // 11
  EXPECT_EQ(t.write_to_read_same_group(), t.CWL + 4 + t.tWTR_L);   // 25
  EXPECT_EQ(t.write_to_read_other_group(), t.CWL + 4 + t.tWTR_S);  // 19
  EXPECT_EQ(t.read_to_precharge(), t.tRTP);
  EXPECT_EQ(t.write_to_precharge(), t.CWL + 4 + t.tWR);  // 34
  EXPECT_EQ(t.column_to_column_same_group(), t.tCCD_L);
  EXPECT_EQ(t.column_to_column_other_group(), 4);

  const ConstraintTable table(t);
  ASSERT_NE(table.four_activate_window(), nullptr);
  EXPECT_EQ(table.four_activate_window()->cycles, t.tFAW);
  EXPECT_EQ(ConstraintTable(to_cycles(presets::pc100_cl2(), sim::clocks::pc100(), 1))
                .four_activate_window(),
            nullptr);
}

TEST(Ddr4Timing, RefusesWhatItCannotModel) {
  EXPECT_THROW(to_cycles(presets::ddr4_2400_cl17(), sim::clocks::ddr4_2400(), 4), Error);  // BC4
  EXPECT_THROW(to_cycles(presets::ddr4_2400_cl17(), sim::ClockDomain("fast", 800), 8), Error);
  TimingNs bad = presets::ddr4_2400_cl17();
  bad.ddr4->cwl = 20;
  EXPECT_THROW(to_cycles(bad, sim::clocks::ddr4_2400(), 8), Error);
}

// ---- (b) Every row of the table, and tFAW -------------------------------------------------
// Bank 5 is in group 1 (banks 4-7); bank 6 shares its group, bank 9 does not.
constexpr std::uint32_t kPrevBank = 5, kSameGroupBank = 6, kOtherGroupBank = 9;

using dimm_checks::at;
using dimm_checks::Banks;

bool has_same_bank_row(const ConstraintTable& table, const Constraint& c) {
  for (const Constraint& d : table.rows())
    if (d.prev == c.prev && d.next == c.next && d.scope == Scope::kSameBank) return true;
  return false;
}

std::vector<Banks> pairings(const ConstraintTable& table, const Constraint& c) {
  switch (c.scope) {
    case Scope::kSameBank:
      return {{kPrevBank, kPrevBank}};
    case Scope::kOtherBank:
      return {{kPrevBank, kSameGroupBank}, {kPrevBank, kOtherGroupBank}};
    case Scope::kAnyBank:
      return {{kPrevBank, kPrevBank}, {kPrevBank, kSameGroupBank}, {kPrevBank, kOtherGroupBank}};
    case Scope::kSameBankGroup:  // the bank itself is in its group: checked
                                 // too where no same-bank row binds harder
      if (has_same_bank_row(table, c)) return {{kPrevBank, kSameGroupBank}};
      return {{kPrevBank, kSameGroupBank}, {kPrevBank, kPrevBank}};
    case Scope::kOtherBankGroup:
      return {{kPrevBank, kOtherGroupBank}};
  }
  return {};
}

// The bank pairings a row is checked with, except where the bank state rules
// the later command out (a READ with auto precharge leaves its bank idle).
std::vector<Banks> banks_for(const ConstraintTable& table, const Constraint& c) {
  std::vector<Banks> out;
  for (Banks b : pairings(table, c)) {
    const bool own_bank_closed =
        c.prev == Command::kRda && is_column_command(c.next) && b.prev == b.next;
    if (!own_bank_closed) out.push_back(b);
  }
  return out;
}

TEST(Ddr4Constraints, EveryRowIllegalOneCycleEarlyAndLegalOnTime) {
  std::size_t checked = 0;
  for (const TimingNs& preset : {presets::ddr4_2400_cl17(), presets::ddr4_2400_cl17_x8()}) {
    const DimmConfig cfg = ddr4_config(preset);
    const ConstraintTable table = Dimm(cfg).constraints();
    for (const Constraint& c : table.rows()) {
      for (Banks b : banks_for(table, c)) {
        std::ostringstream trace;
        trace << preset.name << ": " << c << ", banks " << b.prev << " -> " << b.next;
        SCOPED_TRACE(trace.str());
        // ACTs 20 cycles apart, `c.prev` at 300: tRC, tFAW and tRAS are over.
        dimm_checks::check_constraint(cfg, c, b, {.spacing = 20, .t0 = 300});
        ++checked;
      }
    }
  }
  // 41 rows; 14 any-bank rows with three pairings (RDA -> WR not on its own,
  // idle, bank); 4 same-group rows also on the bank itself (RD -> RD,
  // WR -> WR, WR -> RD, RD -> RDA).
  EXPECT_EQ(checked, 2u * (41u + 2u * 14u - 1u + 4u));
}

// The fifth ACT in any tFAW window is illegal. On x8 parts tFAW (26) exceeds
// four tRRD_S (16): four ACTs to the four groups tRRD_S apart, then a fifth
// (to the first group, tRRD_L after its ACT long over) waits for tFAW.
TEST(Ddr4Constraints, FifthActivateInTheFourActivateWindowIsIllegal) {
  Dimm d(ddr4_config(presets::ddr4_2400_cl17_x8()));
  const TimingCycles& t = d.timing();
  const Cycle t0 = 100;
  const std::array<std::uint32_t, 4> banks{0, 4, 8, 12};  // one per bank group
  for (std::size_t i = 0; i < banks.size(); ++i)
    d.issue(Command::kAct, at(banks[i]), t0 + static_cast<Cycle>(i) * t.tRRD_S);
  const Cycle bound = t0 + t.tFAW;
  ASSERT_GT(bound, t0 + 4 * t.tRRD_S);  // tFAW, not tRRD_S, binds
  EXPECT_EQ(d.earliest(Command::kAct, 1, t0 + 13), bound);
  const Gate g = d.gate(Command::kAct, 1, bound - 1);
  ASSERT_NE(g.binding, nullptr);
  EXPECT_EQ(g.binding, d.constraints().four_activate_window());
  EXPECT_EQ(g.since, t0);
  EXPECT_FALSE(d.can_issue(Command::kAct, at(1), bound - 1));
  try {
    d.issue(Command::kAct, at(1), bound - 1);
    ADD_FAILURE() << "a fifth ACT inside tFAW was accepted";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("violates tFAW"), std::string::npos) << what;
    EXPECT_NE(what.find("bank 0 at cycle 100"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(d.issue(Command::kAct, at(1), bound));
  // The window slides: the sixth waits for tFAW after the second.
  EXPECT_EQ(d.earliest(Command::kAct, 13, bound + 1),
            std::max(t0 + t.tRRD_S + t.tFAW, bound + t.tRRD_S));

  // x4 parts at 2400: tFAW = 16 = 4 tRRD_S, the fifth ACT is illegal one
  // clock early and legal on time whichever of the two names it.
  Dimm x4(ddr4_config());
  const TimingCycles& u = x4.timing();
  for (std::size_t i = 0; i < banks.size(); ++i)
    x4.issue(Command::kAct, at(banks[i]), t0 + static_cast<Cycle>(i) * u.tRRD_S);
  EXPECT_FALSE(x4.can_issue(Command::kAct, at(1), t0 + u.tFAW - 1));
  EXPECT_NO_THROW(x4.issue(Command::kAct, at(1), t0 + u.tFAW));
}

// ---- (c) Sequences -----------------------------------------------------------------------
Issued issue_asap(Dimm& d, Command cmd, const Address& a, Cycle now) {
  return d.issue(cmd, a, d.earliest(cmd, a.bank, now));
}

TEST(Ddr4Sequences, ColumnCommandsAcrossGroupsAreSeamlessWithinAGroupTccdL) {
  Dimm d(ddr4_config());
  const TimingCycles& t = d.timing();
  for (std::uint32_t bank : {0u, 4u}) issue_asap(d, Command::kAct, at(bank), 0);
  // Alternating groups: tCCD_S = BL/2 apart, data back to back.
  Issued prev = issue_asap(d, Command::kRd, at(0, 0), 1);
  for (std::uint32_t i = 1; i < 8; ++i) {
    const Issued next = issue_asap(d, Command::kRd, at(i % 2 == 0 ? 0 : 4, i * 8), prev.cycle + 1);
    EXPECT_EQ(next.cycle - prev.cycle, t.burst_cycles());
    EXPECT_EQ(next.data->first, prev.data->last + 1);
    EXPECT_EQ(next.data->last - next.data->first + 1, 4);  // BL8 at two beats a clock
    prev = next;
  }
  // One group: tCCD_L apart, a gap of tCCD_L - BL/2 on the data bus.
  const Issued same = issue_asap(d, Command::kRd, at(4, 200), prev.cycle + 1);
  EXPECT_EQ(same.cycle - prev.cycle, t.tCCD_L);
  EXPECT_EQ(same.data->first - prev.data->last - 1, t.tCCD_L - t.burst_cycles());
  // A write: data CWL after the WRITE, the turn-around after the read.
  const Issued wr = issue_asap(d, Command::kWr, at(0, 8), same.cycle + 1);
  EXPECT_EQ(wr.cycle - same.cycle, t.CL + t.burst_cycles() + 2 - t.CWL);
  EXPECT_EQ(wr.data->first - wr.cycle, t.CWL);
  EXPECT_EQ(wr.data->first - same.data->last - 1, 2);  // turn-around and preamble
}

TEST(Ddr4Sequences, RowConflictIsTrpPlusTrcdPlusCl) {
  Dimm d(ddr4_config());
  const TimingCycles& t = d.timing();
  const Address row_a{3, 100, 0}, row_b{3, 200, 0};
  const Issued act_a = issue_asap(d, Command::kAct, row_a, 0);
  const Issued rd_a = issue_asap(d, Command::kRd, row_a, 1);
  EXPECT_EQ(rd_a.cycle - act_a.cycle, t.tRCD);
  const Issued pre = issue_asap(d, Command::kPre, row_b, rd_a.cycle + 1);
  EXPECT_EQ(pre.cycle - act_a.cycle, std::max(t.tRAS, t.tRCD + t.tRTP));
  const Issued act_b = issue_asap(d, Command::kAct, row_b, pre.cycle + 1);
  const Issued rd_b = issue_asap(d, Command::kRd, row_b, act_b.cycle + 1);
  EXPECT_EQ(rd_b.data->first - pre.cycle, t.tRP + t.tRCD + t.CL);
  EXPECT_EQ(rd_b.data->last + 1 - pre.cycle, t.tRP + t.tRCD + t.CL + t.burst_cycles());
}

// ---- (d) The compiled table against the scan ---------------------------------------------
TEST(Ddr4Constraints, CompiledEarliestEqualsTheTableScan) {
  for (const TimingNs& preset : {presets::ddr4_2400_cl17(), presets::ddr4_2400_cl17_x8()}) {
    SCOPED_TRACE(preset.name);
    Dimm dimm(ddr4_config(preset));
    const std::array kinds{Command::kAct, Command::kAct, Command::kRd,   Command::kWr,
                           Command::kRda, Command::kPre, Command::kPrea, Command::kRef};
    const std::array checked{Command::kAct, Command::kRd,   Command::kWr, Command::kRda,
                             Command::kPre, Command::kPrea, Command::kRef};
    const std::uint64_t issued = dimm_checks::run_random_sequence(dimm, kinds, checked, 2500, 23);
    EXPECT_GT(issued, 300u);
    EXPECT_GT(dimm.stats().total().activates, 100u);
    EXPECT_GT(dimm.stats().total().writes, 20u);
  }
}

}  // namespace VOXCAST_UNITY_ID
