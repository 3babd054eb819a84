// Address generator and interpolation processor (docs/pipeline.md §3), the
// three checks of STYLE.md:
//  (a) hls/interpolation_processor.hpp == refmodel/bittrue/interpolation.cpp on
//      every bit (value and the 3 gradient components) at random positions
//      (inside, on and outside the box), on odd, even and 1-voxel dimensions,
//      with crop boxes, through both bank views, and along whole rays
//      (ray setup + stepping + interpolation, hls::march_ray), all three presets;
//  (b) fixed point against ref::interpolate within a bound derived from the
//      weight and sample widths;
//  (c) 8-way interleaving: every 2x2x2 neighbourhood of small odd-sized volumes
//      reads 8 distinct banks, each at the word of the right voxel.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "hls/geometry_processor.hpp"
#include "hls/host_march.hpp"
#include "hls/interpolation_processor.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/geometry.hpp"
#include "refmodel/bittrue/interpolation.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/preset_profiles.hpp"
#include "refmodel/render/camera.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/volume/gradients.hpp"
#include "refmodel/volume/volume.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast;
using bittrue::Raw;
using ref::Vec3;

// ---- Volumes ----------------------------------------------------------------------------------
struct TestVolume {
  ref::Volume volume;
  ref::GradientField gradients;
};

// Random values in [0, max_value]; central-difference gradients (|g| <= max/2,
// which fits every preset's gradient field when max_value <= 2^vb - 2).
std::unique_ptr<TestVolume> random_volume(std::array<int, 3> dims, int bits,
                                          std::uint32_t max_value, std::uint32_t seed) {
  auto t = std::make_unique<TestVolume>();
  ref::Volume& v = t->volume;
  v.dims = dims;
  v.bits = bits;
  v.source = "random test volume";
  v.data.resize(v.voxel_count());
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::uint32_t> dist(0, max_value);
  for (auto& x : v.data) x = static_cast<std::uint16_t>(dist(rng));
  t->gradients = ref::compute_gradients(v, ref::GradientOperator::Central);
  return t;
}

// A smooth volume: a linear ramp plus a gentle sine, values within [0, max_value].
std::unique_ptr<TestVolume> smooth_volume(std::array<int, 3> dims, int bits,
                                          std::uint32_t max_value) {
  auto t = std::make_unique<TestVolume>();
  ref::Volume& v = t->volume;
  v.dims = dims;
  v.bits = bits;
  v.source = "smooth test volume";
  v.data.resize(v.voxel_count());
  const double scale = max_value / 2.0;
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x) {
        const double f = (x + 2.0 * y + 3.0 * z) / (dims[0] + 2.0 * dims[1] + 3.0 * dims[2]) +
                         0.9 * std::sin(0.3 * x + 0.2 * y - 0.25 * z);
        v.data[v.index(x, y, z)] = static_cast<std::uint16_t>(std::lround(scale * (1.0 + f / 1.9)));
      }
  t->gradients = ref::compute_gradients(v, ref::GradientOperator::Central);
  return t;
}

bittrue::FrameRegisters box_registers(const std::array<int, 3>& dims, const std::array<int, 3>& lo,
                                      const std::array<int, 3>& hi) {
  bittrue::FrameRegisters r;
  r.dims = dims;
  r.LO = lo;
  r.HI = hi;
  return r;
}
bittrue::FrameRegisters box_registers(const std::array<int, 3>& dims) {
  return box_registers(dims, {0, 0, 0}, {dims[0] - 1, dims[1] - 1, dims[2] - 1});
}

