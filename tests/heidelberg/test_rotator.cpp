// The rotator in double precision (docs/heidelberg.md §2-4): exact identity and
// 90-degree permutations, interpolation weights, perspective, Sobel.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "refmodel/render/heidelberg/rotator.hpp"
#include "tests/heidelberg/fixtures.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

namespace hb = ref::heidelberg;

TEST(HeidelbergRotator, ZeroRotationZoomOneReproducesTheInputExactly) {
  const ref::Volume v = random_volume(6, 8, 5, 1);
  for (auto interp : {ref::HeidelbergInterpolation::Gaussian, ref::HeidelbergInterpolation::Trilinear}) {
    ref::Scene s = heidelberg_scene(6, 8, 5);
    s.heidelberg.interpolation = interp;
    const hb::DensityVolume dv = hb::make_density_volume(s, v);
    const hb::ViewTransform vt = hb::make_view_transform(s.heidelberg, v, hb::view_dims(s, v), 0.0);
    for (int k = 0; k < 5; ++k) {
      const hb::Plane p = hb::rotate_plane(dv, vt, interp, s.heidelberg.gaussian_sigma, k);
      for (int j = 0; j < 8; ++j)
        for (int i = 0; i < 6; ++i) ASSERT_EQ(p.at(i, j), dv.at(i, j, k)) << i << "," << j << "," << k;
    }
  }
}

TEST(HeidelbergRotator, NinetyDegreesAboutZIsThePermutationOfTheClosedForm) {
  // R = Rz(90): p = c + R^T v = (c + v_y, c - v_x, c + v_z), i.e. view voxel
  // (i, j, k) shows data voxel (j, N-1-i, k).
  const int n = 6;
  const ref::Volume v = random_volume(n, n, n, 2);
  ref::Scene s = heidelberg_scene(n, n, n);
  s.heidelberg.angle_deg = 90.0;
  const hb::DensityVolume dv = hb::make_density_volume(s, v);
  const hb::ViewTransform vt = hb::make_view_transform(s.heidelberg, v, hb::view_dims(s, v), 0.0);
  for (int k = 0; k < n; ++k) {
    const hb::Plane p = hb::rotate_plane(dv, vt, s.heidelberg.interpolation, 0.5, k);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) ASSERT_EQ(p.at(i, j), dv.at(j, n - 1 - i, k));
  }
}

TEST(HeidelbergRotator, MultiplesOfNinetyDegreesAboutEachAxisArePermutations) {
  const int n = 4;
  const ref::Volume v = random_volume(n, n, n, 3);
  for (const glm::dvec3 axis : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)})
    for (double angle : {90.0, 180.0, 270.0, -90.0}) {
      ref::Scene s = heidelberg_scene(n, n, n);
      s.heidelberg.axis = axis;
      s.heidelberg.angle_deg = angle;
      const hb::ViewTransform vt = hb::make_view_transform(s.heidelberg, v, hb::view_dims(s, v), 0.0);
      const hb::DensityVolume dv = hb::make_density_volume(s, v);
      std::set<std::array<int, 3>> hit;
      for (int k = 0; k < n; ++k) {
        const hb::Plane p = hb::rotate_plane(dv, vt, s.heidelberg.interpolation, 0.5, k);
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) {
            const glm::dvec3 q = hb::data_position(vt, i, j, k);
            ASSERT_EQ(q, glm::round(q)) << "not on the lattice: axis " << axis.x << axis.y << axis.z;
            const std::array<int, 3> d{static_cast<int>(q.x), static_cast<int>(q.y), static_cast<int>(q.z)};
            ASSERT_EQ(p.at(i, j), dv.at(d[0], d[1], d[2]));
            hit.insert(d);
          }
      }
      EXPECT_EQ(hit.size(), static_cast<std::size_t>(n * n * n)) << "angle " << angle;
      for (const auto& d : hit)
        for (int a = 0; a < 3; ++a) EXPECT_TRUE(d[a] >= 0 && d[a] < n);
    }
}

