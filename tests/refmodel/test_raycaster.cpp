// Closed-form tests of the double-precision ray caster (the ground truth).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render_fixtures.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

// --- Opacity correction: the result does not depend on the sampling rate ---------

class ConstantSlab : public ::testing::TestWithParam<double> {};

TEST_P(ConstantSlab, CentrePixelOpacityIsTheClosedForm) {
  const double oversampling = GetParam();
  const double alpha = 0.05;
  const ref::Volume v = constant_volume(32, 100);
  ref::Scene s = constant_alpha_scene(alpha);
  s.render.width = s.render.height = 33;  // odd: the centre pixel's ray is the axis
  s.render.oversampling = oversampling;
  s.camera.height = 40.0;
  s.camera.pose = {{15.5, -20.0, 15.5}, {15.5, 15.5, 15.5}, {0.0, 0.0, 1.0}};

  const OneRay r = cast_pixel(s, v, 16, 16);
  const double step = 1.0 / oversampling;
  const double n = static_cast<double>(r.stats.samples);
  // render.partial_segments (the default): the last sample weighs by its
  // fractional segment, so the opacity is that of the chord itself, 31 voxels,
  // at every sampling rate (docs/pipeline.md §7a).
  EXPECT_NEAR(r.rgba.a, 1.0 - std::pow(1.0 - alpha, 31.0), 1e-9);
  // The chord through the voxel-centre box is 31 voxels long; the n samples of
  // `step` cover it to within one step.
  EXPECT_NEAR(r.segment.length(), 31.0, 1e-12);
  EXPECT_GE(n * step, 31.0);
  EXPECT_LE(n * step, 31.0 + step + 1e-12);
  // Premultiplied white: colour equals opacity.
  EXPECT_NEAR(r.rgba.r, r.rgba.a, 1e-12);
}

TEST_P(ConstantSlab, ObliquePerspectiveRayMatchesItsChord) {
  const double oversampling = GetParam();
  const double alpha = 0.02;
  const ref::Volume v = constant_volume(24, 100);
  ref::Scene s = constant_alpha_scene(alpha);
  s.camera.projection = ref::Projection::Perspective;
  s.camera.fov_deg = 30.0;
  s.render.width = s.render.height = 9;
  s.render.oversampling = oversampling;
  s.camera.pose = {{-10.0, -13.0, 30.0}, {11.5, 11.5, 11.5}, {0.0, 0.0, 1.0}};

  for (int py : {2, 4, 6}) {
    const OneRay r = cast_pixel(s, v, 3, py);
    ASSERT_TRUE(r.stats.hit);
    const double step = 1.0 / oversampling;
    const double n = static_cast<double>(r.stats.samples);
    // Partial segments (the default): the chord's own opacity at any rate.
    EXPECT_NEAR(r.rgba.a, 1.0 - std::pow(1.0 - alpha, r.segment.length()), 1e-9);
    EXPECT_GE(n * step, r.segment.length());
    EXPECT_LE(n * step, r.segment.length() + step + 1e-12);
  }
}

INSTANTIATE_TEST_SUITE_P(Oversampling, ConstantSlab, ::testing::Values(0.5, 1.0, 2.0, 4.0, 8.0));

TEST(OpacityCorrection, SplittingAStepDoesNotChangeOpacity) {
  // Two half steps transmit exactly what one whole step does.
  for (double a : {0.0, 0.01, 0.3, 0.9, 0.999}) {
    const double whole = ref::opacity_correct(a, 1.0);
    const double half = ref::opacity_correct(a, 0.5);
    EXPECT_NEAR(1.0 - whole, (1.0 - half) * (1.0 - half), 1e-15) << "alpha " << a;
  }
  EXPECT_EQ(ref::opacity_correct(1.0, 0.25), 1.0);
  EXPECT_EQ(ref::opacity_correct(0.0, 4.0), 0.0);
}

// --- Box phantom: the silhouette is the projection of the box ---------------------

