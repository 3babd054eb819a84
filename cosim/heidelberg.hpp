// VIRIM's path through the harness (render.algorithm = "heidelberg";
// docs/heidelberg.md §8): the hls kernels of hls/virim/ on the host, and the
// render and cosim commands for Heidelberg scenes. The rtl cycle model does
// not cover this path yet.
#pragma once

#include <string>

#include "cosim/commands.hpp"
#include "cosim/cosim.hpp"
#include "hls/virim/parity_memory.hpp"
#include "refmodel/bittrue/heidelberg.hpp"

namespace voxcast::cosim {

bool hls_supports_heidelberg(const HeidelbergProfile& p);

// Renders with the hls kernels, lines in parallel (each line resets the
// memory's suppression state, so the image and the counts do not depend on
// the thread count); `stats` sums the parity memory's counters.
ref::QuantImage hls_render_heidelberg(const bittrue::VirimSetup& setup,
                                      const bittrue::VirimMemory& memory, int threads = 0,
                                      hls::virim::MemoryStats* stats = nullptr);

RenderSummary run_render_heidelberg(const ref::Scene& scene, const RenderOptions& options);
CosimResult run_cosim_heidelberg(const ref::Scene& scene, const std::string& out_dir);
void print_cosim_summary_heidelberg(std::ostream& os, const ref::Scene& scene,
                                    const CosimResult& r);

}  // namespace voxcast::cosim
