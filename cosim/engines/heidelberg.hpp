// VIRIM's path through the harness (render.algorithm = "heidelberg";
// docs/heidelberg.md §8): the hls kernels of hls/virim/ on the host, and the
// render and cosim commands for Heidelberg scenes; the rtl engine is VIRIM's
// cycle model (rtl_model/virim/, docs/virim-rtl.md).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "cosim/engines/render.hpp"
#include "cosim/engines/cosim.hpp"
#include "hls/virim/parity_memory.hpp"
#include "refmodel/bittrue/heidelberg.hpp"
#include "rtl_model/virim/stats.hpp"

namespace voxcast::cosim {

bool hls_supports_heidelberg(const HeidelbergProfile& p);

// Renders with the hls kernels, lines in parallel (each line resets the
// memory's suppression state, so the image and the counts do not depend on
// the thread count); `stats` sums the parity memory's counters.
ref::QuantImage hls_render_heidelberg(const bittrue::VirimSetup& setup,
                                      const bittrue::VirimMemory& memory, int threads = 0,
                                      hls::virim::MemoryStats* stats = nullptr);

// The rtl engine's figures as report.json holds them ("rtl").
nlohmann::json virim_rtl_json(const ref::Scene& scene, const rtl::virim::VirimRtlStats& stats);
// Throws voxcast::Error naming the first pixel where the two images differ.
void check_rtl_matches_hls(const ref::QuantImage& rtl_image, const ref::QuantImage& hls_image);

RenderSummary run_render_heidelberg(const ref::Scene& scene, const RenderOptions& options);
// strict: refuse a scene with precision hazards (cosim/engines/warnings.hpp).
CosimResult run_cosim_heidelberg(const ref::Scene& scene, const std::string& out_dir,
                                 bool strict = false);
void print_cosim_summary_heidelberg(std::ostream& os, const ref::Scene& scene,
                                    const CosimResult& r);

}  // namespace voxcast::cosim
