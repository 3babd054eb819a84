// Reflectance-map unit (hls/reflectance_map.hpp, docs/pipeline.md §5), the three
// checks of STYLE.md for the vizard2, balanced and precise presets:
//  (a) hls == bit-true exactly: every cube-map cell, a dense box of small
//      gradients (zero, ties, one-LSB components), a fixed-seed sample of
//      gradients of every magnitude, isotropic and anisotropic volumes;
//  (b) D and S against the float reference's reflectance(surface_normal(g)) with
//      a bound derived from the cell size and the widths;
//  (c) closed forms: the six axis directions land in the centre cell of their
//      face, every cell-centre direction in its own cell, ties and the iu clamp,
//      N = 0 gives D = S = 0, and the vizard2 maps are 3 KB.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <glm/geometric.hpp>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hls/reflectance_map.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/bittrue/shading.hpp"
#include "refmodel/precision/preset_profiles.hpp"
#include "refmodel/render/raycaster.hpp"

namespace {

using namespace voxcast;
namespace bt = voxcast::bittrue;

template <PrecisionProfile P>
struct Profile {
  static constexpr PrecisionProfile value = P;
};
using Presets = ::testing::Types<Profile<kVizard2>, Profile<kBalanced>, Profile<kPrecise>>;
struct PresetNames {
  template <class T>
  static std::string GetName(int i) {
    static const char* const names[] = {"vizard2", "balanced", "precise"};
    return names[i];
  }
};

using G3 = std::array<double, 3>;

// The default scene's lights (a 0.7 headlight and a 0.5 directional light), an
// oblique view, shininess 24.
ref::ShadingSetup scene_shading() {
  ref::Light head;
  head.type = ref::LightType::Headlight;
  head.intensity = 0.7;
  ref::Light dir;
  dir.type = ref::LightType::Directional;
  dir.direction = {1.0, -1.0, 1.0};
  dir.intensity = 0.5;
  return ref::make_shading_setup({head, dir}, ref::Vec3(0.0, 253.5, -86.5), 24.0);
}

constexpr std::array<ref::Vec3, 2> kWorldScales = {ref::Vec3(1.0, 1.0, 1.0),
                                                   ref::Vec3(1.0, 1.37, 2.5)};

template <class T>
class ReflectanceMapTest : public ::testing::Test {
 protected:
  static constexpr PrecisionProfile kP = T::value;
  using Params = hls::ReflectanceParams<kP>;
  using gradient_t = typename Params::gradient_t;

  // Largest stored gradient magnitude: 2^(gradient_bits - gradient_frac_bits - 1) - 1 LSB.
  static double g_limit() {
    return std::ldexp(1.0, kP.gradient_bits - kP.gradient_frac_bits - 1) -
           std::ldexp(1.0, -kP.gradient_frac_bits);
  }
  static double lsb() { return std::ldexp(1.0, -kP.sample_frac_bits); }
  static double on_grid(double x) {
    return bt::sat(bt::q_rnd(x, kP.sample_frac_bits), -g_limit(), g_limit());
  }

  void SetUp() override {
    shading_ = scene_shading();
    fs_.profile = kP;
    bt::make_reflectance_maps(kP, shading_, fs_.rm_diffuse, fs_.rm_specular);
    map_ = std::make_unique<hls::ReflectanceMap<kP>>();
    ASSERT_TRUE(hls::host::load_reflectance_map<kP>(*map_, fs_.rm_diffuse, fs_.rm_specular));
    use_world_scale(kWorldScales[0]);
  }

  void use_world_scale(const ref::Vec3& ws) {
    world_scale_ = ws;
    for (int k = 0; k < 3; ++k)
      fs_.regs.IS[static_cast<std::size_t>(k)] =
          bt::to_raw(bt::q_rnd(1.0 / ws[k], kP.dir_frac_bits), kP.dir_frac_bits);
    regs_ = hls::host::reflectance_registers<kP>(fs_.regs);
  }

