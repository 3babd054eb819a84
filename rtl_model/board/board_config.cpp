#include "rtl_model/board/board_config.hpp"

#include <sstream>

#include "refmodel/error.hpp"
#include "rtl_model/layout/burst_layout.hpp"
#include "rtl_model/layout/vizard2_layout.hpp"

namespace voxcast::rtl {
namespace {
[[noreturn]] void cannot_model(const board::Board& b, const std::string& why) {
  throw Error("board " + b.name + " (" + b.origin +
              "): the cycle model cannot simulate it: " + why);
}
}  // namespace

namespace {

// A DDR4 board: the card of N pipelines at the core clock on the board's four
// channels (pipeline/burst_card.hpp), each channel the DRAM model's.
RtlConfig ddr4_card_config(const board::Board& b) {
  const board::Memory& m = b.memory;
  if (m.dimms != layout::kBurstChannels)
    cannot_model(b, "memory.dimms = " + std::to_string(m.dimms) +
                        " (the DDR4 card lays the volume out over " +
                        std::to_string(layout::kBurstChannels) + " channels)");
  RtlConfig c;
  c.pipeline.dimm = channel_config_for_board(b);
  const sdram::Geometry& g = c.pipeline.dimm.geometry;
  if (g.bank_groups != static_cast<std::uint32_t>(layout::kBankGroups))
    cannot_model(b, "memory.bank_groups = " + std::to_string(g.bank_groups) +
                        " (the DDR4 card's burst layout skews bricks over " +
                        std::to_string(layout::kBankGroups) + " bank groups)");
  c.card.enabled = true;
  c.card.core_period_ps = b.core().period_ps;
  return c;
}

RtlConfig sdr_card_config(const board::Board& b) {
  const board::Memory& m = b.memory;
  if (m.dimms != layout::kDimms)
    cannot_model(b, "memory.dimms = " + std::to_string(m.dimms) +
                        " (the VIZARD II layout interleaves the volume over " +
                        std::to_string(layout::kDimms) + ")");
  if (b.core().period_ps != b.memory_clock().period_ps) {
    std::ostringstream os;
    os << "the core clock '" << b.core_clock << "' (" << b.core().period_ns()
       << " ns) differs from the memory clock '" << m.clock << "' (" << b.memory_clock().period_ns()
       << " ns); the model runs the pipeline at the SDRAM clock (2001 paper §2.3)";
    cannot_model(b, os.str());
  }
  RtlConfig c;
  c.pipeline.dimm.geometry = m.geometry;
  c.pipeline.dimm.timing = m.timing;
  c.pipeline.dimm.clock = b.memory_clock().domain();
  c.pipeline.dimm.burst_length = m.burst_length;
  // Convert once here so a grade that is not rated for the clock fails with
  // the board's name, not at the first frame.
  try {
    (void)sdram::to_cycles(m.timing, c.pipeline.dimm.clock, m.burst_length);
  } catch (const Error& e) {
    cannot_model(b, e.what());
  }
  return c;
}

}  // namespace

RtlConfig rtl_config_for_board(const board::Board& b) {
  const board::Memory& m = b.memory;
  if (m.type == "ddr4") return ddr4_card_config(b);
  if (m.type != "sdr")
    cannot_model(b, "memory.type = \"" + m.type + "\" (the card model runs SDR SDRAM or DDR4)");
  return sdr_card_config(b);
}

sdram::DimmConfig channel_config_for_board(const board::Board& b) {
  const board::Memory& m = b.memory;
  const auto cannot = [&](const std::string& key, const std::string& why) {
    throw Error("board " + b.name + " (" + b.origin + "): " + key +
                ": the DRAM model cannot simulate it: " + why);
  };
  // The standards' burst lengths: JESD79-4B fixes DDR4 at BL8 (BC4 is not
  // modelled); SDR SDRAM's mode register gives 1, 2, 4 or 8 (full page not modelled).
  const int bl = m.burst_length;
  if (m.type == "ddr4" && bl != 8)
    cannot("memory.burst_length", std::to_string(bl) + " (DDR4 bursts are BL8)");
  if (m.type == "sdr" && bl != 1 && bl != 2 && bl != 4 && bl != 8)
    cannot("memory.burst_length",
           std::to_string(bl) + " (SDR bursts of 1, 2, 4 or 8 are modelled)");
  sdram::DimmConfig c;
  c.geometry = m.geometry;
  c.timing = m.timing;
  c.clock = b.memory_clock().domain();
  c.burst_length = bl;
  try {
    (void)sdram::to_cycles(m.timing, c.clock, bl);
  } catch (const Error& e) {
    cannot("memory.timing", e.what());
  }
  return c;
}

pci::PciConfig pci_config_for_board(const board::Board& b) {
  if (b.host.interface != "pci")
    throw Error("board " + b.name + ": host.interface = \"" + b.host.interface +
                "\"; the bus model is 32/64-bit parallel PCI");
  pci::PciConfig c;
  c.clock = b.host_clock().domain();
  c.bus_bytes = b.host.bus_bits / 8;
  return c;
}

}  // namespace voxcast::rtl
