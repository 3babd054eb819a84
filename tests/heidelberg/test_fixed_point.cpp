// VIRIM's fixed-point datapath (docs/heidelberg.md §7): the hls kernels equal
// the bit-true twin bit for bit, unit by unit and image by image; the fixed
// point stays within bounds derived from the widths of the double model; the
// parity memory suppresses repeated reads and reads 0 out of bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cosim/engines/engines.hpp"
#include "cosim/engines/heidelberg.hpp"
#include "cosim/reports/metrics.hpp"
#include "cosim/verify/regress.hpp"
#include "hls/virim/host.hpp"
#include "refmodel/bittrue/heidelberg.hpp"
#include "refmodel/render/heidelberg/heidelberg.hpp"
#include "refmodel/render/heidelberg/rotator.hpp"
#include "refmodel/render/heidelberg/slice_model.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "tests/heidelberg/fixtures.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

constexpr HeidelbergProfile HP = kVirimProfile;
using V = hls::virim::VirimParams<HeidelbergTraits<HP>>;

// An oblique, perspective, zoomed, translated view of a random volume.
struct Oblique {
  ref::Volume volume = oblique_volume();
  ref::Scene scene = [] {
    ref::Scene s = oblique_heidelberg_scene();
    s.heidelberg.shininess = 11;
    return s;
  }();
  bittrue::VirimSetup setup = bittrue::make_virim_setup(HP, scene, volume, 0.0);
  bittrue::VirimMemory memory = bittrue::make_virim_memory(volume);
};

TEST(VirimFixedPoint, BusWordIs48BitsAndRoundTrips) {
  static_assert(V::bus_bits == 48, "VIRIM's rotator-DSP bus is 48 bits wide");
  std::mt19937 rng(1);
  for (int t = 0; t < 1000; ++t) {
    hls::virim::BusWord<HeidelbergTraits<HP>> w;
    w.density.range(15, 0) = rng() & 0xffff;
    w.gx.range(15, 0) = rng() & 0xffff;
    w.gy.range(15, 0) = rng() & 0xffff;
    const auto b = hls::virim::unpack_bus_word<HeidelbergTraits<HP>>(hls::virim::pack_bus_word<HeidelbergTraits<HP>>(w));
    ASSERT_EQ(b.density, w.density);
    ASSERT_EQ(b.gx, w.gx);
    ASSERT_EQ(b.gy, w.gy);
  }
}

TEST(VirimFixedPoint, GeometryProcessorEqualsBitTrue) {
  const Oblique o;
  const auto frame = hls::virim::host::load_virim_frame<HeidelbergTraits<HP>>(o.setup);
  for (int k = 0; k < o.setup.H; k += 3)
    for (int j = 0; j < o.setup.D; ++j)
      for (int i = 0; i < o.setup.W; ++i) {
        V::pos_t p[3];
        hls::virim::data_position<HeidelbergTraits<HP>>(frame->geometry, i, j, k, p);
        const bittrue::BtPosition b = bittrue::bt_position(o.setup, i, j, k);
        for (std::size_t a = 0; a < 3; ++a) ASSERT_EQ(p[a].to_double(), b.p[a]) << i << " " << j << " " << k;
      }
}

TEST(VirimFixedPoint, GeometryIsWithinItsRoundingOfTheDoublePosition) {
  // |p_fixed - p| <= 2^-cf (final TRN) + the registers' rounding (2^-cf-1 on
  // base, on 3 matrix entries times |u| <= 2^vbits, and on s_j times |M||v|).
  const Oblique o;
  namespace hb = ref::heidelberg;
  const hb::ViewTransform vt = hb::make_view_transform(o.scene.heidelberg, o.volume, hb::view_dims(o.scene, o.volume), 0.0);
  const double lsb = std::ldexp(1.0, -HP.coord_frac_bits);
  const double bound = lsb + 0.5 * lsb * (1.0 + 3.0 * 32.0 + 3.0 * 32.0);
  for (int k = 0; k < o.setup.H; k += 2)
    for (int j = 0; j < o.setup.D; j += 2)
      for (int i = 0; i < o.setup.W; i += 2) {
        const glm::dvec3 p = hb::data_position(vt, i, j, k);
        const auto b = bittrue::bt_position(o.setup, i, j, k);
        for (int a = 0; a < 3; ++a) ASSERT_NEAR(b.p[static_cast<std::size_t>(a)], p[a], bound);
      }
}

