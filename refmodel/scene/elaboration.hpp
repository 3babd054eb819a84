// Elaboration: which units of the VIZARD II design a scene needs, and at what
// size (issue 6, part 5). A design built for one scene leaves out what the
// scene never uses: MIP needs no classification, shading, reflectance map or
// gradient memory; an unshaded scene no reflectance map and no gradients; a
// parallel camera no perspective hardware (the rsqrt unit); ERT off no
// termination comparator; a shaded or unshaded scene no MIP unit. The voxel
// fields follow the data's real range and the classification table the
// transfer function. docs/resources.md lists the rules; the resource report
// (cosim/hardware/report.hpp) and the cycle model's latencies
// (rtl::pipeline::elaborate_latencies) read this struct.
//
// The struct is plain data: it depends on the profile only, so the rtl model
// and the report can read it without the scene or the volume.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "refmodel/precision/profile.hpp"
#include "refmodel/scene/scene.hpp"
#include "refmodel/volume/gradients.hpp"
#include "refmodel/volume/transfer_function.hpp"
#include "refmodel/volume/volume.hpp"

namespace voxcast::ref {

// A unit left out of the design and why (one line for the report).
struct Omission {
  std::string unit;    // the unit's name in the report (e.g. "reflectance_map")
  std::string reason;  // e.g. "render.mode = mip reads no reflectance"
};

struct Elaboration {
  PrecisionProfile profile;  // the scene's profile, unchanged (the image does not change)
  // Units present (docs/pipeline.md section in brackets).
  bool perspective = true;      // direction per pixel and the rsqrt unit [§1.1-1.2]
  bool parallel_direction = false;  // parallel camera: one view direction U [§1.1]
  bool gradients = true;        // gradient fields of the voxel word and their lerps [§3.4-3.5]
  bool classification = true;   // classification table [§4]
  bool reflectance_map = true;  // reflectance map [§5]
  bool shader = true;           // intensity ka + kd·D + ks·S and colour·I [§6]
  bool compositor = true;       // over operator [§7.1-7.2]
  bool ert = true;              // termination comparator [§7.3]
  bool mip = false;             // maximum register and grey multiply [§7 MIP]
  // Sizes from the data and the transfer function.
  int value_store_bits = 8;     // stored bits of the value field: the data's real range
                                // (the low value_bits - this are constant zeros, §3.4)
  int gradient_store_bits = 8;  // stored bits (sign included) of a gradient component
  int class_entries = 256;      // table entries the data can address (§4.1)
  int class_color_fields = 3;   // r, g, b fields that vary over the table (the rest: registers)
  bool class_alpha_varies = true;
  int class_k_fields = 0;       // ka, kd, ks vary over the table? (one material: 0, registers)
  // Beyond the papers (docs/leaping.md), set by the scene overload below.
  bool space_leaping = false;   // min-max block memory, prefix table, leaping stepper
  int leap_block = 8;           // cells per block edge
  long long leap_blocks = 0;    // blocks the volume needs (the min-max memory's depth)
  bool jitter = false;          // per-pixel start offset hash in the ray set-up
  // render.partial_segments (docs/pipeline.md §7a): the segment-opacity unit,
  // its optical-depth table and its 2^-x ROM; never in MIP (no opacity).
  bool partial_segments = false;
  // render.classification = "preintegrated" (docs/pipeline.md §4a): the 2-D
  // pre-integration table, preint_side^2 entries the data can address (front
  // and back each below round(max · 2^(preint_addr_bits - vb)) + 1), with the
  // classification entry's varying fields; never in MIP.
  bool preintegration = false;
  int preint_side = 256;
  std::vector<Omission> omitted;
};

// What elaboration needs to know about the data.
struct DataRange {
  int volume_bits = 8;             // the volume's declared bits
  unsigned max_stored = 255;       // largest stored value in the data
  double max_gradient = 0.0;       // largest |gradient component|, stored units
};
DataRange data_range(const Volume& volume, const GradientField& gradients);

// The derivation itself: pure, from the profile, the scene's mode, camera, ERT
// threshold and transfer function (stored units), and the data's range.
Elaboration elaborate(const PrecisionProfile& profile, RenderMode mode, Projection projection,
                      double ert_threshold, const TransferFunction& stored_tf,
                      const DataRange& range);

// The same for a scene and its loaded volume (with elaborate_options).
Elaboration elaborate(const Scene& scene, const Volume& volume, const GradientField& gradients);

// Adds render.space_leaping (block memory sized for a volume of `dims`),
// render.jitter and render.partial_segments to `e`, or their omissions.
void elaborate_options(Elaboration& e, const RenderDesc& render, const std::array<int, 3>& dims);

}  // namespace voxcast::ref
