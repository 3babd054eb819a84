// The cycle model configured from a board description: the one place where
// the board's clocks and SDRAM datasheet timing enter the model, so the model,
// the generated constraints (cosim/hardware/constraints.hpp) and the board cannot
// disagree (tests/board/ checks all three).
#pragma once

#include "rtl_model/board/board.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/pci/pci_bus.hpp"

namespace voxcast::rtl {

// The baseline RtlConfig (in-order, eager refresh, scan-line, linear layout)
// with each DIMM's geometry, datasheet timing, clock and burst length from the
// board. An SDR board is the VIZARD II card (RayPipeline); a DDR4 board the
// DDR4 card (RtlConfig::card, pipeline/burst_card.hpp: one pipeline by
// default, each channel channel_config_for_board's, the pipelines at the
// board's core clock). Throws voxcast::Error naming the board when the model
// cannot simulate it: memory that is neither SDR SDRAM nor DDR4, an SDR core
// clock other than the memory clock (the model runs that pipeline at the
// SDRAM clock, as VIZARD II did: 2001 paper §2.3), not four DIMMs (both
// layouts interleave the volume over four), or a DDR4 channel without four
// bank groups or that channel_config_for_board refuses.
RtlConfig rtl_config_for_board(const board::Board& board);

// One channel (one DIMM) of the board's memory as the DRAM model runs it
// (`voxcast dram-trace`): geometry, datasheet timing (SDR or DDR4), the
// memory clock and the burst length. Throws voxcast::Error, one line naming
// the board file, the key and the reason, when the model cannot run it: a
// burst length the standard does not have (memory.burst_length), a grade
// not rated for the clock or not convertible (memory.timing).
sdram::DimmConfig channel_config_for_board(const board::Board& board);

// The host bus of the board as the PCI model's configuration: its clock and
// AD width; the per-transaction latencies stay the model's 2001-chipset
// assumptions (pci/pci_bus.hpp). Throws for a PCIe board.
pci::PciConfig pci_config_for_board(const board::Board& board);

// The shipped board behind vizard2_baseline().
inline constexpr const char* kVizard2BoardName = "vizard2_pci";

}  // namespace voxcast::rtl
