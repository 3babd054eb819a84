#include "rtl_model/pipeline/stats.hpp"

#include <algorithm>
#include <iomanip>
#include <ostream>

namespace voxcast::rtl::pipeline {

namespace {
double ratio(double a, double b) { return b == 0.0 ? 0.0 : a / b; }
}  // namespace

std::ostream& operator<<(std::ostream& os, const StallStats& s) {
  return os << "address generator: no ray " << s.issue_no_ray << ", sample buffer full "
            << s.issue_buffer_full << ", memory queue full " << s.issue_memory_full
            << ", done " << s.issue_idle << "; interpolation: waiting for memory "
            << s.interp_wait_memory << ", blocked " << s.interp_blocked
            << "; setup: no slot " << s.setup_no_slot << "; compositor: blocked "
            << s.composite_blocked;
}

double RtlStats::ns_per_sample() const {
  return ratio(static_cast<double>(cycles) * period_ns(), static_cast<double>(samples));
}
double RtlStats::ns_per_issued_sample() const {
  return ratio(static_cast<double>(cycles) * period_ns(), static_cast<double>(samples_issued));
}
double RtlStats::samples_per_cycle() const {
  return ratio(static_cast<double>(samples), static_cast<double>(cycles));
}

std::uint64_t RtlStats::row_hits() const {
  std::uint64_t n = 0;
  for (const auto& d : dimms) n += d.controller.row_hits;
  return n;
}
std::uint64_t RtlStats::row_misses() const {
  std::uint64_t n = 0;
  for (const auto& d : dimms) n += d.controller.row_misses;
  return n;
}
std::uint64_t RtlStats::row_conflicts() const {
  std::uint64_t n = 0;
  for (const auto& d : dimms) n += d.controller.row_conflicts;
  return n;
}
double RtlStats::row_hit_rate() const {
  const auto all = row_hits() + row_misses() + row_conflicts();
  return ratio(static_cast<double>(row_hits()), static_cast<double>(all));
}
std::uint64_t RtlStats::activates() const {
  std::uint64_t n = 0;
  for (const auto& d : dimms)
    for (const auto& b : d.dimm.banks) n += b.activates;
  return n;
}
std::uint64_t RtlStats::refreshes() const {
  std::uint64_t n = 0;
  for (const auto& d : dimms) n += d.dimm.refreshes;
  return n;
}
std::uint64_t RtlStats::bytes_read() const {
  std::uint64_t n = 0;
  for (const auto& d : dimms) n += d.controller.bytes;
  return n;
}
double RtlStats::samples_per_second() const {
  return ratio(static_cast<double>(samples), seconds());
}
double RtlStats::peak_bytes() const { return bus_bytes_per_cycle * static_cast<double>(cycles); }

double CardStats::cache_hit_rate() const {
  return ratio(static_cast<double>(cache_hits),
               static_cast<double>(cache_hits + cache_pending_hits + cache_misses));
}
double CardStats::channel_utilisation() const {
  std::uint64_t busiest = 0;
  for (const auto b : bursts) busiest = std::max(busiest, b);
  return ratio(static_cast<double>(busiest * static_cast<std::uint64_t>(burst_clocks)),
               static_cast<double>(memory_cycles));
}
double CardStats::pipeline_utilisation(Cycle core_cycles) const {
  return ratio(static_cast<double>(busiest_pipeline_issues), static_cast<double>(core_cycles));
}
const char* CardStats::bound(Cycle core_cycles) const {
  const double pipes = pipeline_utilisation(core_cycles), channels = channel_utilisation();
  if (std::max(pipes, channels) < kSaturated) return "latency";
  return channels > pipes ? "channels" : "pipelines";
}
double RtlStats::bandwidth_utilisation() const {
  return ratio(static_cast<double>(bytes_read()), peak_bytes());
}
double RtlStats::bandwidth_mb_s() const {
  return ratio(static_cast<double>(bytes_read()) * 1e-6, seconds());
}

std::ostream& operator<<(std::ostream& os, const RtlStats& s) {
  os << std::fixed << std::setprecision(3);
  os << "frame: " << s.cycles << " cycles at " << s.clock_mhz << " MHz = " << s.seconds() * 1e3
     << " ms (" << s.fps() << " fps)\n";
  os << "rays " << s.rays << " (" << s.rays_hit << " hit, " << s.rays_ert
     << " ended early by ERT)\n";
  os << "samples: " << s.samples << " composited, " << s.samples_issued << " issued, "
     << s.samples_discarded << " discarded after ERT; " << s.ns_per_sample()
     << " ns/sample (" << s.ns_per_issued_sample() << " per issued), " << s.samples_per_cycle()
     << " samples/cycle\n";
  if (s.leaps > 0)
    os << "space leaping: " << s.samples_skipped << " samples skipped in " << s.leaps
       << " leaps (" << s.samples_skipped_discarded << " of them after ERT)\n";
  if (s.issue_bypasses > 0)
    os << "row-hit issue: " << s.issue_bypasses
       << " samples issued ahead of the oldest ready ray (at most " << s.issue_longest_bypass
       << " in a row)\n";
  if (s.card.pipelines > 0) {
    const CardStats& k = s.card;
    os << "DDR4 card: " << k.pipelines << " pipeline(s) at " << s.clock_mhz << " MHz, channels at "
       << k.memory_mhz << " MHz (" << k.memory_cycles << " memory cycles); "
       << s.samples_per_second() * 1e-9 << " G samples/s\n"
       << "  brick cache (" << k.cache_lines << " lines per channel): hits " << k.cache_hits
       << ", pending hits " << k.cache_pending_hits << ", misses " << k.cache_misses
       << " (hit rate " << k.cache_hit_rate() << "); bursts per channel";
    for (const auto b : k.bursts) os << " " << b;
    os << "\n  bound: " << k.bound(s.cycles) << " (busiest channel's data bus "
       << 100.0 * k.channel_utilisation() << "% busy, busiest pipeline issuing "
       << 100.0 * k.pipeline_utilisation(s.cycles) << "% of clocks)\n";
  }
  os << "memory: row hits " << s.row_hits() << ", misses " << s.row_misses() << ", conflicts "
     << s.row_conflicts() << " (hit rate " << s.row_hit_rate() << "); activates "
     << s.activates() << ", refreshes " << s.refreshes() << "; " << s.bandwidth_mb_s()
     << " MB/s = " << s.bandwidth_utilisation() * 100.0 << "% of peak\n";
  for (std::size_t d = 0; d < s.dimms.size(); ++d) {
    os << "  DIMM " << d << ": " << s.dimms[d].controller << "\n    activates per bank:";
    for (const auto& b : s.dimms[d].dimm.banks) os << " " << b.activates;
    os << ", refreshes " << s.dimms[d].dimm.refreshes << "\n";
  }
  os << "stalls: " << s.stalls << "\n";
  for (const auto& f : s.fifos) os << "  FIFO '" << f.name << "' depth " << f.depth << ": " << f.stats << "\n";
  os << "simulation: " << s.evaluated_cycles << " of " << s.cycles << " cycles evaluated\n";
  return os;
}

}  // namespace voxcast::rtl::pipeline
