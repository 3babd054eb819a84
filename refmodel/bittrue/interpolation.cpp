#include "refmodel/bittrue/interpolation.hpp"

#include <algorithm>
#include <cmath>
#include <ostream>

#include "refmodel/bittrue/quantize.hpp"

namespace voxcast::bittrue {

std::array<BtCorner, 8> bt_corners(const PrecisionProfile& pr, const FrameRegisters& r,
                                   const std::array<double, 3>& p) {
  std::array<int, 3> i0{};
  std::array<double, 3> fq{};
  for (std::size_t k = 0; k < 3; ++k) {
    const double c = std::clamp(p[k], static_cast<double>(r.LO[k]), static_cast<double>(r.HI[k]));
    i0[k] = r.dims[k] == 1 ? 0 : std::min(static_cast<int>(std::floor(c)), r.dims[k] - 2);
    fq[k] = q_rnd(c - i0[k], pr.weight_bits);
  }
  const std::size_t hx = static_cast<std::size_t>((r.dims[0] + 1) / 2);
  const std::size_t hy = static_cast<std::size_t>((r.dims[1] + 1) / 2);
  std::array<BtCorner, 8> corners;
  for (int j = 0; j < 8; ++j) {
    BtCorner& c = corners[static_cast<std::size_t>(j)];
    c.weight = 1.0;
    for (std::size_t k = 0; k < 3; ++k) {
      const int d = (j >> k) & 1;
      c.voxel[k] = i0[k] + d;
      c.weight *= d ? fq[k] : 1.0 - fq[k];
    }
    const int x = c.voxel[0], y = c.voxel[1], z = c.voxel[2];
    c.bank = (x & 1) | (y & 1) << 1 | (z & 1) << 2;
    c.word = static_cast<std::size_t>(x >> 1) + static_cast<std::size_t>(y >> 1) * hx +
             static_cast<std::size_t>(z >> 1) * hx * hy;
  }
  return corners;
}

std::ostream& operator<<(std::ostream& os, const BtSample& s) {
  os << "BtSample{value " << s.value << ", g (" << s.g[0] << ", " << s.g[1] << ", " << s.g[2]
     << ")}";
  return os;
}

BtSample bt_interpolate(const PrecisionProfile& pr, const FrameRegisters& r, const VoxelMemory& mem,
                        const std::array<double, 3>& p) {
  double value = 0.0;
  std::array<double, 3> g{};
  for (const BtCorner& c : bt_corners(pr, r, p)) {
    const VoxelWord& w = mem.banks[static_cast<std::size_t>(c.bank)][c.word];
    value += w.value * c.weight;  // exact: vb + 3wb bits
    for (std::size_t k = 0; k < 3; ++k)
      g[k] += from_raw(w.gradient[k], pr.gradient_frac_bits) * c.weight;  // exact
  }
  BtSample s;
  s.value = q_rnd(value, pr.sample_frac_bits);
  for (std::size_t k = 0; k < 3; ++k) s.g[k] = q_rnd(g[k], pr.sample_frac_bits);
  return s;
}

}  // namespace voxcast::bittrue