  hls::RmCell<kP> hls_cell(const G3& g) const {
    const gradient_t gc[3] = {gradient_t(g[0]), gradient_t(g[1]), gradient_t(g[2])};
    return hls::rm_cell<kP>(gc, regs_);
  }
  hls::Reflect<kP> hls_reflect(const G3& g) const {
    const gradient_t gc[3] = {gradient_t(g[0]), gradient_t(g[1]), gradient_t(g[2])};
    return hls::reflect(*map_, regs_, gc);
  }

  // (a) one gradient: cell, D and S, hls against bit-true.
  void expect_same(const G3& g) const {
    const hls::RmCell<kP> hc = hls_cell(g);
    const bt::BtCell bc = bt::bt_rm_cell(kP, fs_.regs.IS, g);
    ASSERT_EQ(hc.valid, bc.valid) << g[0] << ", " << g[1] << ", " << g[2];
    if (bc.valid) {
      ASSERT_EQ(static_cast<int>(hc.index.to_uint()), bc.index)
          << g[0] << ", " << g[1] << ", " << g[2];
    }
    const hls::Reflect<kP> hr = hls_reflect(g);
    const bt::BtReflect br = bt::bt_reflectance(fs_, g);
    ASSERT_EQ(hr.D.to_double(), br.D);
    ASSERT_EQ(hr.S.to_double(), br.S);
  }

  // The unit normal at the centre of cell `index`, and its corners (§5.4).
  static ref::Vec3 cell_point(int index, double du, double dv) {
    const int res = kP.rm_res;
    const int face = index / (res * res), iv = (index / res) % res, iu = index % res;
    const int m = face / 2, a = m == 0 ? 1 : 0, b = m == 2 ? 1 : 2;
    ref::Vec3 n(0.0);
    n[m] = (face & 1) ? -1.0 : 1.0;
    n[a] = (iu + du) * 2.0 / res - 1.0;
    n[b] = (iv + dv) * 2.0 / res - 1.0;
    return glm::normalize(n);
  }
  // Largest distance from the cell centre to a point of the cell: at a corner (the
  // cell is a convex spherical quadrilateral much smaller than a hemisphere).
  static double cell_radius(int index) {
    const ref::Vec3 c = cell_point(index, 0.5, 0.5);
    double r = 0.0;
    for (const double du : {0.0, 1.0})
      for (const double dv : {0.0, 1.0})
        r = std::max(r, glm::length(cell_point(index, du, dv) - c));
    return r;
  }

  ref::ShadingSetup shading_;
  bt::FrameSetup fs_;
  std::unique_ptr<hls::ReflectanceMap<kP>> map_;
  hls::ReflectanceRegisters<kP> regs_;
  ref::Vec3 world_scale_{1.0};
};
TYPED_TEST_SUITE(ReflectanceMapTest, Presets, PresetNames);

// ---- (a) bit-exact against the bit-true reference ----------------------------------------

// Every cell, reached by (minus) its centre direction at a large magnitude, isotropic and
// anisotropic; isotropic, the centre direction lands in its own cell (c).
TYPED_TEST(ReflectanceMapTest, EveryCellMatchesBitTrue) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const double scale = std::ldexp(1.0, P.gradient_bits - P.gradient_frac_bits - 2);
  for (const ref::Vec3& ws : kWorldScales) {
    this->use_world_scale(ws);
    for (int index = 0; index < TestFixture::Params::cells; ++index) {
      const ref::Vec3 n = TestFixture::cell_point(index, 0.5, 0.5);
      const G3 g = {TestFixture::on_grid(-n.x * scale), TestFixture::on_grid(-n.y * scale),
                    TestFixture::on_grid(-n.z * scale)};
      this->expect_same(g);
      if (ws == kWorldScales[0]) {
        ASSERT_EQ(static_cast<int>(this->hls_cell(g).index.to_uint()), index);
      }
    }
  }
}