// The packed words of a VoxelMemory (§3.4 layout), for hls::PackedBanks.
template <PrecisionProfile P>
struct PackedMemory {
  using word_t = typename hls::InterpolationParams<ProfileTraits<P>>::packed_word_t;
  std::array<std::vector<word_t>, 8> words;
  hls::PackedBanks<ProfileTraits<P>> banks;
  explicit PackedMemory(const bittrue::VoxelMemory& mem) {
    const hls::host::BitTrueBanks<ProfileTraits<P>> view(mem);
    for (int b = 0; b < 8; ++b) {
      const auto ib = static_cast<std::size_t>(b);
      for (std::size_t w = 0; w < mem.banks[ib].size(); ++w)
        words[ib].push_back(hls::pack_voxel_word<ProfileTraits<P>>(
            view.read(b, typename hls::InterpolationParams<ProfileTraits<P>>::word_addr_t(w))));
      banks.bank[b] = words[ib].data();
    }
  }
};

template <class P>
std::array<double, 4> as_doubles(const hls::Sample<P>& s) {
  return {s.value.to_double(), s.g[0].to_double(), s.g[1].to_double(), s.g[2].to_double()};
}
std::array<double, 4> as_doubles(const bittrue::BtSample& s) {
  return {s.value, s.g[0], s.g[1], s.g[2]};
}

// ---- (a) bit-exact at positions --------------------------------------------------------------
struct BoxCase {
  std::array<int, 3> dims;
  std::array<int, 3> lo, hi;
};

template <PrecisionProfile P>
void check_positions_bit_exact(const BoxCase& c, std::uint32_t seed) {
  SCOPED_TRACE(::testing::Message()
               << "dims " << c.dims[0] << "x" << c.dims[1] << "x" << c.dims[2]);
  using G = hls::GeometryParams<ProfileTraits<P>>;
  const std::uint32_t vmax = (std::uint32_t{1} << P.value_bits) - 1u;
  // Full range, so that gradients saturate in the narrow presets too.
  const auto tv = random_volume(c.dims, P.value_bits, vmax, seed);
  const bittrue::VoxelMemory mem = bittrue::make_voxel_memory(P, tv->volume, tv->gradients);
  const bittrue::FrameRegisters fr = box_registers(c.dims, c.lo, c.hi);
  const auto regs = hls::host::load_geometry_registers<ProfileTraits<P>>(fr);
  const hls::host::BitTrueBanks<ProfileTraits<P>> view(mem);
  const PackedMemory<P> packed(mem);

  std::mt19937 rng(seed + 1);
  const Raw one = Raw{1} << P.pos_frac_bits;
  std::vector<std::array<Raw, 3>> positions;
  for (int i = 0; i < 3000; ++i) {
    std::array<Raw, 3> r{};
    for (std::size_t k = 0; k < 3; ++k) {
      // Mostly inside, some up to 0.7 voxel outside (clamped), some on the grid.
      std::uniform_int_distribution<Raw> d(c.lo[k] * one - 7 * one / 10,
                                           c.hi[k] * one + 7 * one / 10);
      r[k] = d(rng);
      if (i % 5 == 0) r[k] = (r[k] / one) * one;            // integer positions
      if (i % 7 == 0) r[k] = (r[k] / one) * one + one / 2;  // cell centres
    }
    positions.push_back(r);
  }
  positions.push_back({c.hi[0] * one, c.hi[1] * one, c.hi[2] * one});  // the last voxel
  positions.push_back({c.lo[0] * one, c.lo[1] * one, c.lo[2] * one});

  for (const auto& r : positions) {
    typename G::pos_t p[3];
    std::array<double, 3> pd{};
    for (int k = 0; k < 3; ++k) {
      p[k] = hls::host::from_raw_bits<typename G::pos_t>(r[static_cast<std::size_t>(k)]);
      pd[static_cast<std::size_t>(k)] = p[k].to_double();
    }
    SCOPED_TRACE(::testing::Message() << "p = (" << pd[0] << ", " << pd[1] << ", " << pd[2] << ")");
    const auto b = as_doubles(bittrue::bt_interpolate(P, fr, mem, pd));
    ASSERT_EQ(as_doubles(hls::interpolate<ProfileTraits<P>>(regs, view, p)), b);
    ASSERT_EQ(as_doubles(hls::interpolate<ProfileTraits<P>>(regs, packed.banks, p)), b);
  }
}

