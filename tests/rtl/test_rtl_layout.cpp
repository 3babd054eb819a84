// The VIZARD II volume memory (rtl_model/layout): every 2x2x2 neighbourhood
// is one word from each of the four DIMMs and holds the volume's voxels; the
// 64-bit bus word is [v(x+1) : v(x)]; the hls datapath reads the same corners
// through the four-DIMM bank view; every address mapping is injective and
// inside the DIMM.
#include <gtest/gtest.h>

#include <array>
#include <random>
#include <set>
#include <tuple>

#include "hls/interpolation_processor.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/preset_profiles.hpp"
#include "rtl_model/layout/address_mapping.hpp"
#include "rtl_model/layout/bricked_mapping.hpp"
#include "rtl_model/layout/vizard2_layout.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

using rtl::layout::DimmWord;
using rtl::layout::Vizard2Layout;
using rtl::layout::Vizard2Memory;
using rtl::layout::WordCoord;
using rtl::layout::WordGrid;

// A volume whose voxel words are distinct: value and gradients from (x, y, z).
bittrue::VoxelMemory numbered_memory(std::array<int, 3> dims) {
  bittrue::VoxelMemory m;
  m.dims = dims;
  const int hx = (dims[0] + 1) / 2, hy = (dims[1] + 1) / 2, hz = (dims[2] + 1) / 2;
  for (auto& b : m.banks) b.assign(static_cast<std::size_t>(hx * hy * hz), bittrue::VoxelWord{});
  for (int z = 0; z < dims[2]; ++z)
    for (int y = 0; y < dims[1]; ++y)
      for (int x = 0; x < dims[0]; ++x) {
        const int b = (x & 1) | (y & 1) << 1 | (z & 1) << 2;
        auto& w = m.banks[static_cast<std::size_t>(b)]
                         [static_cast<std::size_t>((x >> 1) + (y >> 1) * hx + (z >> 1) * hx * hy)];
        w.value = static_cast<std::uint32_t>(1 + x + 7 * y + 13 * z) & 0xffu;
        w.gradient = {x - 60, y - 3, 100 - z};
      }
  return m;
}

template <PrecisionProfile P>
std::tuple<unsigned, std::int64_t, std::int64_t, std::int64_t> fields(const hls::VoxelWordFx<ProfileTraits<P>>& v) {
  return {v.value.to_uint(), v.g[0].range().to_uint64(), v.g[1].range().to_uint64(),
          v.g[2].range().to_uint64()};
}

template <PrecisionProfile P>
void check_neighbourhoods(std::array<int, 3> dims) {
  SCOPED_TRACE(::testing::Message() << "dims " << dims[0] << "x" << dims[1] << "x" << dims[2]);
  const bittrue::VoxelMemory mem = numbered_memory(dims);
  const Vizard2Memory<ProfileTraits<P>> dimms(mem);
  const hls::host::BitTrueBanks<ProfileTraits<P>> banks(mem);
  auto voxel = [&](int x, int y, int z) {  // the hls design's view of the volume
    const int hx = (dims[0] + 1) / 2, hy = (dims[1] + 1) / 2;
    const int b = (x & 1) | (y & 1) << 1 | (z & 1) << 2;
    return banks.read(b, typename hls::InterpolationParams<ProfileTraits<P>>::word_addr_t(
                             (x >> 1) + (y >> 1) * hx + (z >> 1) * hx * hy));
  };
  const int last[3] = {std::max(dims[0] - 2, 0), std::max(dims[1] - 2, 0), std::max(dims[2] - 2, 0)};
  for (int z = 0; z <= last[2]; ++z)
    for (int y = 0; y <= last[1]; ++y)
      for (int x = 0; x <= last[0]; ++x) {
        const auto words = Vizard2Layout::neighbourhood({x, y, z});
        for (int j = 0; j < 8; ++j) {
          const int cx = x + (j & 1), cy = y + ((j >> 1) & 1), cz = z + ((j >> 2) & 1);
          // The corner is in DIMM (cy&1)|(cz&1)<<1, half cx - x of its word.
          const int d = Vizard2Layout::dimm_of(cy, cz);
          const WordCoord& c = words[static_cast<std::size_t>(d)];
          ASSERT_EQ(c, Vizard2Layout::word_of(x, cy, cz)) << "corner " << j;
          const auto v = Vizard2Layout::voxel_of(d, c, j & 1);
          ASSERT_EQ(v, (std::array<int, 3>{cx, cy, cz}));
          const DimmWord<ProfileTraits<P>> w = dimms.word(d, c);
          const auto& half = (j & 1) ? w.hi : w.lo;
          if (cx < dims[0] && cy < dims[1] && cz < dims[2]) {
            ASSERT_EQ(fields<P>(half), fields<P>(voxel(cx, cy, cz)))
                << "corner " << j << " at (" << x << ", " << y << ", " << z << ")";
          } else {  // beyond a 1-voxel axis: the zero padding the hls banks hold
            ASSERT_EQ(fields<P>(half), fields<P>(hls::VoxelWordFx<ProfileTraits<P>>{})) << "corner " << j;
          }
        }
        // Four distinct DIMMs, one word each: the whole neighbourhood in one access.
        std::set<int> used;
        for (int j = 0; j < 8; ++j)
          used.insert(Vizard2Layout::dimm_of(y + ((j >> 1) & 1), z + ((j >> 2) & 1)));
        ASSERT_EQ(used.size(), std::size_t{4});
      }
  // Every word of every DIMM lies in the grid.
  const Vizard2Layout layout(dims);
  EXPECT_EQ(layout.grid().nx, static_cast<std::uint32_t>(dims[0]));
  EXPECT_EQ(layout.grid().ny2, static_cast<std::uint32_t>((dims[1] + 1) / 2));
  EXPECT_EQ(layout.grid().nz2, static_cast<std::uint32_t>((dims[2] + 1) / 2));
}

