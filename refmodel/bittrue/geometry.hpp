// Bit-true twin of the geometry processor (docs/pipeline.md §1-2): the same
// datapath as hls/geometry_processor.hpp in plain double, rounding at exactly
// the spec's points with the quantizers of quantize.hpp (not the fixed-point
// class). Every value is exact in double (the spec keeps intermediates below
// 2^53 LSBs), so the two implementations must agree on every bit.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <vector>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/precision/profile.hpp"

namespace voxcast::bittrue {

// One pixel's ray (§1.5-1.6). Positions and steps in index space; k_in, k_out
// in samples. A miss has n = 0 and p0 = k_in = k_out = 0.
struct BtRay {
  bool hit = false;
  std::uint64_t n = 0;  // up to 2^(addr_bits + pos_frac_bits)
  std::array<double, 3> p0{}, s{};
  double k_in = 0.0, k_out = 0.0;
};
std::ostream& operator<<(std::ostream& os, const BtRay& ray);

// §1.1-1.2, perspective: the unit direction u (world space) of pixel (px, py).
std::array<double, 3> bt_unit_direction(const PrecisionProfile& profile, const FrameRegisters& regs,
                                        const std::vector<Raw>& rsqrt_seed, int px, int py);

// §1.4: the ray origin (index space) of pixel (px, py).
std::array<double, 3> bt_ray_origin(const PrecisionProfile& profile, const FrameRegisters& regs,
                                    int px, int py);

// §1: ray setup of pixel (px, py), perspective or parallel as the registers say
// (a parallel camera never reads rsqrt_seed).
BtRay bt_ray_setup(const PrecisionProfile& profile, const FrameRegisters& regs,
                   const std::vector<Raw>& rsqrt_seed, int px, int py);
BtRay bt_ray_setup(const FrameSetup& setup, int px, int py);

// §2: the next sample position, p + s (exact).
std::array<double, 3> bt_step(const std::array<double, 3>& p, const std::array<double, 3>& s);

}  // namespace voxcast::bittrue
