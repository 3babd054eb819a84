// The VIZARD II ray-casting pipeline, top level (docs/pipeline.md): the units
// of this folder composed per ray, and the frame loop a vendor tool
// synthesizes. Like the units (layer 1 of the Vitis-Libraries split) it carries
// no interface pragmas: the top with them is hls/vizard2_synth_top.cpp (layer 2).
//
//   geometry processor (ray setup, stepping) -> address generator ->
//   interpolation processor -> classification table -> reflectance map ->
//   shader -> compositor (ERT, MIP) -> output quantization
//   (the segment-opacity unit, §7a, weights the classified opacity of a ray's
//   first and last samples beside the reflectance map and the shader)
//
// A MIP or unshaded frame never reads the reflectance map and a parallel camera
// never reads the rsqrt ROM, so a design built for such scenes omits them
// (docs/pipeline.md §1.2, §5): every template here takes the design's unit set
// U (hls/units.hpp; default AllUnits, the run-time-configurable design), and an
// absent unit is neither a member of FrameState nor instantiated in cast_ray.
#pragma once

#include <cstdint>
#include <type_traits>

#include "hls/classification_table.hpp"
#include "hls/compositor.hpp"
#include "hls/geometry_processor.hpp"
#include "hls/interpolation_processor.hpp"
#include "hls/preintegration_table.hpp"
#include "hls/reflectance_map.hpp"
#include "hls/segment_opacity.hpp"
#include "hls/shader.hpp"
#include "hls/space_leaping_unit.hpp"
#include "hls/pragma.hpp"
#include "hls/types.hpp"
#include "hls/units.hpp"

