#include "rtl_model/layout/burst_layout.hpp"

#include <algorithm>
#include <bit>
#include <sstream>

#include "refmodel/error.hpp"

namespace voxcast::rtl::layout {

namespace {

bool power_of_two(int v) { return v > 0 && std::has_single_bit(static_cast<unsigned>(v)); }

std::uint64_t ceil_div(std::uint64_t a, std::uint64_t b) { return (a + b - 1) / b; }

// The two axes along which a cell crosses a brick boundary most often (the
// shortest brick edges: a cell at i0 crosses along k when i0 + 1 starts a new
// brick, for 1 in brick[k] positions), y and z first on a tie as on the 2001
// card, whose DIMM was the voxel's (y, z) parity.
std::array<int, 2> choose_channel_axes(const std::array<int, 3>& brick) {
  std::array<int, 3> order{1, 2, 0};
  std::stable_sort(order.begin(), order.end(), [&brick](int a, int b) {
    return brick[static_cast<std::size_t>(a)] < brick[static_cast<std::size_t>(b)];
  });
  std::array<int, 2> axes{order[0], order[1]};
  std::sort(axes.begin(), axes.end());
  return axes;
}

}  // namespace

BurstLayout::BurstLayout(std::array<int, 3> dims, std::array<int, 3> brick, int voxels_per_burst,
                         BankGroupMap groups, const BurstMemory& memory, RowMap rows)
    : dims_(dims), brick_(brick), groups_(groups), memory_(memory), rows_(rows) {
  std::ostringstream name;
  name << brick[0] << "x" << brick[1] << "x" << brick[2];
  for (int k = 0; k < 3; ++k) {
    if (dims[static_cast<std::size_t>(k)] < 1)
      throw Error("burst layout: volume extent " +
                  std::to_string(dims[static_cast<std::size_t>(k)]) + " along axis " +
                  std::to_string(k) + " is not positive");
    if (!power_of_two(brick[static_cast<std::size_t>(k)]))
      throw Error("burst layout " + name.str() + ": brick edges must be powers of two");
  }
  if (brick[0] * brick[1] * brick[2] != voxels_per_burst)
    throw Error("burst layout " + name.str() + ": a burst holds " +
                std::to_string(voxels_per_burst) + " voxels, the brick " +
                std::to_string(brick[0] * brick[1] * brick[2]));
  if (!power_of_two(memory.banks_per_group) ||
      !power_of_two(static_cast<int>(memory.bursts_per_row())))
    throw Error("burst layout: banks per group and bursts per row must be powers of two");
  for (std::size_t k = 0; k < 3; ++k) log2_[k] = std::countr_zero(static_cast<unsigned>(brick[k]));
  channel_axes_ = choose_channel_axes(brick);
  // One channel's bricks: half the bricks along each channel axis (their
  // parity is the channel), x padded to whole groups of four bricks so that
  // four x-consecutive bricks share a column address in the four bank groups.
  for (std::size_t k = 0; k < 3; ++k) {
    std::uint64_t n =
        ceil_div(static_cast<std::uint64_t>(dims[k]), static_cast<std::uint64_t>(brick[k]));
    if (static_cast<int>(k) == channel_axes_[0] || static_cast<int>(k) == channel_axes_[1])
      n = ceil_div(n, 2);
    grid_[k] = n;
  }
  grid_[0] = ceil_div(grid_[0], kBankGroups) * kBankGroups;
  const auto banks = static_cast<std::uint64_t>(memory.banks_per_group);
  std::uint64_t rows_needed = 0;
  if (rows == RowMap::kLinear) {
    rows_needed = ceil_div(grid_[0] * grid_[1] * grid_[2] / kBankGroups,
                           std::uint64_t{memory.bursts_per_row()} * banks);
  } else {
    // The row's bricks (bursts per row x the four groups) as a cube, the
    // extra bit of an uneven split on x, then y; x keeps at least the two
    // bits of a group of four.
    const int bits = std::countr_zero(memory.bursts_per_row() * static_cast<unsigned>(kBankGroups));
    block_log2_ = {(bits + 2) / 3, (bits + 1) / 3, bits / 3};
    if (block_log2_[0] < 2)
      throw Error("burst layout: a row must hold at least one group of four bursts per bank group");
    for (std::size_t k = 0; k < 3; ++k)
      blocks_[k] = ceil_div(grid_[k], std::uint64_t{1} << block_log2_[k]);
    blocks_[0] = ceil_div(blocks_[0], banks) * banks;
    rows_needed = blocks_[0] * blocks_[1] * blocks_[2] / banks;
  }
  if (rows_needed > memory.rows)
    throw Error("burst layout " + this->name() + ": the volume needs " +
                std::to_string(rows_needed) + " rows in each bank of a channel, a bank has " +
                std::to_string(memory.rows));
}

std::string BurstLayout::name() const {
  std::ostringstream os;
  os << brick_[0] << "x" << brick_[1] << "x" << brick_[2]
     << (groups_ == BankGroupMap::kSkewed ? "-skewed" : "-plain")
     << (rows_ == RowMap::kBlocks ? "-blocks" : "");
  return os.str();
}

BurstAddress BurstLayout::burst_of(const std::array<int, 3>& v) const {
  std::array<std::uint64_t, 3> b{};  // the brick's coordinates in the volume
  for (std::size_t k = 0; k < 3; ++k) b[k] = static_cast<std::uint64_t>(v[k]) >> log2_[k];
  BurstAddress a;
  const auto ax0 = static_cast<std::size_t>(channel_axes_[0]);
  const auto ax1 = static_cast<std::size_t>(channel_axes_[1]);
  a.channel = static_cast<int>((b[ax0] & 1u) | (b[ax1] & 1u) << 1);
  std::array<std::uint64_t, 3> c = b;  // in the channel's grid
  c[ax0] >>= 1;
  c[ax1] >>= 1;
  a.index = c[0] + grid_[0] * (c[1] + grid_[1] * c[2]);
  // Four x-consecutive bricks of the channel's grid (one index group) share
  // bank, row and column in the four bank groups: plain by their x, skewed by
  // x + y + z in the channel's grid, a permutation of 0..3 over the four either
  // way. Skewed, the next brick of the channel along any axis is in another
  // group.
  const std::uint64_t group_sum = groups_ == BankGroupMap::kSkewed ? c[0] + c[1] + c[2] : c[0];
  a.bank_group = static_cast<int>(group_sum % kBankGroups);
  const auto columns_per_burst = static_cast<std::uint64_t>(memory_.burst_bytes) / 8u;
  const auto banks = static_cast<std::uint64_t>(memory_.banks_per_group);
  if (rows_ == RowMap::kLinear) {
    const std::uint64_t m = a.index / kBankGroups;
    const std::uint64_t per_row = memory_.bursts_per_row();
    a.column = static_cast<std::uint32_t>((m % per_row) * columns_per_burst);
    const std::uint64_t bank_row = m / per_row;
    a.bank = static_cast<int>(bank_row % banks);
    a.row = static_cast<std::uint32_t>(bank_row / banks);
    return a;
  }
  // The brick's place in its cube (x fastest) gives the column; four
  // x-consecutive places share it, one per bank group, as above.
  std::array<std::uint64_t, 3> cube{};
  std::uint64_t place = 0;
  int shift = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    cube[k] = c[k] >> block_log2_[k];
    place |= (c[k] & ((std::uint64_t{1} << block_log2_[k]) - 1u)) << shift;
    shift += block_log2_[k];
  }
  a.column = static_cast<std::uint32_t>((place / kBankGroups) * columns_per_burst);
  // Four x-consecutive cubes share a row number, one per bank.
  a.bank = static_cast<int>((cube[0] + cube[1] + cube[2]) % banks);
  a.row =
      static_cast<std::uint32_t>((cube[0] + blocks_[0] * (cube[1] + blocks_[1] * cube[2])) / banks);
  return a;
}

