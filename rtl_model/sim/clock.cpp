#include "rtl_model/sim/clock.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <sstream>

#include "refmodel/error.hpp"

namespace voxcast::rtl::sim {

Picoseconds ps_from_ns(double ns) {
  if (!std::isfinite(ns) || ns < 0.0) {
    std::ostringstream os;
    os << "duration " << ns << " ns is not a finite non-negative number";
    throw Error(os.str());
  }
  return std::llround(ns * 1000.0);
}

ClockDomain::ClockDomain(std::string name, Picoseconds period_ps)
    : name_(std::move(name)), period_ps_(period_ps) {
  if (period_ps_ <= 0) {
    std::ostringstream os;
    os << "clock '" << name_ << "': period " << period_ps_ << " ps is not positive";
    throw Error(os.str());
  }
}

ClockDomain ClockDomain::from_mhz(std::string name, double mhz) {
  if (!std::isfinite(mhz) || mhz <= 0.0) {
    std::ostringstream os;
    os << "clock '" << name << "': frequency " << mhz << " MHz is not positive";
    throw Error(os.str());
  }
  return ClockDomain(std::move(name), std::llround(1.0e6 / mhz));
}

double ClockDomain::period_ns() const { return static_cast<double>(period_ps_) / 1000.0; }

double ClockDomain::frequency_mhz() const { return 1.0e6 / static_cast<double>(period_ps_); }

Cycle ClockDomain::cycles_at_least(Picoseconds duration) const {
  if (duration < 0) throw Error("clock '" + name_ + "': negative duration");
  return (duration + period_ps_ - 1) / period_ps_;
}

Cycle ClockDomain::cycles_at_most(Picoseconds duration) const {
  if (duration < 0) throw Error("clock '" + name_ + "': negative duration");
  return duration / period_ps_;
}

Cycle ClockDomain::edge_at_or_after(Cycle cycle, const ClockDomain& from) const {
  return edge_at_or_after(from.time_of(cycle));
}

Cycle ClockDomain::cycles_covering(Cycle cycles, const ClockDomain& from) const {
  return cycles_at_least(from.time_of(cycles));
}

std::ostream& operator<<(std::ostream& os, const ClockDomain& clock) {
  return os << clock.name() << " (" << clock.period_ns() << " ns, " << clock.frequency_mhz()
            << " MHz)";
}

namespace clocks {
ClockDomain pc100() { return ClockDomain("sdram-pc100", 10'000); }
ClockDomain pc133() { return ClockDomain("sdram-pc133", 7'500); }
ClockDomain ddr4_2400() { return ClockDomain("ddr4-2400", 833); }
ClockDomain pci33() { return ClockDomain("pci33", 30'000); }
}  // namespace clocks

std::size_t MultiClock::add(ClockDomain domain) {
  domains_.emplace_back(std::move(domain), 0);
  return domains_.size() - 1;
}

MultiClock::Tick MultiClock::advance() {
  if (domains_.empty()) throw Error("MultiClock::advance: no clock domain was added");
  Tick tick;
  tick.time = std::numeric_limits<Picoseconds>::max();
  for (const auto& [clock, next] : domains_) tick.time = std::min(tick.time, clock.time_of(next));
  for (std::size_t i = 0; i < domains_.size(); ++i) {
    auto& [clock, next] = domains_[i];
    if (clock.time_of(next) == tick.time) {
      tick.edges.push_back({i, next});
      ++next;
    }
  }
  return tick;
}

}  // namespace voxcast::rtl::sim
