// The rtl engine on a DDR4 board (RtlConfig::card.enabled): the frame through
// BurstCard (pipeline/burst_card.hpp) with the burst layout the U250 study
// chose, 4x2x2-skewed-blocks (docs/sdram.md §9).
#pragma once

#include "refmodel/bittrue/frame_setup.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/layout/burst_layout.hpp"

namespace voxcast::rtl {

// The card's burst layout for a volume of `dims` and voxels of `voxel_bytes`
// (4: 16 voxels in a 4x2x2 brick; 8: 2x2x2; 16: 2x2x1) on the channel `dimm`.
// Throws voxcast::Error if the volume does not fit a channel.
layout::BurstLayout card_burst_layout(const std::array<int, 3>& dims, int voxel_bytes,
                                      const sdram::DimmConfig& dimm);

// One frame. Throws voxcast::Error as rtl_render.
RtlResult render_ddr4_card(const bittrue::FrameSetup& setup, const bittrue::VoxelMemory& memory,
                           const RtlConfig& config);

}  // namespace voxcast::rtl
