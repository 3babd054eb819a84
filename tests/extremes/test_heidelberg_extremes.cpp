// The Heidelberg path at its extremes (issue 7; docs/extremes.md, "Heidelberg
// path"): a fully opaque first voxel, a fully transparent volume and the 45 deg
// light entering at a plane's corner, each on the three engines of the path
// (double reference, bit-true twin, hls kernels; hls == bit-true exactly) and
// each against a value that follows from docs/heidelberg.md §5 and §7.5.
//
// Every scene views the data cube unrotated at zoom 1 with the view cube the
// size of the data cube, so view voxel (i, j, k) samples data voxel (i, j, k)
// exactly (§2: p = c + v; both interpolation masks give weight 1 to the lattice
// point, §3 and §7.3): plane k is the data's z = k slice, row j its y = j row.
#include <gtest/gtest.h>

#include <cmath>
#include <array>
#include <cstdint>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

#include "cosim/engines/heidelberg.hpp"
#include "refmodel/bittrue/heidelberg.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/render/heidelberg/heidelberg.hpp"
#include "rtl_model/virim/engine.hpp"
#include "tests/heidelberg/fixtures.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

constexpr HeidelbergProfile HP = kVirimProfile;

struct HeidelbergRun {
  ref::Image ref;        // double reference
  ref::QuantImage bt;    // bit-true twin
  ref::QuantImage hls;   // hls kernels
  bittrue::VirimSetup setup;
};

// One scene through the engines; hls must equal bit-true, rtl hls on every pixel.
HeidelbergRun run_engines(const ref::Scene& scene, const ref::Volume& volume) {
  HeidelbergRun r;
  r.ref = ref::heidelberg::render(scene, volume, 0.0, 1);
  r.setup = bittrue::make_virim_setup(HP, scene, volume, 0.0);
  const bittrue::VirimMemory mem = bittrue::make_virim_memory(volume);
  r.bt = bittrue::bt_render_heidelberg(r.setup, mem, 1);
  r.hls = cosim::hls_render_heidelberg(r.setup, mem, 1);
  EXPECT_EQ(r.hls.pixels, r.bt.pixels) << "hls differs from bit-true";
  rtl::virim::VirimRtlConfig two_modules;  // VIRIM's cycle model on the same extremes
  two_modules.modules = 2;
  EXPECT_EQ(rtl::virim::virim_rtl_render(r.setup, mem, two_modules, 1).image.pixels, r.hls.pixels)
      << "rtl differs from hls";
  return r;
}

double full_scale() { return std::ldexp(1.0, HP.out_bits) - 1.0; }

// --- 1. Fully opaque first voxel ----------------------------------------------------

// Rows y = 0, 1 of every plane have density 1 (value 255 on the identity LUT);
// rows y >= 2 hold `behind`. Row 1 is opaque too so that the front voxel's
// Sobel gradient (which reads row 1) does not depend on what lies behind.
constexpr int kOpW = 12, kOpD = 10, kOpH = 6;
ref::Volume opaque_front(const std::function<std::uint16_t(int, int, int)>& behind) {
  return make_volume(kOpW, kOpD, kOpH, 8, [&](int x, int y, int z) {
    return y < 2 ? std::uint16_t{255} : behind(x, y, z);
  });
}

ref::Scene opaque_scene(double wd0, double wd45, double ws45, double wl, int shininess) {
  ref::Scene s = heidelberg_scene(kOpW, kOpD, kOpH);
  s.heidelberg.diffuse_0 = wd0, s.heidelberg.diffuse_45 = wd45;
  s.heidelberg.specular_45 = ws45, s.heidelberg.luminosity = wl;
  s.heidelberg.shininess = shininess;
  s.heidelberg.light = 1.0;
  return s;
}