TEST(BoxPhantom, SilhouetteLandsOnThePredictedPixels) {
  const int n = 32;
  const ref::Volume v = ref::make_phantom("box", n);
  const int lo = n / 4, hi = n - 1 - n / 4;
  ref::Scene s = constant_alpha_scene(1.0);
  // Binary classification: opaque from value 100 up. Between a box voxel (200)
  // and an empty one (0) the interpolated value crosses 100 half-way, so on
  // rays through voxel centres the opaque set is exactly the box's columns.
  s.tf_points = {ref::TfPoint{0.0, {0, 0, 0}, 0.0}, ref::TfPoint{100.0, {1, 1, 1}, 1.0}};
  s.tf_interpolation = ref::TfInterpolation::Binary;
  s.render.width = s.render.height = n;
  s.camera.height = n;
  const double c = (n - 1) / 2.0;
  // Looking along +z with up = +y: image right is -x, so pixel (px, py) is the
  // column through voxel centre (n-1-px, n-1-py).
  s.camera.pose = {{c, c, -5.0}, {c, c, c}, {0.0, 1.0, 0.0}};
  const ref::GradientField g = ref::compute_gradients(v, s.volume.gradient);
  const ref::Image img = ref::render_image(ref::make_render_inputs(s, v, g, s.camera.pose), 2);
  int opaque = 0;
  for (int py = 0; py < n; ++py)
    for (int px = 0; px < n; ++px) {
      const int x = n - 1 - px, y = n - 1 - py;
      const bool inside = x >= lo && x <= hi && y >= lo && y <= hi;
      EXPECT_EQ(img.at(px, py).a, inside ? 1.0 : 0.0) << "pixel " << px << "," << py;
      opaque += inside;
    }
  EXPECT_EQ(opaque, (hi - lo + 1) * (hi - lo + 1));
}

// --- Trilinear interpolation is exact on a linear ramp ---------------------------

TEST(Interpolation, ExactOnALinearRamp) {
  const auto ramp = [](double x, double y, double z) { return 3.0 + 2.0 * x + 5.0 * y + 7.0 * z; };
  const ref::Volume v = make_volume(9, 7, 5, 8, [&](int x, int y, int z) {
    return static_cast<std::uint16_t>(ramp(x, y, z));
  });
  const ref::GradientField g = ref::compute_gradients(v, ref::GradientOperator::Central);
  std::mt19937_64 rng(20011994);
  std::uniform_real_distribution<double> ux(0.0, 8.0), uy(0.0, 6.0), uz(0.0, 4.0);
  for (int i = 0; i < 2000; ++i) {
    const ref::Vec3 p{ux(rng), uy(rng), uz(rng)};
    const ref::Sample s = ref::interpolate(v, g, p);
    EXPECT_NEAR(s.value, ramp(p.x, p.y, p.z), 1e-9) << p.x << "," << p.y << "," << p.z;
  }
  // Interior gradients of a ramp are its slopes, exactly.
  const ref::Sample s = ref::interpolate(v, g, {4.25, 3.5, 2.75});
  EXPECT_EQ(s.gradient, ref::Vec3(2.0, 5.0, 7.0));
  // Grid corners and the far faces are exact as well.
  EXPECT_NEAR(ref::interpolate(v, g, {8.0, 6.0, 4.0}).value, ramp(8, 6, 4), 1e-12);
  EXPECT_NEAR(ref::interpolate(v, g, {0.0, 0.0, 0.0}).value, ramp(0, 0, 0), 1e-12);
}

TEST(Interpolation, SingleVoxelAxesAreHandled) {
  const ref::Volume v = make_volume(1, 1, 1, 8, [](int, int, int) { return std::uint16_t{77}; });
  const ref::GradientField g = ref::compute_gradients(v, ref::GradientOperator::Sobel);
  const ref::Sample s = ref::interpolate(v, g, {0.0, 0.0, 0.0});
  EXPECT_EQ(s.value, 77.0);
  EXPECT_EQ(s.gradient, ref::Vec3(0.0));
}

TEST(Gradients, SobelOfARampIsTheSlope) {
  const ref::Volume v = make_volume(6, 6, 6, 8, [](int x, int y, int z) {
    return static_cast<std::uint16_t>(10 + 3 * x + 4 * y + 5 * z);
  });
  const ref::GradientField g = ref::compute_gradients(v, ref::GradientOperator::Sobel);
  EXPECT_EQ(glm::dvec3(g.at(v.index(2, 3, 3))), ref::Vec3(3.0, 4.0, 5.0));
}

// --- MIP along axis-aligned rays is the column maximum ---------------------------

