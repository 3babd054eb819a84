// The bit-true reference ray caster: the units of docs/pipeline.md composed
// into a whole ray, in double, rounding where the hardware rounds. It checks
// the hls kernels independently of the fixed-point class (hls == bit-true on
// every bit), and records a per-sample trace so a mismatch can be pinned to the
// unit where the engines first diverge.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/geometry.hpp"
#include "refmodel/bittrue/interpolation.hpp"
#include "refmodel/bittrue/shading.hpp"
#include "refmodel/render/quant_image.hpp"
#include "refmodel/render/raycaster.hpp"

namespace voxcast::bittrue {

// Every unit's output for one sample, as values on their fixed-point grids.
// The hls engine fills the same structure, so traces compare field by field.
struct SampleTrace {
  std::array<double, 3> position{};  // geometry processor (stepping)
  double value = 0.0;                // interpolation processor
  std::array<double, 3> gradient{};
  int class_address = 0;             // classification table
  double alpha = 0.0;
  double diffuse = 0.0, specular = 0.0;  // reflectance map
  std::array<double, 3> shaded{};        // shader
  std::array<double, 4> accumulator{};   // compositor (C, A) or MIP maximum in [0]
};

struct RayTrace {
  bool hit = false;
  std::uint64_t samples = 0;
  std::array<double, 3> p0{}, step{};  // ray setup
  std::vector<SampleTrace> trace;
  std::array<std::uint32_t, 4> out{};
};

// Units in pipeline order, for naming where two traces diverge.
enum class Unit {
  RaySetup, Stepping, Interpolation, Classification, ReflectanceMap, Shader, Compositor, Output
};
const char* to_string(Unit u);

struct Divergence {
  bool diverged = false;
  std::uint64_t sample = 0;  // index along the ray (for RaySetup/Output: 0)
  Unit unit = Unit::Output;
};
// The first unit, in pipeline order and sample order, whose outputs differ.
Divergence first_divergence(const RayTrace& a, const RayTrace& b);

// One pixel. `trace` (optional) receives every sample's unit outputs;
// `stats` (optional) what the ray did, as ref::FrameStats defines it: the
// geometry processor's hit flag, the samples read and those space leaping
// skipped, and whether ERT ended the ray before its last sample position.
std::array<std::uint32_t, 4> bt_cast_ray(const FrameSetup& setup, const VoxelMemory& memory,
                                         int px, int py, RayTrace* trace = nullptr,
                                         ref::RayStats* stats = nullptr);

// Space leaping (setup.leap set): whether the block with index `block` is
// empty (hls::block_empty), and whether the sample at `pos` lies in an empty
// block (hls::block_address, then block_empty).
bool bt_block_empty(const FrameSetup& setup, std::size_t block);
bool bt_skips(const FrameSetup& setup, const std::array<double, 3>& pos);

// The whole frame, rows over `threads` workers (bit-identical for any count).
ref::QuantImage bt_render_image(const FrameSetup& setup, const VoxelMemory& memory,
                                int threads = 0, ref::FrameStats* stats = nullptr);

}  // namespace voxcast::bittrue
