// Reflectance-map unit (hls/reflectance_map.hpp, docs/pipeline.md §5), the three
// checks of STYLE.md for the presets (vizard2: nearest cell; balanced and precise:
// bilinear, §5.5) and for profiles that exercise the other mode of each (balanced
// nearest at rm_res 64, vizard2 bilinear) and the odd corners of the bilinear
// grid (odd rm_res with few weight bits, rm_res = 1):
//  (a) hls == bit-true exactly (cell, in-cell position, D and S): every cube-map
//      cell, a dense box of small gradients (zero, ties, one-LSB components), a
//      fixed-seed sample of gradients of every magnitude, isotropic and
//      anisotropic volumes;
//  (b) D and S against the float reference's reflectance(surface_normal(g)) with
//      a bound derived from the cell size and the widths: O(h) for the nearest
//      cell, O(h²) for bilinear where the cell does not straddle a terminator;
//  (c) closed forms: the six axis directions land in the centre cell (nearest)
//      or read the face-centre corner entry (bilinear) of their face, every
//      cell-centre direction lands in its own cell (and reads the rounded mean of
//      its four corners), every corner direction reads its own entry (also across
//      cube edges, where the faces' entries coincide), ties and the edge clamp,
//      N = 0 gives D = S = 0, and the table sizes (vizard2: 3 KB).
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

#include "preset_types.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast;
namespace bt = voxcast::bittrue;

using test::Profile;

// The other mode of each preset, and the bilinear grid's odd cases.
constexpr PrecisionProfile kBalancedNearest = [] {
  PrecisionProfile p = kBalanced;
  p.rm_bilinear = 0;
  p.rm_res = 64;
  return p;
}();
constexpr PrecisionProfile kVizard2Bilinear = [] {
  PrecisionProfile p = kVizard2;
  p.rm_bilinear = 1;
  return p;
}();
// Odd rm_res (no corner at the face centre), 3 weight bits, an integer bit.
constexpr PrecisionProfile kOddBilinear = [] {
  PrecisionProfile p = kVizard2;
  p.rm_bilinear = 1;
  p.rm_res = 7;
  p.rm_weight_bits = 3;
  p.rm_int_bits = 1;
  return p;
}();
// One cell per face (its four corners are the cube's), the widest weights.
constexpr PrecisionProfile kOneCellBilinear = [] {
  PrecisionProfile p = kBalanced;
  p.rm_bilinear = 1;
  p.rm_res = 1;
  p.rm_weight_bits = 12;
  return p;
}();
static_assert(kVizard2.rm_bilinear == 0 && kBalanced.rm_bilinear == 1 &&
              kPrecise.rm_bilinear == 1);

using Presets = ::testing::Types<Profile<kVizard2>, Profile<kBalanced>, Profile<kPrecise>,
                                 Profile<kBalancedNearest>, Profile<kVizard2Bilinear>,
                                 Profile<kOddBilinear>, Profile<kOneCellBilinear>>;
struct PresetNames {
  template <class T>
  static std::string GetName(int i) {
    static const char* const names[] = {"vizard2",          "balanced",     "precise",
                                        "balanced_nearest", "vizard2_bilinear", "odd_bilinear",
                                        "one_cell_bilinear"};
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
  using Params = hls::ReflectanceParams<ProfileTraits<kP>>;
  using gradient_t = typename Params::gradient_t;
  static constexpr bool kBilinear = Params::bilinear;
  static constexpr int kRes = kP.rm_res;
  static constexpr int kSide = Params::side;  // entries per face row

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
    map_ = std::make_unique<hls::ReflectanceMap<ProfileTraits<kP>>>();
    ASSERT_TRUE(hls::host::load_reflectance_map<ProfileTraits<kP>>(*map_, fs_.rm_diffuse, fs_.rm_specular));
    use_world_scale(kWorldScales[0]);
  }

  void use_world_scale(const ref::Vec3& ws) {
    world_scale_ = ws;
    for (int k = 0; k < 3; ++k)
      fs_.regs.IS[static_cast<std::size_t>(k)] =
          bt::to_raw(bt::q_rnd(1.0 / ws[k], kP.dir_frac_bits), kP.dir_frac_bits);
    regs_ = hls::host::reflectance_registers<ProfileTraits<kP>>(fs_.regs);
  }