template <PrecisionProfile P>
void check_all_positions_bit_exact() {
  const std::vector<BoxCase> cases = {
      {{7, 5, 9}, {0, 0, 0}, {6, 4, 8}},    // odd dims
      {{8, 6, 4}, {0, 0, 0}, {7, 5, 3}},    // even dims
      {{11, 9, 10}, {2, 1, 3}, {9, 7, 6}},  // crop box
      {{1, 6, 4}, {0, 0, 0}, {0, 5, 3}},    // a 1-voxel axis
      {{13, 1, 1}, {0, 0, 0}, {12, 0, 0}},  // a line
      {{2, 2, 2}, {0, 0, 0}, {1, 1, 1}},    // one cell
      {{1, 1, 1}, {0, 0, 0}, {0, 0, 0}},    // one voxel
  };
  std::uint32_t seed = 11;
  for (const BoxCase& c : cases) check_positions_bit_exact<P>(c, seed++);
}

TEST(InterpolationProcessor, BitExactVizard2) { check_all_positions_bit_exact<kVizard2>(); }
TEST(InterpolationProcessor, BitExactBalanced) { check_all_positions_bit_exact<kBalanced>(); }
TEST(InterpolationProcessor, BitExactPrecise) { check_all_positions_bit_exact<kPrecise>(); }

// sample_frac_bits < gradient_frac_bits: interpolated gradients round up past
// the largest stored value (the extra integer bit of gradient_t).
inline constexpr PrecisionProfile kCoarseSamples = [] {
  PrecisionProfile p;
  p.gradient_bits = 10;
  p.gradient_frac_bits = 4;
  p.sample_frac_bits = 1;
  p.weight_bits = 3;
  return p;
}();
TEST(InterpolationProcessor, BitExactCoarseSamples) {
  check_all_positions_bit_exact<kCoarseSamples>();
}

// ---- (a) bit-exact along rays: geometry + stepping + interpolation ----------------------------
template <PrecisionProfile P>
void check_rays_bit_exact(ref::Projection projection) {
  SCOPED_TRACE(projection == ref::Projection::Perspective ? "perspective" : "parallel");
  const std::uint32_t vmax = (std::uint32_t{1} << P.value_bits) - 2u;
  const auto tv = smooth_volume({21, 17, 19}, P.value_bits, vmax);
  ref::Scene scene;
  scene.tf_points = {ref::TfPoint{0.0, {1.0, 1.0, 1.0}, 0.5}};
  scene.volume.crop = ref::Crop{{1, 2, 0}, {19, 15, 17}};
  scene.render.width = 23;
  scene.render.height = 19;
  scene.render.oversampling = 1.5;
  scene.camera.projection = projection;
  scene.camera.fov_deg = 45.0;
  scene.camera.height = 30.0;
  const ref::CameraPose pose{{-12.0, -20.0, 30.0}, {10.0, 8.0, 9.0}, {0.0, 0.0, 1.0}};
  const ref::RenderInputs in = ref::make_render_inputs(scene, tv->volume, tv->gradients, pose);
  const bittrue::FrameRegisters fr = bittrue::make_frame_registers(P, scene, in);
  const std::vector<Raw> seed = bittrue::make_rsqrt_seed(P);
  const bittrue::VoxelMemory mem = bittrue::make_voxel_memory(P, tv->volume, tv->gradients);
  const auto regs = hls::host::load_geometry_registers<ProfileTraits<P>>(fr);
  auto rom = std::make_unique<hls::RsqrtRom<ProfileTraits<P>>>();
  hls::host::load_rsqrt_rom<ProfileTraits<P>>(seed, *rom);
  const hls::host::BitTrueBanks<ProfileTraits<P>> view(mem);

  std::uint64_t samples = 0;
  for (int py = 0; py < scene.render.height; ++py)
    for (int px = 0; px < scene.render.width; ++px) {
      SCOPED_TRACE(::testing::Message() << "pixel (" << px << ", " << py << ")");
      const hls::RaySetup<ProfileTraits<P>> h = hls::ray_setup<ProfileTraits<P>>(regs, rom->seed, px, py);
      const bittrue::BtRay b = bittrue::bt_ray_setup(P, fr, seed, px, py);
      ASSERT_EQ(h.n.to_uint64(), b.n);
      std::vector<std::array<double, 4>> hs;
      auto sink = [&hs](std::uint64_t, const auto&, const hls::Sample<ProfileTraits<P>>& s) {
        hs.push_back(as_doubles(s));
        return true;
      };
      hls::march_ray<ProfileTraits<P>>(regs, view, h, sink);
      ASSERT_EQ(hs.size(), b.n);
      std::array<double, 3> q = b.p0;
      for (std::uint64_t k = 0; k < b.n; ++k) {
        ASSERT_EQ(hs[k], as_doubles(bittrue::bt_interpolate(P, fr, mem, q))) << "sample " << k;
        q = bittrue::bt_step(q, b.s);
      }
      samples += b.n;
      // The sink ends the ray (early ray termination) after its third sample.
      if (b.n > 3) {
        std::uint64_t consumed = 0;
        auto stop = [&consumed](std::uint64_t k, const auto&, const hls::Sample<ProfileTraits<P>>&) {
          ++consumed;
          return k < 2;
        };
        hls::march_ray<ProfileTraits<P>>(regs, view, h, stop);
        ASSERT_EQ(consumed, 3u);
      }
    }
  EXPECT_GT(samples, 1000u);
}

