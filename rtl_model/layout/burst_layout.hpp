// The volume on DDR4 channels in 64-byte bursts: the layouts the U250 card
// could use, and what a frame's samples cost in bursts on each (issue 23 part
// 2's design question, docs/sdram.md §9).
//
// On the 2001 card one access to each of the four PC100 DIMMs (one 64-bit
// word, BL 1) returns a voxel and its x-neighbour, and the four DIMMs together
// the 2x2x2 cell of any sample (vizard2_layout.hpp). A DDR4 channel moves
// 64 bytes per access (BL8 on 64 data bits, JESD79-4B §3.3): 16 voxels of 32
// bits (the vizard2 profile's packed word) or 8 of 64 bits. So a burst must
// hold a brick of voxels, and what decides the layout is how many bursts a
// frame's samples need:
//
//   BurstLayout   a brick shape (voxels per burst along x, y, z), the channel
//                 of each brick (the parities of its coordinates along the two
//                 axes a cell crosses most often, so a cell's bricks spread over
//                 the four channels), and each brick's DDR4 address in its
//                 channel: bank group, bank, row, column. The bank group is the
//                 brick's x (plain) or x + y + z (skewed) in the channel's grid,
//                 modulo 4: skewed, the channel's next brick along any axis is
//                 in another group, so successive bursts of a ray meet tCCD_S,
//                 not tCCD_L.
//   BurstCounter  the bursts a stream of samples (ray by ray, each sample's
//                 cell) fetches under three reuse schemes: none (every sample
//                 fetches its cell's bricks), ray (a ray keeps the bricks of its
//                 previous sample: a register per ray slot), cache (a direct-
//                 mapped brick cache of K lines per channel, shared by the
//                 rays, indexed by a hash of the brick's index); per channel
//                 the bursts, the bank-group changes, the
//                 row outcomes (open page) and the data-bus clocks they need.
//
// The counts are exact for the stream; the clocks are the data bus's bound
// (BL/2 per burst, tCCD_L instead of tCCD_S between two bursts of one bank
// group; activates, refresh and the read-to-data latency not counted): what
// the layout allows, not what a controller reaches (that is the cycle model's).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace voxcast::rtl::layout {

inline constexpr int kBurstChannels = 4;  // the U250's four DDR4 DIMMs
inline constexpr int kBankGroups = 4;     // 8Gb x4/x8 DDR4: 4 groups of 4 banks

// One channel's memory and data bus as the study needs them. Defaults: the
// U250 board's module (constraints/boards/alveo_u250.toml: MT40A2G4 8Gb x4,
// 16 banks in 4 groups, 1K columns of the 64-bit bus) at DDR4-2400 (JESD79-4B:
// BL8 is 4 clocks of 1200 MHz, tCCD_S = 4, tCCD_L = 6 clocks).
struct BurstMemory {
  int burst_bytes = 64;  // BL8 x 8 bytes
  int banks_per_group = 4;
  std::uint32_t columns = 1024;  // 8-byte columns per row
  std::uint32_t rows = 131072;
  double clock_mhz = 1200.0;
  int burst_clocks = 4;  // BL/2: the data bus is busy 4 clocks per burst
  int tCCD_S = 4;        // column to column, other bank group
  int tCCD_L = 6;        // column to column, same bank group

  std::uint32_t bursts_per_row() const {
    return columns * 8u / static_cast<std::uint32_t>(burst_bytes);
  }
};

enum class BankGroupMap : std::uint8_t {
  kPlain,   // bank group = x mod 4 (the brick's place in its channel's grid)
  kSkewed,  // bank group = (x + y + z) mod 4 (likewise)
};

// Which DDR4 row and bank a brick's group of four lands in.
enum class RowMap : std::uint8_t {
  // The channel's bricks in x-fastest order, 128 groups of four to a row,
  // rows filling the banks in turn: a row is a run of x-lines.
  kLinear,
  // A row holds a cube of the channel's bricks (8x8x8 for 128 bursts of 64
  // bytes in an 8 KB row, times the four bank groups), and the cube's bank is
  // the sum of its coordinates modulo the banks: a ray leaving a cube along
  // any axis opens a row in another bank, and the rows of the cubes around
  // stay open for the rays next to it.
  kBlocks,
};

// A burst's place on the card: its channel and DDR4 address.
struct BurstAddress {
  int channel = 0;
  int bank_group = 0;
  int bank = 0;  // within the group
  std::uint32_t row = 0;
  std::uint32_t column = 0;  // first column of the burst
  std::uint64_t index = 0;   // the brick's index in its channel (unique there)

  friend bool operator==(const BurstAddress&, const BurstAddress&) = default;
};

class BurstLayout {
 public:
  // Throws voxcast::Error unless every brick edge is a power of two, their
  // product is `voxels_per_burst`, and the volume fits the channel.
  BurstLayout(std::array<int, 3> dims, std::array<int, 3> brick, int voxels_per_burst,
              BankGroupMap groups, const BurstMemory& memory = {}, RowMap rows = RowMap::kLinear);

  // "4x2x2-plain", "4x2x2-skewed", with "-blocks" for RowMap::kBlocks.
  std::string name() const;
  RowMap rows() const { return rows_; }
  const std::array<int, 3>& brick() const { return brick_; }
  // The two axes whose brick parities choose the channel.
  const std::array<int, 2>& channel_axes() const { return channel_axes_; }
  BankGroupMap groups() const { return groups_; }
  const BurstMemory& memory() const { return memory_; }