TEST(HeidelbergRotator, WeightsSumToOneAndTheGaussianInterpolatesAtLatticePoints) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int t = 0; t < 1000; ++t) {
    const glm::dvec3 f(u(rng), u(rng), u(rng));
    double sg = 0, st = 0;
    for (double w : hb::gaussian_weights(f, 0.5)) sg += w;
    for (double w : hb::trilinear_weights(f)) st += w;
    EXPECT_NEAR(sg, 1.0, 1e-14);
    EXPECT_NEAR(st, 1.0, 1e-14);
    // Symmetry of the per-axis pair.
    EXPECT_NEAR(hb::gaussian_axis_weight(f.x, 0.7) + hb::gaussian_axis_weight(1.0 - f.x, 0.7), 1.0, 1e-14);
  }
  EXPECT_EQ(hb::gaussian_weights({0, 0, 0}, 0.5)[0], 1.0);  // footnote 3: distance 1 gets 0
  // Gaussian pair at d = 1/4, sigma 1/2: e^-0.25 / (e^-0.25 + e^-2.25).
  EXPECT_NEAR(hb::gaussian_axis_weight(0.25, 0.5),
              std::exp(-0.25) / (std::exp(-0.25) + std::exp(-2.25)), 1e-15);
}

TEST(HeidelbergRotator, TrilinearIsExactOnALinearRamp) {
  const ref::Volume v = make_volume(8, 8, 8, 8, [](int x, int y, int z) {
    return static_cast<std::uint16_t>(10 + 3 * x + 5 * y + 7 * z);
  });
  ref::Scene s = heidelberg_scene(8, 8, 8);
  const hb::DensityVolume dv = hb::make_density_volume(s, v);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(1.0, 6.0);
  for (int t = 0; t < 200; ++t) {
    const glm::dvec3 p(u(rng), u(rng), u(rng));
    EXPECT_NEAR(hb::resample(dv, p, ref::HeidelbergInterpolation::Trilinear, 0.5),
                (10 + 3 * p.x + 5 * p.y + 7 * p.z) / 255.0, 1e-12);
  }
}

TEST(HeidelbergRotator, PerspectiveScalesEachPlaneByItsDistanceFromTheEye) {
  ref::Scene s = heidelberg_scene(16, 9, 16);
  s.heidelberg.perspective = 20.0;
  const ref::Volume v = random_volume(16, 16, 16, 6);
  const hb::ViewTransform vt = hb::make_view_transform(s.heidelberg, v, hb::view_dims(s, v), 0.0);
  EXPECT_DOUBLE_EQ(hb::plane_scale(vt, 4), 1.0);          // the centre plane
  EXPECT_DOUBLE_EQ(hb::plane_scale(vt, 0), 16.0 / 20.0);  // near: enlarged (samples shrink)
  EXPECT_DOUBLE_EQ(hb::plane_scale(vt, 8), 24.0 / 20.0);  // far: shrunk
  // A pixel column's samples lie on a line through the eye at (c_x, c_y - 20).
  const glm::dvec3 a = hb::data_position(vt, 0, 0, 7), b = hb::data_position(vt, 0, 8, 7);
  const glm::dvec3 eye = vt.volume_center - glm::dvec3(0.0, 20.0, 0.0);
  const glm::dvec3 da = a - eye, db = b - eye;
  EXPECT_NEAR(da.x / da.y, db.x / db.y, 1e-12);
}

TEST(HeidelbergRotator, SobelOfALinearRampIsItsSlope) {
  hb::Plane p(10, 10);
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) p.at(i, j) = 0.2 + 0.03 * i - 0.02 * j;
  const hb::PlaneGradients g = hb::sobel(p, nullptr, nullptr);
  for (int j = 1; j < 9; ++j)
    for (int i = 1; i < 9; ++i) {
      EXPECT_NEAR(g.gx.at(i, j), 0.03, 1e-15);
      EXPECT_NEAR(g.gy.at(i, j), -0.02, 1e-15);
      EXPECT_EQ(g.gz.at(i, j), 0.0);
    }
  // 3D: a ramp along z between the planes.
  hb::Plane lo(10, 10), hi(10, 10);
  for (double& x : lo.v) x = 0.1;
  for (double& x : hi.v) x = 0.3;
  hb::Plane mid(10, 10);
  for (double& x : mid.v) x = 0.2;
  const hb::PlaneGradients g3 = hb::sobel(mid, &lo, &hi);
  EXPECT_NEAR(g3.gz.at(5, 5), 0.1, 1e-15);
  EXPECT_NEAR(g3.gx.at(5, 5), 0.0, 1e-15);
}

}  // namespace
}  // namespace voxcast::test