// Both ways Vizard2Memory reads the host's words: the packed words (fields of
// at most 16 bits: vizard2, balanced) and the eight bank arrays (precise).
TEST(Vizard2Layout, EveryNeighbourhoodIsOneWordPerDimm) {
  static_assert(hls::host::EngineBanks<ProfileTraits<kVizard2>>::kPacked &&
                hls::host::EngineBanks<ProfileTraits<kBalanced>>::kPacked &&
                !hls::host::EngineBanks<ProfileTraits<kPrecise>>::kPacked);
  for (const auto& dims : std::vector<std::array<int, 3>>{
           {5, 4, 3}, {6, 7, 5}, {2, 2, 2}, {1, 3, 2}, {4, 1, 1}, {9, 6, 8}}) {
    check_neighbourhoods<kVizard2>(dims);
    check_neighbourhoods<kBalanced>(dims);
    check_neighbourhoods<kPrecise>(dims);
  }
}

// The 64-bit bus word of the vizard2 profile: two 32-bit packed voxel words.
TEST(Vizard2Layout, BusWordIsTwoPackedVoxels) {
  static_assert(hls::InterpolationParams<ProfileTraits<kVizard2>>::word_bits == 32);
  const std::array<int, 3> dims{7, 6, 5};
  const bittrue::VoxelMemory mem = numbered_memory(dims);
  const Vizard2Memory<ProfileTraits<kVizard2>> dimms(mem);
  const Vizard2Layout layout(dims);
  const WordGrid& g = layout.grid();
  for (int d = 0; d < 4; ++d)
    for (std::uint32_t z2 = 0; z2 < g.nz2; ++z2)
      for (std::uint32_t y2 = 0; y2 < g.ny2; ++y2)
        for (std::uint32_t x = 0; x < g.nx; ++x) {
          const WordCoord c{x, y2, z2};
          const std::uint64_t bus = dimms.bus_word(d, c);
          const auto v = Vizard2Layout::voxel_of(d, c, 0);
          const auto lo = hls::pack_voxel_word<ProfileTraits<kVizard2>>(dimms.voxel(v[0], v[1], v[2])).to_uint64();
          const auto hi =
              hls::pack_voxel_word<ProfileTraits<kVizard2>>(dimms.voxel(v[0] + 1, v[1], v[2])).to_uint64();
          ASSERT_EQ(bus & 0xffffffffu, lo);
          ASSERT_EQ(bus >> 32, hi);
          if (v[0] + 1 == dims[0]) {
            ASSERT_EQ(hi, 0u) << "x + 1 beyond the volume reads zero";
          }
          if (v[1] < dims[1] && v[2] < dims[2]) {
            ASSERT_EQ(lo & 0xffu, (1u + static_cast<unsigned>(v[0] + 7 * v[1] + 13 * v[2])) & 0xffu);
          }
        }
}