TEST(Mip, AxisAlignedRaysReturnTheColumnMaximum) {
  const int n = 16;
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> val(0, 255);
  const ref::Volume v = make_volume(n, n, n, 8, [&](int, int, int) {
    return static_cast<std::uint16_t>(val(rng));
  });
  ref::Scene s = constant_alpha_scene(0.0);
  s.render.mode = ref::RenderMode::Mip;
  s.render.width = s.render.height = n;
  s.camera.height = n;
  const double c = (n - 1) / 2.0;
  s.camera.pose = {{c, c, -3.0}, {c, c, c}, {0.0, 1.0, 0.0}};
  const ref::GradientField g = ref::compute_gradients(v, s.volume.gradient);
  const ref::Image img = ref::render_image(ref::make_render_inputs(s, v, g, s.camera.pose), 2);
  for (int py = 0; py < n; ++py)
    for (int px = 0; px < n; ++px) {
      const int x = n - 1 - px, y = n - 1 - py;
      int peak = 0;
      for (int z = 0; z < n; ++z) peak = std::max<int>(peak, v.at(x, y, z));
      EXPECT_DOUBLE_EQ(img.at(px, py).r, peak / 255.0) << px << "," << py;
    }
}

// --- Early ray termination ----------------------------------------------------------

TEST(EarlyRayTermination, DiffersFromNoErtByAtMostTheResidualTransparency) {
  const ref::Volume v = ref::make_phantom("shells", 48);
  ref::Scene s;
  s.tf_points = {{0.0, {0, 0, 0}, 0.0}, {70.0, {1.0, 0.5, 0.2}, 0.3}, {240.0, {0.2, 0.6, 1.0}, 0.9}};
  s.camera.pose = {{23.5, -60.0, 40.0}, {23.5, 23.5, 23.5}, {0, 0, 1}};
  s.render.width = s.render.height = 40;
  s.lights = {ref::Light{}};
  const ref::GradientField g = ref::compute_gradients(v, s.volume.gradient);
  const ref::Image with_ert = ref::render_image(ref::make_render_inputs(s, v, g, s.camera.pose), 2);
  s.render.ert_threshold = 1.0;
  const ref::Image without = ref::render_image(ref::make_render_inputs(s, v, g, s.camera.pose), 2);
  int terminated = 0;
  for (std::size_t i = 0; i < with_ert.pixels.size(); ++i) {
    const double residual = 1.0 - with_ert.pixels[i].a;
    if (with_ert.pixels[i].a >= 0.98) ++terminated;
    for (int c = 0; c < 4; ++c)
      EXPECT_LE(std::abs(without.pixels[i][c] - with_ert.pixels[i][c]), residual + 1e-12);
  }
  EXPECT_GT(terminated, 100);  // the test must exercise termination
}

// --- Degenerate rays ---------------------------------------------------------------

struct DegenerateRay {
  const char* name;
  ref::Vec3 eye, center;
  double expected_chord;
};

void PrintTo(const DegenerateRay& d, std::ostream* os) { *os << d.name; }

class DegenerateRays : public ::testing::TestWithParam<DegenerateRay> {};

TEST_P(DegenerateRays, GiveFiniteExpectedOpacity) {
  const DegenerateRay& d = GetParam();
  const double alpha = 0.1;
  const ref::Volume v = constant_volume(32, 100);
  ref::Scene s = constant_alpha_scene(alpha);
  s.render.width = s.render.height = 1;  // the only ray is the view axis
  s.camera.height = 1.0;
  const ref::Vec3 dir = d.center - d.eye;
  s.camera.pose = {d.eye, d.center, std::abs(dir.z) > 0 ? ref::Vec3(0, 1, 0) : ref::Vec3(0, 0, 1)};
  const OneRay r = cast_pixel(s, v, 0, 0);
  ASSERT_TRUE(r.stats.hit) << d.name;
  EXPECT_TRUE(std::isfinite(r.rgba.a));
  EXPECT_NEAR(r.segment.length(), d.expected_chord, 1e-12) << d.name;
  // Partial segments (the default): the opacity of the chord; the last of its
  // chord + 1 samples sits on the exit and weighs 0.
  EXPECT_NEAR(r.rgba.a, 1.0 - std::pow(1.0 - alpha, d.expected_chord), 1e-9) << d.name;
  EXPECT_EQ(r.stats.samples, static_cast<std::uint32_t>(d.expected_chord) + 1) << d.name;
}

