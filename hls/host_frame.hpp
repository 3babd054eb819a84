// Host side of the design (not synthesized): the precision profiles the
// kernels are compiled for, the dispatch from a run-time profile to its
// instantiation, and loading a frame's on-chip state from the shared host
// set-up. Used by every engine built on the kernels (cosim's hls engine, the
// rtl model), so they agree on what is compiled and on how a frame is loaded.
#pragma once

#include "hls/pragma.hpp"

#if VOXCAST_HLS_HOST_CODE
#include <memory>
#include <string>

#include "hls/vizard2_top.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/preset_profiles.hpp"

namespace voxcast {
namespace hls {
namespace host {

// The profiles the kernels are compiled for: the presets. A profile is a
// template parameter of every kernel (as a synthesized design fixes its
// widths), so each one here is one instantiation of the whole pipeline.
template <class... Ps>
struct ProfileList {};
using CompiledProfiles = ProfileList<Vizard2Traits, BalancedTraits, PreciseTraits>;
inline constexpr const char* kCompiledProfileNames = "the presets vizard2, balanced, precise";

// Calls fn.template operator()<P>() for the compiled profile (a traits type)
// equal to `p`; false if none is.
template <class Fn, class... Ps>
bool dispatch_profile(const PrecisionProfile& p, Fn&& fn, ProfileList<Ps...>) {
  return ((p == profile_value<Ps>() ? (fn.template operator()<Ps>(), true) : false) || ...);
}
template <class Fn>
bool dispatch_profile(const PrecisionProfile& p, Fn&& fn) {
  return dispatch_profile(p, fn, CompiledProfiles{});
}

inline FrameMode frame_mode(ref::RenderMode m) {
  switch (m) {
    case ref::RenderMode::Shaded: return FrameMode::Shaded;
    case ref::RenderMode::Unshaded: return FrameMode::Unshaded;
    case ref::RenderMode::Mip: return FrameMode::Mip;
  }
  return FrameMode::Shaded;
}

// The unit set type of a Units value (the C++20 side names unit sets by value).
template <Units V>
using UnitsType = UnitSet<V.perspective, V.parallel_direction, V.gradients, V.classification,
                          V.reflectance_map, V.shader, V.compositor, V.ert, V.mip,
                          V.space_leaping, V.partial_segments, V.preintegration>;

// Throws voxcast::Error unless a design with units U can render the frame
// (its camera and render mode; an elaborated top runs only its scene's kind).
template <class U>
void check_frame_fits(const bittrue::FrameSetup& fs, const std::string& engine) {
  constexpr Units u = units_of<U>();
  const bool camera = fs.regs.perspective ? u.perspective : u.parallel_direction;
  const ref::RenderMode m = fs.regs.mode;
  const bool mode = m == ref::RenderMode::Mip        ? can_mip(u)
                    : m == ref::RenderMode::Unshaded ? can_composite(u)
                                                     : can_shade(u);
  if (!camera || !mode)
    throw Error(engine + ": the design has no " + (camera ? "" : "units for this camera") +
                (!camera && !mode ? " and no " : "") +
                (mode ? "" : "path for render.mode = " + std::string(ref::to_string(m))) +
                " (it was elaborated for another scene)");
  if (fs.regs.mode != ref::RenderMode::Mip && !u.ert && fs.regs.ert_enabled)
    throw Error(engine + ": the design has no ERT comparator, the frame asks for "
                "render.ert_threshold < 1 (it was elaborated for another scene)");
}

// The card's registers and tables for one frame, loaded from the host set-up
// (megabytes for the wide profiles: on the heap), for a design with units U
// (hls/units.hpp): an absent unit's table is not loaded. `engine` names the
// caller in errors.
template <class P, class U = AllUnits>
std::unique_ptr<FrameState<P, U>> load_frame_state(const bittrue::FrameSetup& fs,
                                                   const std::string& engine) {
  check_frame_fits<U>(fs, engine);
  auto f = std::make_unique<FrameState<P, U>>();
  f->geometry = load_geometry_registers<P>(fs.regs);
  if constexpr (U::perspective) {
    if (fs.regs.perspective) load_rsqrt_rom<P>(fs.rsqrt_seed, f->rsqrt);
  }
  if constexpr (U::classification) {
    if (!load_class_table<P>(f->class_table, fs.class_table))
      throw Error(engine + ": classification table size does not match the profile");
  }
  if constexpr (U::reflectance_map) {
    f->reflectance_regs = reflectance_registers<P>(fs.regs);
    if (fs.regs.mode == ref::RenderMode::Shaded &&
        !load_reflectance_map<P>(f->reflectance, fs.rm_diffuse, fs.rm_specular))
      throw Error(engine + ": reflectance map size does not match the profile");
  }
  f->compositor = compositor_registers<P>(fs.regs);
  f->mode = frame_mode(fs.regs.mode);
  if constexpr (U::space_leaping) {
    if (fs.leap) load_leap<P>(*fs.leap, f->leap, f->minmax, engine);
  } else if (fs.leap) {
    throw Error(engine + ": the design has no space-leaping unit, the frame asks for "
                "render.space_leaping = true (it was elaborated for another scene)");
  }
  if constexpr (U::partial_segments) {
    if (fs.segments && !load_segment_tables<P>(f->segments, *fs.segments))
      throw Error(engine + ": segment opacity table size does not match the profile");
  } else if (fs.segments) {
    throw Error(engine + ": the design has no segment-opacity unit, the frame asks for "
                "render.partial_segments = true (it was elaborated for another scene)");
  }
  if (fs.preint_table && (fs.leap || fs.segments))
    throw Error(engine + ": a pre-integrated frame cannot leap or weight partial segments "
                "(render.classification = \"preintegrated\", docs/pipeline.md §4a)");
  if constexpr (U::preintegration) {
    f->preint.enabled = false;
    if (fs.preint_table && !load_preint_table<P>(f->preint, *fs.preint_table))
      throw Error(engine + ": pre-integration table size does not match the profile");
  } else if (fs.preint_table) {
    throw Error(engine + ": the design has no pre-integration table, the frame asks for "
                "render.classification = \"preintegrated\" (it was elaborated for another "
                "scene)");
  }
  return f;
}

}  // namespace host
}  // namespace hls
}  // namespace voxcast
#endif
