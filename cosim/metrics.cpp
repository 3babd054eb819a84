#include "cosim/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "refmodel/error.hpp"

namespace voxcast::cosim {
namespace {

double channel_error_lsb(const ref::QuantImage& test, const ref::Image& truth, std::size_t i,
                         int c) {
  return std::abs(static_cast<double>(test.pixels[i][c]) - truth.pixels[i][c] * test.full_scale());
}

void check_sizes(const ref::QuantImage& test, const ref::Image& truth) {
  if (test.width != truth.width || test.height != truth.height)
    throw Error("cannot compare a " + std::to_string(test.width) + "x" +
                std::to_string(test.height) + " image with a " + std::to_string(truth.width) +
                "x" + std::to_string(truth.height) + " one");
}

}  // namespace

Accuracy measure_accuracy(const ref::QuantImage& test, const ref::Image& truth) {
  check_sizes(test, truth);
  Accuracy a;
  double sum = 0.0, sum_sq = 0.0;
  std::size_t within = 0;
  const std::size_t n = test.pixels.size();
  for (std::size_t i = 0; i < n; ++i) {
    double worst_here = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double e = channel_error_lsb(test, truth, i, c);
      sum += e;
      sum_sq += e * e;
      worst_here = std::max(worst_here, e);
    }
    if (worst_here <= 1.0) ++within;
    if (worst_here > a.max_abs_err_lsb) {
      a.max_abs_err_lsb = worst_here;
      a.worst_x = static_cast<int>(i % static_cast<std::size_t>(test.width));
      a.worst_y = static_cast<int>(i / static_cast<std::size_t>(test.width));
    }
  }
  const double count = 3.0 * static_cast<double>(std::max<std::size_t>(n, 1));
  a.mean_abs_err_lsb = sum / count;
  a.rms_err_lsb = std::sqrt(sum_sq / count);
  a.psnr_db = a.rms_err_lsb > 0.0 ? 20.0 * std::log10(test.full_scale() / a.rms_err_lsb)
                                  : std::numeric_limits<double>::infinity();
  a.pct_within_1lsb = 100.0 * static_cast<double>(within) / static_cast<double>(std::max<std::size_t>(n, 1));
  return a;
}

ref::Image error_heat_map(const ref::QuantImage& test, const ref::Image& truth,
                          double full_scale_lsb) {
  check_sizes(test, truth);
  ref::Image map(test.width, test.height);
  for (std::size_t i = 0; i < test.pixels.size(); ++i) {
    double e = 0.0;
    for (int c = 0; c < 3; ++c) e = std::max(e, channel_error_lsb(test, truth, i, c));
    const double t = std::clamp(e / full_scale_lsb, 0.0, 1.0);
    // black -> red -> yellow -> white
    map.pixels[i] = glm::dvec4(std::clamp(3.0 * t, 0.0, 1.0), std::clamp(3.0 * t - 1.0, 0.0, 1.0),
                               std::clamp(3.0 * t - 2.0, 0.0, 1.0), 1.0);
  }
  return map;
}

}  // namespace voxcast::cosim
