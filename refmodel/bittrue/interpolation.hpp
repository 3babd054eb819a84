// Bit-true twin of the address generator and interpolation processor
// (docs/pipeline.md §3): the same datapath as hls/interpolation_processor.hpp
// in plain double, written independently (the sum over the 8 corners of
// v·wx·wy·wz, where the hls kernel uses nested lerps), rounding only where the
// spec rounds. Every intermediate is exact in double.
#pragma once

#include <array>
#include <cstddef>
#include <iosfwd>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/precision/profile.hpp"

namespace voxcast::bittrue {

// One of the 8 neighbours of a sample position (§3.2-3.3).
struct BtCorner {
  std::array<int, 3> voxel{};  // voxel coordinate (may be dim along a 1-voxel axis: padding)
  int bank = 0;                // (x&1) | (y&1)<<1 | (z&1)<<2
  std::size_t word = 0;        // (x>>1) + (y>>1)·hx + (z>>1)·hx·hy
  double weight = 0.0;         // wx·wy·wz, exact (3·weight_bits fraction bits)
};

// §3.1-3.3: the neighbours of p (index space), corner j = dx | dy<<1 | dz<<2.
std::array<BtCorner, 8> bt_corners(const PrecisionProfile& profile, const FrameRegisters& regs,
                                   const std::array<double, 3>& p);

// §3.5: value (stored units) and gradient (index space), sample_frac_bits each.
struct BtSample {
  double value = 0.0;
  std::array<double, 3> g{};
};
std::ostream& operator<<(std::ostream& os, const BtSample& s);
BtSample bt_interpolate(const PrecisionProfile& profile, const FrameRegisters& regs,
                        const VoxelMemory& memory, const std::array<double, 3>& p);

}  // namespace voxcast::bittrue