TEST(InterpolationProcessor, BitExactAlongRays) {
  for (ref::Projection proj : {ref::Projection::Perspective, ref::Projection::Parallel}) {
    check_rays_bit_exact<kVizard2>(proj);
    check_rays_bit_exact<kBalanced>(proj);
    check_rays_bit_exact<kPrecise>(proj);
  }
}

// ---- (b) against the float reference ----------------------------------------------------------
// Derived bound. The exact trilinear interpolation T(fx, fy, fz) of the 8 corner
// values is affine in each weight, and its derivative along one axis is a
// bilinear interpolation of corner differences, so at most the corners' range R.
// Weight addressing moves each f by |Q_RND(f, wb) - f| <= 2^-(wb+1): the exact
// sum with quantized weights is within R·3·2^-(wb+1) of T(f); the one Q_RND to
// sf bits adds 2^-(sf+1):
//   |value - ref::interpolate(p).value| <= R_v·3·2^-(wb+1) + 2^-(sf+1).
// Gradients: the stored components are Q_RND(g, gfb) (no saturation for these
// volumes: |g| <= (2^vb - 2)/2 < 2^(gb-1-gfb) in every preset), each within
// 2^-(gfb+1) of the float gradient, and a convex combination keeps that:
//   |g - ref::interpolate(p).gradient| <= R_g·3·2^-(wb+1) + 2^-(gfb+1) + 2^-(sf+1),
// with R_g the range of the stored component over the 8 corners.
struct InterpStats {
  double worst_value_ratio = 0.0, worst_value = 0.0, value_bound = 0.0;
  double worst_grad_ratio = 0.0, worst_grad = 0.0, grad_bound = 0.0;
};

