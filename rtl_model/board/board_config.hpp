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
// board. Throws voxcast::Error naming the board when the model cannot
// simulate it: memory that is not SDR SDRAM (the Dimm is an SDR device), or a
// core clock other than the memory clock (the model runs the pipeline at the
// SDRAM clock, as VIZARD II did: 2001 paper §2.3), or not four DIMMs (the
// VIZARD II layout interleaves the volume over four).
RtlConfig rtl_config_for_board(const board::Board& board);

// The host bus of the board as the PCI model's configuration: its clock and
// AD width; the per-transaction latencies stay the model's 2001-chipset
// assumptions (pci/pci_bus.hpp). Throws for a PCIe board.
pci::PciConfig pci_config_for_board(const board::Board& board);

// The shipped board behind vizard2_baseline().
inline constexpr const char* kVizard2BoardName = "vizard2_pci";

}  // namespace voxcast::rtl