  hls::RmCell<ProfileTraits<kP>> hls_cell(const G3& g) const {
    const gradient_t gc[3] = {gradient_t(g[0]), gradient_t(g[1]), gradient_t(g[2])};
    return hls::rm_cell<ProfileTraits<kP>>(gc, regs_);
  }
  hls::Reflect<ProfileTraits<kP>> hls_reflect(const G3& g) const {
    const gradient_t gc[3] = {gradient_t(g[0]), gradient_t(g[1]), gradient_t(g[2])};
    return hls::reflect(*map_, regs_, gc);
  }

  // (a) one gradient: cell, in-cell position, D and S, hls against bit-true.
  void expect_same(const G3& g) const {
    const hls::RmCell<ProfileTraits<kP>> hc = hls_cell(g);
    const bt::BtCell bc = bt::bt_rm_cell(kP, fs_.regs.IS, g);
    ASSERT_EQ(hc.valid, bc.valid) << g[0] << ", " << g[1] << ", " << g[2];
    if (bc.valid) {
      ASSERT_EQ(static_cast<int>(hc.index.to_uint()), bc.index)
          << g[0] << ", " << g[1] << ", " << g[2];
      ASSERT_EQ(static_cast<std::int64_t>(hc.fu.range().to_uint64()), bc.fu)
          << g[0] << ", " << g[1] << ", " << g[2];
      ASSERT_EQ(static_cast<std::int64_t>(hc.fv.range().to_uint64()), bc.fv)
          << g[0] << ", " << g[1] << ", " << g[2];
    }
    const hls::Reflect<ProfileTraits<kP>> hr = hls_reflect(g);
    const bt::BtReflect br = bt::bt_reflectance(fs_, g);
    ASSERT_EQ(hr.D.to_double(), br.D) << g[0] << ", " << g[1] << ", " << g[2];
    ASSERT_EQ(hr.S.to_double(), br.S) << g[0] << ", " << g[1] << ", " << g[2];
  }

  // Table layout (§5.3, §5.5): entry (i, j) of a face; a cell index decoded into the
  // face and the cell (i, j) (in bilinear mode the index of the cell's lower corner).
  static int entry_index(int face, int i, int j) { return (face * kSide + j) * kSide + i; }
  struct CellRef {
    int face, i, j;
  };
  static CellRef decode(int index) {
    return {index / (kSide * kSide), index % kSide, (index / kSide) % kSide};
  }
  // The unit normal at grid position (s, t) of a face, in cells from its low edges
  // (§5.4: the cell centre is (i + 1/2, j + 1/2); §5.5: corner (i, j) is (i, j)).
  static ref::Vec3 face_point(int face, double s, double t) {
    const int m = face / 2, a = m == 0 ? 1 : 0, b = m == 2 ? 1 : 2;
    ref::Vec3 n(0.0);
    n[m] = (face & 1) ? -1.0 : 1.0;
    n[a] = s * 2.0 / kRes - 1.0;
    n[b] = t * 2.0 / kRes - 1.0;
    return glm::normalize(n);
  }
  static ref::Vec3 cell_point(const CellRef& c, double du, double dv) {
    return face_point(c.face, c.i + du, c.j + dv);
  }
  // Largest distance from the cell centre to a point of the cell: at a corner (the
  // cell is a convex spherical quadrilateral much smaller than a hemisphere).
  static double cell_radius(const CellRef& c) {
    const ref::Vec3 centre = cell_point(c, 0.5, 0.5);
    double r = 0.0;
    for (const double du : {0.0, 1.0})
      for (const double dv : {0.0, 1.0})
        r = std::max(r, glm::length(cell_point(c, du, dv) - centre));
    return r;
  }

  // The gradient whose normal N = -g is exactly at grid position (s2/2, t2/2) of a face
  // (s2, t2 in half cells): |N[m]| = rm_res, N[a] = s2 - rm_res, N[b] = t2 - rm_res, so
  // (N[a] + |N[m]|)·rm_res / (2|N[m]|) = s2/2 exactly. Integers: on every sf grid.
  static G3 grid_gradient(int face, int s2, int t2) {
    const int m = face / 2, a = m == 0 ? 1 : 0, b = m == 2 ? 1 : 2;
    G3 n{};
    n[static_cast<std::size_t>(m)] = (face & 1) ? -kRes : kRes;
    n[static_cast<std::size_t>(a)] = s2 - kRes;
    n[static_cast<std::size_t>(b)] = t2 - kRes;
    return {-n[0], -n[1], -n[2]};
  }
  // Raw entries of the tables.
  std::int64_t raw_d(int index) const { return fs_.rm_diffuse[static_cast<std::size_t>(index)]; }
  std::int64_t raw_s(int index) const { return fs_.rm_specular[static_cast<std::size_t>(index)]; }
  static double from_raw(std::int64_t v) { return bt::from_raw(v, kP.rm_frac_bits); }