template <PrecisionProfile P>
void check_against_float(const TestVolume& tv, InterpStats& st, std::uint32_t seed) {
  using G = hls::GeometryParams<ProfileTraits<P>>;
  const std::array<int, 3> dims = tv.volume.dims;
  const bittrue::VoxelMemory mem = bittrue::make_voxel_memory(P, tv.volume, tv.gradients);
  const bittrue::FrameRegisters fr = box_registers(dims);
  const auto regs = hls::host::load_geometry_registers<ProfileTraits<P>>(fr);
  const hls::host::BitTrueBanks<ProfileTraits<P>> view(mem);
  const double wq = 3.0 * std::ldexp(1.0, -(P.weight_bits + 1));
  const double half_sf = std::ldexp(1.0, -(P.sample_frac_bits + 1));
  const double half_gfb = std::ldexp(1.0, -(P.gradient_frac_bits + 1));
  std::mt19937 rng(seed);
  const Raw one = Raw{1} << P.pos_frac_bits;
  for (int i = 0; i < 4000; ++i) {
    typename G::pos_t p[3];
    std::array<double, 3> pd{};
    for (int k = 0; k < 3; ++k) {
      std::uniform_int_distribution<Raw> d(0, (dims[static_cast<std::size_t>(k)] - 1) * one);
      p[k] = hls::host::from_raw_bits<typename G::pos_t>(d(rng));
      pd[static_cast<std::size_t>(k)] = p[k].to_double();
    }
    const auto h = as_doubles(hls::interpolate<ProfileTraits<P>>(regs, view, p));
    const ref::Sample f = ref::interpolate(tv.volume, tv.gradients, Vec3(pd[0], pd[1], pd[2]));
    double vmin = 1e300, vmax = -1e300;
    std::array<double, 3> gmin{1e300, 1e300, 1e300}, gmax{-1e300, -1e300, -1e300};
    for (const bittrue::BtCorner& c : bittrue::bt_corners(P, fr, pd)) {
      if (c.voxel[0] >= dims[0] || c.voxel[1] >= dims[1] || c.voxel[2] >= dims[2]) continue;
      const bittrue::VoxelWord& w = mem.banks[static_cast<std::size_t>(c.bank)][c.word];
      vmin = std::min(vmin, double(w.value)), vmax = std::max(vmax, double(w.value));
      for (std::size_t k = 0; k < 3; ++k) {
        const double g = std::ldexp(double(w.gradient[k]), -P.gradient_frac_bits);
        gmin[k] = std::min(gmin[k], g), gmax[k] = std::max(gmax[k], g);
      }
    }
    const double vbound = (vmax - vmin) * wq + half_sf;
    const double verr = std::fabs(h[0] - f.value);
    ASSERT_LE(verr, vbound) << "p = (" << pd[0] << ", " << pd[1] << ", " << pd[2] << ")";
    if (verr / vbound > st.worst_value_ratio)
      st.worst_value_ratio = verr / vbound, st.worst_value = verr, st.value_bound = vbound;
    for (int k = 0; k < 3; ++k) {
      const auto ik = static_cast<std::size_t>(k);
      const double gbound = (gmax[ik] - gmin[ik]) * wq + half_gfb + half_sf;
      const double gerr = std::fabs(h[ik + 1] - f.gradient[k]);
      ASSERT_LE(gerr, gbound) << "component " << k;
      if (gerr / gbound > st.worst_grad_ratio)
        st.worst_grad_ratio = gerr / gbound, st.worst_grad = gerr, st.grad_bound = gbound;
    }
  }
}

template <PrecisionProfile P>
void check_all_against_float(const char* name) {
  const std::uint32_t vmax = (std::uint32_t{1} << P.value_bits) - 2u;
  InterpStats st;
  check_against_float<P>(*random_volume({12, 9, 10}, P.value_bits, vmax, 5), st, 1);
  check_against_float<P>(*smooth_volume({16, 13, 11}, P.value_bits, vmax), st, 2);
  check_against_float<P>(*random_volume({1, 7, 6}, P.value_bits, vmax, 6), st, 3);
  std::printf(
      "[ %s ] value: worst err/bound %.3f (%.4g of %.4g); gradient: worst err/bound %.3f "
      "(%.4g of %.4g)\n",
      name, st.worst_value_ratio, st.worst_value, st.value_bound, st.worst_grad_ratio,
      st.worst_grad, st.grad_bound);
}

TEST(InterpolationProcessor, WithinDerivedBoundOfFloatVizard2) {
  check_all_against_float<kVizard2>("vizard2");
}
TEST(InterpolationProcessor, WithinDerivedBoundOfFloatBalanced) {
  check_all_against_float<kBalanced>("balanced");
}
TEST(InterpolationProcessor, WithinDerivedBoundOfFloatPrecise) {
  check_all_against_float<kPrecise>("precise");
}