TEST(VirimFixedPoint, WeightRomSumsToOneAndIsWithinOneLsbOfTheMask) {
  for (auto interp : {ref::HeidelbergInterpolation::Gaussian, ref::HeidelbergInterpolation::Trilinear})
    for (int wb = 3; wb <= 6; ++wb) {
      HeidelbergProfile p = HP;
      p.weight_bits = wb;
      const int n = 1 << wb;
      const double one = std::ldexp(1.0, p.weight_frac_bits);
      for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
          for (int x = 0; x < n; ++x) {
            const auto e = bittrue::rom_entry(p, interp, 0.5, x, y, z);
            std::uint32_t sum = 0;
            for (std::uint32_t w : e) sum += w;
            ASSERT_EQ(sum, static_cast<std::uint32_t>(one));
            const glm::dvec3 f = glm::dvec3(x, y, z) / double(n);
            const auto w = interp == ref::HeidelbergInterpolation::Trilinear
                               ? ref::heidelberg::trilinear_weights(f)
                               : ref::heidelberg::gaussian_weights(f, 0.5);
            for (std::size_t c = 0; c < 8; ++c) ASSERT_LT(std::abs(e[c] - w[c] * one), 1.0);
          }
    }
}

TEST(VirimFixedPoint, RotatedDensitiesEqualBitTrue) {
  const Oblique o;
  const auto frame = hls::virim::host::load_virim_frame<HeidelbergTraits<HP>>(o.setup);
  hls::virim::ParityMemory<HeidelbergTraits<HP>> mem;
  hls::virim::host::bank_pointers(o.memory, mem.bank);
  mem.regs = frame->memory;
  mem.reset();
  for (int k = 0; k < o.setup.H; k += 2)
    for (int j = 0; j < o.setup.D; ++j)
      for (int i = 0; i < o.setup.W; ++i)
        ASSERT_EQ(hls::virim::rotator_voxel<HeidelbergTraits<HP>>(*frame, mem, i, j, k).to_double(),
                  bittrue::bt_density(o.setup, o.memory, i, j, k));
}

TEST(VirimFixedPoint, ParityMemorySuppressesRepeatsAndReadsZeroOutOfBounds) {
  const ref::Volume v = random_volume(8, 8, 8, 9);
  const bittrue::VirimMemory m = bittrue::make_virim_memory(v);
  hls::virim::ParityMemory<HeidelbergTraits<HP>> mem;
  hls::virim::host::bank_pointers(m, mem.bank);
  for (int a = 0; a < 3; ++a) {  // two statements: a comma between int_t values is concatenation
    mem.regs.lo[a] = 0;
    mem.regs.hi[a] = 7;
  }
  mem.regs.hy = 4;
  mem.regs.hx2 = 2;
  mem.reset();
  std::uint16_t val[8];
  bool valid[8];
  const auto read = [&](int x, int y, int z) {
    const V::coord_t c[3] = {x, y, z};
    mem.read8(c, val, valid);
  };
  read(2, 3, 4);
  for (int c = 0; c < 8; ++c) {
    ASSERT_TRUE(valid[c]);
    ASSERT_EQ(val[c], v.at(2 + (c & 1), 3 + ((c >> 1) & 1), 4 + ((c >> 2) & 1)));
  }
  EXPECT_EQ(mem.stats.suppressed, 0u);
  read(2, 3, 4);  // the same neighbourhood: every unit holds its data
  EXPECT_EQ(mem.stats.suppressed, 8u);
  read(3, 3, 4);  // one step in x: the 4 units of the shared x = 3 face repeat
  EXPECT_EQ(mem.stats.suppressed, 12u);
  for (int c = 0; c < 8; ++c) ASSERT_EQ(val[c], v.at(3 + (c & 1), 3 + ((c >> 1) & 1), 4 + ((c >> 2) & 1)));
  read(-1, 7, 0);  // x = -1 and y = 8 are outside: only 2 of 8 are in the cube
  int in = 0;
  for (int c = 0; c < 8; ++c) {
    const int x = -1 + (c & 1), y = 7 + ((c >> 1) & 1), z = (c >> 2) & 1;
    const bool inside = x >= 0 && y <= 7;
    ASSERT_EQ(valid[c], inside);
    ASSERT_EQ(val[c], inside ? v.at(x, y, z) : 0);
    in += inside;
  }
  EXPECT_EQ(in, 2);
  EXPECT_EQ(mem.stats.out_of_bounds, 6u);
  EXPECT_EQ(mem.stats.accesses, 32u);
  // Software-set bounds (a crop) cut reads inside the cube too.
  mem.regs.hi[2] = 4;
  read(2, 3, 4);
  for (int c = 0; c < 8; ++c) ASSERT_EQ(valid[c], ((c >> 2) & 1) == 0);
}

