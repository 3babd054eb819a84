// The accuracy metrics against closed forms: SSIM (Wang et al. 2004) on images
// whose window statistics are known, and against an independent implementation;
// PSNR and LSB figures of a known error.
#include <gtest/gtest.h>

#include <cmath>

#include "cosim/reports/metrics.hpp"

namespace VOXCAST_UNITY_ID {

using voxcast::cosim::Plane;
using voxcast::cosim::ssim;

constexpr double kL = 255.0;
const double kC1 = (0.01 * kL) * (0.01 * kL), kC2 = (0.03 * kL) * (0.03 * kL);

// A plane with structure everywhere (no two neighbouring windows alike).
Plane textured(int w, int h) {
  Plane p(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) p.at(x, y) = (x * 37 + y * 91 + (x * y) % 17) % 256;
  return p;
}

// The luminance term of SSIM, the whole of it when both windows are constant
// (their variances and covariance vanish, and the structure term is C2/C2 = 1).
double luminance_term(double mx, double my) {
  return (2.0 * mx * my + kC1) / (mx * mx + my * my + kC1);
}

TEST(Ssim, OfAnImageWithItselfIsExactlyOne) {
  const Plane x = textured(31, 17);
  EXPECT_EQ(ssim(x, x, kL), 1.0);
}

TEST(Ssim, ConstantShiftOfAConstantImageIsTheLuminanceTerm) {
  for (double shift : {1.0, 10.0, 30.0, 128.0}) {
    const Plane x(16, 13, 100.0), y(16, 13, 100.0 + shift);
    EXPECT_NEAR(ssim(x, y, kL), luminance_term(100.0, 100.0 + shift), 1e-12) << shift;
  }
}

TEST(Ssim, ContrastChangeOfAConstantImageIsTheLuminanceTerm) {
  for (double gain : {0.25, 0.5, 0.9, 2.0}) {
    const Plane x(12, 12, 80.0), y(12, 12, 80.0 * gain);
    EXPECT_NEAR(ssim(x, y, kL), luminance_term(80.0, 80.0 * gain), 1e-12) << gain;
  }
}

// A checkerboard a +- s: the Gaussian-weighted mean of a window at (u, v) is
// a + (-1)^(u+v) s g with g = (sum_i w_i (-1)^i)^2, and shifting by d leaves the
// variances and covariance equal (structure term 1), so the mean SSIM is the
// mean of the luminance term over the two kinds of window.
TEST(Ssim, ShiftedCheckerboardMatchesTheClosedForm) {
  const double a = 120.0, s = 40.0, d = 25.0;
  Plane x(20, 20), y(20, 20);  // 10 x 10 windows: 50 of each sign
  for (int v = 0; v < 20; ++v)
    for (int u = 0; u < 20; ++u) {
      x.at(u, v) = a + ((u + v) % 2 ? -s : s);
      y.at(u, v) = x.at(u, v) + d;
    }
  double alternating = 0.0, sum = 0.0;
  for (int i = 0; i < 11; ++i) {
    const double w = std::exp(-(i - 5.0) * (i - 5.0) / (2.0 * 1.5 * 1.5));
    sum += w;
    alternating += (i % 2 ? -w : w);
  }
  const double g = (alternating / sum) * (alternating / sum);
  const double expected =
      0.5 * (luminance_term(a + s * g, a + s * g + d) + luminance_term(a - s * g, a - s * g + d));
  EXPECT_NEAR(ssim(x, y, kL), expected, 1e-9);
}

// scikit-image 0.19.3 (Debian python3-skimage), an independent implementation:
//   structural_similarity(x, y, gaussian_weights=True, sigma=1.5,
//                         use_sample_covariance=False, data_range=255)
// with x, y as below (x = textured(23, 19)) gives 0.967115276580253.
TEST(Ssim, EqualsScikitImageOnATexturedPair) {
  const Plane x = textured(23, 19);
  Plane y(23, 19);
  for (int v = 0; v < 19; ++v)
    for (int u = 0; u < 23; ++u) y.at(u, v) = x.at(u, v) * 0.8 + 20 + ((u + 2 * v) % 7) * 3;
  EXPECT_NEAR(ssim(x, y, kL), 0.967115276580253, 1e-12);
}

TEST(Ssim, IsNotDefinedBelowTheWindowSize) {
  const Plane x(10, 40, 5.0);
  EXPECT_TRUE(std::isnan(ssim(x, x, kL)));
}

// Truth all zero; every colour channel of the test 2 LSB: rms = max = 2 LSB,
// PSNR = 20 log10(255 / 2), no pixel within 1 LSB.
TEST(Accuracy, PsnrOfAUniformKnownError) {
  const voxcast::ref::Image truth(16, 16);
  voxcast::ref::QuantImage test(16, 16, 8);
  for (auto& p : test.pixels) p = {2, 2, 2, 255};
  const voxcast::cosim::Accuracy a = voxcast::cosim::measure_accuracy(test, truth);
  EXPECT_DOUBLE_EQ(a.rms_err_lsb, 2.0);
  EXPECT_DOUBLE_EQ(a.max_abs_err_lsb, 2.0);
  EXPECT_DOUBLE_EQ(a.psnr_db, 20.0 * std::log10(255.0 / 2.0));
  EXPECT_EQ(a.pct_within_1lsb, 0.0);
}

// Half the pixels off by 1 LSB in one channel: rms = sqrt(8 / (3 * 16)),
// every pixel within 1 LSB; the worst pixel is the first one off.
TEST(Accuracy, PsnrOfASparseKnownError) {
  const voxcast::ref::Image truth(4, 4);
  voxcast::ref::QuantImage test(4, 4, 8);
  for (std::size_t i = 1; i < test.pixels.size(); i += 2) test.pixels[i][1] = 1;
  const voxcast::cosim::Accuracy a = voxcast::cosim::measure_accuracy(test, truth);
  const double rms = std::sqrt(8.0 / 48.0);
  EXPECT_NEAR(a.rms_err_lsb, rms, 1e-15);
  EXPECT_NEAR(a.psnr_db, 20.0 * std::log10(255.0 / rms), 1e-12);
  EXPECT_EQ(a.pct_within_1lsb, 100.0);
  EXPECT_EQ(a.worst_x, 1);
  EXPECT_EQ(a.worst_y, 0);
}

TEST(Accuracy, QuantizeRoundsEachChannelToTheNearestLevel) {
  voxcast::ref::Image img(3, 1);
  img.pixels[0] = {0.0, 1.0, 0.5, 1.0};
  img.pixels[1] = {0.499 / 255.0, 0.501 / 255.0, 254.4 / 255.0, 0.0};
  img.pixels[2] = {-0.1, 1.1, 100.0 / 255.0, 0.25};
  const voxcast::ref::QuantImage q = voxcast::cosim::quantize(img, 8);
  EXPECT_EQ(q.pixels[0], (std::array<std::uint32_t, 4>{0, 255, 128, 255}));
  EXPECT_EQ(q.pixels[1], (std::array<std::uint32_t, 4>{0, 1, 254, 0}));
  EXPECT_EQ(q.pixels[2], (std::array<std::uint32_t, 4>{0, 255, 100, 64}));
}

}  // namespace