  ref::ShadingSetup shading_;
  bt::FrameSetup fs_;
  std::unique_ptr<hls::ReflectanceMap<ProfileTraits<kP>>> map_;
  hls::ReflectanceRegisters<ProfileTraits<kP>> regs_;
  ref::Vec3 world_scale_{1.0};
};
TYPED_TEST_SUITE(ReflectanceMapTest, Presets, PresetNames);

// The closed forms of the corner grid (§5.5), for the bilinear profiles only.
template <class T>
class BilinearReflectanceMapTest : public ReflectanceMapTest<T> {
  static_assert(ReflectanceMapTest<T>::kBilinear);
};
using BilinearProfiles = ::testing::Types<Profile<kBalanced>, Profile<kPrecise>,
                                          Profile<kVizard2Bilinear>, Profile<kOddBilinear>,
                                          Profile<kOneCellBilinear>>;
struct BilinearNames {
  template <class T>
  static std::string GetName(int i) {
    static const char* const names[] = {"balanced", "precise", "vizard2_bilinear",
                                        "odd_bilinear", "one_cell_bilinear"};
    return names[i];
  }
};
TYPED_TEST_SUITE(BilinearReflectanceMapTest, BilinearProfiles, BilinearNames);

// ---- (a) bit-exact against the bit-true reference ----------------------------------------