TEST(VirimFixedPoint, SliceProcessorEqualsBitTrueOnRandomWords) {
  const Oblique o;
  const auto frame = hls::virim::host::load_virim_frame<HeidelbergTraits<HP>>(o.setup);
  std::mt19937 rng(11);
  for (int t = 0; t < 20000; ++t) {
    hls::virim::BusWord<HeidelbergTraits<HP>> w;
    w.density.range(15, 0) = rng() & 0xffff;
    // Gradients as the Sobel/8 of densities makes them: in (-1/2, 1/2); small ones often.
    const int shift = static_cast<int>(rng() % 12);
    w.gx.range(15, 0) = static_cast<std::uint64_t>(static_cast<std::int16_t>(rng() & 0xffff) >> shift) & 0xffff;
    w.gy.range(15, 0) = static_cast<std::uint64_t>(static_cast<std::int16_t>(rng() & 0xffff) >> shift) & 0xffff;
    V::light_t t0, t45;
    t0.range(V::lf, 0) = rng() % ((1u << V::lf) + 1);
    t45.range(V::lf, 0) = rng() % ((1u << V::lf) + 1);
    V::acc_t acc;
    acc.range(V::lf + 1, 0) = rng() % (1u << V::lf);
    bittrue::BtVoxelState st{t0.to_double(), acc.to_double()};
    const double bt45 = bittrue::bt_slice_voxel(
        o.setup, {w.density.to_double(), w.gx.to_double(), w.gy.to_double()}, t45.to_double(), st);
    const V::light_t h45 = hls::virim::slice_voxel<HeidelbergTraits<HP>>(frame->slice, w, t45, t0, acc);
    ASSERT_EQ(h45.to_double(), bt45);
    ASSERT_EQ(t0.to_double(), st.t0);
    ASSERT_EQ(acc.to_double(), st.acc) << "word " << t;
  }
}

TEST(VirimFixedPoint, PhongIsWithinTheBoundOfItsWidths) {
  // c = g / m: m = floor(|g|) is at most 1 LSB (2^-gb) low, so the relative
  // error is at most 2^-gb / m_fixed, plus the quotient's truncation (2^-cof)
  // and, for c45, 1/√2's rounding (2^-cof-1).
  const Oblique o;
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-0.35, 0.35);
  const double gl = std::ldexp(1.0, -HP.gradient_bits), cl = std::ldexp(1.0, -HP.cos_frac_bits);
  for (int t = 0; t < 20000; ++t) {
    const double gx = std::floor(u(rng) / gl) * gl, gy = std::floor(u(rng) / gl) * gl;
    const double m = std::hypot(gx, gy);
    if (m < 1.0 / 256) continue;
    const auto f = bittrue::bt_phong(o.setup, gx, gy);
    const auto d = ref::heidelberg::phong_factors(gx, gy, 0.0);
    const double rel = gl / (m - gl);
    ASSERT_NEAR(f.c0, d.c0, rel + cl);
    ASSERT_NEAR(f.c45, d.c45, std::sqrt(2.0) * rel + 2 * cl);
    ASSERT_NEAR(f.surface, d.surface, 2 * gl + cl);
  }
}

TEST(VirimFixedPoint, SlabTransmittanceIsWithinOneLsbPerVoxel) {
  // T <- T - TRN(T rho) loses at most 1 LSB (2^-lf) per voxel against (1-rho)^n.
  const int n = 64;
  const ref::Volume v = make_volume(4, n, 4, 8, [](int, int, int) { return std::uint16_t{37}; });
  ref::Scene s = heidelberg_scene(4, n, 4);
  const bittrue::VirimSetup setup = bittrue::make_virim_setup(HP, s, v, 0.0);
  const double rho = setup.lut[37];
  EXPECT_NEAR(rho, 37.0 / 255.0, std::ldexp(1.0, -HP.density_bits));
  bittrue::BtVoxelState st;
  double t45 = 1.0;
  for (int j = 0; j < n; ++j) {
    t45 = bittrue::bt_slice_voxel(setup, {rho, 0.0, 0.0}, t45, st);
    const double exact = std::pow(1.0 - rho, j + 1), bound = (j + 1) * std::ldexp(1.0, -HP.light_frac_bits);
    ASSERT_GE(st.t0, exact);  // the floor of the absorbed share leaves T0 high
    ASSERT_LE(st.t0, exact + bound);
    ASSERT_EQ(t45, st.t0);  // both lights: the same factor per voxel
  }
}

