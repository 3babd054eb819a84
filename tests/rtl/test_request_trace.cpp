// A request trace through one channel (rtl_model/trace/request_trace.hpp,
// `voxcast dram-trace`, docs/sdram.md "dram-trace"):
//  (a) DRAMsim3's trace format: what it accepts, and every malformed line an
//      error naming the file and line;
//  (b) the address mapping (DRAMsim3's field orders) and the board's channel
//      (alveo_u250 gives the DDR4 preset; errors name file, key and reason);
//  (c) closed forms, each within 1 %: streaming bandwidth with refresh, the
//      row-conflict latency, the tFAW-limited activate rate; DDR4 and PC100.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "refmodel/error.hpp"
#include "rtl_model/board/board.hpp"
#include "rtl_model/board/board_config.hpp"
#include "rtl_model/trace/request_trace.hpp"

namespace VOXCAST_UNITY_ID {

namespace sdram = voxcast::rtl::sdram;
namespace board = voxcast::rtl::board;
namespace rt = voxcast::rtl::trace;
using sdram::Cycle;
using voxcast::Error;

sdram::DimmConfig u250_channel() {
  return voxcast::rtl::channel_config_for_board(board::shipped_board("alveo_u250"));
}
sdram::DimmConfig pc100_channel() {
  return voxcast::rtl::channel_config_for_board(board::shipped_board("vizard2_pci"));
}

std::string error_of(const std::string& text) {
  std::istringstream in(text);
  try {
    (void)rt::parse_request_trace(in, "t.trc");
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

// ---- (a) The format ----------------------------------------------------------------------
TEST(RequestTrace, ReadsDramsim3sFormat) {
  std::istringstream in(
      "# a comment\n"
      "0x40 READ 0\n"
      "\n"
      "80 WRITE 3   # a tail\n"
      "0xC0 P_MEM_RD 3\n"
      "0x100 P_MEM_WR 10\n"
      "0x140 read 11\n");
  const auto t = rt::parse_request_trace(in, "t.trc");
  ASSERT_EQ(t.size(), 5u);
  EXPECT_EQ(t[0].address, 0x40u);
  EXPECT_EQ(t[0].kind, sdram::RequestKind::kRead);
  EXPECT_EQ(t[1].address, 0x80u);
  EXPECT_EQ(t[1].kind, sdram::RequestKind::kWrite);
  EXPECT_EQ(t[1].cycle, 3);
  EXPECT_EQ(t[1].line, 4);
  EXPECT_EQ(t[2].kind, sdram::RequestKind::kRead);
  EXPECT_EQ(t[3].kind, sdram::RequestKind::kWrite);
  EXPECT_EQ(t[4].cycle, 11);
}

TEST(RequestTrace, MalformedLinesNameFileLineAndWhat) {
  EXPECT_EQ(error_of("0x40 READ 0\n0xZZ READ 1\n"),
            "t.trc:2: address \"0xZZ\" is not a hexadecimal number");
  EXPECT_NE(error_of("0x40 FETCH 0\n").find("t.trc:1: operation \"FETCH\" is not READ, WRITE"),
            std::string::npos);
  EXPECT_NE(error_of("\n\n0x40 READ\n").find("t.trc:3: expected \"ADDRESS OPERATION CYCLE\""),
            std::string::npos);
  EXPECT_EQ(error_of("0x40 READ 1.5\n"), "t.trc:1: cycle \"1.5\" is not a whole number of clocks");
  EXPECT_EQ(error_of("0x40 READ -1\n"), "t.trc:1: cycle \"-1\" is not a whole number of clocks");
  EXPECT_EQ(error_of("0x40 READ 1 2\n"), "t.trc:1: unexpected \"2\" after the cycle");
  EXPECT_EQ(error_of("0x40 READ 9\n0x80 READ 8\n"),
            "t.trc:2: cycle 8 is before the previous request's 9 (a trace is in cycle order)");
}

// ---- (b) Mapping and the board's channel -------------------------------------------------
TEST(RequestTrace, AddressMappingIsDramsim3s) {
  const sdram::DimmConfig c = u250_channel();
  const rt::AddressMapping m(c.geometry, 8);  // rochrababgco
  EXPECT_EQ(m.capacity_bytes(), std::uint64_t{16} << 30);
  EXPECT_EQ(m.burst_bytes(), 64u);
  EXPECT_EQ(m.describe(),
            "\"rochrababgco\": row[33:17] bank[16:15] bankgroup[14:13] column[12:6] burst "
            "byte[5:0]");
  // bank group 2, bank 1, row 5, burst 3 (columns 24-31)
  const std::uint64_t a = (5ull << 17) | (1ull << 15) | (2ull << 13) | (3ull << 6) | 17;
  EXPECT_EQ(m.map(a), (sdram::Address{2 * 4 + 1, 5, 24}));
  EXPECT_EQ(m.byte_address(m.map(a)), a & ~63ull);
  const rt::AddressMapping bg_low(c.geometry, 8, "rochrabacobg");
  EXPECT_EQ(bg_low.map(64), (sdram::Address{4, 0, 0}));  // the next burst: the next group
  EXPECT_THROW(rt::AddressMapping(c.geometry, 8, "rochrababgbg"), Error);
  EXPECT_THROW(rt::AddressMapping(c.geometry, 8, "rowcolbank"), Error);

  std::istringstream in("0x3ffffffc0 READ 0\n0x400000000 READ 1\n");
  const auto t = rt::parse_request_trace(in, "big.trc");
  try {
    rt::check_addresses(t, m, "big.trc");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "big.trc:2: address 0x400000000 is beyond the channel's capacity (16384 MiB: "
              "addresses below 0x400000000)");
  }
}

TEST(RequestTrace, TheU250ChannelIsTheDdr4Preset) {
  const sdram::DimmConfig c = u250_channel();
  EXPECT_EQ(c.clock.period_ps(), 833);
  EXPECT_EQ(c.geometry.bank_groups, 4u);
  const auto from_board = sdram::to_cycles(c.timing, c.clock, 8);
  const auto preset = sdram::to_cycles(sdram::presets::ddr4_2400_cl17(), c.clock, 8);
  std::ostringstream a, b;
  a << from_board;
  b << preset;
  EXPECT_EQ(a.str(), b.str());
  // The card model runs the board as a whole on the same channel
  // (tests/rtl/test_ddr4_card.cpp).
  const auto card = voxcast::rtl::rtl_config_for_board(board::shipped_board("alveo_u250"));
  EXPECT_TRUE(card.card.enabled);
  std::ostringstream d;
  d << sdram::to_cycles(card.pipeline.dimm.timing, card.pipeline.dimm.clock, 8);
  EXPECT_EQ(d.str(), b.str());
  // A channel the model cannot run: one line naming the board file, key and reason.
  std::string text = board::shipped_board_text("alveo_u250");
  text.replace(text.find("burst_length = 8"), 16, "burst_length = 4");
  try {
    (void)voxcast::rtl::channel_config_for_board(board::parse_board(text, "u250_bc4.toml"));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "board alveo_u250 (u250_bc4.toml): memory.burst_length: the DRAM model cannot "
              "simulate it: 4 (DDR4 bursts are BL8)");
  }
}

// ---- (c) Closed forms --------------------------------------------------------------------
// `n` bursts in address order from cycle 0, all waiting at once (a streaming
// reader that never lets the queue run dry).
std::vector<rt::TraceRequest> stream(std::uint64_t n, std::uint64_t burst_bytes) {
  std::vector<rt::TraceRequest> t(n);
  for (std::uint64_t i = 0; i < n; ++i) t[i].address = i * burst_bytes;
  return t;
}

void expect_within_1_percent(double measured, double closed_form) {
  EXPECT_NEAR(measured, closed_form, 0.01 * closed_form);
}

// DDR4 streaming with the bank group in the lowest address bits
// ("rochrabacobg"): consecutive bursts alternate groups, so reads go
// max(tCCD_S, BL/2) = 4 clocks apart and the data bus never idles; rows
// change every 128 bursts per group, prepared ahead by FR-FCFS from the
// 32-deep queue (tRP + tRCD = 34 clocks < 32 bursts x 4 clocks). Each
// refresh (eager: at every tREFI) costs L clocks: PREA waits tRTP after the
// last READ t0, REF tRP later, ACT tRFC later, the next READ tRCD later,
// where a READ would have gone at t0 + BL/2:
//   L = tRTP + tRP + tRFC + tRCD - BL/2 = 9 + 17 + 421 + 17 - 4 = 460,
//   B = 64 B / (BL/2 tCK) x (1 - L / tREFI) = 19.208 x (1 - 460/9363) = 18.264 GB/s.
TEST(RequestTraceClosedForms, Ddr4StreamingBandwidthWithRefresh) {
  const sdram::DimmConfig c = u250_channel();
  const sdram::TimingCycles t = sdram::to_cycles(c.timing, c.clock, 8);
  const rt::AddressMapping m(c.geometry, 8, "rochrabacobg");
  const std::uint64_t n = 20 * t.tREFI / t.burst_cycles();  // about 20 refreshes
  const rt::TraceRunResult r = rt::run_request_trace(c, stream(n, 64), m);
  const double peak = 64.0 / (static_cast<double>(t.burst_cycles()) * c.clock.period_ns());
  const double loss = static_cast<double>(t.tRTP + t.tRP + t.tRFC + t.tRCD - t.burst_cycles());
  const double closed = peak * (1.0 - loss / static_cast<double>(t.tREFI));
  EXPECT_NEAR(r.peak_gbs, peak, 1e-9);
  expect_within_1_percent(r.bandwidth_gbs, closed);
  EXPECT_GE(r.refreshes, 18u);
  EXPECT_EQ(r.requests, n);
  // Every row change opened a row; a refresh may close a row opened for a
  // request before its READ (it is opened again).
  EXPECT_GE(r.activates, r.row_conflicts + r.row_misses);
  ::testing::Test::RecordProperty("ddr4_stream_gbs", std::to_string(r.bandwidth_gbs));
}

// PC100 (vizard2_pci: CL2, BL1) streaming: one beat a clock; a refresh costs
// tRP + tRFC + tRCD = 11 clocks per tREFI = 1562 (PREA in the next READ's
// slot; docs/sdram.md §5): B = 8 B x 100 MHz x (1 - 11/1562) = 794.37 MB/s.
TEST(RequestTraceClosedForms, Pc100StreamingBandwidthWithRefresh) {
  const sdram::DimmConfig c = pc100_channel();
  const sdram::TimingCycles t = sdram::to_cycles(c.timing, c.clock, c.burst_length);
  const rt::AddressMapping m(c.geometry, c.burst_length);
  const std::uint64_t n = 20 * t.tREFI;
  const rt::TraceRunResult r = rt::run_request_trace(c, stream(n, 8), m);
  const double loss = static_cast<double>(t.tRP + t.tRFC + t.tRCD);
  const double closed = 8.0 / c.clock.period_ns() * (1.0 - loss / static_cast<double>(t.tREFI));
  expect_within_1_percent(r.bandwidth_gbs, closed);
  EXPECT_NEAR(closed, 0.79437, 1e-5);
  ::testing::Test::RecordProperty("pc100_stream_gbs", std::to_string(r.bandwidth_gbs));
}

// Every request a row conflict: one bank, rows alternating, a request every
// `gap` clocks (long enough for tRAS, tRTP and tRC of the previous access),
// the run shorter than tREFI (no refresh). The first request opens its row
// (a miss: tRCD + CL + burst); each later one is PRE -> ACT -> READ -> end of
// its data: tRP + tRCD + CL + burst clocks (DDR4-2400 CL17: 17 + 17 + 17 + 4
// = 55 clocks = 45.8 ns; PC100 CL2 BL1: 2 + 2 + 2 + 1 = 7 clocks = 70 ns,
// VIZARD II's "70 ns for a pre-charge and row activate").
void expect_conflict_latency(const sdram::DimmConfig& c, Cycle gap) {
  const sdram::TimingCycles t = sdram::to_cycles(c.timing, c.clock, c.burst_length);
  const rt::AddressMapping m(c.geometry, c.burst_length);
  const std::size_t n = static_cast<std::size_t>((t.tREFI - 2 * gap) / gap);
  std::vector<rt::TraceRequest> trace(n);
  for (std::size_t i = 0; i < n; ++i) {
    trace[i].address = m.byte_address(sdram::Address{0, static_cast<std::uint32_t>(i % 2), 0});
    trace[i].cycle = static_cast<Cycle>(i) * gap;
  }
  const rt::TraceRunResult r = rt::run_request_trace(c, trace, m);
  const Cycle conflict = t.tRP + t.tRCD + t.CL + t.burst_cycles();
  const Cycle miss = t.tRCD + t.CL + t.burst_cycles();
  EXPECT_EQ(r.refreshes, 0u);
  EXPECT_EQ(r.row_conflicts, n - 1);
  EXPECT_EQ(r.row_misses, 1u);
  EXPECT_EQ(r.latency_p50, conflict);
  EXPECT_EQ(r.latency_max, conflict);
  const double mean =
      static_cast<double>(conflict * static_cast<Cycle>(n - 1) + miss) / static_cast<double>(n);
  expect_within_1_percent(r.latency_mean, static_cast<double>(conflict));
  EXPECT_DOUBLE_EQ(r.latency_mean, mean);
  ::testing::Test::RecordProperty(c.timing.name + " conflict_latency_mean",
                                  std::to_string(r.latency_mean));
}

TEST(RequestTraceClosedForms, RowConflictLatencyIsTrpTrcdClBurst) {
  {
    SCOPED_TRACE("DDR4-2400");
    expect_conflict_latency(u250_channel(), 100);
  }
  {
    SCOPED_TRACE("PC100");
    expect_conflict_latency(pc100_channel(), 20);
  }
}

// Records every ACT's cycle.
struct ActivateLog final : sdram::CommandObserver {
  std::vector<Cycle> cycles;
  void on_command(sdram::Command cmd, const sdram::Address&, Cycle now) override {
    if (cmd == sdram::Command::kAct) cycles.push_back(now);
  }
};

// tFAW bounds the activate rate: every request opens a new row in the next
// of the 16 banks, the bank groups in turn, all waiting from cycle 0. On x8
// parts (tFAW 26 > 4 tRRD_S = 16) nothing else binds: tRC per bank (56) is
// met (a bank's next ACT is 16 ACTs = 4 windows = 104 clocks later), reads
// need 4 x BL/2 = 16 data clocks per window, PRE + ACT + RD 12 command clocks.
// So 4 ACTs per tFAW: the ACTs' mean spacing is tFAW / 4 = 6.5 clocks, the
// bandwidth 4 x 64 B / (tFAW tCK) = 11.82 GB/s (the run, shorter than tREFI,
// has no refresh).
TEST(RequestTraceClosedForms, ActivateRateIsFourPerTfaw) {
  sdram::DimmConfig c = u250_channel();
  c.timing = sdram::presets::ddr4_2400_cl17_x8();  // 1 KB page: tFAW binds
  const sdram::TimingCycles t = sdram::to_cycles(c.timing, c.clock, 8);
  const rt::AddressMapping m(c.geometry, 8);
  const std::size_t n = 1000;
  std::vector<rt::TraceRequest> trace(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto group = static_cast<std::uint32_t>(i % 4),
               bank = static_cast<std::uint32_t>(i / 4 % 4);
    const auto row = static_cast<std::uint32_t>(i / 16 + 1);
    trace[i].address = m.byte_address(sdram::Address{group * 4 + bank, row, 0});
  }
  ActivateLog log;
  const rt::TraceRunResult r = rt::run_request_trace(c, trace, m, {.observer = &log});
  ASSERT_EQ(log.cycles.size(), n);
  EXPECT_EQ(r.refreshes, 0u);
  // Never five ACTs in a window of tFAW clocks.
  for (std::size_t i = 4; i < log.cycles.size(); ++i)
    EXPECT_GE(log.cycles[i] - log.cycles[i - 4], t.tFAW) << i;
  const double spacing = static_cast<double>(log.cycles.back() - log.cycles.front()) /
                         static_cast<double>(log.cycles.size() - 1);
  expect_within_1_percent(spacing, static_cast<double>(t.tFAW) / 4.0);
  const double closed = 4.0 * 64.0 / (static_cast<double>(t.tFAW) * c.clock.period_ns());
  expect_within_1_percent(r.bandwidth_gbs, closed);
  ::testing::Test::RecordProperty("tfaw_act_spacing", std::to_string(spacing));
  ::testing::Test::RecordProperty("tfaw_gbs", std::to_string(r.bandwidth_gbs));
}

}  // namespace VOXCAST_UNITY_ID
