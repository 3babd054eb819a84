// The Heidelberg model in double precision (docs/heidelberg.md §5): a
// homogeneous slab attenuates both lights by the known factors, a plane at a
// known angle gives the Phong values of its normal, background identification
// and stereo parallax.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "refmodel/render/heidelberg/heidelberg.hpp"
#include "refmodel/render/heidelberg/rotator.hpp"
#include "refmodel/render/heidelberg/slice_model.hpp"
#include "tests/heidelberg/fixtures.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

namespace hb = ref::heidelberg;

// Self-luminosity only (weight 1): a voxel sends (E0 + E45)/2 towards the
// viewer, so the line's value follows the two lights' intensities in closed form.
hb::SliceParams luminosity_only(double light) {
  hb::SliceParams s;
  s.light = light;
  s.diffuse_0 = s.diffuse_45 = s.specular_45 = 0.0;
  s.luminosity = 1.0;
  return s;
}

TEST(HeidelbergSlice, HomogeneousSlabAttenuatesBothLightsByTheKnownFactors) {
  const int W = 40, D = 12;
  const double r = 0.15, L = 0.8;
  std::vector<double> rho(W * D, r), zero(W * D, 0.0);
  const hb::Line line = hb::trace_slice(luminosity_only(L), W, D, rho.data(), zero.data(), zero.data(), nullptr);
  const double t = 1.0 - r;
  for (int x = 0; x < W; ++x) {
    // 0 deg light: (1 - rho)^D through the slab; it is also the way back.
    EXPECT_NEAR(line.transmitted[static_cast<std::size_t>(x)], std::pow(t, D), 1e-14);
    // 45 deg light at (x, j): (1 - rho)^min(j, x) (it enters at the front, or
    // at the side x = 0 after x voxels).
    double expect = 0.0;
    for (int j = 0; j < D; ++j) {
      const double i0 = L * std::pow(t, j), i45 = L * std::pow(t, std::min(j, x));
      expect += 0.5 * (i0 + i45) * r * std::pow(t, j);
    }
    EXPECT_NEAR(line.value[static_cast<std::size_t>(x)], expect, 1e-14) << "x = " << x;
  }
  // Far from the side both lights have the same factor: the closed sum.
  const double far = L * r * (1.0 - std::pow(t, 2 * D)) / (1.0 - t * t);
  EXPECT_NEAR(line.value[W - 1], far, 1e-14);
}

TEST(HeidelbergSlice, BackgroundIsWhereTheLightLeavingTheFarEndExceedsTheThreshold) {
  const int W = 3, D = 10;
  std::vector<double> rho(W * D, 0.0), zero(W * D, 0.0);
  for (int j = 0; j < D; ++j) rho[static_cast<std::size_t>(j * W + 1)] = 0.01;  // column 1: 0.99^10
  for (int j = 0; j < D; ++j) rho[static_cast<std::size_t>(j * W + 2)] = 0.5;
  hb::SliceParams s = luminosity_only(1.0);
  s.background_threshold = 0.9;
  const hb::Line line = hb::trace_slice(s, W, D, rho.data(), zero.data(), zero.data(), nullptr);
  EXPECT_EQ(line.background[0], 1);  // empty column
  EXPECT_EQ(line.background[1], std::pow(0.99, 10) > 0.9 ? 1 : 0);
  EXPECT_EQ(line.background[2], 0);
}

