#include "rtl_model/trace/request_trace.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <fstream>
#include <memory>
#include <ostream>
#include <sstream>

#include "refmodel/error.hpp"
#include "rtl_model/sched/registry.hpp"
#include "rtl_model/sdram/controller.hpp"

namespace voxcast::rtl::trace {

// ---- Parsing -----------------------------------------------------------------------------
namespace {

[[noreturn]] void bad_line(const std::string& origin, int line, const std::string& what) {
  throw Error(origin + ":" + std::to_string(line) + ": " + what);
}

// DRAMsim3's operations (src/common.cc, operator>> for Transaction).
bool kind_of(const std::string& op, sdram::RequestKind& kind) {
  static const std::array<const char*, 4> writes{"WRITE", "write", "P_MEM_WR", "BOFF"};
  static const std::array<const char*, 4> reads{"READ", "read", "P_MEM_RD", "P_FETCH"};
  const auto is = [&](const auto& names) {
    return std::any_of(names.begin(), names.end(), [&](const char* n) { return op == n; });
  };
  if (is(writes)) {
    kind = sdram::RequestKind::kWrite;
    return true;
  }
  if (is(reads)) {
    kind = sdram::RequestKind::kRead;
    return true;
  }
  return false;
}

// A whole token as an unsigned number in `base`; false on anything else.
bool whole_number(const std::string& token, int base, std::uint64_t& value) {
  if (token.empty() || token[0] == '-' || token[0] == '+') return false;
  try {
    std::size_t used = 0;
    value = std::stoull(token, &used, base);
    return used == token.size();
  } catch (const std::exception&) {
    return false;
  }
}

TraceRequest parse_line(const std::string& text, const std::string& origin, int line) {
  std::istringstream in(text);
  std::string address, op, cycle, extra;
  in >> address >> op >> cycle >> extra;
  if (cycle.empty())
    bad_line(
        origin, line,
        "expected \"ADDRESS OPERATION CYCLE\" (DRAMsim3's trace format), got \"" + text + "\"");
  if (!extra.empty()) bad_line(origin, line, "unexpected \"" + extra + "\" after the cycle");
  TraceRequest r;
  r.line = line;
  std::string hex = address;
  if (hex.size() > 2 && hex[0] == '0' && (hex[1] == 'x' || hex[1] == 'X')) hex = hex.substr(2);
  if (!whole_number(hex, 16, r.address))
    bad_line(origin, line, "address \"" + address + "\" is not a hexadecimal number");
  if (!kind_of(op, r.kind))
    bad_line(origin, line,
             "operation \"" + op +
                 "\" is not READ, WRITE (or read, write, P_MEM_RD, P_FETCH, "
                 "P_MEM_WR, BOFF)");
  // A cycle far below Cycle's range, so that cycles and delays added to it cannot overflow.
  constexpr std::uint64_t kLastCycle = std::uint64_t{1} << 48;
  std::uint64_t c = 0;
  if (!whole_number(cycle, 10, c))
    bad_line(origin, line, "cycle \"" + cycle + "\" is not a whole number of clocks");
  if (c > kLastCycle) bad_line(origin, line, "cycle " + cycle + " is beyond 2^48 clocks");
  r.cycle = static_cast<Cycle>(c);
  return r;
}

}  // namespace

std::vector<TraceRequest> parse_request_trace(std::istream& in, const std::string& origin) {
  std::vector<TraceRequest> out;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    if (const std::size_t hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    TraceRequest r = parse_line(text, origin, line);
    if (!out.empty() && r.cycle < out.back().cycle)
      bad_line(origin, line,
               "cycle " + std::to_string(r.cycle) + " is before the previous request's " +
                   std::to_string(out.back().cycle) + " (a trace is in cycle order)");
    out.push_back(r);
  }
  return out;
}

std::vector<TraceRequest> read_request_trace(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("cannot read trace file " + path);
  return parse_request_trace(in, path);
}

// ---- Address mapping ---------------------------------------------------------------------
namespace {
int log2_exact(std::uint64_t v, const std::string& what) {
  if (!std::has_single_bit(v)) throw Error("address mapping: " + what + " is not a power of two");
  return std::countr_zero(v);
}
}  // namespace

AddressMapping::AddressMapping(const sdram::Geometry& g, int burst_length, const std::string& order)
    : order_(order),
      banks_per_group_(g.banks_per_group()),
      beats_per_burst_(static_cast<std::uint32_t>(burst_length)) {
  // Step 1: the widths (DRAMsim3 src/configuration.cc: the request is one
  // burst; its byte offset is log2(BL x bus bytes) bits).
  const std::uint64_t bursts_per_row = g.columns / beats_per_burst_;
  const std::vector<std::pair<std::string, int>> widths = {
      {"ch", 0},
      {"ra", 0},
      {"bg", log2_exact(g.bank_groups, "the bank-group count")},
      {"ba", log2_exact(g.banks_per_group(), "the banks per group")},
      {"ro", log2_exact(g.rows, "the row count")},
      {"co", log2_exact(bursts_per_row, "the bursts per row")},
  };
  offset_bits_ = log2_exact(std::uint64_t{beats_per_burst_} * g.bytes_per_beat(), "the burst");
  // Step 2: the order, most significant first, each field once.
  if (order.size() != 2 * widths.size())
    throw Error("address mapping \"" + order +
                "\": expected the six fields ch, ra, bg, ba, ro, "
                "co once each, most significant first (DRAMsim3's address_mapping)");
  for (std::size_t i = 0; i < order.size(); i += 2) {
    const std::string code = order.substr(i, 2);
    const auto w =
        std::find_if(widths.begin(), widths.end(), [&](const auto& f) { return f.first == code; });
    const bool repeated =
        std::any_of(fields_.begin(), fields_.end(), [&](const Field& f) { return f.code == code; });
    if (w == widths.end() || repeated)
      throw Error("address mapping \"" + order + "\": \"" + code +
                  "\" is not one of ch, ra, bg, ba, ro, co or is repeated");
    fields_.push_back(Field{code, w->second, 0});
  }
  // Step 3: bit positions, least significant field last in the order.
  int low = offset_bits_;
  for (auto f = fields_.rbegin(); f != fields_.rend(); ++f) {
    f->low = low;
    low += f->bits;
  }
  address_bits_ = low;
}

std::uint32_t AddressMapping::field(std::uint64_t address, const char* code) const {
  for (const Field& f : fields_)
    if (f.code == code)
      return static_cast<std::uint32_t>((address >> f.low) & ((std::uint64_t{1} << f.bits) - 1));
  return 0;
}

sdram::Address AddressMapping::map(std::uint64_t address) const {
  return sdram::Address{
      .bank = field(address, "bg") * banks_per_group_ + field(address, "ba"),
      .row = field(address, "ro"),
      .column = field(address, "co") * beats_per_burst_,
  };
}

std::uint64_t AddressMapping::place(const char* code, std::uint32_t value) const {
  for (const Field& f : fields_)
    if (f.code == code) return std::uint64_t{value} << f.low;
  return 0;
}

std::uint64_t AddressMapping::byte_address(const sdram::Address& a) const {
  return place("bg", a.bank / banks_per_group_) | place("ba", a.bank % banks_per_group_) |
         place("ro", a.row) | place("co", a.column / beats_per_burst_);
}

std::string AddressMapping::describe() const {
  std::ostringstream os;
  const auto name = [](const std::string& code) -> std::string {
    if (code == "bg") return "bankgroup";
    if (code == "ba") return "bank";
    if (code == "ro") return "row";
    if (code == "co") return "column";
    return code;
  };
  os << "\"" << order_ << "\":";
  for (const Field& f : fields_)
    if (f.bits > 0) os << " " << name(f.code) << "[" << f.low + f.bits - 1 << ":" << f.low << "]";
  os << " burst byte[" << offset_bits_ - 1 << ":0]";
  return os.str();
}

void check_addresses(const std::vector<TraceRequest>& trace, const AddressMapping& mapping,
                     const std::string& origin) {
  for (const TraceRequest& r : trace) {
    if (mapping.contains(r.address)) continue;
    std::ostringstream os;
    os << origin << ":" << r.line << ": address 0x" << std::hex << r.address
       << " is beyond the channel's capacity (" << std::dec << (mapping.capacity_bytes() >> 20)
       << " MiB: addresses below 0x" << std::hex << mapping.capacity_bytes() << ")";
    throw Error(os.str());
  }
}

// ---- The run -----------------------------------------------------------------------------
namespace {
Cycle nearest_rank(const std::vector<Cycle>& sorted, double q) {
  if (sorted.empty()) return 0;
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(sorted.size())));
  return sorted[std::clamp<std::size_t>(rank, 1, sorted.size()) - 1];
}
}  // namespace

