// The per-sample units behind interpolation, as both card models run them:
// classification with the pre-integration front (docs/pipeline.md §4a) and
// the segment-opacity unit (§7a), the reflectance map and the shader, and the
// compositor's step with early ray termination (§7) or MIP's running maximum.
// RayPipeline (the VIZARD II card, ray_pipeline.hpp) and BurstCard (the DDR4
// card, burst_card.hpp) stage them differently in time, but each must equal
// hls::cast_ray bit for bit, so the units' order and their per-ray registers
// are written once, here.
#pragma once

#include <cstdint>

#include "hls/vizard2_top.hpp"
#include "rtl_model/pipeline/stats.hpp"

namespace voxcast::rtl::pipeline {

// The classification entry of `in`, sample `pos` of a ray of `n`, whose
// previous sample at this stage is `front` (a register per ray, updated to
// `in`). `lit` is set to the sample the shading stage lights: `in`, with the
// segment's front gradient under pre-integration (§4a).
template <class P>
hls::ClassEntry<P> classify_sample(const hls::FrameState<P>& f, const hls::Sample<P>& in,
                                   std::uint64_t pos, std::uint64_t n,
                                   const hls::SegmentWeights<P>& weights, hls::Sample<P>& front,
                                   hls::Sample<P>& lit) {
  // A ray's first sample (pos 0) ends no segment.
  hls::ClassEntry<P> e = hls::classify_entry<P>(f.class_table, f.preint, pos == 0, front.value,
                                                in.value, hls::Has<true>{});
  lit = in;
  if (f.preint.enabled)
    for (int a = 0; a < 3; ++a) lit.g[a] = front.g[a];
  front = in;
  e.alpha = hls::segment_opacity<P>(f.segments, hls::class_address<P>(in.value), e.alpha,
                                    hls::sample_weight<P>(weights, pos, n));
  return e;
}

// The colour of a classified sample of nonzero alpha, lit at `lit`'s
// gradient when the frame is shaded.
template <class P>
hls::ShadedColor<P> shade_sample(const hls::FrameState<P>& f, const hls::ClassEntry<P>& e,
                                 const hls::Sample<P>& lit, bool shaded) {
  hls::Reflect<P> r{0, 0};
  if (shaded) r = hls::reflect<P>(f.reflectance, f.reflectance_regs, lit.g);
  return hls::shade<P>(e, r, shaded);
}

// The compositor's step for one sample of a ray: MIP's running maximum, or
// front-to-back compositing of a sample of nonzero alpha. True if the ray
// reached early ray termination.
template <class P>
bool composite_sample(const hls::FrameState<P>& f, bool mip, hls::Accumulator<P>& acc,
                      typename hls::CompositorParams<P>::value_t& peak,
                      const typename hls::CompositorParams<P>::value_t& value,
                      const hls::ShadedColor<P>& c,
                      const typename hls::CompositorParams<P>::alpha_t& alpha) {
  if (mip) {
    hls::mip_update<P>(peak, value);
    return false;
  }
  if (alpha == 0) return false;
  hls::composite<P>(acc, c, alpha);
  return hls::ert_reached<P>(acc, f.compositor);
}

// A finished ray's accumulator as the output unit takes it.
template <class P>
hls::Accumulator<P> ray_result(const hls::FrameState<P>& f, bool mip,
                               const hls::Accumulator<P>& acc,
                               const typename hls::CompositorParams<P>::value_t& peak) {
  return mip ? hls::mip_pixel<P>(peak, f.compositor) : acc;
}

// Early ray termination at the sample at place `pos` of a ray of `n` samples
// (the k-th it issued), with `next` samples issued or leapt over and `issued`
// issued (ref::FrameStats): the ray ended early unless pos is its last
// sample; the samples the issue stage leapt over beyond pos count as
// discarded skips, as the issued ones beyond it count as discarded samples.
inline void count_early_end(RtlStats& stats, std::uint64_t n, std::uint64_t next,
                            std::uint64_t issued, std::uint64_t pos, std::uint64_t k) {
  if (pos + 1 < n) ++stats.rays_ert;
  stats.samples_skipped_discarded += (next - 1 - pos) - (issued - 1 - k);
}

}  // namespace voxcast::rtl::pipeline