// The front voxel (j = 0) absorbs both lights whole: rho = 1, I0 = I45 = L = 1
// (T0 = T45 = 1 at the front, §5.1), so E0 = E45 = 1 and the voxels behind see
// T0 = 0 (§5.5: they add e T0 = 0). Its Sobel gradient (§4; rows j-1 outside
// read 0, rows j and j+1 are 1) is (0, 1/2) inside, (3/8, 3/8) at x = 0 and
// (-3/8, 3/8) at x = W-1, so with r = 1/√2 (§5.3, surface = fade = 1):
//   inside:  c0 = 1, c45 = r, rv = r  ->  pixel = wd0 + wd45 r + ws45 r^n + wl
//   x = 0:   c0 = r, c45 = 1, rv = r  ->  pixel = wd0 r + wd45 + ws45 r^n + wl
//   x = W-1: c0 = r, c45 = 0, rv = -r ->  pixel = wd0 r + wl
// (each below E0 + E45 = 2 and below 1, so neither min of §5.4/5.5 applies).
std::vector<double> opaque_front_closed_form(double wd0, double wd45, double ws45, double wl, int n) {
  const double r = 1.0 / std::numbers::sqrt2, spec = ws45 * std::pow(r, n);
  std::vector<double> col(kOpW, wd0 + wd45 * r + spec + wl);
  col.front() = wd0 * r + wd45 + spec + wl;
  col.back() = wd0 * r + wl;
  return col;
}

TEST(HeidelbergExtremes, FullyOpaqueFirstVoxelGivesItsOwnScatteringAndHidesEverythingBehind) {
  // Weights on the 8-bit user-weight grid (exact in fixed point), chosen so
  // that 255 * pixel lies >= 0.47 levels from a rounding boundary.
  const double wd0 = 0.25, wd45 = 0.4375, ws45 = 0.4375, wl = 0.0625;
  const int n = 3;
  const ref::Scene s = opaque_scene(wd0, wd45, ws45, wl, n);
  const std::vector<double> expect = opaque_front_closed_form(wd0, wd45, ws45, wl, n);
  // The fixed point differs from the closed form by its roundings (§7.5): the
  // density 1 saturates to 1 - 2^-16, the cosines are off by at most
  // 2^-16/|g| + 2^-14 (|g| >= 1/2), and about ten TRN steps of 2^-14 or
  // 2^-16 follow: below 16 * 2^-14 in all, i.e. 0.25 levels, which leaves the
  // nearest level unchanged.
  const double delta = 16.0 * std::ldexp(1.0, -HP.cos_frac_bits);
  std::vector<std::uint32_t> level(kOpW);
  for (int x = 0; x < kOpW; ++x) {
    const double v = expect[static_cast<std::size_t>(x)] * full_scale();
    ASSERT_GT(std::abs(v - std::floor(v) - 0.5), delta * full_scale()) << "x = " << x;
    level[static_cast<std::size_t>(x)] = static_cast<std::uint32_t>(std::lround(v));
  }

  std::mt19937 rng(7);
  std::uniform_int_distribution<int> u(0, 255);
  std::vector<std::uint16_t> noise(static_cast<std::size_t>(kOpW * kOpD * kOpH));
  for (auto& v : noise) v = static_cast<std::uint16_t>(u(rng));
  const std::function<std::uint16_t(int, int, int)> behinds[] = {
      [](int, int, int) { return std::uint16_t{0}; },    // empty behind
      [](int, int, int) { return std::uint16_t{255}; },  // opaque behind
      [&](int x, int y, int z) { return noise[static_cast<std::size_t>((z * kOpD + y) * kOpW + x)]; }};
  std::vector<HeidelbergRun> runs;
  for (const auto& behind : behinds) runs.push_back(run_engines(s, opaque_front(behind)));

  for (const HeidelbergRun& r : runs) {
    for (int y = 0; y < kOpH; ++y)
      for (int x = 0; x < kOpW; ++x) {
        const glm::dvec4 p = r.ref.at(x, y);
        ASSERT_TRUE(std::isfinite(p.r) && std::isfinite(p.a));
        EXPECT_NEAR(p.r, expect[static_cast<std::size_t>(x)], 1e-12) << x << "," << y;
        EXPECT_EQ(p.a, 1.0);  // T0(D) = 0: not background
        const std::array<std::uint32_t, 4> q = r.bt.at(x, y);
        EXPECT_EQ(q[0], level[static_cast<std::size_t>(x)]) << x << "," << y;
        EXPECT_EQ(q[3], 255u);
      }
    // Nothing behind the front voxel contributes, in any engine: in double
    // T0 = 0 exactly; in fixed point T0 = 1 - TRN(1 - 2^-16) = 2^-16 stays
    // there (TRN(2^-16 rho) = 0 for rho < 1), so I0 = 2^-16, E0 = 0 and
    // e <= E45 < 1 adds TRN(e 2^-16) = 0 to the accumulator.
    EXPECT_EQ(r.ref.pixels, runs[0].ref.pixels);
    EXPECT_EQ(r.bt.pixels, runs[0].bt.pixels);
  }
  // The fixed-point leak itself, from the LUT (density 1 saturates, §7.3).
  EXPECT_EQ(runs[0].setup.lut[255], 1.0 - std::ldexp(1.0, -HP.density_bits));
}