// Every gradient with components in [-R, R] LSBs: zero, one-LSB normals, ties of every kind.
TYPED_TEST(ReflectanceMapTest, SmallGradientBoxMatchesBitTrue) {
  constexpr int R = 12;
  for (const ref::Vec3& ws : kWorldScales) {
    this->use_world_scale(ws);
    for (int x = -R; x <= R; ++x)
      for (int y = -R; y <= R; ++y)
        for (int z = -R; z <= R; ++z)
          this->expect_same(
              {x * TestFixture::lsb(), y * TestFixture::lsb(), z * TestFixture::lsb()});
  }
}

// Random directions at log-uniform magnitudes from 1 LSB to the stored field's limit.
TYPED_TEST(ReflectanceMapTest, RandomGradientsMatchBitTrue) {
  std::mt19937_64 rng(0x4EF1);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> log_mag(
      0.0, std::log2(TestFixture::g_limit()) + TestFixture::kP.sample_frac_bits);
  for (const ref::Vec3& ws : kWorldScales) {
    this->use_world_scale(ws);
    for (int n = 0; n < 60000; ++n) {
      const ref::Vec3 d = glm::normalize(ref::Vec3(normal(rng), normal(rng), normal(rng)));
      const double mag = std::ldexp(std::exp2(log_mag(rng)), -TestFixture::kP.sample_frac_bits);
      this->expect_same({TestFixture::on_grid(d.x * mag), TestFixture::on_grid(d.y * mag),
                         TestFixture::on_grid(d.z * mag)});
    }
  }
}