TraceRunResult run_request_trace(const sdram::DimmConfig& dimm,
                                 const std::vector<TraceRequest>& trace,
                                 const AddressMapping& mapping, const TraceRunConfig& config) {
  check_addresses(trace, mapping, "trace");
  const int window = static_cast<int>(config.queue_depth);
  // Read data leaves the controller the cycle it completes (DRAMsim3's
  // callbacks), so the return path must never hold a column command back:
  // one slot per clock from a READ to the end of its data is enough.
  const sdram::TimingCycles t = sdram::to_cycles(dimm.timing, dimm.clock, dimm.burst_length);
  const auto in_flight_max = static_cast<std::size_t>(std::max(t.CL, t.CWL) + t.burst_cycles() + 1);
  sdram::Controller ctl(
      dimm, sched::make_scheduler(config.scheduler, {.reorder_window = window}),
      sched::make_refresh_policy("eager"),
      sdram::ControllerConfig{.queue_depth = config.queue_depth,
                              .return_depth = std::max(config.queue_depth, in_flight_max)});
  if (config.observer != nullptr) ctl.set_observer(config.observer);

  // Step 1: each cycle, the requests whose cycle has come enter while the
  // queue has room; the controller ticks; completions leave. Cycles in which
  // nothing can change are skipped (Controller::next_event).
  std::vector<Cycle> latencies;
  latencies.reserve(trace.size());
  Cycle end = 0;
  std::size_t next = 0;
  Cycle now = trace.empty() ? 0 : trace.front().cycle;
  while (next < trace.size() || !ctl.idle()) {
    while (next < trace.size() && trace[next].cycle <= now && ctl.ready()) {
      const TraceRequest& req = trace[next];
      ctl.push(sdram::Request{
          .id = next, .kind = req.kind, .address = mapping.map(req.address), .arrival = now});
      ++next;
    }
    ctl.tick(now);
    while (ctl.completions().valid()) {
      const sdram::Completion c = ctl.completions().pop();
      latencies.push_back(c.data.last + 1 - trace[c.request.id].cycle);
      end = std::max(end, c.data.last + 1);
    }
    Cycle wake = ctl.next_event(now);
    if (next < trace.size() && ctl.ready())
      wake = std::min(wake, std::max(now + 1, trace[next].cycle));
    now = wake;
  }

  // Step 2: the statistics.
  const sdram::ControllerStats& s = ctl.stats();
  TraceRunResult r;
  r.requests = trace.size();
  r.reads = s.reads;
  r.writes = s.writes;
  r.cycles = end;
  r.clock_ns = dimm.clock.period_ns();
  r.bytes = s.bytes;
  const double seconds = static_cast<double>(end) * r.clock_ns * 1e-9;
  r.bandwidth_gbs = seconds > 0 ? static_cast<double>(r.bytes) / seconds * 1e-9 : 0;
  r.peak_gbs = static_cast<double>(mapping.burst_bytes()) /
               (static_cast<double>(t.burst_cycles()) * r.clock_ns);
  std::sort(latencies.begin(), latencies.end());
  double sum = 0;
  for (Cycle l : latencies) sum += static_cast<double>(l);
  r.latency_mean = latencies.empty() ? 0 : sum / static_cast<double>(latencies.size());
  r.latency_p50 = nearest_rank(latencies, 0.50);
  r.latency_p90 = nearest_rank(latencies, 0.90);
  r.latency_p99 = nearest_rank(latencies, 0.99);
  r.latency_max = latencies.empty() ? 0 : latencies.back();
  r.row_hits = s.row_hits;
  r.row_misses = s.row_misses;
  r.row_conflicts = s.row_conflicts;
  r.activates = ctl.dimm().stats().total().activates;
  r.refreshes = ctl.dimm().stats().refreshes;
  r.refresh_stall_cycles = s.refresh_cycles + static_cast<Cycle>(r.refreshes) * t.tRFC;
  return r;
}

std::ostream& operator<<(std::ostream& os, const TraceRunResult& r) {
  return os << r.requests << " requests (" << r.reads << " reads, " << r.writes << " writes) in "
            << r.cycles << " cycles: " << r.bandwidth_gbs << " GB/s (" << r.percent_of_peak()
            << " % of " << r.peak_gbs << "), latency mean " << r.latency_mean << " p50 "
            << r.latency_p50 << " p90 " << r.latency_p90 << " p99 " << r.latency_p99 << " max "
            << r.latency_max << " cycles, rows " << r.row_hits << " hit / " << r.row_misses
            << " miss / " << r.row_conflicts << " conflict, " << r.refreshes << " REF ("
            << r.refresh_stall_cycles << " stall cycles)";
}

}  // namespace voxcast::rtl::trace
