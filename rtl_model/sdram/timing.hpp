// SDRAM timing as data (docs/sdram.md §2-3).
//
//   TimingNs        one speed grade as its datasheet gives it: nanoseconds,
//                   plus the few parameters the datasheet gives in clocks.
//   ns_to_cycles    THE one place where datasheet nanoseconds become cycles.
//   TimingCycles    the parameters in cycles of one clock, and the derived
//                   delays (each with its datasheet formula).
//   ConstraintTable THE one table of (previous command -> later command,
//                   scope, minimum cycles), as Ramulator 2's timing
//                   constraints and DRAMSim3's per-command timing lists.
//                   The device model gates every command with it, and the
//                   tests check every row (illegal one cycle early, legal on
//                   time) by iterating over it.
//
// VIZARD II's "70 ns for a precharge and row activate" (2001 paper, §2.3): on
// PC100 parts (Micron -8E: tRP = tRCD = 20 ns, tRAS = 50 ns, tRC = 70 ns; PC100
// DIMMs carry the same figures in SPD bytes 27-30) two readings give 70 ns:
//   - the row cycle tRC = tRAS + tRP = 50 + 20 = 70 ns: a new row in the same
//     bank every 7 clocks at 100 MHz, whatever the CAS latency;
//   - a row conflict's PRECHARGE -> ACTIVE -> READ -> first data at CL3:
//     tRP + tRCD + CL = 20 + 20 + 30 = 70 ns (60 ns at CL2).
// Both presets below keep those values; the tests assert both readings.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rtl_model/sdram/command.hpp"
#include "rtl_model/sim/clock.hpp"

namespace voxcast::rtl::sdram {

// A DDR4 minimum as JESD79-4B gives it: max(ck clocks, ns nanoseconds) (the
// speed-bin and timing-parameter tables, e.g. tRRD_S = max(4nCK, 3.3ns)).
// ck = 0: nanoseconds only; ns = 0: clocks only.
struct ClocksOrNs {
  int ck = 0;
  double ns = 0;
};

// The parameters DDR4 adds to an SDR grade (JESD79-4B): bank groups make
// column-to-column, activate-to-activate and write-to-read delays depend on
// whether the two commands address the same bank group (_L) or another (_S);
// tFAW bounds any four activates; writes have a latency CWL; reads close a
// row tRTP after the READ.
struct Ddr4Ns {
  int cwl = 0;        // CAS write latency, clocks (MR2; AL = 0, no CRC, 1tCK preambles)
  ClocksOrNs tRRD_S;  // ACT to ACT, other bank group
  ClocksOrNs tRRD_L;  // ACT to ACT, same bank group
  ClocksOrNs tFAW;    // four-activate window: a fifth ACT at least tFAW after the 4th-last
  ClocksOrNs tCCD_S;  // column to column, other bank group
  ClocksOrNs tCCD_L;  // column to column, same bank group
  ClocksOrNs tWTR_S;  // end of write data to READ, other bank group
  ClocksOrNs tWTR_L;  // end of write data to READ, same bank group
  ClocksOrNs tRTP;    // READ to PRECHARGE
};

// Which JEDEC standard a grade follows: its command timing rules differ.
enum class Standard : std::uint8_t { kSdr, kDdr4 };

std::string_view name(Standard s);

// One speed grade of one SDRAM component, in the datasheet's units. Minimum
// values unless named _max.
struct TimingNs {
  std::string name;        // "PC100 CL2"
  std::string part;        // component and speed grade
  std::string source;      // datasheet, revision, page and table
  double tCK_min_ns = 0;   // minimum clock period at this CAS latency, tCK(CL)
  int cas_latency = 0;     // CL in clocks: the mode-register value
  double tRCD_ns = 0;      // ACTIVE to READ or WRITE
  double tRP_ns = 0;       // PRECHARGE command period
  double tRAS_ns = 0;      // ACTIVE to PRECHARGE
  double tRAS_max_ns = 0;  // a row may stay open at most this long
  double tRC_ns = 0;       // ACTIVE to ACTIVE, same bank
  double tRRD_ns = 0;      // ACTIVE bank a to ACTIVE bank b
  double tWR_ns = 0;       // last data-in to PRECHARGE (manual-precharge value)
  double tRFC_ns = 0;      // AUTO REFRESH period
  double tREF_ms = 0;      // every row refreshed within tREF ...
  int refresh_count = 0;   // ... by this many AUTO REFRESH commands
  int tCCD_ck = 0;         // READ/WRITE to READ/WRITE, clocks
  int tCDL_ck = 0;         // last data-in to new READ/WRITE, clocks
  int tMRD_ck = 0;         // LOAD MODE REGISTER to command; listed, not modelled
  // Set for a DDR4 grade (tRRD_ns, tCCD_ck and tCDL_ck are then unused: the
  // bank-group pairs here replace them); empty for SDR SDRAM.
  std::optional<Ddr4Ns> ddr4;