int BurstLayout::cell_bursts(const std::array<int, 3>& i0, std::array<BurstAddress, 8>& out) const {
  int n = 0;
  for (int corner = 0; corner < 8; ++corner) {
    std::array<int, 3> v = i0;
    bool outside = false;
    for (std::size_t k = 0; k < 3; ++k) {
      if ((corner >> k) & 1) ++v[k];
      outside = outside || v[k] >= dims_[k];
    }
    if (outside) continue;  // a one-voxel extent: the unit reads its padding
    const BurstAddress a = burst_of(v);
    bool seen = false;
    for (int j = 0; j < n && !seen; ++j)
      seen = out[static_cast<std::size_t>(j)].channel == a.channel &&
             out[static_cast<std::size_t>(j)].index == a.index;
    if (!seen) out[static_cast<std::size_t>(n++)] = a;
  }
  return n;
}

std::vector<std::array<int, 3>> burst_shapes(int voxels_per_burst) {
  std::vector<std::array<int, 3>> shapes{{voxels_per_burst, 1, 1}};
  for (int x = 1; x <= 4; x *= 2)
    for (int y = 1; y <= 4; y *= 2)
      for (int z = 1; z <= 4; z *= 2)
        if (x * y * z == voxels_per_burst && !(x == voxels_per_burst && y == 1 && z == 1))
          shapes.push_back({x, y, z});
  return shapes;
}

