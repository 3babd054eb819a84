// The volume in 64-byte DDR4 bursts (rtl_model/layout/burst_layout.hpp):
//  (a) every voxel in exactly one burst, every burst one brick, every brick
//      its own DDR4 address, for every shape and bank-group map;
//  (b) a cell's bursts are the bricks it crosses: prod_k (1 + [i0_k + 1 starts
//      a brick]), spread so that no channel gets more than the crossings of
//      the axis that does not choose the channel;
//  (c) the counter on rays whose bursts, bank groups, rows and bus clocks
//      follow in closed form from the layout and DDR4-2400's tCCD_S / tCCD_L.
#include <gtest/gtest.h>

#include <array>
#include <map>
#include <set>
#include <tuple>
#include <vector>

#include "refmodel/error.hpp"
#include "rtl_model/layout/burst_layout.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast::rtl::layout;
using voxcast::Error;

constexpr std::array<BankGroupMap, 2> kGroups{BankGroupMap::kPlain, BankGroupMap::kSkewed};
constexpr std::array<std::pair<BankGroupMap, RowMap>, 4> kMaps{{
    {BankGroupMap::kPlain, RowMap::kLinear},
    {BankGroupMap::kSkewed, RowMap::kLinear},
    {BankGroupMap::kPlain, RowMap::kBlocks},
    {BankGroupMap::kSkewed, RowMap::kBlocks},
}};

std::array<int, 3> brick_of(const std::array<int, 3>& v, const std::array<int, 3>& brick) {
  return {v[0] / brick[0], v[1] / brick[1], v[2] / brick[2]};
}

// ---- (a) A bijection of bricks onto DDR4 addresses ----------------------------------------
TEST(BurstLayout, EveryVoxelIsInOneBurstAndEveryBurstIsOneBrick) {
  const std::array<int, 3> dims{20, 12, 9};  // no extent a multiple of every brick edge
  for (const int vpb : {16, 8, 4}) {
    for (const auto& shape : burst_shapes(vpb)) {
      for (const auto& [g, rows] : kMaps) {
        const BurstLayout layout(dims, shape, vpb, g, BurstMemory{}, rows);
        SCOPED_TRACE(layout.name());
        using Key = std::tuple<int, int, int, std::uint32_t, std::uint32_t>;
        std::map<Key, std::array<int, 3>> brick_at;  // address -> the brick it holds
        std::set<std::pair<int, std::uint64_t>> indices;
        for (int z = 0; z < dims[2]; ++z)
          for (int y = 0; y < dims[1]; ++y)
            for (int x = 0; x < dims[0]; ++x) {
              const BurstAddress a = layout.burst_of({x, y, z});
              ASSERT_GE(a.channel, 0);
              ASSERT_LT(a.channel, kBurstChannels);
              ASSERT_LT(a.bank_group, kBankGroups);
              const Key k{a.channel, a.bank_group, a.bank, a.row, a.column};
              const auto b = brick_of({x, y, z}, shape);
              const auto [it, fresh] = brick_at.emplace(k, b);
              ASSERT_EQ(it->second, b) << "two bricks at one address";
              if (fresh) indices.insert({a.channel, a.index});
            }
        // As many bursts as bricks, and the channel index names each once.
        const std::size_t bricks = static_cast<std::size_t>(((dims[0] + shape[0] - 1) / shape[0]) *
                                                            ((dims[1] + shape[1] - 1) / shape[1]) *
                                                            ((dims[2] + shape[2] - 1) / shape[2]));
        EXPECT_EQ(brick_at.size(), bricks);
        EXPECT_EQ(indices.size(), bricks);
      }
    }
  }
}

TEST(BurstLayout, ShapesAreTheLineAndTheSmallBricks) {
  // 16 voxels: the line plus every power-of-two brick with edges <= 4 (six).
  const auto s16 = burst_shapes(16);
  EXPECT_EQ(s16.size(), 7u);
  EXPECT_EQ(s16.front(), (std::array<int, 3>{16, 1, 1}));
  for (const auto& s : s16) EXPECT_EQ(s[0] * s[1] * s[2], 16);
  EXPECT_EQ(burst_shapes(8).size(), 8u);  // 8x1x1 and the seven bricks of edges <= 4
}