TEST(HeidelbergSlice, APlaneAtAKnownAngleGivesThePhongValuesOfItsNormal) {
  // Density rising along the direction a = (sin θ, cos θ) (into the object):
  // the outward normal n = -a is θ from the viewer's direction, so
  // n·L0 = cos θ, n·L45 = cos(45° - θ), and the 45 deg light's reflection is
  // 2θ - 45° from the viewer: R·V = cos(2θ - 45°).
  for (double deg : {0.0, 10.0, 30.0, 60.0}) {
    const double th = deg * std::numbers::pi / 180.0;
    const double ax = std::sin(th), ay = std::cos(th);
    hb::Plane p(12, 12);
    for (int j = 0; j < 12; ++j)
      for (int i = 0; i < 12; ++i) p.at(i, j) = 0.5 + 0.02 * (ax * i + ay * j);
    const hb::PlaneGradients g = hb::sobel(p, nullptr, nullptr);
    const hb::PhongFactors ph = hb::phong_factors(g.gx.at(6, 6), g.gy.at(6, 6), 0.0);
    EXPECT_NEAR(ph.c0, std::cos(th), 1e-12) << deg;
    EXPECT_NEAR(ph.c45, std::cos(std::numbers::pi / 4 - th), 1e-12) << deg;
    EXPECT_NEAR(ph.rv, std::cos(2 * th - std::numbers::pi / 4), 1e-12) << deg;
    EXPECT_NEAR(ph.surface, 0.04, 1e-12);  // min(1, 2|g|), |g| = 0.02
    // What a voxel of that plane scatters, term by term.
    hb::SliceParams s;
    s.diffuse_0 = 0.3, s.diffuse_45 = 0.2, s.specular_45 = 0.7, s.luminosity = 0.1;
    s.shininess = 4;
    const double i0 = 0.9, i45 = 0.6, rho = 0.5;
    const double expect = i0 * rho * 0.3 * std::max(0.0, std::cos(th)) +
                          i45 * rho * (0.2 * std::max(0.0, std::cos(std::numbers::pi / 4 - th)) +
                                       0.7 * std::pow(std::max(0.0, std::cos(2 * th - std::numbers::pi / 4)), 4) * 0.04) +
                          0.1 * 0.5 * (i0 + i45) * rho;
    EXPECT_NEAR(hb::scattered(s, i0, i45, rho, ph), expect, 1e-12) << deg;
  }
}

TEST(HeidelbergSlice, ScatteredLightNeverExceedsTheAbsorbedEnergy) {
  hb::SliceParams s;
  s.diffuse_0 = s.diffuse_45 = s.specular_45 = s.luminosity = 1.0;
  s.shininess = 1;
  const hb::PhongFactors ph = hb::phong_factors(0.2, 0.2, 0.0);  // facing both lights
  EXPECT_DOUBLE_EQ(hb::scattered(s, 1.0, 1.0, 0.4, ph), 0.8);
}

TEST(HeidelbergStereo, TwoEyesFourDegreesApartShowTheParallaxOfAPointAtKnownDepth) {
  // A small ball at depth d behind the cube's centre: each eye turns the cube
  // by ±2° about the view's z axis, moving its image by -d sin(±2°).
  const int n = 64;
  const double d = 20.0;
  const glm::dvec3 c(31.5, 31.5 + d, 31.5);
  const ref::Volume v = make_volume(n, n, n, 8, [&](int x, int y, int z) {
    // A faint, smooth ball (densities below 0.04): the lights barely change
    // inside it, so its image is symmetric about its projection.
    const double r2 = (x - c.x) * (x - c.x) + (y - c.y) * (y - c.y) + (z - c.z) * (z - c.z);
    return static_cast<std::uint16_t>(std::lround(10.0 * std::exp(-r2 / 8.0)));
  });
  ref::Scene s = heidelberg_scene(n, n, n);
  s.heidelberg.diffuse_0 = s.heidelberg.diffuse_45 = s.heidelberg.specular_45 = 0.0;
  s.heidelberg.luminosity = 1.0;  // isotropic: the image of the ball is symmetric
  s.heidelberg.background_threshold = 1.0;  // no background cut on the pixel grid
  s.heidelberg.stereo_deg = 4.0;
  s.heidelberg.interpolation = ref::HeidelbergInterpolation::Trilinear;
  const std::vector<double> eyes = hb::eye_offsets(s.heidelberg);
  ASSERT_EQ(eyes.size(), 2u);
  double cx[2];
  for (int e = 0; e < 2; ++e) {
    const ref::Image img = hb::render(s, v, eyes[static_cast<std::size_t>(e)], 1);
    double sum = 0, sx = 0;
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        sum += img.at(x, y).r;
        sx += img.at(x, y).r * x;
      }
    ASSERT_GT(sum, 0.0);
    cx[e] = sx / sum - 0.5 * (n - 1);
  }
  const double s2 = std::sin(2.0 * std::numbers::pi / 180.0);
  EXPECT_NEAR(cx[0], d * s2, 0.1);
  EXPECT_NEAR(cx[1], -d * s2, 0.1);
  EXPECT_NEAR(cx[0] - cx[1], 2.0 * d * s2, 0.05);  // 1.40 pixels
}

}  // namespace
}  // namespace voxcast::test