// ---- (b) against the float reference ------------------------------------------------------
// With n = surface_normal(g) (the truth) and n_c the centre of the cell the unit picks:
//   * world scaling: |gw[k] - g[k]/ws[k]| <= e[k] = 2^-(sf+1) + |g[k]|·2^-(df+1) (IS and gw
//     each round once), and the perturbed normal moves by at most 2|e|/|g/ws|;
//   * the perturbed normal lies in the closed cell: within the cell radius r_c (largest
//     centre-to-corner distance) of n_c. So |n - n_c| <= d = r_c + 2|e|/|g/ws|;
//   * D(n) = sum I_l max(0, n·L_l) is sum(I_l)-Lipschitz: |D(n) - D(n_c)| <= sum(I_l)·d;
//   * S(n) = sum I_l [n·L_l > 0] max(0, n·H_l)^k: along the chord from n to n_c, x·H is
//     linear, so the slope k·(x·H)^(k-1) is at most k·h^(k-1), h = max(0, n·H, n_c·H), and
//     where n·L and n_c·L differ in sign the gate jumps by at most h^k;
//   * the entry is SAT(Q_RND(·, rm_frac_bits), 0, max): 2^-(rm_frac_bits+1) plus what the
//     saturation cuts off above max = 2^rm_int_bits - 2^-rm_frac_bits.
TYPED_TEST(ReflectanceMapTest, WithinDerivedBoundOfFloatReflectance) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const double half_entry = std::ldexp(1.0, -(P.rm_frac_bits + 1));
  const double entry_max = std::ldexp(1.0, P.rm_int_bits) - std::ldexp(1.0, -P.rm_frac_bits);
  const double k = this->shading_.shininess;
  double sum_i = 0.0;
  for (const auto& t : this->shading_.lights) sum_i += t.intensity;

  std::mt19937_64 rng(0xB0B);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> log_mag(
      4.0, std::log2(TestFixture::g_limit()) + P.sample_frac_bits);
  double worst_d = 0.0, worst_s = 0.0, worst_d_ratio = 0.0, worst_s_ratio = 0.0;
  // Gradients of at least 1/16 of the field's limit: the cell size dominates the error.
  double worst_d_large = 0.0, worst_s_large = 0.0;
  for (const ref::Vec3& ws : kWorldScales) {
    this->use_world_scale(ws);
    for (int n = 0; n < 40000; ++n) {
      const ref::Vec3 dir = glm::normalize(ref::Vec3(normal(rng), normal(rng), normal(rng)));
      const double mag = std::ldexp(std::exp2(log_mag(rng)), -P.sample_frac_bits);
      const ref::Vec3 g(TestFixture::on_grid(dir.x * mag), TestFixture::on_grid(dir.y * mag),
                        TestFixture::on_grid(dir.z * mag));
      const ref::Vec3 gw = g / ws;
      if (glm::length(gw) == 0.0) continue;
      const hls::RmCell<P> cell = this->hls_cell({g.x, g.y, g.z});
      ASSERT_TRUE(cell.valid);
      const int index = static_cast<int>(cell.index.to_uint());
      const hls::Reflect<P> got = this->hls_reflect({g.x, g.y, g.z});

      const ref::Vec3 nt = ref::surface_normal(g, ws);
      const ref::Reflectance want = ref::reflectance(this->shading_, nt);
      const ref::Vec3 nc = TestFixture::cell_point(index, 0.5, 0.5);
      const ref::Reflectance at_centre = ref::reflectance(this->shading_, nc);

      double e2 = 0.0;
      for (int a = 0; a < 3; ++a) {
        const double e = std::ldexp(1.0, -(P.sample_frac_bits + 1)) +
                         std::abs(g[a]) * std::ldexp(1.0, -(P.dir_frac_bits + 1));
        e2 += e * e;
      }
      const double d =
          TestFixture::cell_radius(index) + std::min(2.0, 2.0 * std::sqrt(e2) / glm::length(gw));

      const double bound_d = half_entry + std::max(0.0, at_centre.diffuse - entry_max) + sum_i * d;
      double bound_s = half_entry + std::max(0.0, at_centre.specular - entry_max);
      for (const auto& t : this->shading_.lights) {
        const double h = std::max({0.0, glm::dot(nt, t.halfway), glm::dot(nc, t.halfway)});
        bound_s += t.intensity * k * std::pow(h, k - 1.0) * d;
        if ((glm::dot(nt, t.light) > 0.0) != (glm::dot(nc, t.light) > 0.0))
          bound_s += t.intensity * std::pow(h, k);
      }
      const double err_d = std::abs(got.D.to_double() - want.diffuse);
      const double err_s = std::abs(got.S.to_double() - want.specular);
      ASSERT_LE(err_d, bound_d) << "g = " << g.x << ", " << g.y << ", " << g.z;
      ASSERT_LE(err_s, bound_s) << "g = " << g.x << ", " << g.y << ", " << g.z;
      worst_d = std::max(worst_d, err_d);
      worst_s = std::max(worst_s, err_s);
      if (glm::length(g) >= TestFixture::g_limit() / 16) {
        worst_d_large = std::max(worst_d_large, err_d);
        worst_s_large = std::max(worst_s_large, err_s);
      }
      worst_d_ratio = std::max(worst_d_ratio, err_d / bound_d);
      worst_s_ratio = std::max(worst_s_ratio, err_s / bound_s);
    }
  }
  this->RecordProperty("worst_D_error", std::to_string(worst_d));
  this->RecordProperty("worst_S_error", std::to_string(worst_s));
  this->RecordProperty("worst_D_error_large_gradient", std::to_string(worst_d_large));
  this->RecordProperty("worst_S_error_large_gradient", std::to_string(worst_s_large));
  this->RecordProperty("worst_D_error_over_bound", std::to_string(worst_d_ratio));
  this->RecordProperty("worst_S_error_over_bound", std::to_string(worst_s_ratio));
}

// ---- (c) closed forms ------------------------------------------------------------------------

