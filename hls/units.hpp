// Compile-time unit switches of the VIZARD II top level (issue 6, part 5): the
// hls side of ref::Elaboration (refmodel/scene/elaboration.hpp), same names,
// same meaning. A top takes its unit set as a type, UnitSet<...> with one
// static constexpr bool per unit (the traits style of Vitis Libraries L1, in
// the C++14 the vendor front ends read); the units it marks absent are neither
// members of its frame state nor instantiated in its ray loop (tag dispatch in
// hls/vizard2_top.hpp), so a vendor tool never sees them. `voxcast
// synth-script` writes the set derived from a scene into elaborated_config.hpp
// (cosim/hardware/synth_script.hpp, docs/synthesis.md).
//
// AllUnits is the run-time-configurable design the hls engine and the rtl
// model run: every unit present, the camera and the render mode chosen by
// registers per frame.
//
// Units is the same set as a value, for the host side (elaboration, reports,
// checks); units_of<U>() converts, and the rules below are written once, on
// the value.
#pragma once

#include <type_traits>

namespace voxcast {
namespace hls {

struct Units {
  bool perspective = true;      // per-pixel direction and the rsqrt unit [§1.1-1.2]
  bool parallel_direction = true;  // parallel camera: one view direction U [§1.1]
  bool gradients = true;        // the gradient fields' consumer (reflectance map) [§3.4-3.5]
  bool classification = true;   // classification table [§4]
  bool reflectance_map = true;  // reflectance map and its registers [§5]
  bool shader = true;           // ka + kd·D + ks·S and colour·I [§6]
  bool compositor = true;       // over operator [§7.1-7.2]
  bool ert = true;              // termination comparator [§7.3]
  bool mip = true;              // maximum register and grey multiply [§7 MIP]
  bool space_leaping = true;    // min-max block memory, prefix table, leap search (docs/leaping.md)
  bool partial_segments = true;  // segment opacity: optical-depth table, 2^-x ROM [§7a]
  bool preintegration = true;   // pre-integration table: (front, back) -> segment class [§4a]
};

// The unit set as a type, in the order of Units' fields.
template <bool Perspective, bool ParallelDirection, bool Gradients, bool Classification,
          bool ReflectanceMap, bool Shader, bool Compositor, bool Ert, bool Mip,
          bool SpaceLeaping, bool PartialSegments, bool Preintegration>
struct UnitSet {
  static constexpr bool perspective = Perspective;
  static constexpr bool parallel_direction = ParallelDirection;
  static constexpr bool gradients = Gradients;
  static constexpr bool classification = Classification;
  static constexpr bool reflectance_map = ReflectanceMap;
  static constexpr bool shader = Shader;
  static constexpr bool compositor = Compositor;
  static constexpr bool ert = Ert;
  static constexpr bool mip = Mip;
  static constexpr bool space_leaping = SpaceLeaping;
  static constexpr bool partial_segments = PartialSegments;
  static constexpr bool preintegration = Preintegration;
};

using AllUnits =
    UnitSet<true, true, true, true, true, true, true, true, true, true, true, true>;

template <class U>
constexpr Units units_of() {
  return Units{U::perspective, U::parallel_direction, U::gradients,  U::classification,
               U::reflectance_map, U::shader,    U::compositor, U::ert,
               U::mip,          U::space_leaping, U::partial_segments, U::preintegration};
}

constexpr bool same_units(Units a, Units b) {
  return a.perspective == b.perspective && a.parallel_direction == b.parallel_direction &&
         a.gradients == b.gradients && a.classification == b.classification &&
         a.reflectance_map == b.reflectance_map && a.shader == b.shader &&
         a.compositor == b.compositor && a.ert == b.ert && a.mip == b.mip &&
         a.space_leaping == b.space_leaping && a.partial_segments == b.partial_segments &&
         a.preintegration == b.preintegration;
}

// The render modes a design with these units can run (the frame's mode
// register chooses among them when more than one).
constexpr bool can_mip(Units u) { return u.mip; }
constexpr bool can_composite(Units u) {
  return u.classification && u.shader && u.compositor;
}
constexpr bool can_shade(Units u) { return can_composite(u) && u.reflectance_map; }

// A design must be able to draw something, and a ray needs a direction.
constexpr bool consistent(Units u) {
  return (can_mip(u) || can_composite(u)) && (u.perspective || u.parallel_direction) &&
         (!u.reflectance_map || u.gradients) && (!u.ert || can_composite(u)) &&
         (!u.space_leaping || can_composite(u)) &&  // leaping skips samples the TF makes empty
         (!u.partial_segments || can_composite(u)) &&  // it weights the compositor's opacity
         (!u.preintegration || can_composite(u));  // it classifies for the compositor
}
static_assert(consistent(units_of<AllUnits>()), "the full design must be consistent");

// Compile-time selection between a present and an absent unit (or between two
// forms of one): the overload taking Has<false> is the absent unit's, and the
// present unit's code is not instantiated for it. C++14 tag dispatch, where
// C++17 would write `if constexpr`.
template <bool B>
using Has = std::integral_constant<bool, B>;

// A stand-in member for an absent unit: no storage a tool could map to RAM.
struct AbsentUnit {};

}  // namespace hls
}  // namespace voxcast
