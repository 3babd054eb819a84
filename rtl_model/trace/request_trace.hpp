// A memory-request trace through one channel, the way the DRAM simulators
// run theirs (`voxcast dram-trace`, docs/sdram.md "dram-trace"), so that
// voxcast's PC100 and DDR4 models can be compared with DRAMsim3 or
// Ramulator 2 on the same trace.
//
//   parse_request_trace  DRAMsim3's text format: one request a line,
//                        "0x<hex address> <op> <cycle>"
//   AddressMapping       byte address -> bank group, bank, row, column, by a
//                        DRAMsim3 field order ("rochrababgco")
//   run_request_trace    the requests through the reference Controller
//                        (FR-FCFS, open page, eager refresh), the Dimm the
//                        referee of every command; the statistics a DRAM
//                        simulator prints
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "rtl_model/sdram/dimm.hpp"
#include "rtl_model/sdram/observer.hpp"
#include "rtl_model/sdram/scheduler.hpp"

namespace voxcast::rtl::trace {

using sdram::Cycle;

struct TraceRequest {
  std::uint64_t address = 0;  // byte address in the channel
  sdram::RequestKind kind = sdram::RequestKind::kRead;
  Cycle cycle = 0;  // when the requester issues it, in memory-clock cycles
  int line = 0;     // in the trace file, for messages
};

// DRAMsim3's trace format (src/common.cc, operator>> for Transaction: a hex
// address, an operation, a decimal cycle, whitespace-separated). Writes are
// WRITE, write, P_MEM_WR and BOFF, as DRAMsim3 reads them; reads are READ,
// read, P_MEM_RD and P_FETCH (DRAMsim3 takes any other word as a read; here
// it is an error). The address may carry a 0x prefix. Blank lines and lines
// or tails starting with '#' are skipped. Cycles must not decrease.
// Throws voxcast::Error "ORIGIN:LINE: what is wrong" for a malformed line.
std::vector<TraceRequest> parse_request_trace(std::istream& in, const std::string& origin);
// Throws voxcast::Error naming the file when it cannot be read.
std::vector<TraceRequest> read_request_trace(const std::string& path);

// Byte address -> DIMM address, DRAMsim3's way (src/configuration.cc): the
// low log2(BL x bus bytes) bits are the byte in the burst, then the fields in
// the reverse of `order`, which lists them most significant first in
// two-letter codes: ch (channel), ra (rank), bg (bank group), ba (bank in
// the group), ro (row), co (column, in bursts). One channel and one rank are
// modelled: ch and ra are 0 bits wide. The default, row-bank-bankgroup-
// column, is DRAMsim3's DDR4 configurations' "rochrababgco".
class AddressMapping {
 public:
  static constexpr const char* kDefaultOrder = "rochrababgco";
  // Throws voxcast::Error for an order that is not the six fields once each.
  AddressMapping(const sdram::Geometry& geometry, int burst_length,
                 const std::string& order = kDefaultOrder);

  std::uint64_t capacity_bytes() const { return std::uint64_t{1} << address_bits_; }
  std::uint64_t burst_bytes() const { return std::uint64_t{1} << offset_bits_; }
  bool contains(std::uint64_t address) const { return (address >> address_bits_) == 0; }
  // The address's burst (the byte offset in it dropped). Precondition: contains().
  sdram::Address map(std::uint64_t address) const;
  // The inverse: the byte address of the burst at `a` (a.column a multiple of BL).
  std::uint64_t byte_address(const sdram::Address& a) const;
  // "row[33:17] bank[16:15] bankgroup[14:13] column[12:6] burst byte[5:0]"
  std::string describe() const;
  const std::string& order() const { return order_; }

 private:
  struct Field {
    std::string code;  // "ro", "ba", ...
    int bits = 0;
    int low = 0;  // least significant bit in the byte address
  };
  std::uint32_t field(std::uint64_t address, const char* code) const;
  std::uint64_t place(const char* code, std::uint32_t value) const;

  std::string order_;
  std::uint32_t banks_per_group_ = 1;
  std::uint32_t beats_per_burst_ = 1;
  int offset_bits_ = 0;
  int address_bits_ = 0;
  std::vector<Field> fields_;  // most significant first
};

// Throws voxcast::Error "ORIGIN:LINE: address 0x... is beyond the channel's
// capacity" for the first request outside `mapping`.
void check_addresses(const std::vector<TraceRequest>& trace, const AddressMapping& mapping,
                     const std::string& origin);

struct TraceRunConfig {
  std::string scheduler = "fr-fcfs";
  // Pending requests (the controller's queue, FR-FCFS's reorder window). The
  // read-data return path never back-pressures (data leaves as it completes).
  std::size_t queue_depth = 32;
  sdram::CommandObserver* observer = nullptr;  // told of every command; may be null
};

struct TraceRunResult {
  std::uint64_t requests = 0, reads = 0, writes = 0;
  Cycle cycles = 0;          // cycle 0 to the end of the last request's data
  double clock_ns = 0;       // the memory clock's period
  std::uint64_t bytes = 0;   // requests x burst bytes
  double bandwidth_gbs = 0;  // bytes / (cycles x clock), 1 GB = 10^9 bytes
  double peak_gbs = 0;       // one burst every burst_cycles() clocks
  // From the trace's cycle to the end of the last data beat (as DRAMsim3
  // counts a read from its arrival to its callback): time waiting for queue
  // space included. Nearest-rank percentiles.
  double latency_mean = 0;
  Cycle latency_p50 = 0, latency_p90 = 0, latency_p99 = 0, latency_max = 0;
  std::uint64_t row_hits = 0, row_misses = 0, row_conflicts = 0;
  std::uint64_t activates = 0;
  std::uint64_t refreshes = 0;
  // Cycles the refresh took the channel from the requests: from the refresh
  // decision to the REF (closing the rows) plus tRFC after each REF.
  Cycle refresh_stall_cycles = 0;

  double percent_of_peak() const { return peak_gbs > 0 ? 100.0 * bandwidth_gbs / peak_gbs : 0; }
};

// Runs `trace` (addresses checked) on one DIMM configured by `dimm`; the
// requests enter the controller at their cycle, or as soon as the queue has
// room. Throws voxcast::Error if the scheduler or a command breaks a rule.
TraceRunResult run_request_trace(const sdram::DimmConfig& dimm,
                                 const std::vector<TraceRequest>& trace,
                                 const AddressMapping& mapping, const TraceRunConfig& config = {});

std::ostream& operator<<(std::ostream& os, const TraceRunResult& r);

}  // namespace voxcast::rtl::trace