// The hls address generator's access, translated to the four DIMM words,
// gathers the same corners as the hls design's own 8-bank view.
template <PrecisionProfile P>
void check_gather(std::array<int, 3> dims) {
  using G = hls::GeometryParams<ProfileTraits<P>>;
  const bittrue::VoxelMemory mem = numbered_memory(dims);
  const Vizard2Memory<ProfileTraits<P>> dimms(mem);
  const Vizard2Layout layout(dims);
  const hls::host::BitTrueBanks<ProfileTraits<P>> banks(mem);
  hls::GeometryRegisters<ProfileTraits<P>> r;
  for (int k = 0; k < 3; ++k) {
    r.LO[k] = 0;
    r.HI[k] = dims[static_cast<std::size_t>(k)] - 1;
    r.LAST[k] = static_cast<unsigned>(dims[static_cast<std::size_t>(k)] - 1);
    r.dims[k] = static_cast<unsigned>(dims[static_cast<std::size_t>(k)]);
  }
  r.HX = static_cast<unsigned>((dims[0] + 1) / 2);
  r.HXY = static_cast<unsigned>((dims[0] + 1) / 2 * ((dims[1] + 1) / 2));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.7, 1.0);
  for (int i = 0; i < 3000; ++i) {
    typename G::pos_t p[3];
    for (int k = 0; k < 3; ++k) p[k] = u(rng) * dims[static_cast<std::size_t>(k)];
    const hls::BankAccess<ProfileTraits<P>> acc = hls::address_generator<ProfileTraits<P>>(r, p);
    const auto words = Vizard2Layout::neighbourhood(layout.corner<ProfileTraits<P>>(acc));
    std::array<DimmWord<ProfileTraits<P>>, 4> w;
    for (int d = 0; d < 4; ++d)
      w[static_cast<std::size_t>(d)] = dimms.word(d, words[static_cast<std::size_t>(d)]);
    const rtl::layout::Dimm4Banks<ProfileTraits<P>> view{w.data(), acc.parity};
    hls::VoxelWordFx<ProfileTraits<P>> a[8], b[8];
    hls::gather<ProfileTraits<P>>(view, acc, a);
    hls::gather<ProfileTraits<P>>(banks, acc, b);
    for (int j = 0; j < 8; ++j) ASSERT_EQ(fields<P>(a[j]), fields<P>(b[j])) << "corner " << j;
  }
}

TEST(Vizard2Layout, HlsGatherSeesTheSameCorners) {
  for (const auto& dims : std::vector<std::array<int, 3>>{{9, 6, 8}, {8, 8, 8}, {1, 5, 3}, {5, 1, 2}}) {
    SCOPED_TRACE(::testing::Message() << dims[0] << "x" << dims[1] << "x" << dims[2]);
    check_gather<kVizard2>(dims);
    check_gather<kBalanced>(dims);
  }
}

// ---- Address mappings -----------------------------------------------------------------------
void check_injective(const rtl::layout::AddressMapping& m) {
  SCOPED_TRACE(std::string(m.name()));
  const WordGrid& g = m.grid();
  const auto& geo = m.geometry();
  std::set<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> seen;
  for (std::uint32_t z = 0; z < g.nz2; ++z)
    for (std::uint32_t y = 0; y < g.ny2; ++y)
      for (std::uint32_t x = 0; x < g.nx; ++x) {
        const rtl::sdram::Address a = m.map({x, y, z});
        ASSERT_LT(a.bank, geo.banks);
        ASSERT_LT(a.row, geo.rows);
        ASSERT_LT(a.column, geo.columns);
        ASSERT_TRUE(seen.insert({a.bank, a.row, a.column}).second)
            << "two words at bank " << a.bank << " row " << a.row << " column " << a.column;
      }
}

