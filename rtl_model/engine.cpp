#include "rtl_model/engine.hpp"

#include <memory>
#include <ostream>

#include "hls/vizard2_top.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/preset_profiles.hpp"
#include "rtl_model/layout/vizard2_layout.hpp"
#include "rtl_model/pipeline/ray_pipeline.hpp"

namespace voxcast::rtl {
namespace {

// The compiled profiles, as in cosim/hls_engine.cpp: each is one
// instantiation of the whole pipeline.
template <PrecisionProfile... Ps>
struct ProfileList {};
using CompiledProfiles = ProfileList<kVizard2, kBalanced, kPrecise>;
constexpr const char* kCompiledNames = "the presets vizard2, balanced, precise";

hls::FrameMode frame_mode(ref::RenderMode m) {
  switch (m) {
    case ref::RenderMode::Shaded: return hls::FrameMode::Shaded;
    case ref::RenderMode::Unshaded: return hls::FrameMode::Unshaded;
    case ref::RenderMode::Mip: return hls::FrameMode::Mip;
  }
  return hls::FrameMode::Shaded;
}

// The card's registers and tables, loaded from the host set-up (megabytes for
// the wide profiles: on the heap).
template <PrecisionProfile P>
std::unique_ptr<hls::FrameState<P>> load_frame(const bittrue::FrameSetup& fs) {
  auto f = std::make_unique<hls::FrameState<P>>();
  f->geometry = hls::host::load_geometry_registers<P>(fs.regs);
  if (fs.regs.perspective) hls::host::load_rsqrt_rom<P>(fs.rsqrt_seed, f->rsqrt);
  if (!hls::host::load_class_table<P>(f->class_table, fs.class_table))
    throw Error("rtl engine: classification table size does not match the profile");
  f->reflectance_regs = hls::host::reflectance_registers<P>(fs.regs);
  if (fs.regs.mode == ref::RenderMode::Shaded &&
      !hls::host::load_reflectance_map<P>(f->reflectance, fs.rm_diffuse, fs.rm_specular))
    throw Error("rtl engine: reflectance map size does not match the profile");
  f->compositor = hls::host::compositor_registers<P>(fs.regs);
  f->mode = frame_mode(fs.regs.mode);
  return f;
}

template <PrecisionProfile P>
RtlResult render(const bittrue::FrameSetup& fs, const bittrue::VoxelMemory& memory,
                 const RtlConfig& config) {
  if (memory.dims != fs.regs.dims) throw Error("rtl engine: voxel memory and frame set-up differ in dims");
  const auto frame = load_frame<P>(fs);
  const layout::Vizard2Layout layout(memory.dims);
  const auto mapping =
      layout::make_address_mapping(config.mapping, layout.grid(), config.pipeline.dimm.geometry);
  pipeline::RayPipeline<P> pipe(*frame, memory, *mapping, config.pipeline, config.scheduler,
                                config.refresh);
  RtlResult r;
  r.image = pipe.run(fs.regs.width, fs.regs.height, r.stats);
  return r;
}

template <class Fn, PrecisionProfile... Ps>
bool dispatch(const PrecisionProfile& p, Fn&& fn, ProfileList<Ps...>) {
  return ((p == Ps ? (fn.template operator()<Ps>(), true) : false) || ...);
}

}  // namespace

std::ostream& operator<<(std::ostream& os, const RtlConfig& c) {
  return os << c.pipeline << "; layout " << c.mapping << ", scheduler " << c.scheduler
            << ", refresh " << c.refresh << "; " << c.pipeline.dimm;
}

RtlConfig vizard2_baseline() { return RtlConfig{}; }

RtlResult rtl_render(const bittrue::FrameSetup& setup, const bittrue::VoxelMemory& memory,
                     const RtlConfig& config) {
  RtlResult r;
  if (!dispatch(setup.profile, [&]<PrecisionProfile P>() { r = render<P>(setup, memory, config); },
                CompiledProfiles{}))
    throw Error(std::string("this precision profile is not compiled into the rtl engine (") +
                kCompiledNames + ")");
  return r;
}

bool rtl_supports(const PrecisionProfile& p) {
  return dispatch(p, []<PrecisionProfile>() {}, CompiledProfiles{});
}

std::string rtl_supported_profiles() { return kCompiledNames; }

}  // namespace voxcast::rtl