TEST(HeidelbergExtremes, FullyOpaqueFirstVoxelAtFullWeightsSaturatesWithoutOverflow) {
  // All four weights 1: e = min(E0 + E45, ...) = 2 inside (§5.4), the largest
  // value the datapath holds (acc < 4 in ufixed<lf+2, 2>); the pixel clamps to
  // 1 (§5.5) and the level to full scale, no wrap-around.
  const ref::Scene s = opaque_scene(1.0, 1.0, 1.0, 1.0, 1);
  const HeidelbergRun r = run_engines(s, opaque_front([](int, int, int) { return std::uint16_t{255}; }));
  for (int y = 0; y < kOpH; ++y)
    for (int x = 0; x < kOpW; ++x) {
      ASSERT_TRUE(std::isfinite(r.ref.at(x, y).r));
      EXPECT_EQ(r.ref.at(x, y), glm::dvec4(1.0, 1.0, 1.0, 1.0)) << x << "," << y;
      EXPECT_EQ(r.bt.at(x, y), (std::array<std::uint32_t, 4>{255, 255, 255, 255})) << x << "," << y;
    }
}

// --- 2. Fully transparent volume ----------------------------------------------------

TEST(HeidelbergExtremes, FullyTransparentVolumeIsBackgroundEverywhere) {
  // Density 0 everywhere (and outside the cube, §1): no voxel absorbs, so the
  // 0 deg light leaves every line's far end as it entered, T0(D) = 1 exactly
  // in double and in fixed point (T0 -= TRN(T0 * 0) = 0). Any threshold below
  // 1 makes every pixel background (§5.6): alpha 0 (double) and all channels 0
  // (fixed point); even 1 - 2^-16, one LSB of the light below 1, which fails
  // if a single LSB were absorbed anywhere. Threshold 1 (off) makes no pixel
  // background, and then every pixel is 0: nothing scattered.
  const ref::Volume v = make_volume(16, 16, 16, 8, [](int, int, int) { return std::uint16_t{0}; });
  ref::Scene s = heidelberg_scene(20, 18, 14);
  // An oblique, perspective, zoomed view: every sample is an interpolation.
  s.heidelberg.axis = {0.3, -0.5, 1.0};
  s.heidelberg.angle_deg = 37.0;
  s.heidelberg.zoom = 1.3;
  s.heidelberg.perspective = 40.0;
  for (double threshold : {0.95, 1.0 - std::ldexp(1.0, -HP.light_frac_bits), 1.0}) {
    s.heidelberg.background_threshold = threshold;
    const HeidelbergRun r = run_engines(s, v);
    const bool off = threshold >= 1.0;
    const glm::dvec4 want_ref = off ? glm::dvec4(0.0, 0.0, 0.0, 1.0) : glm::dvec4(0.0);
    const std::array<std::uint32_t, 4> want_bt{0, 0, 0, off ? 255u : 0u};
    for (int y = 0; y < 14; ++y)
      for (int x = 0; x < 20; ++x) {
        ASSERT_EQ(r.ref.at(x, y), want_ref) << "threshold " << threshold << " at " << x << "," << y;
        ASSERT_EQ(r.bt.at(x, y), want_bt) << "threshold " << threshold << " at " << x << "," << y;
      }
  }
}

// --- 3. The 45 deg light entering at a plane's corner -----------------------------

