// voxcast dram-trace BOARD TRACE [--mapping ORDER] [--queue N] [--scheduler NAME]
// [--json FILE]: a request trace in DRAMsim3's text format through one
// channel of the board's memory (docs/sdram.md "dram-trace").
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "cosim/commands/command.hpp"
#include "cosim/reports/files.hpp"
#include "rtl_model/board/board.hpp"
#include "rtl_model/board/board_config.hpp"
#include "rtl_model/sched/registry.hpp"
#include "rtl_model/trace/request_trace.hpp"

namespace voxcast::cosim::commands {
namespace {

struct DramTraceArgs {
  std::string board, trace, mapping = rtl::trace::AddressMapping::kDefaultOrder, json;
  std::string scheduler = "fr-fcfs";
  std::size_t queue = 32;
};

nlohmann::json to_json(const rtl::trace::TraceRunResult& r, const DramTraceArgs& a,
                       const rtl::board::Board& b, const rtl::trace::AddressMapping& m) {
  const auto ns = [&](double cycles) { return cycles * r.clock_ns; };
  return {
      {"board", b.name},
      {"board_file", b.origin},
      {"trace", a.trace},
      {"timing", b.memory.timing.name},
      {"clock_ns", r.clock_ns},
      {"mapping", m.order()},
      {"mapping_bits", m.describe()},
      {"scheduler", a.scheduler},
      {"queue_depth", a.queue},
      {"requests", r.requests},
      {"reads", r.reads},
      {"writes", r.writes},
      {"cycles", r.cycles},
      {"bytes", r.bytes},
      {"bandwidth_gbs", r.bandwidth_gbs},
      {"peak_gbs", r.peak_gbs},
      {"percent_of_peak", r.percent_of_peak()},
      {"latency_cycles",
       {{"mean", r.latency_mean},
        {"p50", r.latency_p50},
        {"p90", r.latency_p90},
        {"p99", r.latency_p99},
        {"max", r.latency_max}}},
      {"latency_ns",
       {{"mean", ns(r.latency_mean)},
        {"p50", ns(static_cast<double>(r.latency_p50))},
        {"p90", ns(static_cast<double>(r.latency_p90))},
        {"p99", ns(static_cast<double>(r.latency_p99))},
        {"max", ns(static_cast<double>(r.latency_max))}}},
      {"row_hits", r.row_hits},
      {"row_misses", r.row_misses},
      {"row_conflicts", r.row_conflicts},
      {"activates", r.activates},
      {"refreshes", r.refreshes},
      {"refresh_stall_cycles", r.refresh_stall_cycles},
  };
}

void print(std::ostream& os, const rtl::trace::TraceRunResult& r, const DramTraceArgs& a,
           const rtl::board::Board& b, const rtl::sdram::DimmConfig& c,
           const rtl::trace::AddressMapping& m) {
  const auto ns = [&](double cycles) { return cycles * r.clock_ns; };
  os << std::fixed << std::setprecision(2);
  os << "board       " << b.name << " (" << b.origin << "), one channel: " << c.geometry << "\n"
     << "timing      " << c.timing.name << " at " << c.clock << "\n"
     << "mapping     " << m.describe() << "\n"
     << "controller  " << a.scheduler << ", queue " << a.queue
     << ", open page, eager refresh; latency from the trace's cycle to the end of the data\n"
     << "requests    " << r.requests << " (" << r.reads << " reads, " << r.writes << " writes)\n"
     << "cycles      " << r.cycles << " (" << ns(static_cast<double>(r.cycles)) / 1000.0 << " us)\n"
     << "bandwidth   " << r.bandwidth_gbs << " GB/s (" << r.percent_of_peak() << " % of "
     << r.peak_gbs << " GB/s)\n"
     << "latency     mean " << r.latency_mean << ", p50 " << r.latency_p50 << ", p90 "
     << r.latency_p90 << ", p99 " << r.latency_p99 << ", max " << r.latency_max << " cycles\n"
     << "            mean " << ns(r.latency_mean) << ", p50 "
     << ns(static_cast<double>(r.latency_p50)) << ", p90 " << ns(static_cast<double>(r.latency_p90))
     << ", p99 " << ns(static_cast<double>(r.latency_p99)) << ", max "
     << ns(static_cast<double>(r.latency_max)) << " ns\n"
     << "rows        " << r.row_hits << " hits, " << r.row_misses << " misses, " << r.row_conflicts
     << " conflicts (" << r.activates << " ACT)\n"
     << "refresh     " << r.refreshes << " REF, " << r.refresh_stall_cycles << " stall cycles\n";
}

}  // namespace

Subcommand add_dram_trace(CLI::App& voxcast) {
  auto a = std::make_shared<DramTraceArgs>();
  CLI::App* cmd = voxcast.add_subcommand(
      "dram-trace",
      "Run a memory-request trace (DRAMsim3's text format) through one channel of a board's "
      "memory: bandwidth, latency, row hits, refresh");
  cmd->add_option("board", a->board,
                  "Shipped board name (vizard2_pci, alveo_u250) or a board .toml")
      ->required();
  cmd->add_option("trace", a->trace, "Trace file: one '0x<address> READ|WRITE <cycle>' a line")
      ->required();
  cmd->add_option("--mapping", a->mapping,
                  "Address bit fields, most significant first, DRAMsim3's codes (ch ra bg ba ro "
                  "co)")
      ->capture_default_str();
  cmd->add_option("--queue", a->queue, "Controller queue depth (and FR-FCFS window)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  cmd->add_option("--scheduler", a->scheduler, "Command scheduler")
      ->capture_default_str()
      ->check(CLI::IsMember(rtl::sched::scheduler_names()));
  cmd->add_option("--json", a->json, "Also write the results as JSON here");
  return {cmd, [a] {
            const rtl::board::Board board = rtl::board::load_board(a->board);
            const rtl::sdram::DimmConfig channel = rtl::channel_config_for_board(board);
            const rtl::trace::AddressMapping mapping(channel.geometry, channel.burst_length,
                                                     a->mapping);
            const auto trace = rtl::trace::read_request_trace(a->trace);
            rtl::trace::check_addresses(trace, mapping, a->trace);
            const auto result = rtl::trace::run_request_trace(
                channel, trace, mapping, {.scheduler = a->scheduler, .queue_depth = a->queue});
            print(std::cout, result, *a, board, channel, mapping);
            if (!a->json.empty())
              write_text_file(a->json, to_json(result, *a, board, mapping).dump(2) + "\n");
            return 0;
          }};
}

}  // namespace voxcast::cosim::commands