// A linear ramp is interpolated exactly by trilinear interpolation; with
// weight addressing the error is the weight rounding times the slope.
TEST(InterpolationProcessor, LinearRampWithinWeightRounding) {
  constexpr PrecisionProfile P = kBalanced;
  using G = hls::GeometryParams<ProfileTraits<P>>;
  ref::Volume v;
  v.dims = {9, 9, 9};
  v.bits = 12;
  v.data.resize(v.voxel_count());
  for (int z = 0; z < 9; ++z)
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 9; ++x)
        v.data[v.index(x, y, z)] = static_cast<std::uint16_t>(100 * x + 30 * y + 7 * z);
  const ref::GradientField g = ref::compute_gradients(v, ref::GradientOperator::Central);
  const bittrue::VoxelMemory mem = bittrue::make_voxel_memory(P, v, g);
  const bittrue::FrameRegisters fr = box_registers(v.dims);
  const auto regs = hls::host::load_geometry_registers<ProfileTraits<P>>(fr);
  const hls::host::BitTrueBanks<ProfileTraits<P>> view(mem);
  const double half_w = std::ldexp(1.0, -(P.weight_bits + 1));
  const double half_sf = std::ldexp(1.0, -(P.sample_frac_bits + 1));
  std::mt19937 rng(7);
  std::uniform_int_distribution<Raw> d(0, Raw{8} << P.pos_frac_bits);
  for (int i = 0; i < 2000; ++i) {
    typename G::pos_t p[3];
    double exact = 0.0;
    const double slope[3] = {100.0, 30.0, 7.0};
    for (int k = 0; k < 3; ++k) {
      p[k] = hls::host::from_raw_bits<typename G::pos_t>(d(rng));
      exact += slope[k] * p[k].to_double();
    }
    const double value = hls::interpolate<ProfileTraits<P>>(regs, view, p).value.to_double();
    ASSERT_LE(std::fabs(value - exact), (100.0 + 30.0 + 7.0) * half_w + half_sf);
  }
}

