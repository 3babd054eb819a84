// Accuracy of a quantized image against the float truth, in output LSBs.
//
// The truth's channel x in [0, 1] is worth x * (2^bits - 1) LSBs; a quantized
// channel q differs from it by |q - x (2^bits - 1)|. Figures are over the three
// colour channels (premultiplied, the volume alone).
#pragma once

#include <cstdint>

#include <cstddef>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "refmodel/render/image.hpp"
#include "refmodel/render/quant_image.hpp"

namespace voxcast::cosim {

struct Accuracy {
  double max_abs_err_lsb = 0.0;
  double mean_abs_err_lsb = 0.0;
  double rms_err_lsb = 0.0;
  double psnr_db = 0.0;          // 20 log10(peak / rms); +inf when rms = 0
  double pct_within_1lsb = 0.0;  // pixels whose three channels are all within 1 LSB
  double ssim = 0.0;             // mean SSIM of the three channels; NaN if smaller than 11x11
  int worst_x = -1, worst_y = -1;
};

Accuracy measure_accuracy(const ref::QuantImage& test, const ref::Image& truth);

// The figures as the reports' JSON gives them: psnr_db ("inf" when exact),
// the LSB errors, pct_within_1lsb, ssim (null when undefined) and worst_pixel.
nlohmann::json accuracy_json(const Accuracy& a);

// How many pixels have their worst channel's error (as measure_accuracy
// measures it, in LSBs) in each bin: exactly 0, at most 1, 2, 4, 8, 16, and
// more than 16. The bins sum to the pixel count; bin 0 plus bin 1 is
// measure_accuracy's pct_within_1lsb share.
struct ErrorHistogram {
  static constexpr int kBins = 7;
  static constexpr double kUpper[kBins - 1] = {0.0, 1.0, 2.0, 4.0, 8.0, 16.0};
  static const char* label(int bin);  // "0", "<=1", "<=2", ..., ">16"
  std::uint64_t count[kBins] = {};
};
ErrorHistogram error_histogram(const ref::QuantImage& test, const ref::Image& truth);

// --- SSIM (Wang, Bovik, Sheikh & Simoncelli, IEEE Trans. Image Processing 13(4),
// 2004, eq. 13 and section III-C) ---------------------------------------------
// One channel as numbers on the output's scale (LSBs, 0 .. 2^bits - 1), row-major.
struct Plane {
  int width = 0, height = 0;
  std::vector<double> v;
  Plane() = default;
  Plane(int w, int h, double fill = 0.0)
      : width(w), height(h), v(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), fill) {}
  double& at(int x, int y) { return v[static_cast<std::size_t>(y) * width + x]; }
  double at(int x, int y) const { return v[static_cast<std::size_t>(y) * width + x]; }
};

// The paper's constants: an 11x11 circular-symmetric Gaussian window of
// standard deviation 1.5 (normalised to sum 1), K1 = 0.01, K2 = 0.03.
struct SsimParams {
  int window = 11;
  double sigma = 1.5;
  double k1 = 0.01, k2 = 0.03;
};

// Mean SSIM over every window position that lies wholly inside the image (the
// paper's MATLAB "valid" filtering), with C1 = (K1 L)^2, C2 = (K2 L)^2 and
// L = dynamic_range:
//   SSIM = (2 mx my + C1)(2 sxy + C2) / ((mx^2 + my^2 + C1)(sx^2 + sy^2 + C2)),
// m, s^2 and sxy the window-weighted means, variances and covariance
// (docs/accuracy.md). NaN when the image is smaller than the window.
double ssim(const Plane& x, const Plane& y, double dynamic_range, const SsimParams& p = {});

// A quantized image's colour channel c as a Plane, and the truth's channel c on
// the same scale (x * (2^bits - 1)).
Plane channel_plane(const ref::QuantImage& img, int c);
Plane channel_plane(const ref::Image& img, int c, double full_scale);

// The double image as an ideal card would output it: each channel rounded to
// the nearest of `bits` bits (for measuring the float reference's own sampling
// error on the same scale as the design's).
ref::QuantImage quantize(const ref::Image& img, int bits);

// Heat map of the largest channel error per pixel: black = 0, through red and
// yellow to white at `full_scale_lsb` LSBs and above.
ref::Image error_heat_map(const ref::QuantImage& test, const ref::Image& truth,
                          double full_scale_lsb);

}  // namespace voxcast::cosim