TEST(AddressMapping, EveryMappingIsInjectiveAndInside) {
  const auto geo = rtl::sdram::geometries::mt4lsdt864a();
  for (const WordGrid& g : {WordGrid{10, 5, 3}, WordGrid{16, 8, 8}, WordGrid{33, 7, 9}, WordGrid{1, 1, 1}})
    for (const std::string& name : rtl::layout::mapping_names()) {
      rtl::layout::MappingSpec spec;
      spec.name = name;
      check_injective(*rtl::layout::make_address_mapping(spec, g, geo));
      if (name == "bricked" || name == "bricked-swizzled") {
        spec.brick = {4, 2, 1};
        check_injective(*rtl::layout::make_address_mapping(spec, g, geo));
      }
    }
}

// The 256^3 volume: 256 x 128 x 128 words per DIMM, 32 MB of the 64 MB module.
TEST(AddressMapping, VizardVolumeOnTheModule) {
  const auto geo = rtl::sdram::geometries::mt4lsdt864a();
  const Vizard2Layout layout({256, 256, 256});
  EXPECT_EQ(layout.grid().words() * geo.bytes_per_beat(), std::uint64_t{32} << 20);
  rtl::layout::MappingSpec linear;
  const auto lin = rtl::layout::make_address_mapping(linear, layout.grid(), geo);
  // Linear: x streams through a row of 512 columns (two lines of x), the
  // next 512 words open the next bank.
  EXPECT_EQ(lin->map({0, 0, 0}), (rtl::sdram::Address{0, 0, 0}));
  EXPECT_EQ(lin->map({255, 1, 0}), (rtl::sdram::Address{0, 0, 511}));
  EXPECT_EQ(lin->map({0, 2, 0}), (rtl::sdram::Address{1, 0, 0}));
  EXPECT_EQ(lin->map({0, 8, 0}), (rtl::sdram::Address{0, 1, 0}));
  // Bricked 8x8x8: one brick is one row.
  rtl::layout::MappingSpec bricked;
  bricked.name = "bricked";
  const auto br = rtl::layout::make_address_mapping(bricked, layout.grid(), geo);
  const rtl::sdram::Address first = br->map({0, 0, 0});
  for (std::uint32_t z = 0; z < 8; ++z)
    for (std::uint32_t y = 0; y < 8; ++y)
      for (std::uint32_t x = 0; x < 8; ++x) {
        const rtl::sdram::Address a = br->map({x, y, z});
        ASSERT_EQ(a.bank, first.bank);
        ASSERT_EQ(a.row, first.row);
      }
  EXPECT_NE(br->map({8, 0, 0}).bank, first.bank);
  // Morton: an aligned 8x8x8 cube is one row too.
  rtl::layout::MappingSpec morton;
  morton.name = "morton";
  const auto mo = rtl::layout::make_address_mapping(morton, layout.grid(), geo);
  for (std::uint32_t z = 8; z < 16; ++z)
    for (std::uint32_t y = 0; y < 8; ++y)
      for (std::uint32_t x = 8; x < 16; ++x) ASSERT_EQ(mo->map({x, y, z}).row, mo->map({8, 0, 8}).row);
}

// Bricked 8x8x8 on the 256^3 volume: the next brick along x is in another
// bank; along y and z in the same bank for the plain layout and in another
// bank for the swizzled one (what look-ahead activation needs), with each
// brick still one whole row.
TEST(AddressMapping, SwizzledBricksPutEveryNeighbourBrickInAnotherBank) {
  const auto geo = rtl::sdram::geometries::mt4lsdt864a();
  const Vizard2Layout layout({256, 256, 256});
  rtl::layout::MappingSpec plain, swizzled;
  plain.name = "bricked";
  swizzled.name = "bricked-swizzled";
  const auto p = rtl::layout::make_address_mapping(plain, layout.grid(), geo);
  const auto s = rtl::layout::make_address_mapping(swizzled, layout.grid(), geo);
  const WordGrid& g = layout.grid();
  int same_plain_yz = 0, checked = 0;
  for (std::uint32_t z = 0; z + 8 < g.nz2; z += 8)
    for (std::uint32_t y = 0; y + 8 < g.ny2; y += 8)
      for (std::uint32_t x = 0; x + 8 < g.nx; x += 8) {
        const rtl::sdram::Address a = s->map({x, y, z});
        for (std::uint32_t k = 1; k < 8; k += 3)  // still one row per brick
          ASSERT_EQ(s->map({x + k, y + k, z + k}).row, a.row);
        ASSERT_NE(s->map({x + 8, y, z}).bank, a.bank) << x << " " << y << " " << z;
        ASSERT_NE(s->map({x, y + 8, z}).bank, a.bank) << x << " " << y << " " << z;
        ASSERT_NE(s->map({x, y, z + 8}).bank, a.bank) << x << " " << y << " " << z;
        same_plain_yz += (p->map({x, y + 8, z}).bank == p->map({x, y, z}).bank) +
                         (p->map({x, y, z + 8}).bank == p->map({x, y, z}).bank);
        ++checked;
      }
  EXPECT_EQ(same_plain_yz, 2 * checked);
}