// ---- (c) interleaving -------------------------------------------------------------------------
template <PrecisionProfile P>
void check_interleaving(std::array<int, 3> dims) {
  SCOPED_TRACE(::testing::Message() << "dims " << dims[0] << "x" << dims[1] << "x" << dims[2]);
  using G = hls::GeometryParams<ProfileTraits<P>>;
  // Voxel (x, y, z) holds id + 1 (so the zero padding is distinguishable) and
  // the gradient (x, y, z).
  ref::Volume v;
  v.dims = dims;
  v.bits = P.value_bits;
  v.data.resize(v.voxel_count());
  ref::GradientField g;
  g.g.resize(v.voxel_count());
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x) {
        v.data[v.index(x, y, z)] = static_cast<std::uint16_t>(v.index(x, y, z) + 1);
        g.g[v.index(x, y, z)] = glm::vec3(float(x), float(y), float(z));
      }
  const bittrue::VoxelMemory mem = bittrue::make_voxel_memory(P, v, g);

  // The layout: every bank has hx·hy·hz words, every voxel its own word.
  const std::size_t words = static_cast<std::size_t>((dims[0] + 1) / 2) *
                            static_cast<std::size_t>((dims[1] + 1) / 2) *
                            static_cast<std::size_t>((dims[2] + 1) / 2);
  std::size_t used = 0;
  for (const auto& bank : mem.banks) {
    ASSERT_EQ(bank.size(), words);
    for (const bittrue::VoxelWord& w : bank) used += w.value != 0 ? 1 : 0;
  }
  EXPECT_EQ(used, v.voxel_count());

  const bittrue::FrameRegisters fr = box_registers(dims);
  const auto regs = hls::host::load_geometry_registers<ProfileTraits<P>>(fr);
  const hls::host::BitTrueBanks<ProfileTraits<P>> view(mem);
  auto last_cell = [&](int k) {
    return dims[static_cast<std::size_t>(k)] == 1 ? 0 : dims[static_cast<std::size_t>(k)] - 2;
  };
  int neighbourhoods = 0;
  for (int z0 = 0; z0 <= last_cell(2); ++z0)
    for (int y0 = 0; y0 <= last_cell(1); ++y0)
      for (int x0 = 0; x0 <= last_cell(0); ++x0) {
        const int i0[3] = {x0, y0, z0};
        SCOPED_TRACE(::testing::Message() << "i0 = (" << x0 << ", " << y0 << ", " << z0 << ")");
        typename G::pos_t p[3];
        std::array<double, 3> pd{};
        for (int k = 0; k < 3; ++k) {
          // Inside the cell (on the voxel itself along a 1-voxel axis).
          const double c = dims[static_cast<std::size_t>(k)] == 1 ? 0.0 : i0[k] + 0.375;
          p[k] = hls::host::from_raw_bits<typename G::pos_t>(
              static_cast<Raw>(std::ldexp(c, P.pos_frac_bits)));
          pd[static_cast<std::size_t>(k)] = c;
        }
        const hls::BankAccess<ProfileTraits<P>> acc = hls::address_generator<ProfileTraits<P>>(regs, p);
        hls::VoxelWordFx<ProfileTraits<P>> corner[8];
        hls::gather<ProfileTraits<P>>(view, acc, corner);
        const std::array<bittrue::BtCorner, 8> bt = bittrue::bt_corners(P, fr, pd);
        std::set<unsigned> banks;
        for (int j = 0; j < 8; ++j) {
          const unsigned b = static_cast<unsigned>(j) ^ acc.parity;
          banks.insert(b);
          const std::uint64_t addr = acc.addr[b].to_uint64();
          ASSERT_LT(addr, words) << "corner " << j;
          const int x = x0 + (j & 1), y = y0 + ((j >> 1) & 1), z = z0 + ((j >> 2) & 1);
          // The bank the spec assigns to the voxel, and the bit-true twin's choice.
          ASSERT_EQ(b, static_cast<unsigned>((x & 1) | (y & 1) << 1 | (z & 1) << 2));
          ASSERT_EQ(bt[static_cast<std::size_t>(j)].bank, static_cast<int>(b));
          ASSERT_EQ(bt[static_cast<std::size_t>(j)].word, addr);
          const bittrue::VoxelWord& w = mem.banks[b][addr];
          ASSERT_EQ(corner[j].value.to_uint64(), w.value);  // the crossbar
          if (x < dims[0] && y < dims[1] && z < dims[2]) {
            ASSERT_EQ(w.value, v.index(x, y, z) + 1) << "corner " << j;
            const int gf = P.gradient_frac_bits;  // raw = coordinate · 2^gfb
            ASSERT_EQ(w.gradient, (std::array<std::int32_t, 3>{x << gf, y << gf, z << gf}));
          } else {
            // Beyond a 1-voxel axis: the padding word, with weight 0.
            ASSERT_EQ(w.value, 0u);
            ASSERT_EQ(bt[static_cast<std::size_t>(j)].weight, 0.0);
          }
        }
        ASSERT_EQ(banks.size(), 8u) << "the 8 corners must read 8 distinct banks";
        ++neighbourhoods;
      }
  EXPECT_GT(neighbourhoods, 0);

  // On the last voxel of an axis (f = 1 in the last cell, §3.2) every corner
  // is still a voxel of the volume (padding only along a 1-voxel axis).
  typename G::pos_t p[3];
  std::array<double, 3> pd{};
  for (int k = 0; k < 3; ++k) {
    pd[static_cast<std::size_t>(k)] = dims[static_cast<std::size_t>(k)] - 1.0;
    p[k] = hls::host::from_raw_bits<typename G::pos_t>(Raw{dims[static_cast<std::size_t>(k)] - 1}
                                                       << P.pos_frac_bits);
  }
  const hls::BankAccess<ProfileTraits<P>> acc = hls::address_generator<ProfileTraits<P>>(regs, p);
  for (int b = 0; b < 8; ++b) EXPECT_LT(acc.addr[b].to_uint64(), words);
  for (const bittrue::BtCorner& c : bittrue::bt_corners(P, fr, pd))
    for (std::size_t k = 0; k < 3; ++k)
      if (dims[k] > 1) {
        EXPECT_LT(c.voxel[k], dims[k]);
      }
}

