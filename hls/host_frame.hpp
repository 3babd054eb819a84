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

// The card's registers and tables for one frame, loaded from the host set-up
// (megabytes for the wide profiles: on the heap). `engine` names the caller
// in errors.
template <PrecisionProfile P>
std::unique_ptr<FrameState<P>> load_frame_state(const bittrue::FrameSetup& fs,
                                                const std::string& engine) {
  auto f = std::make_unique<FrameState<P>>();
  f->geometry = load_geometry_registers<P>(fs.regs);
  if (fs.regs.perspective) load_rsqrt_rom<P>(fs.rsqrt_seed, f->rsqrt);
  if (!load_class_table<P>(f->class_table, fs.class_table))
    throw Error(engine + ": classification table size does not match the profile");
  f->reflectance_regs = reflectance_registers<P>(fs.regs);
  if (fs.regs.mode == ref::RenderMode::Shaded &&
      !load_reflectance_map<P>(f->reflectance, fs.rm_diffuse, fs.rm_specular))
    throw Error(engine + ": reflectance map size does not match the profile");
  f->compositor = compositor_registers<P>(fs.regs);
  f->mode = frame_mode(fs.regs.mode);
  if (fs.leap) load_leap<P>(*fs.leap, f->leap, f->minmax, engine);
  return f;
}

}  // namespace voxcast::hls::host
#endif