INSTANTIATE_TEST_SUITE_P(
    Geometry, DegenerateRays,
    ::testing::Values(DegenerateRay{"along the x axis", {-5, 15.5, 15.5}, {40, 15.5, 15.5}, 31.0},
                      DegenerateRay{"along a face", {0, -5, 7.25}, {0, 40, 7.25}, 31.0},
                      DegenerateRay{"along an edge", {0, 0, -5}, {0, 0, 40}, 31.0},
                      DegenerateRay{"on the far edge", {31, -2, 31}, {31, 40, 31}, 31.0},
                      DegenerateRay{"starting inside", {15.5, 15.5, 10}, {15.5, 15.5, 40}, 21.0},
                      DegenerateRay{"eye on the boundary", {15.5, 0, 15.5}, {15.5, 40, 15.5},
                                    31.0}),
    [](const ::testing::TestParamInfo<DegenerateRay>& param_info) {
      std::string n = param_info.param.name;
      for (char& c : n) c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
      return n;
    });

TEST(Clip, MissesAreMisses) {
  const ref::Box box{{0, 0, 0}, {10, 10, 10}};
  EXPECT_FALSE(ref::clip({{-1, 11, 5}, {1, 0, 0}}, box));        // parallel, outside
  EXPECT_FALSE(ref::clip({{5, 5, 20}, {0, 0, 1}}, box));         // pointing away
  EXPECT_FALSE(ref::clip({{-1, -1, 5}, {-0.6, 0.8, 0}}, box));  // oblique miss
  const auto s = ref::clip({{5, 5, 20}, {0, 0, -1}}, box);
  ASSERT_TRUE(s);
  EXPECT_EQ(s->t_enter, 10.0);
  EXPECT_EQ(s->t_exit, 20.0);
}

// --- Shading --------------------------------------------------------------------

TEST(Shading, PhongClosedForm) {
  // One directional light at 60 degrees from the normal, viewer along the normal.
  const ref::Vec3 view{0, 0, -1};  // looking along -z: V = +z
  const double pi = 3.14159265358979323846;
  const ref::Vec3 l{std::sin(pi / 3), 0, std::cos(pi / 3)};
  const ref::ShadingSetup setup =
      ref::make_shading_setup({ref::Light{ref::LightType::Directional, l, 2.0}}, view, 8.0);
  const ref::Vec3 n{0, 0, 1};
  const ref::Reflectance r = ref::reflectance(setup, n);
  EXPECT_NEAR(r.diffuse, 2.0 * 0.5, 1e-12);
  EXPECT_NEAR(r.specular, 2.0 * std::pow(std::cos(pi / 6), 8.0), 1e-12);  // H halfway: 30 deg
  // The normal points against the gradient and is zero where it vanishes.
  EXPECT_EQ(ref::surface_normal({0, 0, -4}, {1, 1, 1}), n);
  EXPECT_EQ(ref::surface_normal({0, 0, 0}, {1, 1, 1}), ref::Vec3(0.0));
  const ref::Reflectance none = ref::reflectance(setup, ref::Vec3(0.0));
  EXPECT_EQ(none.diffuse, 0.0);
  EXPECT_EQ(none.specular, 0.0);
}

TEST(Shading, AnisotropicSpacingScalesTheGradient) {
  // A value slope of 1 per index along z with voxels twice as long in z is a
  // slope of 0.5 per world unit; with an equal slope per world unit along x the
  // normal bisects x and z.
  const ref::Vec3 nrm = ref::surface_normal({1.0, 0.0, 2.0}, {1.0, 1.0, 2.0});
  EXPECT_NEAR(nrm.x, -std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(nrm.z, -std::sqrt(0.5), 1e-12);
}

// --- Determinism ------------------------------------------------------------------

TEST(Render, SameBitsForAnyThreadCount) {
  const ref::Volume v = ref::make_phantom("shepp-logan", 40);
  ref::Scene s;
  s.tf_points = {{0.0, {0, 0, 0}, 0.0}, {60.0, {1, 0.8, 0.5}, 0.4}, {255.0, {1, 1, 1}, 0.1}};
  s.camera.pose = {{19.5, -50.0, 30.0}, {19.5, 19.5, 19.5}, {0, 0, 1}};
  s.render.width = s.render.height = 48;
  s.lights = {ref::Light{}};
  const ref::GradientField g = ref::compute_gradients(v, s.volume.gradient);
  const ref::RenderInputs in = ref::make_render_inputs(s, v, g, s.camera.pose);
  const ref::Image one = ref::render_image(in, 1);
  const ref::Image three = ref::render_image(in, 3);
  ASSERT_EQ(one.pixels.size(), three.pixels.size());
  for (std::size_t i = 0; i < one.pixels.size(); ++i) ASSERT_EQ(one.pixels[i], three.pixels[i]);
}

}  // namespace
}  // namespace voxcast::test