  Standard standard() const { return ddr4 ? Standard::kDdr4 : Standard::kSdr; }
  // Average refresh interval: tREF / refresh_count (15.625 us for 64 ms / 4096).
  double tREFI_ns() const;
};

std::ostream& operator<<(std::ostream& os, const TimingNs& t);

// Presets, each citing its datasheet.
namespace presets {
// Micron MT48LC8M16A2-8E at CL2, 100 MHz (the PC100 2-2-2 grade).
TimingNs pc100_cl2();
// The same -8E part with CAS latency 3 in its mode register (PC100 3-2-2);
// the datasheet allows CL3 down to tCK(3) = 8 ns. Row-conflict access:
// tRP + tRCD + CL = 70 ns.
TimingNs pc100_cl3();
// Micron MT48LC8M16A2-75 at CL3, 133 MHz (PC133 3-3-3).
TimingNs pc133_cl3();
// The SDR grades above.
std::vector<TimingNs> all();
// DDR4-2400 17-17-17 (tAA = tRCD = tRP = 14.16 ns) of Micron MT40A2G4 (8Gb
// x4, 1/2 KB page), the components of the Alveo U250's module MTA18ASF2G72PZ-2G3;
// each number's source (JESD79-4B, Micron, and DRAMsim3's / Ramulator 2's
// DDR4 presets as the check) is in `source` and docs/sdram.md "DDR4".
TimingNs ddr4_2400_cl17();
// The same speed grade on x8 components (1 KB page): only tFAW differs
// (max(20nCK, 21ns) instead of max(16nCK, 13ns)), so four activates are
// limited by tFAW, not by 4 tRRD_S: the tests' tFAW case.
TimingNs ddr4_2400_cl17_x8();
}  // namespace presets

enum class Rounding {
  kUpForMinimum,    // minimum delays: ceil (the datasheet's rule)
  kDownForMaximum,  // maximum intervals (tREFI, tRAS(max)): floor
  // DDR4 minimum delays: JEDEC's rounding algorithm with its 2.5 % guard
  // band, nCK = floor((ps * 1000 / tCK_ps + 974) / 1000) in integers (JEDEC
  // DDR4 SPD, Annex L "Rounding algorithms"; Ramulator 2's JEDEC_rounding):
  // tCK is given truncated to 0.833 ns for 1200 MHz, so a plain ceil would
  // make 5 ns (tCCD_L) 7 clocks instead of the 6 every DDR4-2400 table lists.
  kJedecGuardBand,
};

// THE one conversion from datasheet nanoseconds to cycles of `clock`. The
// nanoseconds become integer picoseconds, so the rounding is exact (see
// sim::ClockDomain).
Cycle ns_to_cycles(double ns, const sim::ClockDomain& clock,
                   Rounding rounding = Rounding::kUpForMinimum);

// One preset at one clock and burst length, in cycles.
struct TimingCycles {
  sim::ClockDomain clock;
  Cycle CL;  // CAS latency: READ to first data
  Cycle BL;  // burst length: data beats per READ/WRITE (mode register)
  Cycle tRCD;
  Cycle tRP;
  Cycle tRAS;
  Cycle tRAS_max;  // rounded down
  Cycle tRC;
  Cycle tRRD;
  Cycle tWR;
  Cycle tRFC;
  Cycle tREFI;  // rounded down
  Cycle tCCD;
  Cycle tCDL;
  // DDR4 (zero for SDR): CAS write latency and the bank-group pairs.
  Standard standard = Standard::kSdr;
  Cycle CWL = 0;
  Cycle tRRD_S = 0, tRRD_L = 0;
  Cycle tFAW = 0;
  Cycle tCCD_S = 0, tCCD_L = 0;
  Cycle tWTR_S = 0, tWTR_L = 0;
  Cycle tRTP = 0;

  // Clocks one burst holds the data bus: BL for SDR, BL/2 for DDR (two beats
  // a clock: BL8 is 4 clocks).
  Cycle burst_cycles() const { return standard == Standard::kDdr4 ? BL / 2 : BL; }