const char* name(Reuse r) {
  switch (r) {
    case Reuse::kNone:
      return "none";
    case Reuse::kRay:
      return "ray";
    case Reuse::kCache:
      return "cache";
  }
  return "?";
}

std::uint64_t ReuseLoad::total(std::uint64_t ChannelLoad::*field) const {
  std::uint64_t n = 0;
  for (const ChannelLoad& c : channel) n += c.*field;
  return n;
}

std::uint64_t ReuseLoad::bound_clocks() const {
  std::uint64_t m = 0;
  for (const ChannelLoad& c : channel) m = std::max(m, c.bus_clocks);
  return m;
}

void BurstCounter::check_cache_lines(std::uint32_t cache_lines) {
  if (!std::has_single_bit(cache_lines))
    throw Error("burst study: the brick cache's lines per channel must be a power of two, not " +
                std::to_string(cache_lines));
}

BurstCounter::BurstCounter(const BurstLayout& layout, std::uint32_t cache_lines)
    : layout_(layout), cache_lines_(cache_lines) {
  check_cache_lines(cache_lines);
  cache_bits_ = std::countr_zero(cache_lines);
  for (auto& c : cache_) c.assign(cache_lines, 0);
}

void BurstCounter::begin_ray() { prev_count_ = 0; }

std::size_t BurstCounter::cache_line(std::uint64_t index) const {
  return brick_cache_line(index, cache_bits_);
}

void BurstCounter::fetch(Reuse r, const BurstAddress& b) {
  const auto ri = static_cast<std::size_t>(r);
  ChannelLoad& c = load_[ri].channel[static_cast<std::size_t>(b.channel)];
  Open& o = open_[ri][static_cast<std::size_t>(b.channel)];
  const BurstMemory& m = layout_.memory();
  ++c.bursts;
  const bool same = o.last_group == b.bank_group;
  c.same_group += same ? 1u : 0u;
  c.bus_clocks += static_cast<std::uint64_t>(std::max(m.burst_clocks, same ? m.tCCD_L : m.tCCD_S));
  o.last_group = b.bank_group;
  const auto bank = static_cast<std::size_t>(b.bank_group * m.banks_per_group + b.bank);
  if (!o.open[bank]) {
    ++c.row_misses;
  } else if (o.row[bank] == b.row) {
    ++c.row_hits;
  } else {
    ++c.row_conflicts;
  }
  o.open[bank] = true;
  o.row[bank] = b.row;
  if (recorder_[ri]) recorder_[ri]->push_back(Fetch{samples_ - 1, b});
}

void BurstCounter::sample(const std::array<int, 3>& i0) {
  std::array<BurstAddress, 8> bursts;
  const int n = layout_.cell_bursts(i0, bursts);
  ++samples_;
  for (int j = 0; j < n; ++j) {
    const BurstAddress& b = bursts[static_cast<std::size_t>(j)];
    fetch(Reuse::kNone, b);
    bool held = false;
    for (int q = 0; q < prev_count_ && !held; ++q)
      held = prev_[static_cast<std::size_t>(q)].channel == b.channel &&
             prev_[static_cast<std::size_t>(q)].index == b.index;
    if (!held) fetch(Reuse::kRay, b);
    std::uint64_t& line = cache_[static_cast<std::size_t>(b.channel)][cache_line(b.index)];
    if (line != b.index + 1) {
      line = b.index + 1;
      fetch(Reuse::kCache, b);
    }
  }
  prev_ = bursts;
  prev_count_ = n;
}

double BurstCounter::bound_samples_per_second(Reuse r) const {
  const std::uint64_t clocks = load(r).bound_clocks();
  if (clocks == 0) return 0.0;
  return static_cast<double>(samples_) /
         (static_cast<double>(clocks) / (layout_.memory().clock_mhz * 1e6));
}

}  // namespace voxcast::rtl::layout
