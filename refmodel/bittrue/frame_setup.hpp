// The host's side of the fixed-point design: everything the driver computes in
// double and loads into the card before a frame (docs/pipeline.md §0 and the
// tables of §1, §4, §5), as raw two's-complement integers at the formats the
// profile defines. The hls engine and the bit-true reference both consume this
// one structure, so they check the datapath, not two copies of the set-up.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "refmodel/precision/profile.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/render/space_leaping.hpp"
#include "refmodel/scene/scene.hpp"

namespace voxcast::bittrue {

using Raw = std::int64_t;  // a fixed-point value's integer V (value = V * 2^-F)
using Raw3 = std::array<Raw, 3>;

// docs/pipeline.md §0.
struct FrameRegisters {
  bool perspective = true;
  int width = 0, height = 0;
  ref::RenderMode mode = ref::RenderMode::Shaded;
  Raw3 A{}, B{}, C{};  // perspective directions, dir_frac_bits
  Raw3 O{}, P{}, R{};  // origin plane: pixel (0,0)'s ray origin, increments, pos_frac_bits
  Raw3 U{};            // parallel unit direction, dir_frac_bits
  Raw3 K{};            // step / world_scale per axis, dir_frac_bits
  Raw3 IS{};           // 1 / world_scale per axis, dir_frac_bits
  std::array<int, 3> LO{}, HI{};  // voxel-centre box (crop), integers
  std::array<int, 3> dims{};      // volume dims
  Raw RM = 0;                     // 1 / max_stored, dir_frac_bits (MIP)
  bool ert_enabled = true;
  Raw ert_threshold = 0;          // acc_bits
  bool jitter = false;            // render.jitter: start offset (t_frac_bits) per pixel
  double origin_depth = 0.0;      // the origin plane's depth D from the eye, world units
                                  // (host only: the guard's and the tests' bound)
};

// One voxel word (docs/pipeline.md §3.4).
struct VoxelWord {
  std::uint32_t value = 0;      // value_bits
  std::array<std::int32_t, 3> gradient{};  // gradient_bits signed, gradient_frac_bits
};

// A voxel word in 8 bytes, for a host that reads the banks (the hls engine,
// hls/host_march.hpp): the same fields when value_bits and gradient_bits are
// at most 16.
struct PackedVoxelWord {
  std::uint16_t value = 0;
  std::array<std::int16_t, 3> gradient{};
};
static_assert(sizeof(PackedVoxelWord) == 8, "a packed voxel word is 8 bytes");

// The volume in 8 interleaved banks (docs/pipeline.md §3.3).
struct VoxelMemory {
  std::array<int, 3> dims{};
  std::array<std::vector<VoxelWord>, 8> banks;
  // The same words in the host's layout (docs/performance.md §13): bank b's
  // word a at [8 a + b], 8 bytes each, so the 2x2x2 voxels of one word address
  // share a 64-byte cache line, and a cell's eight corners lie in 1-8 lines (3.4
  // on average over the cell's parities) instead of eight, one per bank array.
  // Null when a field is wider than 16 bits.
  std::shared_ptr<const std::vector<PackedVoxelWord>> packed;
  // The volume's min-max blocks (docs/leaping.md) of the stored values, which the value
  // fields hold << value_shift, built with the memory (make_voxel_memory) at
  // kEngineLeapBlockLog2: what an engine reads that skips empty space on its own when the
  // scene does not ask for space leaping (the hls engine, hls/host_march.hpp; the image
  // is the same bits). Null when the memory was not made by make_voxel_memory.
  std::shared_ptr<const ref::MinMaxBlocks> leap_blocks;
  int value_shift = 0;
};
// The block edge (log2) of VoxelMemory::leap_blocks: 4^3 cells.
inline constexpr int kEngineLeapBlockLog2 = 2;

// One classification-table entry, each field an unsigned fraction (§4).
struct ClassEntry {
  std::uint32_t r = 0, g = 0, b = 0;  // color_bits
  std::uint32_t alpha = 0;            // alpha_bits, opacity-corrected for the step
  std::uint32_t ka = 0, kd = 0, ks = 0;  // k_bits
};

// Space leaping (docs/leaping.md, hls/space_leaping_unit.hpp): the volume's
// min-max blocks (stored values; the value field holds them << value_shift) and
// the prefix count over the classification table's opacity.
struct LeapTables {
  std::shared_ptr<const ref::MinMaxBlocks> blocks;
  int value_shift = 0;
  std::vector<std::uint32_t> nonzero_prefix;  // 2^tf_addr_bits + 1: entries below i with alpha != 0
};
std::vector<std::uint32_t> nonzero_prefix(const std::vector<ClassEntry>& table);

// render.partial_segments (docs/pipeline.md §7a, hls/segment_opacity.hpp): per
// classification entry the optical depth tau2 = -log2(1 - alpha_c) and the
// ROM of 2^-x, both with alpha_bits + segment_guard_bits fraction bits.
// The unit's widths as docs/pipeline.md §7a states them (the bit-true model's own
// derivation; the hls kernel's are hls/widths.hpp's segment_* functions).
inline constexpr int kSegmentGuardBits = 3;  // g
inline int segment_frac_bits(const PrecisionProfile& p) { return p.alpha_bits + kSegmentGuardBits; }
inline int segment_rom_index_bits(const PrecisionProfile& p) {  // r = ceil((ab + g - 3)/2)
  return (p.alpha_bits + kSegmentGuardBits - 2) / 2;
}
inline int segment_max_shift(const PrecisionProfile& p) { return p.alpha_bits + 2; }
struct SegmentTables {
  std::vector<Raw> tau;  // 2^tf_addr_bits entries (§7a.2)
  std::vector<Raw> rom;  // 2^r + 1 entries, 2^-(i·2^-r) (§7a.4)
};
SegmentTables make_segment_tables(const PrecisionProfile& profile,
                                  const std::vector<ClassEntry>& class_table);

struct FrameSetup {
  PrecisionProfile profile;
  FrameRegisters regs;
  std::vector<Raw> rsqrt_seed;           // 2^rsqrt_seed_bits entries, dir_frac_bits (§1.2)
  std::vector<ClassEntry> class_table;   // 2^tf_addr_bits entries (§4)
  std::vector<std::uint32_t> rm_diffuse;   // rm_entries(profile), rm_int_bits.rm_frac_bits (§5)
  std::vector<std::uint32_t> rm_specular;  // likewise
  std::optional<LeapTables> leap;          // render.space_leaping (never in MIP)
  std::optional<SegmentTables> segments;   // render.partial_segments (never in MIP)
  // render.classification = "preintegrated" (§4a, never in MIP): 2^(2 preint_addr_bits)
  // entries, front-major (entry (f << preint_addr_bits) | b), shared between frames of
  // the same transfer function, step and widths (make_preint_table caches it).
  std::shared_ptr<const std::vector<ClassEntry>> preint_table;
};

// Voxel values enter the value field scaled to its full range (docs/pipeline.md
// §3.4): value = stored << value_shift, so an 8-bit volume in a 12-bit field
// uses every classification-table address. Gradients scale with the values.
inline int value_shift(const PrecisionProfile& p, const ref::Volume& v) {
  return p.value_bits > v.bits ? p.value_bits - v.bits : 0;
}

// The transfer function in the value field's units (§3.4: stored values
// shifted by value_shift), the units the tables are addressed in.
ref::TransferFunction field_transfer_function(const PrecisionProfile& p,
                                              const ref::TransferFunction& tf_stored,
                                              const ref::Volume& v);

// Raw integer of Q_RND(x, frac_bits) (ties towards +inf), for register loads.
Raw quantize_rnd(double x, int frac_bits);

// --- Set-up, split by the unit that owns it ---------------------------------
// Geometry processor registers (§0) and the rsqrt seed ROM (§1.2):
// refmodel/bittrue/setup_geometry.cpp.
FrameRegisters make_frame_registers(const PrecisionProfile& profile, const ref::Scene& scene,
                                    const ref::RenderInputs& inputs);
std::vector<Raw> make_rsqrt_seed(const PrecisionProfile& profile);
// The origin plane's depth D from the eye (world units, >= 0), or -1 when no
// plane keeps the corner pixels' origins in the origin register's range.
double origin_plane_depth(const PrecisionProfile& profile, const ref::CameraFrame& camera,
                          const ref::Vec3& world_scale, const ref::Box& index_box);
// The volume's voxel words in their banks (value + quantized gradient property, §3.3-3.4).
VoxelMemory make_voxel_memory(const PrecisionProfile& profile, const ref::Volume& volume,
                              const ref::GradientField& gradients);
// The memory's banks as VoxelMemory::packed lays them out; the fields must fit
// 16 bits (value_bits, gradient_bits <= 16). make_voxel_memory calls it when
// they do; a memory whose banks are edited afterwards must call it again.
std::shared_ptr<const std::vector<PackedVoxelWord>> pack_banks(const VoxelMemory& memory);

// Classification table (§4) and reflectance maps (§5):
// refmodel/bittrue/setup_tables.cpp. `step` is the sampling distance in world
// units (opacity correction is baked into the table).
std::vector<ClassEntry> make_class_table(const PrecisionProfile& profile,
                                         const ref::TransferFunction& tf_stored, double step);
// §4a.3 the pre-integration table: entry (f, b) classifies the segment, `step`
// world units long, over which the value runs linearly from front address f to
// back address b (ref::preintegrate, at stored value addr · 2^(vb - preint_addr_bits)):
// the segment's opacity and its self-attenuated colour over that opacity, as
// raw U fractions; ka, kd, ks of the back sample (the segment is shaded at its
// end). Computed on all cores; the last few tables are kept, so a flythrough
// or a sweep over one transfer function builds each once.
std::shared_ptr<const std::vector<ClassEntry>> make_preint_table(
    const PrecisionProfile& profile, const ref::TransferFunction& tf_stored, double step);
void make_reflectance_maps(const PrecisionProfile& profile, const ref::ShadingSetup& shading,
                           std::vector<std::uint32_t>& diffuse,
                           std::vector<std::uint32_t>& specular);

// All of the above but the voxel memory, for one frame.
FrameSetup make_frame_setup(const PrecisionProfile& profile, const ref::Scene& scene,
                            const ref::RenderInputs& inputs);

}  // namespace voxcast::bittrue