TEST(InterpolationProcessor, EveryNeighbourhoodReadsEightDistinctBanks) {
  check_interleaving<kVizard2>({5, 3, 7});
  check_interleaving<kVizard2>({7, 5, 7});
  check_interleaving<kVizard2>({6, 5, 4});
  check_interleaving<kVizard2>({1, 5, 3});
  check_interleaving<kVizard2>({3, 1, 1});
  check_interleaving<kBalanced>({9, 5, 3});
  check_interleaving<kPrecise>({3, 9, 5});
}

TEST(InterpolationProcessor, PackedWordLayout) {
  constexpr PrecisionProfile P = kVizard2;  // 32-bit word: value + 3 x 8-bit gradient
  hls::VoxelWordFx<ProfileTraits<P>> w;
  w.value = 0xA5;
  w.g[0] = -1;
  w.g[1] = 5;
  w.g[2] = -128;
  const auto packed = hls::pack_voxel_word<ProfileTraits<P>>(w);
  EXPECT_EQ(packed.to_uint64(), 0x8005FFA5u);
  const hls::VoxelWordFx<ProfileTraits<P>> u = hls::unpack_voxel_word<ProfileTraits<P>>(packed);
  EXPECT_EQ(u.value.to_uint64(), 0xA5u);
  EXPECT_EQ(u.g[0].to_double(), -1.0);
  EXPECT_EQ(u.g[1].to_double(), 5.0);
  EXPECT_EQ(u.g[2].to_double(), -128.0);
}

// The hls engine's host layout (VoxelMemory::packed, hls::host::EngineBanks):
// every word of every bank reads the same fields as from the bank arrays, on a
// volume of odd sizes whose gradients saturate; a profile whose fields do not
// fit 16 bits reads the bank arrays; banks of unequal sizes cannot be packed.
template <PrecisionProfile P>
void check_engine_banks_read_the_banks(bool packed) {
  SCOPED_TRACE(P.value_bits);
  using T = ProfileTraits<P>;
  const auto tv =
      random_volume({7, 5, 9}, P.value_bits, (std::uint32_t{1} << P.value_bits) - 1u, 3);
  const bittrue::VoxelMemory mem = bittrue::make_voxel_memory(P, tv->volume, tv->gradients);
  ASSERT_EQ(hls::host::EngineBanks<T>::kPacked, packed);
  ASSERT_EQ(mem.packed != nullptr, packed);
  const auto words = hls::host::engine_packed_words<T>(mem);
  const hls::host::EngineBanks<T> engine(mem, words ? words->data() : nullptr);
  const hls::host::BitTrueBanks<T> banks(mem);
  for (int b = 0; b < 8; ++b)
    for (std::size_t a = 0; a < mem.banks[0].size(); ++a) {
      typename hls::InterpolationParams<T>::word_addr_t addr = a;
      const hls::VoxelWordFx<T> x = engine.read(b, addr), y = banks.read(b, addr);
      ASSERT_EQ(x.value.to_uint64(), y.value.to_uint64()) << b << ", " << a;
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(x.g[c].to_double(), y.g[c].to_double()) << b << ", " << a;
    }
}

TEST(InterpolationProcessor, EngineBanksReadTheBanksWordForWord) {
  check_engine_banks_read_the_banks<kVizard2>(true);
  check_engine_banks_read_the_banks<kBalanced>(true);
  check_engine_banks_read_the_banks<kPrecise>(false);  // 20-bit gradients
  bittrue::VoxelMemory uneven;
  for (std::size_t b = 0; b < 8; ++b) uneven.banks[b].resize(b == 5 ? 3 : 4);
  try {
    bittrue::pack_banks(uneven);
    ADD_FAILURE() << "banks of unequal sizes were packed";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "voxel memory: bank 5 holds 3 words, bank 0 4: the banks cannot be interleaved");
  }
}

}  // namespace
