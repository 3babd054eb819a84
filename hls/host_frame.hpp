// Host side of the design (not synthesized): the precision profiles the
// kernels are compiled for, the dispatch from a run-time profile to its
// instantiation, and loading a frame's on-chip state from the shared host
// set-up. Used by every engine built on the kernels (cosim's hls engine, the
// rtl model), so they agree on what is compiled and on how a frame is loaded.
#pragma once

#ifndef __SYNTHESIS__
#include <memory>
#include <string>

#include "hls/vizard2_top.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/preset_profiles.hpp"

namespace voxcast::hls::host {

// The profiles the kernels are compiled for: the presets. A profile is a
// template parameter of every kernel (as a synthesized design fixes its
// widths), so each one here is one instantiation of the whole pipeline.
template <PrecisionProfile... Ps>
struct ProfileList {};
using CompiledProfiles = ProfileList<kVizard2, kBalanced, kPrecise>;
inline constexpr const char* kCompiledProfileNames = "the presets vizard2, balanced, precise";

// Calls fn.template operator()<P>() for the compiled profile equal to `p`;
// false if none is.
template <class Fn, PrecisionProfile... Ps>
bool dispatch_profile(const PrecisionProfile& p, Fn&& fn, ProfileList<Ps...>) {
  return ((p == Ps ? (fn.template operator()<Ps>(), true) : false) || ...);
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

// Throws voxcast::Error unless a design with units U can render the frame
// (its camera and render mode; an elaborated top runs only its scene's kind).
template <Units U>
void check_frame_fits(const bittrue::FrameSetup& fs, const std::string& engine) {
  const bool camera = fs.regs.perspective ? U.perspective : U.parallel_origin;
  const ref::RenderMode m = fs.regs.mode;
  const bool mode = m == ref::RenderMode::Mip        ? can_mip(U)
                    : m == ref::RenderMode::Unshaded ? can_composite(U)
                                                     : can_shade(U);
  if (!camera || !mode)
    throw Error(engine + ": the design has no " + (camera ? "" : "units for this camera") +
                (!camera && !mode ? " and no " : "") +
                (mode ? "" : "path for render.mode = " + std::string(ref::to_string(m))) +
                " (it was elaborated for another scene)");
  if (fs.regs.mode != ref::RenderMode::Mip && !U.ert && fs.regs.ert_enabled)
    throw Error(engine + ": the design has no ERT comparator, the frame asks for "
                "render.ert_threshold < 1 (it was elaborated for another scene)");
}

// The card's registers and tables for one frame, loaded from the host set-up
// (megabytes for the wide profiles: on the heap), for a design with units U
// (hls/units.hpp): an absent unit's table is not loaded. `engine` names the
// caller in errors.
template <PrecisionProfile P, Units U = kAllUnits>
std::unique_ptr<FrameState<P, U>> load_frame_state(const bittrue::FrameSetup& fs,
                                                   const std::string& engine) {
  check_frame_fits<U>(fs, engine);
  auto f = std::make_unique<FrameState<P, U>>();
  f->geometry = load_geometry_registers<P>(fs.regs);
  if constexpr (U.perspective) {
    if (fs.regs.perspective) load_rsqrt_rom<P>(fs.rsqrt_seed, f->rsqrt);
  }
  if constexpr (U.classification) {
    if (!load_class_table<P>(f->class_table, fs.class_table))
      throw Error(engine + ": classification table size does not match the profile");
  }
  if constexpr (U.reflectance_map) {
    f->reflectance_regs = reflectance_registers<P>(fs.regs);
    if (fs.regs.mode == ref::RenderMode::Shaded &&
        !load_reflectance_map<P>(f->reflectance, fs.rm_diffuse, fs.rm_specular))
      throw Error(engine + ": reflectance map size does not match the profile");
  }
  f->compositor = compositor_registers<P>(fs.regs);
  f->mode = frame_mode(fs.regs.mode);
  if constexpr (U.space_leaping) {
    if (fs.leap) load_leap<P>(*fs.leap, f->leap, f->minmax, engine);
  } else if (fs.leap) {
    throw Error(engine + ": the design has no space-leaping unit, the frame asks for "
                "render.space_leaping = true (it was elaborated for another scene)");
  }
  return f;
}

}  // namespace voxcast::hls::host
#endif
