// Clock domains of the card, and the one place where picoseconds and clock
// cycles meet.
//
// The card has three clocks: the SDRAM clock (PC100, 10 ns), the PCI clock
// (33 MHz, 30 ns) and the core clock of the FPGA design. Every conversion
// between a duration and a number of cycles, or between the cycles of two
// domains, goes through ClockDomain, so each rounding rule is decided once:
//   - a minimum delay (tRCD(min), tRP(min), ...) rounds UP: the datasheet rule
//     "divide by the clock period and round up to the next whole number"
//     (Micron 64Mb SDRAM data sheet, Rev. U, "Bank/Row Activation", p. 46);
//   - a maximum interval (tREFI, tRAS(max)) rounds DOWN, or the interval would
//     be exceeded.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

namespace voxcast::rtl::sim {

// Time in integer picoseconds. Every period and datasheet delay of the card is
// a whole number of picoseconds (7.5 ns for PC133, 30 ns for PCI), so the
// roundings below are exact: 15 ns at 7.5 ns is 2 cycles, never 3.
using Picoseconds = std::int64_t;
// A clock-edge index within one domain; edge 0 is at time 0.
using Cycle = std::int64_t;

// Datasheet nanoseconds to picoseconds (nearest picosecond). Throws
// voxcast::Error for a negative or non-finite value.
Picoseconds ps_from_ns(double ns);

class ClockDomain {
 public:
  // Throws voxcast::Error unless period_ps > 0.
  ClockDomain(std::string name, Picoseconds period_ps);
  // A frequency in MHz, the period rounded to the nearest picosecond. 133 MHz
  // gives 7519 ps: PC133's exact 7.5 ns needs the period constructor.
  static ClockDomain from_mhz(std::string name, double mhz);

  const std::string& name() const { return name_; }
  Picoseconds period_ps() const { return period_ps_; }
  double period_ns() const;
  double frequency_mhz() const;

  // Time of edge `cycle`.
  Picoseconds time_of(Cycle cycle) const { return cycle * period_ps_; }
  // Smallest whole number of cycles lasting at least `duration` (>= 0): the
  // rounding for minimum delays.
  Cycle cycles_at_least(Picoseconds duration) const;
  // Largest whole number of cycles lasting at most `duration` (>= 0): the
  // rounding for maximum intervals.
  Cycle cycles_at_most(Picoseconds duration) const;
  // First edge of this domain at or after time t (t >= 0).
  Cycle edge_at_or_after(Picoseconds t) const { return cycles_at_least(t); }
  // First edge of this domain at or after edge `cycle` of `from`: the earliest
  // edge here that can sample a signal launched there (no synchroniser
  // latency is modelled; a CDC FIFO adds its own).
  Cycle edge_at_or_after(Cycle cycle, const ClockDomain& from) const;
  // Cycles of this domain that last at least `cycles` cycles of `from`.
  Cycle cycles_covering(Cycle cycles, const ClockDomain& from) const;

  friend bool operator==(const ClockDomain&, const ClockDomain&) = default;

 private:
  std::string name_;
  Picoseconds period_ps_;
};

std::ostream& operator<<(std::ostream& os, const ClockDomain& clock);

// The card's clocks.
namespace clocks {
// 10 ns: PC100 (Micron 128Mb SDRAM -8E, tCK(2) = 10 ns).
ClockDomain pc100();
// 7.5 ns (133.33 MHz): PC133 (Micron 128Mb SDRAM -75, tCK(3) = 7.5 ns).
ClockDomain pc133();
// 0.833 ns (1200 MHz): DDR4-2400's command clock, tCK(avg) as JESD79-4B lists
// it (truncated to the ps; the exact 5/6 ns is not a whole number of ps, and
// JEDEC's rounding of DDR4 delays, sdram::Rounding::kJedecGuardBand, is made
// for this truncation).
ClockDomain ddr4_2400();
// 30 ns (33.33 MHz): 33 MHz PCI (PCI Local Bus Specification 2.2, §4.2.3.1:
// Tcyc(min) = 30 ns), 32 bits wide on the VIZARD II card.
ClockDomain pci33();
}  // namespace clocks

// Several domains advanced together in time order, for models that span the
// core, SDRAM and PCI clocks. advance() returns the next instant at which at
// least one domain has an edge, with every domain that has an edge then
// (coincident edges are returned together, so their order is not implied).
class MultiClock {
 public:
  struct Edge {
    std::size_t domain;  // index returned by add()
    Cycle cycle;         // edge index within that domain
  };
  struct Tick {
    Picoseconds time = 0;
    std::vector<Edge> edges;
  };

  // Returns the domain's index. Its first edge is edge 0 at time 0.
  std::size_t add(ClockDomain domain);
  const ClockDomain& domain(std::size_t index) const { return domains_.at(index).first; }
  std::size_t size() const { return domains_.size(); }
  // Throws voxcast::Error when no domain was added.
  Tick advance();
  // Edges of domain `index` returned so far.
  Cycle edges_seen(std::size_t index) const { return domains_.at(index).second; }

 private:
  // (domain, index of its next edge)
  std::vector<std::pair<ClockDomain, Cycle>> domains_;
};

}  // namespace voxcast::rtl::sim
