// Resampling a slice stack onto a regular grid (refmodel/volume/slice_resample.hpp):
// linear ramps, which linear and bilinear interpolation reproduce exactly.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "refmodel/error.hpp"
#include "refmodel/volume/slice_resample.hpp"
#include "tests/common/error_of.hpp"

namespace voxcast::ref {
namespace VOXCAST_UNITY_ID {

// Slices at w = 0, 1, 3 holding 10 w everywhere: gaps 1 and 2, median 2 (the
// upper of two), so planes at w = 0, 2 and 4, the last clamped to the last slice.
TEST(SliceResample, UnevenGapsLinearAlongTheNormal) {
  const StackLayout layout{4, 3, 1.0, 1.0};
  const std::vector<std::uint16_t> a(12, 0), b(12, 10), c(12, 30);
  const std::vector<StackSlice> stack{{"a", a.data(), 0.0, 0.0, 0.0},
                                      {"b", b.data(), 0.0, 0.0, 1.0},
                                      {"c", c.data(), 0.0, 0.0, 3.0}};
  const RegularGrid g = plan_regular_grid(stack, layout, "dir");
  EXPECT_EQ(g.slices, 3);
  EXPECT_EQ(g.spacing_z, 2.0);
  EXPECT_EQ(g.uneven_gaps, 1);  // the gap of 1
  EXPECT_EQ(g.tilt_deg, 0.0);
  const std::vector<std::uint16_t> out = resample_stack(stack, layout, g, 0);
  ASSERT_EQ(out.size(), 36u);
  for (std::size_t k = 0; k < 12; ++k) {
    EXPECT_EQ(out[k], 0);
    EXPECT_EQ(out[12 + k], 20);
    EXPECT_EQ(out[24 + k], 30);
  }
}

// An object f(U) = 10 U + 100 that does not move, seen by two slices whose
// in-plane origins differ by one pixel (a 45 degree tilt): the grid lies half
// way, so each slice is sampled half a pixel off its pixels; bilinear is exact
// on the ramp, and points outside a slice take the fill value.
TEST(SliceResample, ShearIsUndoneBilinearly) {
  const StackLayout layout{6, 2, 1.0, 1.0};
  std::vector<std::uint16_t> s0(12), s1(12);
  for (int j = 0; j < 2; ++j)
    for (int x = 0; x < 6; ++x) {
      s0[static_cast<std::size_t>(j * 6 + x)] = static_cast<std::uint16_t>(10 * (0 + x) + 100);
      s1[static_cast<std::size_t>(j * 6 + x)] = static_cast<std::uint16_t>(10 * (1 + x) + 100);
    }
  const std::vector<StackSlice> stack{{"s0", s0.data(), 0.0, 0.0, 0.0},
                                      {"s1", s1.data(), 1.0, 0.0, 1.0}};
  const RegularGrid g = plan_regular_grid(stack, layout, "dir");
  EXPECT_EQ(g.slices, 2);
  EXPECT_DOUBLE_EQ(g.tilt_deg, 45.0);
  EXPECT_EQ(g.u0, 0.5);
  const std::vector<std::uint16_t> out = resample_stack(stack, layout, g, 7);
  for (int m = 0; m < 2; ++m)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 6; ++i) {
        const std::uint16_t got = out[static_cast<std::size_t>(m * 12 + j * 6 + i)];
        // U = 0.5 + i: slice 0 has pixels up to U = 5, slice 1 from U = 1.
        const bool inside = m == 0 ? i <= 4 : i >= 1;
        if (inside) {
          EXPECT_EQ(got, 10 * i + 105) << m << " " << i;
        } else {
          EXPECT_EQ(got, m == 0 ? (150 + 7 + 1) / 2 : (7 + 110 + 1) / 2) << m << " " << i;
        }
      }
}

TEST(SliceResample, DegenerateStacksAreRefused) {
  const StackLayout layout{4, 4, 1.0, 1.0};
  const std::vector<std::uint16_t> p(16, 0);
  const std::string steep = test::error_of([&] {
    plan_regular_grid({{"a", p.data(), 0.0, 0.0, 0.0}, {"b", p.data(), 1.1, 0.0, 1.0}}, layout,
                      "dir");
  });
  EXPECT_NE(steep.find("dir: the slice positions lean 47.7 deg"), std::string::npos) << steep;
  EXPECT_NE(steep.find("more than 45 deg"), std::string::npos) << steep;
  const std::string zigzag = test::error_of([&] {
    plan_regular_grid({{"a", p.data(), 0.0, 0.0, 0.0},
                       {"b", p.data(), 0.0, 2.0, 1.0},
                       {"c", p.data(), 0.0, 0.0, 2.0}},
                      layout, "dir");
  });
  EXPECT_NE(zigzag.find("dir: b is offset 2.0 pixels sideways"), std::string::npos) << zigzag;
}

}  // namespace VOXCAST_UNITY_ID
}  // namespace voxcast::ref