// The bricked index as its definition reads (bricked_mapping.hpp): the
// brick's number and the word inside it, x fastest, then the bank field
// rotated by (brick y + brick z) of the brick that starts the row group.
// BrickedMapping computes the same from shifts and masks prepared once.
std::uint64_t bricked_index_by_definition(const WordCoord& c, const WordGrid& grid,
                                          const rtl::sdram::Geometry& geo,
                                          std::array<std::uint32_t, 3> brick, bool swizzle) {
  const std::uint32_t v[3] = {c.x, c.y2, c.z2};
  const std::uint32_t n[3] = {grid.nx, grid.ny2, grid.nz2};
  std::uint64_t bricks[3], number = 0, inner = 0, words = 1;
  for (int k = 2; k >= 0; --k) {
    const auto i = static_cast<std::size_t>(k);
    bricks[i] = (n[i] + brick[i] - 1) / brick[i];
    number = number * bricks[i] + v[i] / brick[i];
    inner = inner * brick[i] + v[i] % brick[i];
    words *= brick[i];
  }
  const std::uint64_t index = number * words + inner;
  if (!swizzle) return index;
  const std::uint64_t group = std::uint64_t{geo.columns} * geo.banks;  // words of a row group
  const std::uint64_t first = index / group * group / words;
  const std::uint64_t by = first / bricks[0] % bricks[1], bz = first / (bricks[0] * bricks[1]);
  const std::uint64_t bank = index / geo.columns % geo.banks;
  const std::uint64_t rotated = (bank + by + bz) % geo.banks;
  return index + (rotated - bank) * geo.columns;
}

TEST(AddressMapping, BrickedIndexIsItsDefinition) {
  const auto geo = rtl::sdram::geometries::mt4lsdt864a();
  // Brick counts that are powers of two and that are not (the swizzle
  // divides then), bricks smaller and larger than a row group.
  for (const WordGrid& g : {WordGrid{64, 32, 32}, WordGrid{40, 24, 17}, WordGrid{33, 7, 9}})
    for (const std::array<std::uint32_t, 3> brick :
         {std::array<std::uint32_t, 3>{8, 8, 8}, {4, 2, 1}, {16, 16, 8}})
      for (const bool swizzle : {false, true}) {
        const rtl::layout::BrickedMapping m(g, geo, brick, swizzle);
        for (std::uint32_t z = 0; z < g.nz2; ++z)
          for (std::uint32_t y = 0; y < g.ny2; ++y)
            for (std::uint32_t x = 0; x < g.nx; ++x)
              ASSERT_EQ(m.index({x, y, z}),
                        bricked_index_by_definition({x, y, z}, g, geo, brick, swizzle))
                  << x << " " << y << " " << z << " swizzle " << swizzle;
      }
}

TEST(AddressMapping, RejectsWhatDoesNotFit) {
  const auto geo = rtl::sdram::geometries::mt4lsdt864a();
  const Vizard2Layout big({512, 256, 256});  // 512 x 128 x 128 words: exactly 64 MB
  rtl::layout::MappingSpec spec;
  EXPECT_NO_THROW(rtl::layout::make_address_mapping(spec, big.grid(), geo));
  const Vizard2Layout too_big({512, 256, 258});
  EXPECT_THROW(rtl::layout::make_address_mapping(spec, too_big.grid(), geo), Error);
  spec.name = "bricked";
  spec.brick = {8, 6, 8};
  EXPECT_THROW(rtl::layout::make_address_mapping(spec, Vizard2Layout({16, 16, 16}).grid(), geo), Error);
  spec.name = "hilbert";
  EXPECT_THROW(rtl::layout::make_address_mapping(spec, Vizard2Layout({16, 16, 16}).grid(), geo), Error);
}

}  // namespace
}  // namespace voxcast::test