ref::Scene shipped(const char* name, std::vector<std::string> sets) {
  return ref::load_scene_file(std::string(VOXCAST_SOURCE_DIR) + "/scenes/" + name, sets);
}

TEST(VirimFixedPoint, HlsEqualsBitTrueOnEveryPixelOfTheShippedScene) {
  const ref::Scene s = shipped("heidelberg.toml", {"render.width=64", "render.height=48",
                                                   "heidelberg.depth=64",
                                                   "volume.source=\"phantom:shepp-logan?size=64\""});
  const cosim::SceneVolume sv = cosim::load_scene_volume(s);
  const bittrue::VirimSetup setup = bittrue::make_virim_setup(HP, s, sv.volume, 0.0);
  const bittrue::VirimMemory mem = bittrue::make_virim_memory(sv.volume);
  hls::virim::MemoryStats ms;
  const ref::QuantImage h = cosim::hls_render_heidelberg(setup, mem, 2, &ms);
  const ref::QuantImage b = bittrue::bt_render_heidelberg(setup, mem, 1);
  ASSERT_EQ(h.pixels, b.pixels);
  EXPECT_GT(ms.suppressed, 0u);
  // And close to the double model: the floor `voxcast regress` holds the
  // shipped scene to (docs/heidelberg.md §9: the error is the 6-bit weight
  // addressing's, rounded offsets of at most 1/128 voxel).
  const cosim::Accuracy a = cosim::measure_accuracy(h, ref::heidelberg::render(s, sv.volume, 0.0, 2));
  const cosim::AccuracyFloor floor = cosim::accuracy_floor("virim");
  EXPECT_GE(a.psnr_db, floor.psnr_db);
  EXPECT_GE(a.pct_within_1lsb, floor.pct_within_1lsb);
}

TEST(VirimFixedPoint, HlsEqualsBitTrueWithTrilinearCropAndZoom) {
  // Trilinear weights, software-set bounds inside the cube (reads outside give
  // 0), zoom below 1 (the cube smaller than the view) and a stereo eye.
  ref::Scene s = shipped("heidelberg.toml", {"render.width=48", "render.height=40",
                                             "heidelberg.depth=56", "heidelberg.zoom=0.8",
                                             "heidelberg.interpolation=trilinear",
                                             "volume.source=\"phantom:shepp-logan?size=48\""});
  s.volume.crop = ref::Crop{{4, 6, 0}, {40, 47, 30}};
  const cosim::SceneVolume sv = cosim::load_scene_volume(s);
  const bittrue::VirimSetup setup = bittrue::make_virim_setup(HP, s, sv.volume, -2.0);
  const bittrue::VirimMemory mem = bittrue::make_virim_memory(sv.volume);
  hls::virim::MemoryStats ms;
  ASSERT_EQ(cosim::hls_render_heidelberg(setup, mem, 2, &ms).pixels,
            bittrue::bt_render_heidelberg(setup, mem, 1).pixels);
  EXPECT_GT(ms.out_of_bounds, 0u);
}

TEST(VirimFixedPoint, HlsEqualsBitTrueOnColin27) {
  const std::string path = "/usr/share/mricron/templates/ch2.nii.gz";
  ref::Scene s = shipped("heidelberg.toml", {"render.width=96", "render.height=8",
                                             "heidelberg.depth=120",
                                             "volume.source=\"" + path + "\""});
  const cosim::SceneVolume sv = cosim::load_scene_volume(s);
  const bittrue::VirimSetup setup = bittrue::make_virim_setup(HP, s, sv.volume, 2.0);
  const bittrue::VirimMemory mem = bittrue::make_virim_memory(sv.volume);
  ASSERT_EQ(cosim::hls_render_heidelberg(setup, mem, 2).pixels,
            bittrue::bt_render_heidelberg(setup, mem, 2).pixels);
}

}  // namespace
}  // namespace voxcast::test