TEST(HeidelbergExtremes, FortyFiveDegreeLightFromTheCornerFollowsThePerVoxelProduct) {
  // Plane k: a homogeneous slab of density rho = 0.2 (value 51) in columns
  // x < k, a probe of density rho_p = 0.8 (value 204) at (x, j) = (k, k),
  // nothing else. The 45 deg light reaching the probe entered at the corner
  // (0, 0) (§5.1: T45 = 1 there) and crossed the k slab voxels (m, m),
  // m < k, on the diagonal, each passing 1 - rho (no √2 scaling):
  //   T45(k, k) = (1 - rho)^k.
  // Column k is empty in front of the probe, so T0(k, k) = 1. With only
  // self-luminosity (wl = 1, L = 1), the probe sends wl (E0 + E45)/2 (§5.4),
  // unattenuated back to the viewer (§5.5), and is the only voxel of column k
  // that does:
  //   pixel(k, line k) = rho_p (1 + (1 - rho)^k) / 2.
  // k = 0 is the corner voxel itself: it receives the full entering light,
  // pixel = rho_p.
  const int W = 16, D = 16, H = 12;
  const ref::Volume v = make_volume(W, D, H, 8, [](int x, int y, int z) {
    if (x < z) return std::uint16_t{51};
    return x == z && y == z ? std::uint16_t{204} : std::uint16_t{0};
  });
  ref::Scene s = heidelberg_scene(W, D, H);
  s.heidelberg.diffuse_0 = s.heidelberg.diffuse_45 = s.heidelberg.specular_45 = 0.0;
  s.heidelberg.luminosity = 1.0;
  s.heidelberg.light = 1.0;
  s.heidelberg.background_threshold = 1.0;  // no background: the probe column's value shows
  const HeidelbergRun r = run_engines(s, v);

  const double lf = std::ldexp(1.0, -HP.light_frac_bits);
  const double rho_fx = r.setup.lut[51], rho_p_fx = r.setup.lut[204];
  double t45 = 1.0;  // fixed point: T45 <- T45 - TRN_lf(T45 rho) per voxel (§7.5)
  for (int k = 0; k < H; ++k) {
    const int row = H - 1 - k;
    // Double: the closed form.
    const double pixel = 0.8 * (1.0 + std::pow(0.8, k)) / 2.0;
    EXPECT_NEAR(r.ref.at(k, row).r, pixel, 1e-12) << "k = " << k;
    // Fixed point: the floor of the absorbed share T45 rho leaves T45 high by
    // at most one LSB per voxel, so after k voxels
    // (1 - rho)^k <= T45 <= (1 - rho)^k + k 2^-lf (§7.5).
    const double exact = std::pow(1.0 - rho_fx, k);
    ASSERT_GE(t45, exact);
    ASSERT_LE(t45, exact + k * lf);
    // The level §7.5 gives for that T45: I0 = 1, I45 = T45, E = TRN(I rho_p),
    // e = TRN(wl (E0 + E45)/2) (the Phong terms have weight 0), acc = e * T0 = e.
    const double e0 = bittrue::q_trn(rho_p_fx, HP.light_frac_bits);
    const double e45 = bittrue::q_trn(t45 * rho_p_fx, HP.light_frac_bits);
    const double e = bittrue::q_trn((e0 + e45) / 2.0, HP.light_frac_bits);
    const auto level = static_cast<std::uint32_t>(bittrue::q_rnd(e * full_scale(), 0));  // RND_0
    EXPECT_EQ(r.bt.at(k, row)[0], level) << "k = " << k;
    // And that level against the closed form at the fixed-point densities:
    // within half a level plus the (k + 3) LSBs the floors can move it.
    const double closed = rho_p_fx * (1.0 + exact) / 2.0;
    EXPECT_LE(std::abs(r.bt.at(k, row)[0] - closed * full_scale()), 0.5 + (k + 3) * lf * full_scale())
        << "k = " << k;
    t45 -= bittrue::q_trn(t45 * rho_fx, HP.light_frac_bits);
  }
  // One voxel more or less on the diagonal would move the pixel by
  // rho_p rho (1 - rho)^k / 2 >= 0.08 * 0.8^11 * 255 = 1.8 levels (k <= 11),
  // beyond the bound above: the checks tell a wrong step count apart.
}

}  // namespace
}  // namespace voxcast::test