namespace voxcast {
namespace hls {

enum class FrameMode : std::uint8_t { Shaded = 0, Unshaded = 1, Mip = 2 };

// A unit's state if the design has the unit, else an empty stand-in.
template <bool Present, class T>
using UnitState = typename std::conditional<Present, T, AbsentUnit>::type;

// Everything on chip for one frame: registers and tables, loaded by the host
// between frames. An absent unit's ROM or table is not there at all.
template <class P, class U = AllUnits>
struct FrameState {
  static_assert(consistent(units_of<U>()), "a design needs a ray direction and an output path");
  GeometryRegisters<P> geometry;
  UnitState<U::perspective, RsqrtRom<P>> rsqrt;
  UnitState<U::classification, ClassificationTable<P>> class_table;
  UnitState<U::reflectance_map, ReflectanceRegisters<P>> reflectance_regs;
  UnitState<U::reflectance_map, ReflectanceMap<P>> reflectance;
  CompositorRegisters<P> compositor;
  FrameMode mode;  // among the modes the units allow (can_mip, can_composite, can_shade)
  // Space leaping (hls/space_leaping_unit.hpp): registers, prefix table and the
  // min-max block memory, loaded when the volume is (the blocks) and with the
  // classification table (the prefix counts).
  UnitState<U::space_leaping, LeapRegisters<P>> leap;
  UnitState<U::space_leaping, MinMaxMemory<P>> minmax;
  // render.partial_segments (hls/segment_opacity.hpp, §7a): the optical-depth
  // table, loaded with the classification table, and the 2^-x ROM.
  UnitState<U::partial_segments, SegmentOpacityTables<P>> segments;
  // render.classification = "preintegrated" (hls/preintegration_table.hpp, §4a):
  // the 2-D table, loaded instead of using the classification table's entries.
  UnitState<U::preintegration, PreintegrationTable<P>> preint;
};

// §1 for the cameras the design has: a one-camera design instantiates only its
// set-up (a parallel design has no direction or rsqrt unit).
template <bool Perspective, bool Parallel>
struct Cameras {};

template <class P, class Rom>
RaySetup<P> ray_setup_for(const GeometryRegisters<P>& g, const Rom&, int px, int py,
                          Cameras<false, true>) {
  return ray_setup_parallel<P>(g, px, py);
}
template <class P, class Rom>
RaySetup<P> ray_setup_for(const GeometryRegisters<P>& g, const Rom& rom, int px, int py,
                          Cameras<true, false>) {
  return ray_setup_perspective<P>(g, rom.seed, px, py);
}
template <class P, class Rom>
RaySetup<P> ray_setup_for(const GeometryRegisters<P>& g, const Rom& rom, int px, int py,
                          Cameras<true, true>) {
  return ray_setup<P>(g, rom.seed, px, py);
}
// The ray of pixel (px, py) from the geometry registers and, in a design with
// the perspective unit, the rsqrt ROM (U's absent-unit stand-in otherwise).
template <class P, class U>
RaySetup<P> ray_setup_for(const GeometryRegisters<P>& g,
                          const UnitState<U::perspective, RsqrtRom<P>>& rom, int px, int py) {
  return ray_setup_for<P>(g, rom, px, py, Cameras<U::perspective, U::parallel_direction>{});
}

// The frame's mode as the two flags the datapath uses: the mode register
// decides only between modes the units allow.
template <class U>
bool frame_is_mip(FrameMode mode) {
  constexpr Units u = units_of<U>();
  return can_mip(u) && (!can_composite(u) || mode == FrameMode::Mip);
}
template <class U>
bool frame_is_shaded(FrameMode mode) {
  return can_shade(units_of<U>()) && mode == FrameMode::Shaded;
}

// Tracing hook: the default does nothing and compiles away. The cosim harness
// passes a tracer that records every unit's output (cosim/engines/hls_engine.cpp).
// ray: the ray's set-up; sample: each sample's unit outputs; skip: a leap's
// sample count; ert(k): early ray termination after sample k (of 0 .. n-1).
struct NullTracer {
  template <class Ray>
  void ray(const Ray&) {}
  template <class... Args>
  void sample(const Args&...) {}
  void skip(std::uint64_t) {}
  void ert(std::uint64_t) {}
};

// render_rows' statistics over its rows, as ref::FrameStats defines them
// (refmodel/render/raycaster.hpp, docs/pipeline.md §9).
struct RowStats {
  std::uint64_t samples = 0;                // samples interpolated
  std::uint64_t samples_skipped = 0;        // by space leaping
  std::uint64_t rays_hit = 0;               // the set-up's hit flag (§1.5)
  std::uint64_t rays_terminated_early = 0;  // ERT before the ray's last sample
};

// Counts the rays that hit, those ERT ended before their last sample, and the
// samples space leaping skipped: host statistics (render_rows). The
// synthesized top runs the streamed region (hls/vizard2_dataflow.hpp), which
// counts none of them.
struct StatsCounter : NullTracer {
  RowStats& stats;
  std::uint64_t n = 0;  // the current ray's sample count
  explicit StatsCounter(RowStats& s) : stats(s) {}
  template <class Ray>
  void ray(const Ray& r) {
    n = r.hit ? r.n.to_uint64() : 0;
    if (r.hit) ++stats.rays_hit;
  }
  void skip(std::uint64_t run) { stats.samples_skipped += run; }
  void ert(std::uint64_t k) {
    if (k + 1 < n) ++stats.rays_terminated_early;
  }
};

// ---- The units of cast_ray, each with its absent form -------------------------------------

// MIP (§7 MIP): the maximum register takes the sample; true if the frame is a
// MIP frame (the sample is then done).
template <class P, class Pos, class Tracer>
VOXCAST_HLS_HOST_INLINE bool mip_sample(bool mip, typename CompositorParams<P>::value_t& peak,
                                        const Pos& p, const Sample<P>& s, Tracer& tracer,
                                        Has<true>) {
  if (!mip) return false;
  mip_update<P>(peak, s.value);
  tracer.sample(p, s, peak);
  return true;
}
template <class P, class Pos, class Tracer>
VOXCAST_HLS_HOST_INLINE bool mip_sample(bool, typename CompositorParams<P>::value_t&, const Pos&,
                                        const Sample<P>&, Tracer&, Has<false>) {
  return false;
}

// §5: the reflectance map's lookup for a shaded frame; (0, 0) otherwise.
template <class P, class Map, class Regs>
VOXCAST_HLS_HOST_INLINE Reflect<P> reflect_for(const Map& map, const Regs& regs, bool shaded,
                                               const Sample<P>& s, Has<true>) {
  Reflect<P> r{0, 0};
  if (shaded) r = reflect<P>(map, regs, s.g);
  return r;
}
template <class P, class Map, class Regs>
VOXCAST_HLS_HOST_INLINE Reflect<P> reflect_for(const Map&, const Regs&, bool, const Sample<P>&,
                                               Has<false>) {
  return Reflect<P>{0, 0};
}

// §7.3: the termination comparator; a design without it marches every ray to
// its end.
template <class P>
VOXCAST_HLS_HOST_INLINE bool ray_goes_on(const Accumulator<P>& acc,
                                         const CompositorRegisters<P>& regs, Has<true>) {
  return !ert_reached<P>(acc, regs);
}
template <class P>
VOXCAST_HLS_HOST_INLINE bool ray_goes_on(const Accumulator<P>&, const CompositorRegisters<P>&,
                                         Has<false>) {
  return true;
}

// §6: the shaded colour of a classified sample with alpha != 0: the
// reflectance map's (D, S) for a shaded frame, then the shader. Without a
// reflectance map `shaded` is the constant false (frame_is_shaded), so
// c = U(colour) (§6) and the intensity products inside shade() have no fan-out.
template <class P, class U>
VOXCAST_HLS_HOST_INLINE ShadedColor<P> shade_sample(
    const UnitState<U::reflectance_map, ReflectanceMap<P>>& map,
    const UnitState<U::reflectance_map, ReflectanceRegisters<P>>& regs, bool shaded,
    const ClassEntry<P>& e, const Sample<P>& s, Reflect<P>& r) {
  r = reflect_for<P>(map, regs, shaded, s, Has<can_shade(units_of<U>())>{});
  return shade<P>(e, r, shaded);
}

// §7.1-7.3: the over operator for a classified, shaded sample with alpha != 0;
// false once ERT ends the ray.
template <class P, class U>
VOXCAST_HLS_HOST_INLINE bool composite_step(const CompositorRegisters<P>& regs,
                                            const ShadedColor<P>& c,
                                            const typename ClassificationParams<P>::alpha_t& alpha,
                                            Accumulator<P>& acc) {
  composite<P>(acc, c, alpha);
  return ray_goes_on<P>(acc, regs, Has<U::ert>{});
}

// §7a: a ray's segment weights in a design with the segment-opacity unit; an
// empty stand-in without it.
template <class P, class U>
using RayWeights = UnitState<U::partial_segments, SegmentWeights<P>>;

template <class P, class Tables>
SegmentWeights<P> ray_weights(const Tables& t, const GeometryRegisters<P>& g,
                              const RaySetup<P>& ray, int px, int py, Has<true>) {
  return segment_weights<P>(t, ray, pixel_jitter<P>(g, px, py));
}
template <class P, class Tables>
AbsentUnit ray_weights(const Tables&, const GeometryRegisters<P>&, const RaySetup<P>&, int, int,
                       Has<false>) {
  return AbsentUnit{};
}

// §7a: the weight of sample k of a ray of n samples (an empty stand-in
// without the unit), and the classified entry with its opacity for the
// sample's segment (the table's entry unchanged without the unit).
template <class P, class U>
using SampleWeight =
    UnitState<U::partial_segments, typename SegmentOpacityParams<P>::weight_t>;

template <class P>
VOXCAST_HLS_HOST_INLINE typename SegmentOpacityParams<P>::weight_t weight_of_sample(
    const SegmentWeights<P>& w, std::uint64_t k, std::uint64_t n, Has<true>) {
  return sample_weight<P>(w, k, n);
}
template <class P, class W>
VOXCAST_HLS_HOST_INLINE AbsentUnit weight_of_sample(const W&, std::uint64_t, std::uint64_t,
                                                    Has<false>) {
  return AbsentUnit{};
}

template <class P, class Tables>
VOXCAST_HLS_HOST_INLINE ClassEntry<P> weigh_entry(
    const Tables& t, const typename SegmentOpacityParams<P>::weight_t& w,
    const typename ClassificationParams<P>::value_t& value, ClassEntry<P> e, Has<true>) {
  e.alpha = segment_opacity<P>(t, class_address<P>(value), e.alpha, w);
  return e;
}
template <class P, class Tables, class W>
VOXCAST_HLS_HOST_INLINE ClassEntry<P> weigh_entry(const Tables&, const W&,
                                                  const typename ClassificationParams<P>::value_t&,
                                                  ClassEntry<P> e, Has<false>) {
  return e;
}

// The sample a classified entry is shaded with: the sample itself, or in a
// pre-integrated frame the segment's front sample (§4a: where a ray entering
// a surface gathers most of the segment's opacity), its gradient.
template <class P>
VOXCAST_HLS_HOST_INLINE Sample<P> lit_sample(const PreintegrationTable<P>& preint,
                                             const Sample<P>& front, const Sample<P>& s,
                                             Has<true>) {
  return preint.enabled ? front : s;
}
template <class P, class Preint>
VOXCAST_HLS_HOST_INLINE Sample<P> lit_sample(const Preint&, const Sample<P>&, const Sample<P>& s,
                                             Has<false>) {
  return s;
}

// §4 or §4a: the sample's entry from the classification table, or, in a
// pre-integrated frame, the entry of the segment from the previous sample
// (`front`) to this one from the pre-integration table; `first`: the sample is
// its ray's first, which ends no segment.
template <class P>
VOXCAST_HLS_HOST_INLINE ClassEntry<P> classify_entry(
    const ClassificationTable<P>& table, const PreintegrationTable<P>& preint, bool first,
    const typename ClassificationParams<P>::value_t& front,
    const typename ClassificationParams<P>::value_t& value, Has<true>) {
  if (!preint.enabled) return classify<P>(table, value);
  return first ? no_segment<P>() : classify_segment<P>(preint, front, value);
}
template <class P, class Preint>
VOXCAST_HLS_HOST_INLINE ClassEntry<P> classify_entry(
    const ClassificationTable<P>& table, const Preint&, bool,
    const typename ClassificationParams<P>::value_t&,
    const typename ClassificationParams<P>::value_t& value, Has<false>) {
  return classify<P>(table, value);
}

// §4-7: classification, shading and the over operator for one sample of
// segment weight w (§7a), `front` the previous sample (§4a; `first`: there is
// none); false once ERT ends the ray.
template <class P, class U, class Pos, class Tracer>
VOXCAST_HLS_HOST_INLINE bool composite_sample(const FrameState<P, U>& f, bool shaded,
                                              const SampleWeight<P, U>& w, const Pos& p,
                                              bool first, const Sample<P>& front,
                                              const Sample<P>& s, Accumulator<P>& acc,
                                              Tracer& tracer, Has<true>) {
  const ClassEntry<P> e = weigh_entry<P>(
      f.segments, w, s.value,
      classify_entry<P>(f.class_table, f.preint, first, front.value, s.value,
                        Has<U::preintegration>{}),
      Has<U::partial_segments>{});
  if (e.alpha == 0) {  // transparent: no change, no ERT test (§7)
    tracer.sample(p, s, e, Reflect<P>{0, 0}, ShadedColor<P>{}, acc);
    return true;
  }
  Reflect<P> r;
  const ShadedColor<P> c = shade_sample<P, U>(
      f.reflectance, f.reflectance_regs, shaded, e,
      lit_sample<P>(f.preint, front, s, Has<U::preintegration>{}), r);
  const bool goes_on = composite_step<P, U>(f.compositor, c, e.alpha, acc);
  tracer.sample(p, s, e, r, c, acc);
  return goes_on;
}
template <class P, class U, class Pos, class Tracer>
VOXCAST_HLS_HOST_INLINE bool composite_sample(const FrameState<P, U>&, bool,
                                              const SampleWeight<P, U>&, const Pos&, bool,
                                              const Sample<P>&, const Sample<P>&,
                                              Accumulator<P>&, Tracer&, Has<false>) {
  return true;
}

// Whether the frame leaps: the leap register is set and the frame is not MIP
// (a MIP frame takes every sample); never in a design without the unit.
template <class P, class U>
bool leaping_enabled(const LeapRegisters<P>& lr, bool mip, Has<true>) {
  return lr.enabled && !mip;
}
template <class P, class U, class Lr>
bool leaping_enabled(const Lr&, bool, Has<false>) {
  return false;
}

// Space leaping (docs/leaping.md) when the frame enables it; false if the ray
// was not marched here.
template <class P, class U, class Banks, class PerSample, class Tracer>
bool march_leaping(const FrameState<P, U>& f, const Banks& banks, const RaySetup<P>& ray,
                   bool mip, PerSample& per_sample, Tracer& tracer, Has<true>) {
  if (!leaping_enabled<P, U>(f.leap, mip, Has<true>{})) return false;
  auto skip = [&tracer](std::uint64_t run) { tracer.skip(run); };
  march_ray_leaping<P>(f.geometry, f.leap, f.minmax, banks, ray, per_sample, skip);
  return true;
}
template <class P, class U, class Banks, class PerSample, class Tracer>
bool march_leaping(const FrameState<P, U>&, const Banks&, const RaySetup<P>&, bool, PerSample&,
                   Tracer&, Has<false>) {
  return false;
}

// The MIP frame's pixel from the maximum register (§7 MIP).
template <class P>
void mip_finish(bool mip, const typename CompositorParams<P>::value_t& peak,
                const CompositorRegisters<P>& regs, Accumulator<P>& acc, Has<true>) {
  if (mip) acc = mip_pixel<P>(peak, regs);
}
template <class P>
void mip_finish(bool, const typename CompositorParams<P>::value_t&, const CompositorRegisters<P>&,
                Accumulator<P>&, Has<false>) {}

// One ray through the whole pipeline; `samples` counts the samples it took
// (tracer.skip those space leaping skipped, tracer.ert the sample at which
// early ray termination ended it). Units the design lacks are cut at
// compile time: a MIP-only design has no classification, shading or
// compositing here, a design without MIP no maximum register, one without ERT
// no comparator, one without space leaping no min-max memory or leap search.
template <class P, class U, class Banks, class Tracer = NullTracer>
OutputPixel<P> cast_ray(const FrameState<P, U>& f, const Banks& banks, int px, int py,
                        std::uint64_t& samples, Tracer& tracer) {
  VOXCAST_HLS_PRAGMA(HLS INLINE off)
  constexpr Units u = units_of<U>();
  const RaySetup<P> ray = ray_setup_for<P, U>(f.geometry, f.rsqrt, px, py);
  tracer.ray(ray);
  Accumulator<P> acc;
  if (!ray.hit) return output<P>(acc);
  const bool mip = frame_is_mip<U>(f.mode);
  const bool shaded = frame_is_shaded<U>(f.mode);
  typename CompositorParams<P>::value_t peak = 0;
  using HasMip = Has<can_mip(u)>;
  using HasComposite = Has<can_composite(u)>;
  const RayWeights<P, U> weights =
      ray_weights<P>(f.segments, f.geometry, ray, px, py, Has<U::partial_segments>{});
  const std::uint64_t n = ray.n.to_uint64();
  // §4a: the previous sample, the front of the next segment.
  Sample<P> front;
  auto per_sample = [&](std::uint64_t k, const auto& p, const Sample<P>& s) -> bool {
    ++samples;
    if (mip_sample<P>(mip, peak, p, s, tracer, HasMip{})) return true;
    const SampleWeight<P, U> w = weight_of_sample<P>(weights, k, n, Has<U::partial_segments>{});
    if (k == 0) front = s;  // (read by nothing: the first sample ends no segment)
    const bool goes_on =
        composite_sample<P, U>(f, shaded, w, p, k == 0, front, s, acc, tracer, HasComposite{});
    front = s;
    if (!goes_on) tracer.ert(k);
    return goes_on;
  };
  const bool leaped =
      march_leaping<P, U>(f, banks, ray, mip, per_sample, tracer, Has<U::space_leaping>{});
  if (!leaped) march_ray<P>(f.geometry, banks, ray, per_sample);
  mip_finish<P>(mip, peak, f.compositor, acc, HasMip{});
  return output<P>(acc);
}

// The frame loop over rows [y0, y1) of a width-pixel image: one pixel per
// iteration, written to fb[y * width + x], its counts added to *stats. The
// cosim harness calls it for row ranges on several host threads.
template <class P, class U, class Banks>
void render_rows(const FrameState<P, U>& f, const Banks& banks, int width, int y0, int y1,
                 OutputPixel<P>* fb, RowStats* stats) {
  StatsCounter counter(*stats);
  [[gnu::unused]] row_loop : for (int y = y0; y < y1; ++y) {
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 8192 avg = 256)
    [[gnu::unused]] pixel_loop : for (int x = 0; x < width; ++x) {
      VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 8192 avg = 256)
      fb[y * width + x] = cast_ray<P, U>(f, banks, x, y, stats->samples, counter);
    }
  }
}

}  // namespace hls
}  // namespace voxcast
