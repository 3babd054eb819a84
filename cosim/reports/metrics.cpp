#include "cosim/reports/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

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
  double ssim_sum = 0.0;
  for (int c = 0; c < 3; ++c)
    ssim_sum += ssim(channel_plane(test, c), channel_plane(truth, c, test.full_scale()),
                     test.full_scale());
  a.ssim = ssim_sum / 3.0;
  return a;
}

const char* ErrorHistogram::label(int bin) {
  static const char* names[kBins] = {"0", "<=1", "<=2", "<=4", "<=8", "<=16", ">16"};
  return names[bin];
}

ErrorHistogram error_histogram(const ref::QuantImage& test, const ref::Image& truth) {
  check_sizes(test, truth);
  ErrorHistogram h;
  for (std::size_t i = 0; i < test.pixels.size(); ++i) {
    double worst = 0.0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, channel_error_lsb(test, truth, i, c));
    int bin = 0;
    while (bin < ErrorHistogram::kBins - 1 && worst > ErrorHistogram::kUpper[bin]) ++bin;
    ++h.count[bin];
  }
  return h;
}

namespace {

// The normalised 1-D Gaussian; the 2-D window is its outer product, which is
// the paper's window normalised to sum 1 (exp separates in x and y).
std::vector<double> gaussian_1d(const SsimParams& p) {
  std::vector<double> w(static_cast<std::size_t>(p.window));
  const double centre = 0.5 * (p.window - 1);
  double sum = 0.0;
  for (int i = 0; i < p.window; ++i) {
    const double d = i - centre;
    w[static_cast<std::size_t>(i)] = std::exp(-d * d / (2.0 * p.sigma * p.sigma));
    sum += w[static_cast<std::size_t>(i)];
  }
  for (double& v : w) v /= sum;
  return w;
}

// Window-weighted mean of `in` at every window position wholly inside it
// (rows first, then columns).
Plane filter_valid(const Plane& in, const std::vector<double>& w) {
  const int k = static_cast<int>(w.size());
  const int ow = in.width - k + 1, oh = in.height - k + 1;
  Plane rows(ow, in.height);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0.0;
      for (int i = 0; i < k; ++i) s += w[static_cast<std::size_t>(i)] * in.at(x + i, y);
      rows.at(x, y) = s;
    }
  Plane out(ow, oh);
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0.0;
      for (int i = 0; i < k; ++i) s += w[static_cast<std::size_t>(i)] * rows.at(x, y + i);
      out.at(x, y) = s;
    }
  return out;
}

Plane product(const Plane& a, const Plane& b) {
  Plane p(a.width, a.height);
  for (std::size_t i = 0; i < p.v.size(); ++i) p.v[i] = a.v[i] * b.v[i];
  return p;
}

}  // namespace

double ssim(const Plane& x, const Plane& y, double dynamic_range, const SsimParams& p) {
  if (x.width != y.width || x.height != y.height)
    throw Error("SSIM: cannot compare a " + std::to_string(x.width) + "x" +
                std::to_string(x.height) + " plane with a " + std::to_string(y.width) + "x" +
                std::to_string(y.height) + " one");
  if (x.width < p.window || x.height < p.window) return std::numeric_limits<double>::quiet_NaN();
  const std::vector<double> w = gaussian_1d(p);
  const Plane mx = filter_valid(x, w), my = filter_valid(y, w);
  const Plane exx = filter_valid(product(x, x), w), eyy = filter_valid(product(y, y), w),
              exy = filter_valid(product(x, y), w);
  const double c1 = (p.k1 * dynamic_range) * (p.k1 * dynamic_range);
  const double c2 = (p.k2 * dynamic_range) * (p.k2 * dynamic_range);
  double sum = 0.0;
  for (std::size_t i = 0; i < mx.v.size(); ++i) {
    const double ux = mx.v[i], uy = my.v[i];
    const double sxx = exx.v[i] - ux * ux, syy = eyy.v[i] - uy * uy, sxy = exy.v[i] - ux * uy;
    sum += ((2.0 * ux * uy + c1) * (2.0 * sxy + c2)) /
           ((ux * ux + uy * uy + c1) * (sxx + syy + c2));
  }
  return sum / static_cast<double>(mx.v.size());
}

Plane channel_plane(const ref::QuantImage& img, int c) {
  Plane p(img.width, img.height);
  for (std::size_t i = 0; i < p.v.size(); ++i) p.v[i] = static_cast<double>(img.pixels[i][c]);
  return p;
}

Plane channel_plane(const ref::Image& img, int c, double full_scale) {
  Plane p(img.width, img.height);
  for (std::size_t i = 0; i < p.v.size(); ++i) p.v[i] = img.pixels[i][c] * full_scale;
  return p;
}

ref::QuantImage quantize(const ref::Image& img, int bits) {
  ref::QuantImage q(img.width, img.height, bits);
  const double fs = q.full_scale();
  for (std::size_t i = 0; i < q.pixels.size(); ++i)
    for (int c = 0; c < 4; ++c)
      q.pixels[i][static_cast<std::size_t>(c)] =
          static_cast<std::uint32_t>(std::lround(std::clamp(img.pixels[i][c], 0.0, 1.0) * fs));
  return q;
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

nlohmann::json accuracy_json(const Accuracy& a) {
  return {{"psnr_db", std::isfinite(a.psnr_db) ? nlohmann::json(a.psnr_db) : nlohmann::json("inf")},
          {"max_abs_err_lsb", a.max_abs_err_lsb},
          {"mean_abs_err_lsb", a.mean_abs_err_lsb},
          {"rms_err_lsb", a.rms_err_lsb},
          {"pct_within_1lsb", a.pct_within_1lsb},
          {"ssim", std::isnan(a.ssim) ? nlohmann::json(nullptr) : nlohmann::json(a.ssim)},
          {"worst_pixel", {a.worst_x, a.worst_y}}};
}

}  // namespace voxcast::cosim
