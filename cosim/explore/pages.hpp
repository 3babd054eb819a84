// The report pages (cosim --html, sweep --html): one self-contained HTML file
// per run, beside the images it shows (cosim/reports/html.hpp).
//
// cosim.html: the verdict per engine pair, the images side by side (float,
//   bit-true, hls, the difference heat map, the truth), PSNR/SSIM/LSB against
//   the float and the truth, the error histogram, the first divergence's
//   per-unit trace (hls against bit-true, sample by sample), the cycle model's
//   cycles and stall breakdown, and the resources of the elaborated design.
// sweep.html: each Pareto plot with every point labelled by its configuration
//   and the front marked, and the table of points.
#pragma once

#include <string>

#include "cosim/engines/cosim.hpp"
#include "cosim/explore/sweep_table.hpp"
#include "refmodel/scene/scene.hpp"

namespace voxcast::cosim {

// Reads DIR/report.json (written by run_cosim) for the cycle model's figures.
std::string cosim_page(const ref::Scene& scene, const CosimResult& r, const std::string& out_dir,
                       const std::string& part = "xc7a200t");

std::string sweep_page(const sweep::Table& table);

}  // namespace voxcast::cosim