TEST(BurstLayout, RefusesABrickThatIsNotABurst) {
  try {
    BurstLayout({64, 64, 64}, {4, 4, 2}, 16, BankGroupMap::kPlain);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("holds 16 voxels, the brick 32"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(BurstLayout({64, 64, 64}, {3, 4, 4}, 48, BankGroupMap::kPlain), Error);
  BurstMemory tiny;
  tiny.rows = 1;  // 512 bursts per bank-group slot x 4 banks: 2048 per channel
  EXPECT_THROW(BurstLayout({256, 256, 256}, {4, 2, 2}, 16, BankGroupMap::kPlain, tiny), Error);
}

// ---- (b) A cell's bursts -------------------------------------------------------------------
TEST(BurstLayout, ACellReadsTheBricksItCrossesSpreadOverTheChannels) {
  const std::array<int, 3> dims{16, 16, 16};  // a multiple of every edge
  for (const auto& shape : burst_shapes(16)) {
    const BurstLayout layout(dims, shape, 16, BankGroupMap::kSkewed);
    SCOPED_TRACE(layout.name());
    const auto axes = layout.channel_axes();
    const int other = 3 - axes[0] - axes[1];
    std::array<BurstAddress, 8> out;
    for (int z = 0; z + 1 < dims[2]; ++z)
      for (int y = 0; y + 1 < dims[1]; ++y)
        for (int x = 0; x + 1 < dims[0]; ++x) {
          const std::array<int, 3> i0{x, y, z};
          int expected = 1;
          std::array<bool, 3> crosses{};
          for (std::size_t k = 0; k < 3; ++k) {
            crosses[k] = (i0[k] + 1) % shape[k] == 0;
            expected *= crosses[k] ? 2 : 1;
          }
          const int n = layout.cell_bursts(i0, out);
          ASSERT_EQ(n, expected) << x << " " << y << " " << z;
          std::array<int, kBurstChannels> per_channel{};
          for (int j = 0; j < n; ++j)
            ++per_channel[static_cast<std::size_t>(out[static_cast<std::size_t>(j)].channel)];
          for (const int c : per_channel)
            ASSERT_LE(c, crosses[static_cast<std::size_t>(other)] ? 2 : 1);
        }
  }
}

// ---- (c) Rays in closed form ---------------------------------------------------------------
// A ray of unit steps along axis a from the origin: cells i0 = k e_a, k = 0 .. n-2.
BurstCounter ray_along(const BurstLayout& layout, int axis, int n,
                       std::uint32_t cache_lines = 1024) {
  BurstCounter c(layout, cache_lines);
  c.begin_ray();
  for (int k = 0; k + 1 < n; ++k) {
    std::array<int, 3> i0{0, 0, 0};
    i0[static_cast<std::size_t>(axis)] = k;
    c.sample(i0);
  }
  return c;
}

TEST(BurstCounter, LineBurstsAlongX) {
  // 16x1x1, channels by (y, z) parity: a cell at y = z = 0 reads rows y, y+1
  // and z, z+1 (four channels), two bursts per row where x + 1 = 16, 32, ...
  const int n = 128;
  const BurstLayout layout({n, 2, 2}, {16, 1, 1}, 16, BankGroupMap::kPlain);
  const BurstCounter c = ray_along(layout, 0, n);
  EXPECT_EQ(c.samples(), static_cast<std::uint64_t>(n - 1));
  // No reuse: 4 per cell, 8 at the n/16 - 1 cells that cross a burst.
  EXPECT_EQ(c.load(Reuse::kNone).bursts(), 4u * (n - 1) + 4u * (n / 16 - 1));
  // Ray reuse: each burst of the four rows once: 4 x n/16.
  const ReuseLoad& ray = c.load(Reuse::kRay);
  EXPECT_EQ(ray.bursts(), 4u * n / 16);
  for (const ChannelLoad& ch : ray.channel) {
    EXPECT_EQ(ch.bursts, static_cast<std::uint64_t>(n / 16));
    // x-consecutive bricks of a channel rotate through the four bank groups...
    EXPECT_EQ(ch.same_group, 0u);
    EXPECT_EQ(ch.bus_clocks, 4u * n / 16);  // BL/2 = tCCD_S = 4 clocks each
    // ... and four of them share a row address: the first four open bank 0 of
    // each group, the next four hit those rows.
    EXPECT_EQ(ch.row_misses, 4u);
    EXPECT_EQ(ch.row_hits, static_cast<std::uint64_t>(n / 16 - 4));
    EXPECT_EQ(ch.row_conflicts, 0u);
  }
}

TEST(BurstCounter, SkewedBankGroupsKeepAZRayAtTccdS) {
  // 4x2x2, channels by (y, z) brick parity: a ray along z at x = y = 0 never
  // crosses x or y; it crosses z at odd k. Bricks bz = 0 .. n/2 - 1 alternate
  // channels 0 and 2, so each sees the bricks of one z column in order.
  const int n = 64;
  for (const BankGroupMap g : kGroups) {
    const BurstLayout layout({8, 8, n}, {4, 2, 2}, 16, g);
    SCOPED_TRACE(layout.name());
    const BurstCounter c = ray_along(layout, 2, n);
    EXPECT_EQ(c.load(Reuse::kNone).bursts(), static_cast<std::uint64_t>((n - 1) + (n / 2 - 1)));
    const ReuseLoad& ray = c.load(Reuse::kRay);
    EXPECT_EQ(ray.bursts(), static_cast<std::uint64_t>(n / 2));
    const std::uint64_t per = n / 4;  // bursts on channels 0 and 2
    for (const int ch : {0, 2}) {
      const ChannelLoad& l = ray.channel[static_cast<std::size_t>(ch)];
      EXPECT_EQ(l.bursts, per);
      if (g == BankGroupMap::kPlain) {
        // Plain: x is 0 throughout, every burst in bank group 0: tCCD_L = 6
        // clocks after the first.
        EXPECT_EQ(l.same_group, per - 1);
        EXPECT_EQ(l.bus_clocks, 4 + 6 * (per - 1));
      } else {
        EXPECT_EQ(l.same_group, 0u);
        EXPECT_EQ(l.bus_clocks, 4 * per);
      }
    }
    // The bound: the busiest data bus's clocks at 1200 MHz.
    const double clocks = g == BankGroupMap::kPlain ? 4.0 + 6.0 * (per - 1) : 4.0 * per;
    EXPECT_DOUBLE_EQ(c.bound_samples_per_second(Reuse::kRay), (n - 1) / (clocks / 1.2e9));
  }
}

TEST(BurstCounter, RowCubesKeepAZRayInItsRows) {
  // 4x2x2 skewed on a 256x256x64 volume: the channel's grid is 64 x 64 x 16
  // bricks, and a z ray at x = y = 0 puts 16 bricks (z = 0 .. 15 of the grid)
  // on each of channels 0 and 2, in bank group z mod 4. Linear rows: a z step
  // moves 64 x 64 bricks, 1024 groups of four, 8 rows of 128 groups on: bank
  // 0 of its group, row 2z. So the first burst in each group misses and every
  // later one conflicts: 4 and 12. Cube rows (8x8x8 bricks): z = 0 .. 7 lie in
  // cube 0 (bank 0), 8 .. 15 in cube 1 (bank 1), one row each: per cube the
  // first burst in each group misses and the next one there hits: 8 and 8.
  const int n = 64;
  const BurstLayout linear({256, 256, n}, {4, 2, 2}, 16, BankGroupMap::kSkewed);
  const BurstLayout cubes({256, 256, n}, {4, 2, 2}, 16, BankGroupMap::kSkewed, BurstMemory{},
                          RowMap::kBlocks);
  EXPECT_EQ(cubes.name(), "4x2x2-skewed-blocks");
  const std::uint64_t per = n / 4;  // bursts of the ray on channels 0 and 2
  const BurstCounter on_linear = ray_along(linear, 2, n);
  const BurstCounter on_cubes = ray_along(cubes, 2, n);
  for (const int ch : {0, 2}) {
    const ChannelLoad& l = on_linear.load(Reuse::kRay).channel[static_cast<std::size_t>(ch)];
    EXPECT_EQ(l.bursts, per);
    EXPECT_EQ(l.row_misses, 4u);
    EXPECT_EQ(l.row_hits, 0u);
    EXPECT_EQ(l.row_conflicts, per - 4);
    const ChannelLoad& b = on_cubes.load(Reuse::kRay).channel[static_cast<std::size_t>(ch)];
    EXPECT_EQ(b.row_misses, 8u);
    EXPECT_EQ(b.row_hits, per - 8);
    EXPECT_EQ(b.row_conflicts, 0u);
  }
}

TEST(BurstCounter, RecordsEachFetchWithTheSampleThatNeededIt) {
  // The z ray on 4x2x2: sample 0 fetches brick 0; sample k (odd) crosses into
  // brick (k + 1) / 2 and fetches it; even samples fetch nothing.
  const int n = 64;
  const BurstLayout layout({8, 8, n}, {4, 2, 2}, 16, BankGroupMap::kSkewed);
  BurstCounter c(layout, 1024);
  std::vector<Fetch> fetched;
  c.record(Reuse::kRay, &fetched);
  c.begin_ray();
  for (int k = 0; k + 1 < n; ++k) c.sample({0, 0, k});
  ASSERT_EQ(fetched.size(), static_cast<std::size_t>(n / 2));
  for (std::size_t j = 0; j < fetched.size(); ++j) {
    EXPECT_EQ(fetched[j].sample, j == 0 ? 0u : 2 * j - 1);
    EXPECT_EQ(fetched[j].burst, layout.burst_of({0, 0, static_cast<int>(2 * j)}));
  }
}

TEST(BurstCounter, TheCacheHoldsARayItSawBefore) {
  const int n = 64;
  const BurstLayout layout({8, 8, n}, {2, 2, 4}, 16, BankGroupMap::kSkewed);
  BurstCounter c(layout, 1u << 16);
  for (int pass = 0; pass < 2; ++pass) {
    c.begin_ray();
    for (int k = 0; k + 1 < n; ++k) c.sample({0, 0, k});
  }
  // Ray reuse fetches the ray twice; the cache once (16 bricks along z, 64
  // lines each... far more lines than bricks: no two share a line here).
  EXPECT_EQ(c.load(Reuse::kRay).bursts(), 2u * (n / 4));
  EXPECT_EQ(c.load(Reuse::kCache).bursts(), static_cast<std::uint64_t>(n / 4));
  EXPECT_THROW(BurstCounter(layout, 1000), Error);
}

}  // namespace VOXCAST_UNITY_ID