  // Derived delays (Micron 128Mb SDRAM data sheet, Rev. E, READ/WRITE/
  // PRECHARGE operation and the AC functional characteristics table):
  // A column command may follow another after tCCD, but a READ or WRITE
  // interrupts the burst before it; no burst is truncated here: max(tCCD, BL).
  Cycle column_to_column() const;
  // "PRECHARGE ... issued x cycles before the clock edge at which the last
  // desired data element is valid, where x = CL - 1": the last element is at
  // RD + CL + BL - 1, so a full burst allows PRE at RD + BL.
  Cycle read_to_precharge() const;
  // tWR counts from the clock edge that registers the last data-in, which is
  // WR + BL - 1 (write latency 0): BL - 1 + tWR.
  Cycle write_to_precharge() const;
  // WRITE after READ: the write data (driven with the WRITE) may not meet the
  // read burst (last element at RD + CL + BL - 1) and the bus needs one idle
  // clock to turn around ("at least a single-cycle delay should occur between
  // the last read data and the WRITE command"): CL + BL + 1. Our reading;
  // DRAMSim3's read-to-write (RL + BL + tRTRS - WL) gives the same for
  // SDR (WL = 0, tRTRS = 1).
  Cycle read_to_write() const;
  // READ after WRITE: tCDL after the last data-in: BL - 1 + tCDL.
  Cycle write_to_read() const;

  // DDR4 (JESD79-4B, the READ/WRITE operation chapters and the timing-
  // parameter table; AL = 0, 1tCK preambles):
  //   read_to_precharge()  tRTP (max(4nCK, 7.5ns) already in tRTP)
  //   write_to_precharge() CWL + BL/2 + tWR: tWR counts from the end of the
  //                        write burst
  //   read_to_write()      CL + BL/2 + 2 - CWL: the read burst, a turn-around
  //                        clock and the write preamble before the write data
  // and by bank group:
  //   column to column     max(tCCD_L, BL/2) / max(tCCD_S, BL/2)
  //   write to read        CWL + BL/2 + tWTR_L / tWTR_S: tWTR from the end
  //                        of the write burst
  Cycle column_to_column_same_group() const;
  Cycle column_to_column_other_group() const;
  Cycle write_to_read_same_group() const;
  Cycle write_to_read_other_group() const;
};

// Throws voxcast::Error when the clock is faster than the grade allows at its
// CAS latency (tCK < tCK(CL)), when the burst length is not 1, 2, 4 or 8
// (full-page bursts are not modelled; DDR4: not 8, BL8 fixed), or a
// parameter is inconsistent. SDR: every ns through kUpForMinimum; DDR4:
// through kJedecGuardBand, max(clocks, rounded ns) for the ClocksOrNs pairs.
TimingCycles to_cycles(const TimingNs& timing, const sim::ClockDomain& clock, int burst_length);

std::ostream& operator<<(std::ostream& os, const TimingCycles& t);

// Which banks a constraint couples.
enum class Scope : std::uint8_t {
  kSameBank,   // previous and later command to the same bank
  kOtherBank,  // to different banks of the rank
  kAnyBank,    // any bank of the rank (shared data or command resources), or
               // a rank command (PREA, REF) on either side
  // DDR4 bank groups (JESD79-4B: 4 groups of 4 banks in 8Gb x4/x8): a bank of the later command's
  // bank group, the bank itself included (a same-bank row may bind harder), and a bank of another
  // group. Together they cover every bank, as kAnyBank does.
  kSameBankGroup,
  kOtherBankGroup,
};

std::string_view name(Scope s);
std::ostream& operator<<(std::ostream& os, Scope s);

struct Constraint {
  Command prev;
  Command next;
  Scope scope;
  Cycle cycles;                // minimum distance: next >= prev + cycles
  std::string_view parameter;  // the datasheet parameter or formula, "tRCD", "BL-1+tWR"
};

std::ostream& operator<<(std::ostream& os, const Constraint& c);

class ConstraintTable {
 public:
  // The table of the timing's standard from the converted parameters: SDR
  // SDRAM (docs/sdram.md §3) or DDR4 (docs/sdram.md "DDR4"). Throws
  // voxcast::Error if the table is inconsistent (a rank command with a bank
  // scope, or a pair with both a bank scope and kAnyBank).
  explicit ConstraintTable(const TimingCycles& timing);

  const std::vector<Constraint>& rows() const { return rows_; }
  // DDR4's four-activate window, which is not a pairwise row: an ACT at
  // least `cycles` (tFAW) after the 4th-last ACT to any bank. Given as
  // ACT -> ACT, any bank; nullptr for SDR SDRAM.
  const Constraint* four_activate_window() const { return faw_ ? &*faw_ : nullptr; }
  // ACTs in the window: the fifth in any tFAW is illegal.
  static constexpr std::size_t kActivatesPerWindow = 4;
  // Indices into rows() of the constraints whose later command is `next`.
  const std::vector<std::size_t>& rows_before(Command next) const {
    return by_next_[index_of(next)];
  }

 private:
  void validate() const;
  void sdr_rows(const TimingCycles& t);
  void ddr4_rows(const TimingCycles& t);

  std::vector<Constraint> rows_;
  std::optional<Constraint> faw_;
  std::vector<std::vector<std::size_t>> by_next_;
};

std::ostream& operator<<(std::ostream& os, const ConstraintTable& table);

}  // namespace voxcast::rtl::sdram
