// The hls engine's own skipping of empty blocks (hls/host_march.hpp): the
// chessboard distance of each empty block to the nearest block that is not
// empty, and the length of the run of samples a ray takes inside a cube of
// blocks, each against brute force; the frame's empty blocks kept between
// frames of the same memory and transparent entries. The images it gives are
// the goldens' (regress, and every engine test that renders a scene with
// empty space).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>
#include <string>

#include "hls/host_frame.hpp"
#include "hls/host_march.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "cosim/engines/engines.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

namespace host = hls::host;

// ---- The distance transform ---------------------------------------------------------------

host::EmptyBlocks random_map(std::int64_t nx, std::int64_t ny, std::int64_t nz, double p_full,
                             std::mt19937& rng) {
  host::EmptyBlocks eb;
  eb.n[0] = nx;
  eb.n[1] = ny;
  eb.n[2] = nz;
  eb.distance.resize(static_cast<std::size_t>(nx * ny * nz));
  std::bernoulli_distribution full(p_full);
  for (auto& d : eb.distance) d = full(rng) ? 0 : host::EmptyBlocks::kMaxEmptyDistance;
  return eb;
}

// min over the blocks that are not empty of max(|dx|, |dy|, |dz|), at most 255.
std::uint8_t brute_distance(const host::EmptyBlocks& full, std::int64_t x, std::int64_t y,
                            std::int64_t z) {
  std::int64_t best = host::EmptyBlocks::kMaxEmptyDistance;
  for (std::int64_t qz = 0; qz < full.n[2]; ++qz)
    for (std::int64_t qy = 0; qy < full.n[1]; ++qy)
      for (std::int64_t qx = 0; qx < full.n[0]; ++qx)
        if (full.distance[full.index(qx, qy, qz)] == 0)
          best = std::min(best, std::max({std::abs(qx - x), std::abs(qy - y), std::abs(qz - z)}));
  return static_cast<std::uint8_t>(best);
}

TEST(EngineSkipping, ChessboardDistanceIsTheBruteForceOne) {
  std::mt19937 rng(21);
  const struct {
    std::int64_t nx, ny, nz;
    double p_full;
  } maps[] = {{1, 1, 1, 0.0}, {1, 1, 1, 1.0}, {5, 3, 4, 0.1}, {9, 7, 8, 0.02},
              {9, 7, 8, 0.3}, {16, 2, 11, 0.05}, {12, 12, 12, 0.0}, {12, 12, 12, 0.001}};
  for (const auto& m : maps) {
    const host::EmptyBlocks before = random_map(m.nx, m.ny, m.nz, m.p_full, rng);
    host::EmptyBlocks after = before;
    host::chessboard_distance(after);
    for (std::int64_t z = 0; z < m.nz; ++z)
      for (std::int64_t y = 0; y < m.ny; ++y)
        for (std::int64_t x = 0; x < m.nx; ++x)
          ASSERT_EQ(after.distance[after.index(x, y, z)],
                    brute_distance(before, x, y, z))
              << m.nx << "x" << m.ny << "x" << m.nz << " p=" << m.p_full << " at " << x << ","
              << y << "," << z;
  }
}

// ---- The run of samples inside a cube of blocks -------------------------------------------

using P = BalancedTraits;
using G = hls::GeometryParams<P>;
constexpr int kF = G::pos_t::width - hls::fixed_iwidth<G::pos_t>::value;

hls::GeometryRegisters<P> registers_of(const std::string& scene_name) {
  const ref::Scene s = ref::load_scene_file(
      std::string(VOXCAST_SOURCE_DIR) + "/scenes/" + scene_name,
      {"precision.profile=balanced", "render.width=8", "render.height=8"});
  const cosim::SceneVolume sv = cosim::load_scene_volume(s);
  const ref::RenderInputs in = ref::make_render_inputs(s, sv.volume, sv.gradients, s.camera.pose);
  return host::load_geometry_registers<P>(bittrue::make_frame_setup(s.precision, s, in).regs);
}

G::pos_t position(std::int64_t raw) {
  G::pos_t p;
  hls::write_bits(p, static_cast<std::uint64_t>(raw));
  return p;
}

// The block sample_cell gives the position `raw` along axis a.
std::int64_t block_of(const hls::GeometryRegisters<P>& r, int a, std::int64_t raw, unsigned lb) {
  typename hls::InterpolationParams<P>::cpos_t cp;
  return static_cast<std::int64_t>(hls::sample_cell<P>(r, position(raw), a, cp).to_uint64() >> lb);
}