// An axis direction lands in cell iu = iv = floor(rm_res/2) of its face, at any magnitude.
TYPED_TEST(ReflectanceMapTest, AxisDirectionsLandInTheCentreCellOfTheirFace) {
  constexpr PrecisionProfile P = TestFixture::kP;
  constexpr int res = P.rm_res;
  for (const ref::Vec3& ws : kWorldScales) {
    this->use_world_scale(ws);
    for (int face = 0; face < 6; ++face) {
      for (const double mag : {TestFixture::lsb() * 2, 1.0, TestFixture::g_limit()}) {
        G3 g = {0.0, 0.0, 0.0};
        // N = -gw points along +axis on face 2m, -axis on face 2m + 1.
        g[static_cast<std::size_t>(face / 2)] = (face & 1) ? mag : -mag;
        const hls::RmCell<P> cell = this->hls_cell(g);
        ASSERT_TRUE(cell.valid);
        EXPECT_EQ(static_cast<int>(cell.index.to_uint()),
                  face * res * res + (res / 2) * res + res / 2)
            << "face " << face << " magnitude " << mag;
        this->expect_same(g);
      }
    }
  }
}

// Ties go to the lower axis; N[a] = |N[m]| is clamped to the last cell, N[a] = -|N[m]| is cell 0.
TYPED_TEST(ReflectanceMapTest, TiesAndTheEdgeClamp) {
  constexpr PrecisionProfile P = TestFixture::kP;
  constexpr int res = P.rm_res;
  // N = (1, 1, 0): major axis x (face 0), iu (axis y) clamped to res - 1, iv (axis z) centre.
  EXPECT_EQ(static_cast<int>(this->hls_cell({-1.0, -1.0, 0.0}).index.to_uint()),
            0 * res * res + (res / 2) * res + (res - 1));
  // N = (1, -1, 0): iu = 0.
  EXPECT_EQ(static_cast<int>(this->hls_cell({-1.0, 1.0, 0.0}).index.to_uint()),
            0 * res * res + (res / 2) * res + 0);
  // N = (0, -1, -1): major axis y (face 3), iu (axis x) centre, iv (axis z) = 0.
  EXPECT_EQ(static_cast<int>(this->hls_cell({0.0, 1.0, 1.0}).index.to_uint()),
            3 * res * res + 0 * res + res / 2);
  // N = (-1, 1, 1): major axis x (face 1); u (axis y) and v (axis z) clamp to res - 1.
  EXPECT_EQ(static_cast<int>(this->hls_cell({1.0, -1.0, -1.0}).index.to_uint()),
            1 * res * res + (res - 1) * res + (res - 1));
}

TYPED_TEST(ReflectanceMapTest, ZeroGradientHasNoNormalAndNoLight) {
  for (const ref::Vec3& ws : kWorldScales) {
    this->use_world_scale(ws);
    EXPECT_FALSE(this->hls_cell({0.0, 0.0, 0.0}).valid);
    const auto r = this->hls_reflect({0.0, 0.0, 0.0});
    EXPECT_EQ(r.D.to_double(), 0.0);
    EXPECT_EQ(r.S.to_double(), 0.0);
    // A one-LSB gradient along an axis scaled by 1/2.5 rounds to 0: no normal either.
    this->expect_same({TestFixture::lsb(), 0.0, 0.0});
  }
}

// VIZARD II's maps: 6·16² cells x 8 bits x 2 tables = 3 KB.
TEST(ReflectanceMapVizard2, TwoTablesAreThreeKilobytes) {
  using Params = hls::ReflectanceParams<kVizard2>;
  static_assert(Params::cells == 6 * 16 * 16);
  static_assert(Params::entry_bits == 8);
  EXPECT_EQ(2 * Params::cells * Params::entry_bits / 8, 3 * 1024);
  std::vector<std::uint32_t> d, s;
  bt::make_reflectance_maps(kVizard2, scene_shading(), d, s);
  EXPECT_EQ(d.size() + s.size(), 3u * 1024u);  // one byte per entry
  for (std::size_t i = 0; i < d.size(); ++i) {
    ASSERT_LT(d[i], 256u);
    ASSERT_LT(s[i], 256u);
  }
}

}  // namespace