// Every cell, reached by (minus) its centre direction at a large magnitude, isotropic and
// anisotropic; isotropic, the centre direction lands in its own cell (c) (bilinear: at the
// in-cell position of the quantized direction, near 1/2).
TYPED_TEST(ReflectanceMapTest, EveryCellMatchesBitTrue) {
  constexpr PrecisionProfile P = TestFixture::kP;
  constexpr int res = TestFixture::kRes;
  const double scale = std::ldexp(1.0, P.gradient_bits - P.gradient_frac_bits - 2);
  for (const ref::Vec3& ws : kWorldScales) {
    this->use_world_scale(ws);
    for (int face = 0; face < 6; ++face)
      for (int j = 0; j < res; ++j)
        for (int i = 0; i < res; ++i) {
          const ref::Vec3 n = TestFixture::face_point(face, i + 0.5, j + 0.5);
          const G3 g = {TestFixture::on_grid(-n.x * scale), TestFixture::on_grid(-n.y * scale),
                        TestFixture::on_grid(-n.z * scale)};
          this->expect_same(g);
          if (ws == kWorldScales[0]) {
            ASSERT_EQ(static_cast<int>(this->hls_cell(g).index.to_uint()),
                      TestFixture::entry_index(face, i, j));
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
// Common to both modes, with n = surface_normal(g) (the truth) and n_N the direction of the
// unit's normal N = -gw:
//   * world scaling: |gw[k] - g[k]/ws[k]| <= e[k] = 2^-(sf+1) + |g[k]|·2^-(df+1) (IS and gw
//     each round once), and the perturbed normal moves by d_e = |n_N - n| <= 2|e|/|g/ws|;
//   * D(n) = sum I_l max(0, n·L_l) is I_l-Lipschitz per light (chord distance);
//   * S(n) = sum I_l [n·L_l > 0] max(0, n·H_l)^k: between two points x·H is linear along the
//     chord, so the ungated term changes by at most k·h^(k-1)·|chord|, h = max(0, x·H at the
//     ends), and where the ends differ in the sign of n·L the gate jumps by at most h^k;
//   * an entry is SAT(Q_RND(·, rm_frac_bits), 0, max): 2^-(rm_frac_bits+1) plus what the
//     saturation cuts off above max = 2^rm_int_bits - 2^-rm_frac_bits.
//
// Nearest (§5.3-5.4), n_c the centre of the cell the unit picks: N lies in the closed cell,
// within the cell radius r_c (largest centre-to-corner distance) of n_c, so
// |n - n_c| <= d = r_c + d_e; the error is the entry's plus the Lipschitz and jump terms over
// d: O(h) in the cell size h = 2/rm_res.
//
// Bilinear (§5.5), on the picked face's plane, x_q = the quantized position (i + fu, j + fv),
// n_q its direction, c_0..3 the cell's corner directions, w_c their weights (convex):
//   |out - f(n)| <= 2^-(rf+1)                                (the final Q_RND)
//                 + max_c (2^-(rf+1) + saturation at c)        (sum w_c (E_c - f(c)))
//                 + |sum w_c f(c) - f(n_q)|                    (interpolation, E_I)
//                 + |f(n_q) - f(n)|                            (position: chord <= d_q + d_e)
// with d_q = |n_q - n_N| <= |x_q - x_N| < sqrt(2)·2^(1-wb)/rm_res (the position truncates to
// wb fraction bits of a cell; the plane-to-sphere map p -> p/|p| is 1/|p| <= 1 Lipschitz).
// E_I, per light (the blend is linear in f): on the face plane, with r = |(u, v, ±1)|,
//   n_u = (e_u - n (n·e_u))/r,  |n_u| <= 1/r,  n_uu = (-2 r (n·e_u) n_u - n (1 - (n·e_u)^2))/r^2,
//   the two parts orthogonal, so |n_uu| <= sqrt((1 - y)(1 + 3y))/r^2 <= (2/sqrt 3)/r^2
//   (y = (n·e_u)^2, the maximum at y = 1/3); likewise in v. Then
//   * the cell entirely lit (n·L > 0 on it: c·L - R > 0, c the centre, R the cell radius):
//     f_l is C^1 with bounded second derivatives (k >= 2), |(n·L)_uu| <= (2/sqrt 3)/r^2 and
//     |((n·H)^k)_uu| <= k(k-1) x^(k-2) (n_u·H)^2 + k x^(k-1) |n_uu|
//                    <= [k(k-1) x^(k-2) (1 - x^2) + k x^(k-1) 2/sqrt 3] / r^2
//     (x = n·H in [c·H - R, c·H + R] ∩ [0, 1]; n_u ⊥ n, so |n_u·H| <= |n_u| sqrt(1 - x^2)), and
//     tensor-product linear interpolation errs by at most
//     E_I <= fu(1 - fu)·h^2/2·sup|f_uu| + fv(1 - fv)·h^2/2·sup|f_vv|:  O(h^2);
//   * the cell entirely unlit (c·L + R <= 0): f_l = 0 on it, E_I = 0;
//   * the cell straddling the terminator n·L = 0: E_I <= max_c |f_l(c) - f_l(n_q)|, the
//     Lipschitz and jump terms over max_c |n_c - n_q|: O(h), on a band of cells only.
TYPED_TEST(ReflectanceMapTest, WithinDerivedBoundOfFloatReflectance) {
  constexpr PrecisionProfile P = TestFixture::kP;
  constexpr int res = TestFixture::kRes;
  const double half_entry = std::ldexp(1.0, -(P.rm_frac_bits + 1));
  const double entry_max = std::ldexp(1.0, P.rm_int_bits) - std::ldexp(1.0, -P.rm_frac_bits);
  const double k = this->shading_.shininess;
  ASSERT_GE(k, 2.0);  // the specular lobe is C^1 with a bounded second derivative
  double sum_i = 0.0;
  for (const auto& t : this->shading_.lights) sum_i += t.intensity;
  const double two_over_sqrt3 = 2.0 / std::sqrt(3.0);
  // max of x^(k-2) (1 - x^2) over [lo, hi] (increasing up to x* = sqrt((k-2)/k), then falling).
  const auto lobe_curvature = [k](double lo, double hi) {
    const double x = std::clamp(std::sqrt((k - 2.0) / k), lo, hi);
    return std::pow(x, k - 2.0) * (1.0 - x * x);
  };
  const double slack = 1e-12;  // the float reference's own rounding

  std::mt19937_64 rng(0xB0B);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> log_mag(
      4.0, std::log2(TestFixture::g_limit()) + P.sample_frac_bits);
  double worst_d = 0.0, worst_s = 0.0, worst_d_ratio = 0.0, worst_s_ratio = 0.0;
  // Gradients of at least 1/16 of the field's limit: the cell size dominates the error.
  double worst_d_large = 0.0, worst_s_large = 0.0;
  // Bilinear, large gradients, cells on one side of every terminator: the O(h²) part.
  double worst_d_smooth = 0.0, worst_s_smooth = 0.0;
  for (const ref::Vec3& ws : kWorldScales) {
    this->use_world_scale(ws);
    for (int n = 0; n < 40000; ++n) {
      bool smooth = TestFixture::kBilinear;
      const ref::Vec3 dir = glm::normalize(ref::Vec3(normal(rng), normal(rng), normal(rng)));
      const double mag = std::ldexp(std::exp2(log_mag(rng)), -P.sample_frac_bits);
      const ref::Vec3 g(TestFixture::on_grid(dir.x * mag), TestFixture::on_grid(dir.y * mag),
                        TestFixture::on_grid(dir.z * mag));
      const ref::Vec3 gw = g / ws;
      if (glm::length(gw) == 0.0) continue;
      const hls::RmCell<ProfileTraits<P>> cell = this->hls_cell({g.x, g.y, g.z});
      ASSERT_TRUE(cell.valid);
      const typename TestFixture::CellRef cr =
          TestFixture::decode(static_cast<int>(cell.index.to_uint()));
      const hls::Reflect<ProfileTraits<P>> got = this->hls_reflect({g.x, g.y, g.z});

      const ref::Vec3 nt = ref::surface_normal(g, ws);
      const ref::Reflectance want = ref::reflectance(this->shading_, nt);

      double e2 = 0.0;
      for (int a = 0; a < 3; ++a) {
        const double e = std::ldexp(1.0, -(P.sample_frac_bits + 1)) +
                         std::abs(g[a]) * std::ldexp(1.0, -(P.dir_frac_bits + 1));
        e2 += e * e;
      }
      const double d_e = std::min(2.0, 2.0 * std::sqrt(e2) / glm::length(gw));
      const ref::Vec3 centre = TestFixture::cell_point(cr, 0.5, 0.5);
      const double r_c = TestFixture::cell_radius(cr);

      double bound_d = 0.0, bound_s = 0.0;
      if constexpr (!TestFixture::kBilinear) {
        const ref::Reflectance at_centre = ref::reflectance(this->shading_, centre);
        const double d = r_c + d_e;
        bound_d = half_entry + std::max(0.0, at_centre.diffuse - entry_max) + sum_i * d;
        bound_s = half_entry + std::max(0.0, at_centre.specular - entry_max);
        for (const auto& t : this->shading_.lights) {
          const double h = std::max({0.0, glm::dot(nt, t.halfway), glm::dot(centre, t.halfway)});
          bound_s += t.intensity * k * std::pow(h, k - 1.0) * d;
          if ((glm::dot(nt, t.light) > 0.0) != (glm::dot(centre, t.light) > 0.0))
            bound_s += t.intensity * std::pow(h, k);
        }
      } else {
        const double fu = cell.fu.to_double(), fv = cell.fv.to_double();
        ASSERT_GE(fu, 0.0);
        ASSERT_LE(fu, 1.0);
        ASSERT_GE(fv, 0.0);
        ASSERT_LE(fv, 1.0);
        const ref::Vec3 nq = TestFixture::cell_point(cr, fu, fv);
        std::array<ref::Vec3, 4> corner;
        double sat_d = 0.0, sat_s = 0.0, reach = 0.0;  // reach: max_c |n_c - n_q|
        for (int c = 0; c < 4; ++c) {
          corner[static_cast<std::size_t>(c)] = TestFixture::cell_point(cr, c & 1, c >> 1);
          const ref::Reflectance rc =
              ref::reflectance(this->shading_, corner[static_cast<std::size_t>(c)]);
          sat_d = std::max(sat_d, rc.diffuse - entry_max);
          sat_s = std::max(sat_s, rc.specular - entry_max);
          reach = std::max(reach, glm::length(corner[static_cast<std::size_t>(c)] - nq));
        }
        // 1/r^2 over the cell: r^2 = 1 + u^2 + v^2 is smallest at the cell's point nearest
        // the face centre.
        const auto min_abs = [](double lo, double hi) {
          return (lo <= 0.0 && hi >= 0.0) ? 0.0 : std::min(std::abs(lo), std::abs(hi));
        };
        const double h = 2.0 / res;
        const double umin = min_abs(cr.i * h - 1.0, (cr.i + 1) * h - 1.0);
        const double vmin = min_abs(cr.j * h - 1.0, (cr.j + 1) * h - 1.0);
        const double curv = h * h / 2.0 * (fu * (1.0 - fu) + fv * (1.0 - fv)) /
                            (1.0 + umin * umin + vmin * vmin);
        const double d_q = std::sqrt(2.0) * std::ldexp(1.0, 1 - P.rm_weight_bits) / res;
        const double d_pos = d_q + d_e;

        bound_d = 2.0 * half_entry + std::max(0.0, sat_d);
        bound_s = 2.0 * half_entry + std::max(0.0, sat_s);
        for (const auto& t : this->shading_.lights) {
          const double cl = glm::dot(centre, t.light), ch = glm::dot(centre, t.halfway);
          const double x_lo = std::clamp(ch - r_c, 0.0, 1.0), x_hi = std::clamp(ch + r_c, 0.0, 1.0);
          const double I = t.intensity;
          // E_I.
          if (cl - r_c > 0.0) {
            bound_d += I * two_over_sqrt3 * curv;
            bound_s += I *
                       (k * (k - 1.0) * lobe_curvature(x_lo, x_hi) +
                        k * std::pow(x_hi, k - 1.0) * two_over_sqrt3) *
                       curv;
          } else if (cl + r_c > 0.0) {
            smooth = false;
            bound_d += I * reach;
            bound_s += I * (k * std::pow(x_hi, k - 1.0) * reach + std::pow(x_hi, k));
          }
          // Position: the chord from n to n_q.
          const double hp = std::max({0.0, glm::dot(nt, t.halfway), glm::dot(nq, t.halfway)});
          bound_d += I * d_pos;
          bound_s += I * k * std::pow(hp, k - 1.0) * d_pos;
          if ((glm::dot(nt, t.light) > 0.0) != (glm::dot(nq, t.light) > 0.0))
            bound_s += I * std::pow(hp, k);
        }
      }
      bound_d += slack;
      bound_s += slack;
      const double err_d = std::abs(got.D.to_double() - want.diffuse);
      const double err_s = std::abs(got.S.to_double() - want.specular);
      ASSERT_LE(err_d, bound_d) << "g = " << g.x << ", " << g.y << ", " << g.z;
      ASSERT_LE(err_s, bound_s) << "g = " << g.x << ", " << g.y << ", " << g.z;
      worst_d = std::max(worst_d, err_d);
      worst_s = std::max(worst_s, err_s);
      if (glm::length(g) >= TestFixture::g_limit() / 16) {
        worst_d_large = std::max(worst_d_large, err_d);
        worst_s_large = std::max(worst_s_large, err_s);
        if (smooth) {
          worst_d_smooth = std::max(worst_d_smooth, err_d);
          worst_s_smooth = std::max(worst_s_smooth, err_s);
        }
      }
      worst_d_ratio = std::max(worst_d_ratio, err_d / bound_d);
      worst_s_ratio = std::max(worst_s_ratio, err_s / bound_s);
    }
  }
  this->RecordProperty("worst_D_error", std::to_string(worst_d));
  this->RecordProperty("worst_S_error", std::to_string(worst_s));
  this->RecordProperty("worst_D_error_large_gradient", std::to_string(worst_d_large));
  this->RecordProperty("worst_S_error_large_gradient", std::to_string(worst_s_large));
  if (TestFixture::kBilinear) {
    this->RecordProperty("worst_D_error_large_gradient_smooth_cell", std::to_string(worst_d_smooth));
    this->RecordProperty("worst_S_error_large_gradient_smooth_cell", std::to_string(worst_s_smooth));
  }
  this->RecordProperty("worst_D_error_over_bound", std::to_string(worst_d_ratio));
  this->RecordProperty("worst_S_error_over_bound", std::to_string(worst_s_ratio));
}

// ---- (c) closed forms ------------------------------------------------------------------------

// Nearest: an axis direction lands in cell iu = iv = floor(rm_res/2) of its face, at any
// magnitude. Bilinear: t_u = t_v = rm_res/2; for an even rm_res that is the face-centre corner
// (rm_res/2, rm_res/2), read unchanged (weights (1, 0, 0, 0)); for an odd one the centre of
// cell ((rm_res-1)/2, (rm_res-1)/2), fu = fv = 1/2, which reads the rounded mean of its
// four corners.
TYPED_TEST(ReflectanceMapTest, AxisDirectionsLandInTheCentreOfTheirFace) {
  constexpr PrecisionProfile P = TestFixture::kP;
  constexpr int res = TestFixture::kRes;
  constexpr int side = TestFixture::kSide;
  for (const ref::Vec3& ws : kWorldScales) {
    this->use_world_scale(ws);
    for (int face = 0; face < 6; ++face) {
      for (const double mag : {TestFixture::lsb() * 2, 1.0, TestFixture::g_limit()}) {
        G3 g = {0.0, 0.0, 0.0};
        // N = -gw points along +axis on face 2m, -axis on face 2m + 1.
        g[static_cast<std::size_t>(face / 2)] = (face & 1) ? mag : -mag;
        const hls::RmCell<ProfileTraits<P>> cell = this->hls_cell(g);
        ASSERT_TRUE(cell.valid);
        const int c = res / 2;
        const int index = static_cast<int>(cell.index.to_uint());
        EXPECT_EQ(index, TestFixture::entry_index(face, c, c))
            << "face " << face << " magnitude " << mag;
        const hls::Reflect<ProfileTraits<P>> r = this->hls_reflect(g);
        if (!TestFixture::kBilinear || res % 2 == 0) {
          EXPECT_EQ(cell.fu.to_double(), 0.0);
          EXPECT_EQ(cell.fv.to_double(), 0.0);
          EXPECT_EQ(r.D.to_double(), TestFixture::from_raw(this->raw_d(index)));
          EXPECT_EQ(r.S.to_double(), TestFixture::from_raw(this->raw_s(index)));
        } else {
          EXPECT_EQ(cell.fu.to_double(), 0.5);
          EXPECT_EQ(cell.fv.to_double(), 0.5);
          const int quad[4] = {index, index + 1, index + side, index + side + 1};
          std::int64_t sd = 0, ss = 0;
          for (const int q : quad) sd += this->raw_d(q), ss += this->raw_s(q);
          EXPECT_EQ(r.D.to_double(), TestFixture::from_raw((sd + 2) >> 2));
          EXPECT_EQ(r.S.to_double(), TestFixture::from_raw((ss + 2) >> 2));
        }
        this->expect_same(g);
      }
    }
  }
}

// Bilinear: the exact centre direction of every cell (t = i + 1/2) reads the rounded mean of
// the cell's four corner entries, Q_RND((E00 + E10 + E01 + E11)/4, rm_frac_bits).
TYPED_TEST(BilinearReflectanceMapTest, CellCentresReadTheMeanOfTheirCorners) {
  constexpr PrecisionProfile P = TestFixture::kP;
  constexpr int res = TestFixture::kRes;
  constexpr int side = TestFixture::kSide;
  for (int face = 0; face < 6; ++face)
    for (int j = 0; j < res; ++j)
      for (int i = 0; i < res; ++i) {
        const G3 g = TestFixture::grid_gradient(face, 2 * i + 1, 2 * j + 1);
        const hls::RmCell<ProfileTraits<P>> cell = this->hls_cell(g);
        const int index = TestFixture::entry_index(face, i, j);
        ASSERT_EQ(static_cast<int>(cell.index.to_uint()), index);
        ASSERT_EQ(cell.fu.to_double(), 0.5);
        ASSERT_EQ(cell.fv.to_double(), 0.5);
        const int quad[4] = {index, index + 1, index + side, index + side + 1};
        std::int64_t sd = 0, ss = 0;
        for (const int q : quad) sd += this->raw_d(q), ss += this->raw_s(q);
        const hls::Reflect<ProfileTraits<P>> r = this->hls_reflect(g);
        ASSERT_EQ(r.D.to_double(), TestFixture::from_raw((sd + 2) >> 2));
        ASSERT_EQ(r.S.to_double(), TestFixture::from_raw((ss + 2) >> 2));
        this->expect_same(g);
      }
}

// Bilinear: the direction of every corner (i, j), 0 <= i, j <= rm_res, reads that corner's
// entry unchanged: weights (1, 0, 0, 0), or fu = 1 / fv = 1 at the clamped last cell. On a
// cube edge the tie goes to the lower axis, i.e. possibly to the neighbouring face, whose
// corner there is the same direction: its entries are equal (the map is continuous).
TYPED_TEST(BilinearReflectanceMapTest, CornerDirectionsReadTheirOwnEntry) {
  constexpr PrecisionProfile P = TestFixture::kP;
  constexpr int res = TestFixture::kRes;
  for (int face = 0; face < 6; ++face)
    for (int j = 0; j <= res; ++j)
      for (int i = 0; i <= res; ++i) {
        const G3 g = TestFixture::grid_gradient(face, 2 * i, 2 * j);
        const int index = TestFixture::entry_index(face, i, j);
        const hls::RmCell<ProfileTraits<P>> cell = this->hls_cell(g);
        const bool interior = i > 0 && i < res && j > 0 && j < res;
        if (interior) {
          ASSERT_EQ(static_cast<int>(cell.index.to_uint()), index);
          ASSERT_EQ(cell.fu.to_double(), 0.0);
          ASSERT_EQ(cell.fv.to_double(), 0.0);
        }
        const hls::Reflect<ProfileTraits<P>> r = this->hls_reflect(g);
        ASSERT_EQ(r.D.to_double(), TestFixture::from_raw(this->raw_d(index)))
            << "face " << face << " corner " << i << ", " << j;
        ASSERT_EQ(r.S.to_double(), TestFixture::from_raw(this->raw_s(index)))
            << "face " << face << " corner " << i << ", " << j;
        this->expect_same(g);
      }
}

// Ties go to the lower axis; N[a] = |N[m]| is clamped to the last cell (bilinear: with
// fu = 1), N[a] = -|N[m]| is cell 0 (fu = 0).
TYPED_TEST(ReflectanceMapTest, TiesAndTheEdgeClamp) {
  constexpr int res = TestFixture::kRes;
  constexpr int c = res / 2 < res - 1 ? res / 2 : res - 1;  // the cell of N[a] = 0
  const auto index = [this](const G3& g) {
    return static_cast<int>(this->hls_cell(g).index.to_uint());
  };
  // N = (1, 1, 0): major axis x (face 0), iu (axis y) clamped to res - 1, iv (axis z) centre.
  EXPECT_EQ(index({-1.0, -1.0, 0.0}), TestFixture::entry_index(0, res - 1, c));
  // N = (1, -1, 0): iu = 0.
  EXPECT_EQ(index({-1.0, 1.0, 0.0}), TestFixture::entry_index(0, 0, c));
  // N = (0, -1, -1): major axis y (face 3), iu (axis x) centre, iv (axis z) = 0.
  EXPECT_EQ(index({0.0, 1.0, 1.0}), TestFixture::entry_index(3, c, 0));
  // N = (-1, 1, 1): major axis x (face 1); u (axis y) and v (axis z) clamp to res - 1.
  EXPECT_EQ(index({1.0, -1.0, -1.0}), TestFixture::entry_index(1, res - 1, res - 1));
  if constexpr (TestFixture::kBilinear) {
    EXPECT_EQ(this->hls_cell({-1.0, -1.0, 0.0}).fu.to_double(), 1.0);
    EXPECT_EQ(this->hls_cell({-1.0, 1.0, 0.0}).fu.to_double(), 0.0);
    EXPECT_EQ(this->hls_cell({0.0, 1.0, 1.0}).fv.to_double(), 0.0);
    EXPECT_EQ(this->hls_cell({1.0, -1.0, -1.0}).fu.to_double(), 1.0);
    EXPECT_EQ(this->hls_cell({1.0, -1.0, -1.0}).fv.to_double(), 1.0);
  }
  for (const G3& g : {G3{-1.0, -1.0, 0.0}, G3{-1.0, 1.0, 0.0}, G3{0.0, 1.0, 1.0},
                      G3{1.0, -1.0, -1.0}})
    this->expect_same(g);
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
  using Params = hls::ReflectanceParams<ProfileTraits<kVizard2>>;
  static_assert(!Params::bilinear);
  static_assert(Params::entries == 6 * 16 * 16);
  static_assert(Params::entry_bits == 8);
  EXPECT_EQ(2 * Params::entries * Params::entry_bits / 8, 3 * 1024);
  std::vector<std::uint32_t> d, s;
  bt::make_reflectance_maps(kVizard2, scene_shading(), d, s);
  EXPECT_EQ(d.size() + s.size(), 3u * 1024u);  // one byte per entry
  for (std::size_t i = 0; i < d.size(); ++i) {
    ASSERT_LT(d[i], 256u);
    ASSERT_LT(s[i], 256u);
  }
}

// Bilinear maps hold the corner grid, 6·(rm_res+1)² entries per table (§5.5): balanced
// 6·33² x 14 bits x 2 tables = 22,869 bytes, precise 6·65² x 18 bits x 2 = 114,075 bytes.
TEST(ReflectanceMapBilinear, TablesHoldTheCornerGrid) {
  using B = hls::ReflectanceParams<ProfileTraits<kBalanced>>;
  using Pr = hls::ReflectanceParams<ProfileTraits<kPrecise>>;
  static_assert(B::bilinear && B::entries == 6 * 33 * 33 && B::entry_bits == 14);
  static_assert(Pr::bilinear && Pr::entries == 6 * 65 * 65 && Pr::entry_bits == 18);
  EXPECT_EQ(2 * B::entries * B::entry_bits / 8, 22869);
  EXPECT_EQ(2 * Pr::entries * Pr::entry_bits / 8, 114075);
  for (const PrecisionProfile& p : {kBalanced, kPrecise, kOddBilinear, kOneCellBilinear}) {
    std::vector<std::uint32_t> d, s;
    bt::make_reflectance_maps(p, scene_shading(), d, s);
    const auto n = static_cast<std::size_t>(6 * (p.rm_res + 1) * (p.rm_res + 1));
    EXPECT_EQ(d.size(), n);
    EXPECT_EQ(s.size(), n);
    const std::uint32_t top = (1u << (p.rm_int_bits + p.rm_frac_bits)) - 1u;
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_LE(d[i], top);
      ASSERT_LE(s[i], top);
    }
  }
}

}  // namespace
