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

std::ostream& operator<<(std::ostream& os, const Address& a) {
  return os << "bank " << a.bank << " row " << a.row << " col " << a.column;
}

// ---- Presets -----------------------------------------------------------------------------
double TimingNs::tREFI_ns() const { return tREF_ms * 1.0e6 / refresh_count; }

std::ostream& operator<<(std::ostream& os, const TimingNs& t) {
  return os << t.name << " [" << t.part << "]: tCK(" << t.cas_latency << ") >= " << t.tCK_min_ns
            << " ns, CL " << t.cas_latency << ", tRCD " << t.tRCD_ns << ", tRP " << t.tRP_ns
            << ", tRAS " << t.tRAS_ns << ".." << t.tRAS_max_ns << ", tRC " << t.tRC_ns << ", tRRD "
            << t.tRRD_ns << ", tWR " << t.tWR_ns << ", tRFC " << t.tRFC_ns << ", tREFI "
            << t.tREFI_ns() << " ns (" << t.refresh_count << " REF / " << t.tREF_ms << " ms), tCCD "
            << t.tCCD_ck << " tCDL " << t.tCDL_ck << " tMRD " << t.tMRD_ck << " clocks";
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

}  // namespace presets

// ---- ns -> cycles: the one place ---------------------------------------------------------
Cycle ns_to_cycles(double ns, const sim::ClockDomain& clock, Rounding rounding) {
  const sim::Picoseconds ps = sim::ps_from_ns(ns);
  return rounding == Rounding::kUpForMinimum ? clock.cycles_at_least(ps) : clock.cycles_at_most(ps);
}

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
  if (t.cas_latency < 1 || t.cas_latency > 3) fail("CAS latency must be 1, 2 or 3");
  if (burst_length != 1 && burst_length != 2 && burst_length != 4 && burst_length != 8) {
    fail("burst length " + std::to_string(burst_length) + " is not 1, 2, 4 or 8");
  }
  if (t.refresh_count <= 0 || t.tREF_ms <= 0) fail("no refresh requirement");
  if (t.tCCD_ck < 1 || t.tCDL_ck < 1) fail("tCCD and tCDL are at least one clock");

  // Step 2: every ns parameter through the one conversion.
  const auto up = [&](double ns) { return ns_to_cycles(ns, clock, Rounding::kUpForMinimum); };
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
  if (c.tRAS_max < c.tRAS) fail("tRAS(max) is below tRAS(min)");
  if (c.tREFI <= c.tRFC) fail("tREFI does not exceed tRFC");
  return c;
}

Cycle TimingCycles::column_to_column() const { return std::max(tCCD, BL); }
Cycle TimingCycles::read_to_precharge() const { return BL; }
Cycle TimingCycles::write_to_precharge() const { return BL - 1 + tWR; }
Cycle TimingCycles::read_to_write() const { return CL + BL + 1; }
Cycle TimingCycles::write_to_read() const { return BL - 1 + tCDL; }

std::ostream& operator<<(std::ostream& os, const TimingCycles& t) {
  return os << "at " << t.clock << ": CL " << t.CL << ", BL " << t.BL << ", tRCD " << t.tRCD
            << ", tRP " << t.tRP << ", tRAS " << t.tRAS << ".." << t.tRAS_max << ", tRC " << t.tRC
            << ", tRRD " << t.tRRD << ", tWR " << t.tWR << ", tRFC " << t.tRFC << ", tREFI "
            << t.tREFI << ", tCCD " << t.tCCD << ", tCDL " << t.tCDL << " cycles";
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
  }
  return "?";
}

std::ostream& operator<<(std::ostream& os, Scope s) { return os << name(s); }

std::ostream& operator<<(std::ostream& os, const Constraint& c) {
  return os << c.prev << " -> " << c.next << " (" << c.scope << "): " << c.cycles << " cycles ("
            << c.parameter << ")";
}

ConstraintTable::ConstraintTable(const TimingCycles& t) : by_next_(kCommandCount) {
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
  for (std::size_t i = 0; i < rows_.size(); ++i) by_next_[index_of(rows_[i].next)].push_back(i);
  validate();
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
