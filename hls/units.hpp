// Compile-time unit switches of the VIZARD II top level (issue 6, part 5): the
// hls side of ref::Elaboration (refmodel/scene/elaboration.hpp), same names,
// same meaning. A top takes a Units value as a template parameter; the units it
// marks absent are neither members of its frame state nor instantiated in its
// ray loop (`if constexpr` in hls/vizard2_top.hpp), so a vendor tool never sees
// them. `voxcast synth-script` writes the value derived from a scene into
// elaborated_config.hpp (cosim/synth_script.hpp, docs/synthesis.md).
//
// kAllUnits is the run-time-configurable design the hls engine and the rtl
// model run: every unit present, the camera and the render mode chosen by
// registers per frame.
#pragma once

namespace voxcast::hls {

struct Units {
  bool perspective = true;      // per-pixel direction and the rsqrt unit [§1.1-1.2]
  bool parallel_origin = true;  // per-pixel origin O + px·P + py·R [§1.4]
  bool gradients = true;        // the gradient fields' consumer (reflectance map) [§3.4-3.5]
  bool classification = true;   // classification table [§4]
  bool reflectance_map = true;  // reflectance map and its registers [§5]
  bool shader = true;           // ka + kd·D + ks·S and colour·I [§6]
  bool compositor = true;       // over operator [§7.1-7.2]
  bool ert = true;              // termination comparator [§7.3]
  bool mip = true;              // maximum register and grey multiply [§7 MIP]
  bool space_leaping = true;    // min-max block memory, prefix table, leap search (docs/leaping.md)
  friend constexpr bool operator==(const Units&, const Units&) = default;
};

inline constexpr Units kAllUnits{};

// The render modes a design with these units can run (the frame's mode
// register chooses among them when more than one).
constexpr bool can_mip(const Units& u) { return u.mip; }
constexpr bool can_composite(const Units& u) {
  return u.classification && u.shader && u.compositor;
}
constexpr bool can_shade(const Units& u) { return can_composite(u) && u.reflectance_map; }

// A design must be able to draw something, and a ray needs a direction.
constexpr bool consistent(const Units& u) {
  return (can_mip(u) || can_composite(u)) && (u.perspective || u.parallel_origin) &&
         (!u.reflectance_map || u.gradients) && (!u.ert || can_composite(u)) &&
         (!u.space_leaping || can_composite(u));  // leaping skips samples the TF makes empty
}
static_assert(consistent(kAllUnits));

// A stand-in member for an absent unit: no storage a tool could map to RAM.
struct AbsentUnit {};

}  // namespace voxcast::hls