TEST(EngineSkipping, SamplesInsideIsTheFirstSampleOutsideTheCube) {
  constexpr std::uint64_t kUnlimited = std::numeric_limits<std::uint64_t>::max();
  std::mt19937 rng(25);
  for (const char* scene : {"default.toml", "colin27.toml"}) {
    const hls::GeometryRegisters<P> r = registers_of(scene);
    for (unsigned lb : {2u, 3u}) {
      for (int a = 0; a < 3; ++a) {
        // The crop box in whole voxels (box_t), as positions (pos_t).
        const std::int64_t one = std::int64_t{1} << kF;
        const std::int64_t lo = r.LO[a].to_int64() * one, hi = r.HI[a].to_int64() * one;
        ASSERT_GT(hi - lo, 40 * one) << "a crop box of the scene's size";
        std::uniform_int_distribution<std::int64_t> pos(lo - 3 * one, hi + 3 * one);
        // Steps of 1/16 to 2 voxels either way (the brute force walks the range).
        std::uniform_int_distribution<std::int64_t> step(one / 16, 2 * one);
        std::uniform_int_distribution<std::int64_t> margin(0, 3);
        for (int trial = 0; trial < 400; ++trial) {
          const std::int64_t p = pos(rng);
          const std::int64_t s = trial % 50 == 0 ? 0 : (trial % 2 ? 1 : -1) * step(rng);
          const std::int64_t b = block_of(r, a, p, lb), m = margin(rng);
          const std::uint64_t got =
              host::samples_inside<P>(r, a, p, s, b - m, b + m, lb, kUnlimited);
          // Step until the block leaves [b - m, b + m], or the position is past
          // the clamped range for good (then it never leaves).
          std::uint64_t first_out = kUnlimited;
          for (std::int64_t j = 0; s != 0; ++j) {
            const std::int64_t pj = p + j * s;
            const std::int64_t bj = block_of(r, a, pj, lb);
            if (bj < b - m || bj > b + m) {
              first_out = static_cast<std::uint64_t>(j);
              break;
            }
            if ((s > 0 && pj > hi) || (s < 0 && pj < lo)) break;
          }
          ASSERT_EQ(got, first_out) << scene << " lb=" << lb << " axis " << a << " p=" << p
                                    << " s=" << s << " block " << b << " margin " << m;
        }
      }
    }
  }
}

// ---- The frame's empty blocks, kept between frames ------------------------------------------

// empty_blocks keeps its last result: a second frame of the same memory and
// table reuses it, one whose table makes other entries transparent or another
// memory (even of the same volume) does not, and each result is what
// make_empty_blocks computes afresh.
TEST(EngineSkipping, EmptyBlocksAreKeptForTheSameMemoryAndTransparentEntries) {
  const ref::Scene s =
      ref::load_scene_file(std::string(VOXCAST_SOURCE_DIR) + "/scenes/default.toml",
                           {"precision.profile=balanced", "render.width=8", "render.height=8"});
  const cosim::SceneVolume sv = cosim::load_scene_volume(s);
  const ref::RenderInputs in = ref::make_render_inputs(s, sv.volume, sv.gradients, s.camera.pose);
  const bittrue::FrameSetup fs = bittrue::make_frame_setup(s.precision, s, in);
  const bittrue::VoxelMemory memory =
      bittrue::make_voxel_memory(s.precision, sv.volume, sv.gradients);
  const auto fresh = [&](const bittrue::FrameSetup& f, const bittrue::VoxelMemory& m) {
    return host::make_empty_blocks<P>(bittrue::nonzero_prefix(f.class_table), m)->distance;
  };
  const auto first = host::empty_blocks<P>(fs, memory);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->distance, fresh(fs, memory));
  EXPECT_EQ(host::empty_blocks<P>(fs, memory), first) << "the same frame again: kept";

  // Every entry below the first visible one made visible: fewer empty blocks.
  bittrue::FrameSetup opaque = fs;
  for (bittrue::ClassEntry& e : opaque.class_table) e.alpha = std::max<std::uint32_t>(e.alpha, 1);
  const auto second = host::empty_blocks<P>(opaque, memory);
  ASSERT_TRUE(second);
  EXPECT_NE(second, first);
  EXPECT_EQ(second->distance, fresh(opaque, memory));
  EXPECT_TRUE(std::all_of(second->distance.begin(), second->distance.end(), [](std::uint8_t d) {
    return d == 0;
  })) << "no entry is transparent: no block is empty";

  const bittrue::VoxelMemory again =
      bittrue::make_voxel_memory(s.precision, sv.volume, sv.gradients);
  host::empty_blocks<P>(fs, memory);  // memory's result is the last one
  const auto other = host::empty_blocks<P>(fs, again);
  EXPECT_NE(other, host::empty_blocks<P>(fs, memory)) << "another memory: made afresh";
  EXPECT_EQ(other->distance, first->distance);
}

}  // namespace VOXCAST_UNITY_ID
}  // namespace voxcast::test