  // The burst holding voxel v.
  BurstAddress burst_of(const std::array<int, 3>& v) const;
  // The bursts holding the 2x2x2 cell with lowest corner i0 (the interpolation
  // unit's cell: i0 + 1 stays inside the volume along every axis longer than
  // one voxel), each once; returns how many (1 to 8).
  int cell_bursts(const std::array<int, 3>& i0, std::array<BurstAddress, 8>& out) const;

 private:
  std::array<int, 3> dims_;
  std::array<int, 3> brick_;
  std::array<int, 3> log2_;              // log2 of brick_
  std::array<std::uint64_t, 3> grid_{};  // bricks per axis in one channel's grid
  std::array<int, 2> channel_axes_{};
  BankGroupMap groups_;
  BurstMemory memory_;
  RowMap rows_;
  std::array<int, 3> block_log2_{};        // RowMap::kBlocks: the cube's edges in bricks
  std::array<std::uint64_t, 3> blocks_{};  // cubes per axis (x padded to whole banks)
};

// Brick shapes of `voxels_per_burst` voxels: the line along x (VIZARD II's word
// order, one burst per DIMM row segment) and every power-of-two brick whose
// edges are at most 4.
std::vector<std::array<int, 3>> burst_shapes(int voxels_per_burst);

enum class Reuse : std::uint8_t { kNone, kRay, kCache };
inline constexpr std::array<Reuse, 3> kAllReuse{Reuse::kNone, Reuse::kRay, Reuse::kCache};
const char* name(Reuse r);

// Per channel, what the bursts of one reuse scheme cost.
struct ChannelLoad {
  std::uint64_t bursts = 0;
  std::uint64_t same_group = 0;  // bursts in the bank group of the burst before
  std::uint64_t row_hits = 0, row_misses = 0, row_conflicts = 0;  // open page, 16 banks
  std::uint64_t bus_clocks = 0;  // burst_clocks, or tCCD_L after a burst of the same group
};

struct ReuseLoad {
  std::array<ChannelLoad, kBurstChannels> channel{};
  // A field summed over the channels.
  std::uint64_t total(std::uint64_t ChannelLoad::*field) const;
  std::uint64_t bursts() const { return total(&ChannelLoad::bursts); }
  std::uint64_t same_group() const { return total(&ChannelLoad::same_group); }
  std::uint64_t row_hits() const { return total(&ChannelLoad::row_hits); }
  // The busiest channel's data-bus clocks: the frame's bound.
  std::uint64_t bound_clocks() const;
};

// A burst one reuse scheme fetched, and the sample (its place in the stream,
// from 0) that needed it: what a channel's request trace is made of.
struct Fetch {
  std::uint64_t sample = 0;
  BurstAddress burst;
};

// The line of a direct-mapped brick cache of 2^cache_bits lines that holds
// the brick of channel index `index`: Fibonacci hashing (Knuth, TAOCP vol. 3,
// §6.4), the top bits of index x 2^64 / golden ratio. The brick index's low
// bits alone would map every brick of a z column of a 2^n grid slab onto one
// line. The burst study's counter and the DDR4 card's cache share it.
inline std::size_t brick_cache_line(std::uint64_t index, int cache_bits) {
  if (cache_bits == 0) return 0;
  return static_cast<std::size_t>((index * 0x9E3779B97F4A7C15ull) >> (64 - cache_bits));
}

class BurstCounter {
 public:
  // `cache_lines`: lines per channel of the direct-mapped brick cache (a power
  // of two: check_cache_lines).
  BurstCounter(const BurstLayout& layout, std::uint32_t cache_lines);
  // Throws voxcast::Error naming the value unless it is a power of two.
  static void check_cache_lines(std::uint32_t cache_lines);

  void begin_ray();
  void sample(const std::array<int, 3>& i0);

  std::uint64_t samples() const { return samples_; }
  const ReuseLoad& load(Reuse r) const { return load_[static_cast<std::size_t>(r)]; }
  std::uint32_t cache_lines() const { return cache_lines_; }
  const BurstLayout& layout() const { return layout_; }
  // Samples per second the busiest channel's data bus allows under `r`.
  double bound_samples_per_second(Reuse r) const;
  // Appends every fetch under `r` from now on to *out (null: stop).
  void record(Reuse r, std::vector<Fetch>* out) { recorder_[static_cast<std::size_t>(r)] = out; }

 private:
  struct Open {
    std::array<std::uint32_t, kBankGroups * 4> row{};
    std::array<bool, kBankGroups * 4> open{};
    int last_group = -1;
  };
  void fetch(Reuse r, const BurstAddress& b);
  std::size_t cache_line(std::uint64_t index) const;

  const BurstLayout& layout_;
  std::uint32_t cache_lines_;
  int cache_bits_ = 0;
  std::uint64_t samples_ = 0;
  std::array<ReuseLoad, 3> load_{};
  std::array<std::array<Open, kBurstChannels>, 3> open_{};
  // Ray reuse: the previous sample's bursts (channel, index).
  std::array<BurstAddress, 8> prev_{};
  int prev_count_ = 0;
  // Cache reuse: per channel, the brick index held by each line (+1; 0 empty).
  std::array<std::vector<std::uint64_t>, kBurstChannels> cache_;
  std::array<std::vector<Fetch>*, 3> recorder_{};
};

}  // namespace voxcast::rtl::layout
