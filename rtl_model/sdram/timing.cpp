#include "rtl_model/sdram/timing.hpp"

#include <algorithm>
#include <ostream>
#include <sstream>

#include "refmodel/error.hpp"

namespace voxcast::rtl::sdram {

// ---- Commands and addresses --------------------------------------------------------------
std::string_view name(Command c) {
  switch (c) {
    case Command::kNop:
      return "NOP";
    case Command::kAct:
      return "ACT";
    case Command::kRd:
      return "RD";
    case Command::kWr:
      return "WR";
    case Command::kPre:
      return "PRE";
    case Command::kPrea:
      return "PREA";
    case Command::kRef:
      return "REF";
    case Command::kRda:
      return "RDA";
  }
  return "?";
}

std::ostream& operator<<(std::ostream& os, Command c) { return os << name(c); }

std::string_view name(Standard s) { return s == Standard::kDdr4 ? "DDR4" : "SDR"; }

std::ostream& operator<<(std::ostream& os, const Address& a) {
  return os << "bank " << a.bank << " row " << a.row << " col " << a.column;
}

// ---- Presets -----------------------------------------------------------------------------
double TimingNs::tREFI_ns() const { return tREF_ms * 1.0e6 / refresh_count; }

std::ostream& operator<<(std::ostream& os, const TimingNs& t) {
  os << t.name << " [" << t.part << "]: tCK(" << t.cas_latency << ") >= " << t.tCK_min_ns
     << " ns, CL " << t.cas_latency << ", tRCD " << t.tRCD_ns << ", tRP " << t.tRP_ns << ", tRAS "
     << t.tRAS_ns << ".." << t.tRAS_max_ns << ", tRC " << t.tRC_ns << ", tRRD " << t.tRRD_ns
     << ", tWR " << t.tWR_ns << ", tRFC " << t.tRFC_ns << ", tREFI " << t.tREFI_ns() << " ns ("
     << t.refresh_count << " REF / " << t.tREF_ms << " ms), tCCD " << t.tCCD_ck << " tCDL "
     << t.tCDL_ck << " tMRD " << t.tMRD_ck << " clocks";
  if (t.ddr4) {
    const Ddr4Ns& d = *t.ddr4;
    const auto pair = [&](const char* n, const ClocksOrNs& p) {
      os << ", " << n << " max(" << p.ck << "nCK, " << p.ns << "ns)";
    };
    os << "; DDR4: CWL " << d.cwl;
    pair("tRRD_S", d.tRRD_S);
    pair("tRRD_L", d.tRRD_L);
    pair("tFAW", d.tFAW);
    pair("tCCD_S", d.tCCD_S);
    pair("tCCD_L", d.tCCD_L);
    pair("tWTR_S", d.tWTR_S);
    pair("tWTR_L", d.tWTR_L);
    pair("tRTP", d.tRTP);
  }
  return os;
}

namespace presets {

namespace {
// The 128Mb family's AC tables (Micron "128Mb: x4, x8, x16 SDRAM",
// 128MSDRAM_E, Rev. E, Pub. 1/02): p. 34 "Electrical characteristics and
// recommended AC operating conditions" (the ns values) and the "AC functional
// characteristics" table after it (tCCD = tCDL = 1, tMRD = 2 clocks).
// tWR is the manual-precharge value (15 ns; "1 CLK + 7 ns" applies only to
// auto precharge, which the model does not use). tREF: 64 ms for 4,096 rows.
constexpr const char* kMicron128MbRevE =
    "Micron 128Mb: x4, x8, x16 SDRAM data sheet (128MSDRAM_E, Rev. E, Pub. 1/02), p. 34 "
    "'Electrical characteristics and recommended AC operating conditions' and the "
    "'AC functional characteristics' table";

// The data sheet and the speed grade's column, appended in place: assigning
// the result of operator+ on a temporary is reported by GCC 12 at -O2 as an
// out-of-bounds copy (-Warray-bounds, a false positive: GCC bug 105651).
void set_micron_128mb_source(std::string& source, const char* column) {
  source.assign(kMicron128MbRevE).append(", column ").append(column);
}

TimingNs micron_128mb_8e() {
  TimingNs t;
  t.part = "Micron MT48LC8M16A2-8E (128Mb, 2 Meg x 16 x 4 banks)";
  set_micron_128mb_source(t.source, "-8E");
  t.tRCD_ns = 20;
  t.tRP_ns = 20;
  t.tRAS_ns = 50;
  t.tRAS_max_ns = 120'000;
  t.tRC_ns = 70;
  t.tRRD_ns = 20;
  t.tWR_ns = 15;
  t.tRFC_ns = 70;
  t.tREF_ms = 64;
  t.refresh_count = 4096;
  t.tCCD_ck = 1;
  t.tCDL_ck = 1;
  t.tMRD_ck = 2;
  return t;
}
}  // namespace

TimingNs pc100_cl2() {
  TimingNs t = micron_128mb_8e();
  t.name = "PC100 CL2";
  t.tCK_min_ns = 10;  // tCK(2), -8E
  t.cas_latency = 2;
  return t;
}

TimingNs pc100_cl3() {
  TimingNs t = micron_128mb_8e();
  t.name = "PC100 CL3";
  t.tCK_min_ns = 8;  // tCK(3), -8E: CL3 is legal at 100 MHz
  t.cas_latency = 3;
  return t;
}

TimingNs pc133_cl3() {
  TimingNs t;
  t.name = "PC133 CL3";
  t.part = "Micron MT48LC8M16A2-75 (128Mb, 2 Meg x 16 x 4 banks)";
  set_micron_128mb_source(t.source, "-75");
  t.tCK_min_ns = 7.5;  // tCK(3), -75
  t.cas_latency = 3;
  t.tRCD_ns = 20;
  t.tRP_ns = 20;
  t.tRAS_ns = 44;
  t.tRAS_max_ns = 120'000;
  t.tRC_ns = 66;
  t.tRRD_ns = 15;
  t.tWR_ns = 15;
  t.tRFC_ns = 66;
  t.tREF_ms = 64;
  t.refresh_count = 4096;
  t.tCCD_ck = 1;
  t.tCDL_ck = 1;
  t.tMRD_ck = 2;
  return t;
}

std::vector<TimingNs> all() { return {pc100_cl2(), pc100_cl3(), pc133_cl3()}; }

// Micron MT40A2G4 (8Gb x4) at DDR4-2400 CL17, the grade of the U250's
// MTA18ASF2G72PZ-2G3 module. Checked against DRAMsim3
// configs/DDR4_8Gb_x4_2400.ini (CL 17, CWL 12, tRCD = tRP = 17, tRAS 39,
// tRRD_S 4, tRRD_L 6, tWTR_S 3, tWTR_L 9, tFAW 16, tWR 18, tRTP 9, tCCD_S 4,
// tCCD_L 6, tRFC 420, tREFI 9360 clocks) and Ramulator 2 src/dram/impl/DDR4.cpp
// (preset DDR4_2400U, CL17: nRAS 39, nRC 56, nWR 18, nRTP 9, nCWL 12, nCCDS 4,
// nCCDL 6, nWTRS 3, nWTRL 9; x4: nRRDS 4, nRRDL 6, nFAW 16). docs/sdram.md
// "DDR4" has the table side by side and the two disagreements (tRFC, tREFI).
TimingNs ddr4_2400_cl17() {
  TimingNs t;
  t.name = "DDR4-2400 CL17";
  t.part = "Micron MT40A2G4-083 (8Gb DDR4 x4: 512 Meg x 4, 16 banks in 4 bank groups)";
  t.source =
      "JEDEC JESD79-4B DDR4-2400 speed bin 17-17-17 (tAA = tRCD = tRP = 14.16 ns, tRAS 32 ns, "
      "tRC 46.16 ns, CWL 12 (1st set)) and timing-parameter table for 2400 (tRRD_S(1/2KB) "
      "max(4nCK,3.3ns), tRRD_L(1/2KB) max(4nCK,4.9ns), tFAW(1/2KB) max(16nCK,13ns), tCCD_S 4nCK, "
      "tCCD_L max(5nCK,5ns), tWTR_S max(2nCK,2.5ns), tWTR_L max(4nCK,7.5ns), tRTP "
      "max(4nCK,7.5ns), tWR 15ns, tRFC1 350ns (8Gb), tREFI 7.8us, tRAS(max) 9 x tREFI); "
      "Micron 8Gb DDR4 SDRAM data sheet (MT40A2G4/MT40A1G8/MT40A512M16), speed grade -083; "
      "checked against DRAMsim3 configs/DDR4_8Gb_x4_2400.ini and Ramulator 2 "
      "src/dram/impl/DDR4.cpp (docs/sdram.md, DDR4)";
  t.tCK_min_ns = 0.833;  // tCK(avg) min at CL17: 1200 MHz, truncated to ps as JEDEC lists it
  t.cas_latency = 17;
  t.tRCD_ns = 14.16;
  t.tRP_ns = 14.16;
  t.tRAS_ns = 32;
  t.tRAS_max_ns = 9 * 7800;  // 9 x tREFI
  t.tRC_ns = 46.16;
  t.tWR_ns = 15;
  t.tRFC_ns = 350;  // tRFC1, 8Gb, 1x refresh mode
  // JESD79-4B gives tREFI = 7.8 us (0-85 C) directly; 8192 REF per "64 ms"
  // is nominal (8192 x 7.8 us = 63.8976 ms): the window is the one that
  // makes tREFI 7.8 us, as DRAMsim3 (tREFI 9360 = 7.8 us at 1.2 GHz) and
  // Ramulator 2 (tREFI_BASE 7800 ns) take it.
  t.tREF_ms = 63.8976;
  t.refresh_count = 8192;
  t.tMRD_ck = 8;
  t.ddr4 = Ddr4Ns{
      .cwl = 12,
      .tRRD_S = {4, 3.3},
      .tRRD_L = {4, 4.9},
      .tFAW = {16, 13},
      .tCCD_S = {4, 0},
      .tCCD_L = {5, 5},
      .tWTR_S = {2, 2.5},
      .tWTR_L = {4, 7.5},
      .tRTP = {4, 7.5},
  };
  return t;
}

TimingNs ddr4_2400_cl17_x8() {
  TimingNs t = ddr4_2400_cl17();
  t.name = "DDR4-2400 CL17 x8";
  t.part = "Micron MT40A1G8-083 (8Gb DDR4 x8: 1 Gig x 8, 16 banks in 4 bank groups, 1 KB page)";
  t.source.append("; x8 (1KB page): tFAW max(20nCK,21ns) (Ramulator 2 x8 at 2400: nFAW 26)");
  t.ddr4->tFAW = {20, 21};
  return t;
}

}  // namespace presets

// ---- ns -> cycles: the one place ---------------------------------------------------------
Cycle ns_to_cycles(double ns, const sim::ClockDomain& clock, Rounding rounding) {
  const sim::Picoseconds ps = sim::ps_from_ns(ns);
  switch (rounding) {
    case Rounding::kUpForMinimum:
      return clock.cycles_at_least(ps);
    case Rounding::kDownForMaximum:
      return clock.cycles_at_most(ps);
    case Rounding::kJedecGuardBand:
      // In thousandths of a clock, truncated; + 974 rounds up unless the
      // fraction is below 0.026 (a tCK truncated to whole ps).
      return (ps * 1000 / clock.period_ps() + 974) / 1000;
  }
  return 0;
}

namespace {
// DDR4 (JESD79-4B): the parameters a DDR4 grade adds, each max(clocks,
// rounded ns).
void ddr4_to_cycles(const TimingNs& t, const sim::ClockDomain& clock, TimingCycles& c) {
  const Ddr4Ns& d = *t.ddr4;
  const auto pair = [&](const ClocksOrNs& p) {
    return std::max<Cycle>(p.ck, ns_to_cycles(p.ns, clock, Rounding::kJedecGuardBand));
  };
  c.standard = Standard::kDdr4;
  c.CWL = d.cwl;
  c.tRRD_S = pair(d.tRRD_S);
  c.tRRD_L = pair(d.tRRD_L);
  c.tFAW = pair(d.tFAW);
  c.tCCD_S = pair(d.tCCD_S);
  c.tCCD_L = pair(d.tCCD_L);
  c.tWTR_S = pair(d.tWTR_S);
  c.tWTR_L = pair(d.tWTR_L);
  c.tRTP = pair(d.tRTP);
  // The SDR names, for printing and the rules both standards share.
  c.tRRD = c.tRRD_S;
  c.tCCD = c.tCCD_S;
  c.tCDL = c.tWTR_S;
}
}  // namespace

TimingCycles to_cycles(const TimingNs& t, const sim::ClockDomain& clock, int burst_length) {
  auto fail = [&](const std::string& what) {
    std::ostringstream os;
    os << t.name << " [" << t.part << "] at " << clock << ": " << what;
    throw Error(os.str());
  };
  // Step 1: is the grade rated for this clock at its CAS latency?
  if (clock.period_ps() < sim::ps_from_ns(t.tCK_min_ns)) {
    std::ostringstream os;
    os << "the clock period is below tCK(" << t.cas_latency << ") = " << t.tCK_min_ns << " ns";
    fail(os.str());
  }
  const bool ddr4 = t.standard() == Standard::kDdr4;
  if (ddr4) {
    // JESD79-4B: CL 9..24 in MR0, CWL 9..18 in MR2; BL8 (BC4 not modelled).
    if (t.cas_latency < 9 || t.cas_latency > 24) fail("DDR4 CAS latency must be 9..24");
    if (t.ddr4->cwl < 9 || t.ddr4->cwl > 18 || t.ddr4->cwl > t.cas_latency)
      fail("DDR4 CAS write latency must be 9..18 and at most CL");
    if (burst_length != 8) fail("DDR4 burst length " + std::to_string(burst_length) + " is not 8");
    if (t.ddr4->tCCD_S.ck < 1 && t.ddr4->tCCD_S.ns <= 0) fail("tCCD_S is at least one clock");
  } else {
    if (t.cas_latency < 1 || t.cas_latency > 3) fail("CAS latency must be 1, 2 or 3");
    if (burst_length != 1 && burst_length != 2 && burst_length != 4 && burst_length != 8) {
      fail("burst length " + std::to_string(burst_length) + " is not 1, 2, 4 or 8");
    }
    if (t.tCCD_ck < 1 || t.tCDL_ck < 1) fail("tCCD and tCDL are at least one clock");
  }
  if (t.refresh_count <= 0 || t.tREF_ms <= 0) fail("no refresh requirement");

  // Step 2: every ns parameter through the one conversion.
  const Rounding minimum = ddr4 ? Rounding::kJedecGuardBand : Rounding::kUpForMinimum;
  const auto up = [&](double ns) { return ns_to_cycles(ns, clock, minimum); };
  const auto down = [&](double ns) { return ns_to_cycles(ns, clock, Rounding::kDownForMaximum); };
  TimingCycles c{
      .clock = clock,
      .CL = t.cas_latency,
      .BL = burst_length,
      .tRCD = up(t.tRCD_ns),
      .tRP = up(t.tRP_ns),
      .tRAS = up(t.tRAS_ns),
      .tRAS_max = down(t.tRAS_max_ns),
      .tRC = up(t.tRC_ns),
      .tRRD = up(t.tRRD_ns),
      .tWR = up(t.tWR_ns),
      .tRFC = up(t.tRFC_ns),
      .tREFI = down(t.tREFI_ns()),
      .tCCD = t.tCCD_ck,
      .tCDL = t.tCDL_ck,
  };
  if (ddr4) ddr4_to_cycles(t, clock, c);
  if (c.tRAS_max < c.tRAS) fail("tRAS(max) is below tRAS(min)");
  if (c.tREFI <= c.tRFC) fail("tREFI does not exceed tRFC");
  return c;
}

Cycle TimingCycles::column_to_column() const { return std::max(tCCD, BL); }
Cycle TimingCycles::read_to_precharge() const { return standard == Standard::kDdr4 ? tRTP : BL; }
Cycle TimingCycles::write_to_precharge() const {
  return standard == Standard::kDdr4 ? CWL + burst_cycles() + tWR : BL - 1 + tWR;
}
Cycle TimingCycles::read_to_write() const {
  return standard == Standard::kDdr4 ? CL + burst_cycles() + 2 - CWL : CL + BL + 1;
}
Cycle TimingCycles::write_to_read() const { return BL - 1 + tCDL; }
Cycle TimingCycles::column_to_column_same_group() const { return std::max(tCCD_L, burst_cycles()); }
Cycle TimingCycles::column_to_column_other_group() const {
  return std::max(tCCD_S, burst_cycles());
}
Cycle TimingCycles::write_to_read_same_group() const { return CWL + burst_cycles() + tWTR_L; }
Cycle TimingCycles::write_to_read_other_group() const { return CWL + burst_cycles() + tWTR_S; }

std::ostream& operator<<(std::ostream& os, const TimingCycles& t) {
  os << "at " << t.clock << ": CL " << t.CL << ", BL " << t.BL << ", tRCD " << t.tRCD << ", tRP "
     << t.tRP << ", tRAS " << t.tRAS << ".." << t.tRAS_max << ", tRC " << t.tRC << ", tRRD "
     << t.tRRD << ", tWR " << t.tWR << ", tRFC " << t.tRFC << ", tREFI " << t.tREFI << ", tCCD "
     << t.tCCD << ", tCDL " << t.tCDL << " cycles";
  if (t.standard == Standard::kDdr4) {
    os << "; DDR4: CWL " << t.CWL << ", tRRD_S/L " << t.tRRD_S << "/" << t.tRRD_L << ", tFAW "
       << t.tFAW << ", tCCD_S/L " << t.tCCD_S << "/" << t.tCCD_L << ", tWTR_S/L " << t.tWTR_S << "/"
       << t.tWTR_L << ", tRTP " << t.tRTP;
  }
  return os;
}

// ---- The constraint table ----------------------------------------------------------------
std::string_view name(Scope s) {
  switch (s) {
    case Scope::kSameBank:
      return "same bank";
    case Scope::kOtherBank:
      return "other bank";
    case Scope::kAnyBank:
      return "any bank";
    case Scope::kSameBankGroup:
      return "same bank group";
    case Scope::kOtherBankGroup:
      return "other bank group";
  }
  return "?";
}

std::ostream& operator<<(std::ostream& os, Scope s) { return os << name(s); }

std::ostream& operator<<(std::ostream& os, const Constraint& c) {
  return os << c.prev << " -> " << c.next << " (" << c.scope << "): " << c.cycles << " cycles ("
            << c.parameter << ")";
}

ConstraintTable::ConstraintTable(const TimingCycles& t) : by_next_(kCommandCount) {
  if (t.standard == Standard::kDdr4)
    ddr4_rows(t);
  else
    sdr_rows(t);
  for (std::size_t i = 0; i < rows_.size(); ++i) by_next_[index_of(rows_[i].next)].push_back(i);
  validate();
}

void ConstraintTable::sdr_rows(const TimingCycles& t) {
  using C = Command;
  using S = Scope;
  rows_ = {
      // Row access within one bank (Micron 128Mb, "Bank/Row Activation",
      // "PRECHARGE"): open, use, close, reopen.
      {C::kAct, C::kAct, S::kSameBank, t.tRC, "tRC"},
      {C::kAct, C::kRd, S::kSameBank, t.tRCD, "tRCD"},
      {C::kAct, C::kWr, S::kSameBank, t.tRCD, "tRCD"},
      {C::kAct, C::kPre, S::kSameBank, t.tRAS, "tRAS"},
      {C::kPre, C::kAct, S::kSameBank, t.tRP, "tRP"},
      {C::kRd, C::kPre, S::kSameBank, t.read_to_precharge(), "BL"},
      {C::kWr, C::kPre, S::kSameBank, t.write_to_precharge(), "BL-1+tWR"},
      // Activates to different banks of the rank.
      {C::kAct, C::kAct, S::kOtherBank, t.tRRD, "tRRD"},
      // Column commands share the data bus of the rank, whichever bank.
      {C::kRd, C::kRd, S::kAnyBank, t.column_to_column(), "max(tCCD,BL)"},
      {C::kRd, C::kWr, S::kAnyBank, t.read_to_write(), "CL+BL+1"},
      {C::kWr, C::kRd, S::kAnyBank, t.write_to_read(), "BL-1+tCDL"},
      {C::kWr, C::kWr, S::kAnyBank, t.column_to_column(), "max(tCCD,BL)"},
      // PRECHARGE ALL closes every bank: each bank's PRECHARGE rules apply.
      {C::kAct, C::kPrea, S::kAnyBank, t.tRAS, "tRAS"},
      {C::kRd, C::kPrea, S::kAnyBank, t.read_to_precharge(), "BL"},
      {C::kWr, C::kPrea, S::kAnyBank, t.write_to_precharge(), "BL-1+tWR"},
      {C::kPrea, C::kAct, S::kAnyBank, t.tRP, "tRP"},
      // AUTO REFRESH: every bank precharged for tRP before it, and only NOP
      // during tRFC after it (Micron 128Mb, "AUTO REFRESH").
      {C::kPre, C::kRef, S::kAnyBank, t.tRP, "tRP"},
      {C::kPrea, C::kRef, S::kAnyBank, t.tRP, "tRP"},
      {C::kRef, C::kAct, S::kAnyBank, t.tRFC, "tRFC"},
      {C::kRef, C::kRef, S::kAnyBank, t.tRFC, "tRFC"},
      {C::kRef, C::kPre, S::kAnyBank, t.tRFC, "tRFC"},
      {C::kRef, C::kPrea, S::kAnyBank, t.tRFC, "tRFC"},
      // READ with auto precharge (Micron 128Mb, "READ with auto precharge";
      // Concurrent Auto Precharge): a READ whose bank starts precharging
      // itself where a PRECHARGE after the READ could first go, BL clocks
      // later, and is idle tRP after that. Its rows are the READ's and that
      // internal PRECHARGE's, moved by BL: the precharge must meet tRAS
      // (ACT -> RDA: tRAS - BL) and tWR after a write to the bank. After it
      // the bank is idle: a column command to it is a state error, so the
      // data-bus rows after an RDA couple the other banks only.
      {C::kAct, C::kRda, S::kSameBank, std::max(t.tRCD, t.tRAS - t.read_to_precharge()),
       "max(tRCD,tRAS-BL)"},
      {C::kRda, C::kAct, S::kSameBank, t.read_to_precharge() + t.tRP, "BL+tRP"},
      {C::kRda, C::kPre, S::kSameBank, t.read_to_precharge(), "BL"},
      {C::kRda, C::kPrea, S::kAnyBank, t.read_to_precharge(), "BL"},
      {C::kRda, C::kRef, S::kAnyBank, t.read_to_precharge() + t.tRP, "BL+tRP"},
      {C::kRd, C::kRda, S::kAnyBank, t.column_to_column(), "max(tCCD,BL)"},
      {C::kRda, C::kRd, S::kOtherBank, t.column_to_column(), "max(tCCD,BL)"},
      {C::kRda, C::kRda, S::kOtherBank, t.column_to_column(), "max(tCCD,BL)"},
      {C::kRda, C::kWr, S::kOtherBank, t.read_to_write(), "CL+BL+1"},
      {C::kWr, C::kRda, S::kSameBank,
       std::max(t.write_to_read(), t.write_to_precharge() - t.read_to_precharge()),
       "max(BL-1+tCDL,tWR-1)"},
      {C::kWr, C::kRda, S::kOtherBank, t.write_to_read(), "BL-1+tCDL"},
  };
}

// JESD79-4B (DDR4), AL = 0, 1tCK preambles, one rank; the same rows as
// Ramulator 2's DDR4 (src/dram/impl/DDR4.cpp) and DRAMsim3's timing.cc, with
// "bankgroup" and "rank" levels as kSameBankGroup and kOtherBankGroup.
void ConstraintTable::ddr4_rows(const TimingCycles& t) {
  using C = Command;
  using S = Scope;
  const Cycle ccd_l = t.column_to_column_same_group();
  const Cycle ccd_s = t.column_to_column_other_group();
  const Cycle wtr_l = t.write_to_read_same_group();
  const Cycle wtr_s = t.write_to_read_other_group();
  const Cycle rtp = t.read_to_precharge();
  const Cycle wr_pre = t.write_to_precharge();
  const Cycle rd_wr = t.read_to_write();
  rows_ = {
      // Row access within one bank.
      {C::kAct, C::kAct, S::kSameBank, t.tRC, "tRC"},
      {C::kAct, C::kRd, S::kSameBank, t.tRCD, "tRCD"},
      {C::kAct, C::kWr, S::kSameBank, t.tRCD, "tRCD"},
      {C::kAct, C::kPre, S::kSameBank, t.tRAS, "tRAS"},
      {C::kPre, C::kAct, S::kSameBank, t.tRP, "tRP"},
      {C::kRd, C::kPre, S::kSameBank, rtp, "tRTP"},
      {C::kWr, C::kPre, S::kSameBank, wr_pre, "CWL+BL/2+tWR"},
      // Activates: tRRD_L within a bank group, tRRD_S across groups (tFAW
      // is the window, four_activate_window()).
      {C::kAct, C::kAct, S::kSameBankGroup, t.tRRD_L, "tRRD_L"},
      {C::kAct, C::kAct, S::kOtherBankGroup, t.tRRD_S, "tRRD_S"},
      // Column commands: the group's shared I/O (tCCD_L) or the data bus (tCCD_S).
      {C::kRd, C::kRd, S::kSameBankGroup, ccd_l, "max(tCCD_L,BL/2)"},
      {C::kRd, C::kRd, S::kOtherBankGroup, ccd_s, "max(tCCD_S,BL/2)"},
      {C::kWr, C::kWr, S::kSameBankGroup, ccd_l, "max(tCCD_L,BL/2)"},
      {C::kWr, C::kWr, S::kOtherBankGroup, ccd_s, "max(tCCD_S,BL/2)"},
      {C::kRd, C::kWr, S::kAnyBank, rd_wr, "CL+BL/2+2-CWL"},
      {C::kWr, C::kRd, S::kSameBankGroup, wtr_l, "CWL+BL/2+tWTR_L"},
      {C::kWr, C::kRd, S::kOtherBankGroup, wtr_s, "CWL+BL/2+tWTR_S"},
      // PRECHARGE ALL: each bank's PRECHARGE rules.
      {C::kAct, C::kPrea, S::kAnyBank, t.tRAS, "tRAS"},
      {C::kRd, C::kPrea, S::kAnyBank, rtp, "tRTP"},
      {C::kWr, C::kPrea, S::kAnyBank, wr_pre, "CWL+BL/2+tWR"},
      {C::kPrea, C::kAct, S::kAnyBank, t.tRP, "tRP"},
      // REFRESH: every bank precharged tRP before it, nothing but DES during tRFC.
      {C::kPre, C::kRef, S::kAnyBank, t.tRP, "tRP"},
      {C::kPrea, C::kRef, S::kAnyBank, t.tRP, "tRP"},
      {C::kRef, C::kAct, S::kAnyBank, t.tRFC, "tRFC"},
      {C::kRef, C::kRef, S::kAnyBank, t.tRFC, "tRFC"},
      {C::kRef, C::kPre, S::kAnyBank, t.tRFC, "tRFC"},
      {C::kRef, C::kPrea, S::kAnyBank, t.tRFC, "tRFC"},
      // READ with auto precharge: the internal precharge starts tRTP after
      // the READ (JESD79-4B "READ with auto precharge": AL + tRTP) and must
      // meet tRAS and, after a write to the bank, the write recovery.
      {C::kAct, C::kRda, S::kSameBank, std::max(t.tRCD, t.tRAS - rtp), "max(tRCD,tRAS-tRTP)"},
      {C::kRda, C::kAct, S::kSameBank, rtp + t.tRP, "tRTP+tRP"},
      {C::kRda, C::kPre, S::kSameBank, rtp, "tRTP"},
      {C::kRda, C::kPrea, S::kAnyBank, rtp, "tRTP"},
      {C::kRda, C::kRef, S::kAnyBank, rtp + t.tRP, "tRTP+tRP"},
      {C::kRd, C::kRda, S::kSameBankGroup, ccd_l, "max(tCCD_L,BL/2)"},
      {C::kRd, C::kRda, S::kOtherBankGroup, ccd_s, "max(tCCD_S,BL/2)"},
      {C::kRda, C::kRd, S::kSameBankGroup, ccd_l, "max(tCCD_L,BL/2)"},
      {C::kRda, C::kRd, S::kOtherBankGroup, ccd_s, "max(tCCD_S,BL/2)"},
      {C::kRda, C::kRda, S::kSameBankGroup, ccd_l, "max(tCCD_L,BL/2)"},
      {C::kRda, C::kRda, S::kOtherBankGroup, ccd_s, "max(tCCD_S,BL/2)"},
      {C::kRda, C::kWr, S::kAnyBank, rd_wr, "CL+BL/2+2-CWL"},
      {C::kWr, C::kRda, S::kSameBank, std::max(wtr_l, wr_pre - rtp),
       "max(CWL+BL/2+tWTR_L,CWL+BL/2+tWR-tRTP)"},
      {C::kWr, C::kRda, S::kSameBankGroup, wtr_l, "CWL+BL/2+tWTR_L"},
      {C::kWr, C::kRda, S::kOtherBankGroup, wtr_s, "CWL+BL/2+tWTR_S"},
  };
  faw_ = Constraint{C::kAct, C::kAct, S::kAnyBank, t.tFAW, "tFAW"};
}

void ConstraintTable::validate() const {
  for (const Constraint& c : rows_) {
    auto fail = [&](std::string_view what) {
      std::ostringstream os;
      os << "constraint table: " << c << ": " << what;
      throw Error(os.str());
    };
    if (c.prev == Command::kNop || c.next == Command::kNop) fail("NOP is never constrained");
    if ((is_rank_command(c.prev) || is_rank_command(c.next)) && c.scope != Scope::kAnyBank) {
      fail("a rank command couples every bank");
    }
    if (c.cycles < 1) fail("a later command needs at least one clock");
    for (const Constraint& d : rows_) {
      const bool same_pair = &c != &d && c.prev == d.prev && c.next == d.next;
      if (same_pair && (c.scope == d.scope || c.scope == Scope::kAnyBank)) {
        fail("the pair is listed twice or overlaps an any-bank row");
      }
    }
  }
}

std::ostream& operator<<(std::ostream& os, const ConstraintTable& table) {
  for (const Constraint& c : table.rows()) os << c << "\n";
  return os;
}

}  // namespace voxcast::rtl::sdram
