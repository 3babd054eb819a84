// The VIZARD II ray-casting pipeline, top level (docs/pipeline.md): the units
// of this folder composed per ray, and the frame loop a vendor tool
// synthesizes. Layer 2 of the Vitis-Libraries split: the units (layer 1) carry
// no interface pragmas; this file does.
//
//   geometry processor (ray setup, stepping) -> address generator ->
//   interpolation processor -> classification table -> reflectance map ->
//   shader -> compositor (ERT, MIP) -> output quantization
//
// A MIP or unshaded frame never reads the reflectance map and a parallel camera
// never reads the rsqrt ROM, so a design built for such scenes omits them
// (docs/pipeline.md §1.2, §5): every template here takes the design's Units
// (hls/units.hpp; default kAllUnits, the run-time-configurable design), and an
// absent unit is neither a member of FrameState nor instantiated in cast_ray.
#pragma once

#include <cstdint>
#include <type_traits>

#include "hls/classification_table.hpp"
#include "hls/compositor.hpp"
#include "hls/geometry_processor.hpp"
#include "hls/interpolation_processor.hpp"
#include "hls/reflectance_map.hpp"
#include "hls/shader.hpp"
#include "hls/space_leaping_unit.hpp"
#include "hls/pragma.hpp"
#include "hls/types.hpp"
#include "hls/units.hpp"

namespace voxcast::hls {

enum class FrameMode : std::uint8_t { Shaded = 0, Unshaded = 1, Mip = 2 };

// A unit's state if the design has the unit, else an empty stand-in.
template <bool Present, class T>
using UnitState = std::conditional_t<Present, T, AbsentUnit>;

// Everything on chip for one frame: registers and tables, loaded by the host
// between frames. An absent unit's ROM or table is not there at all.
template <PrecisionProfile P, Units U = kAllUnits>
struct FrameState {
  static_assert(consistent(U), "a design needs a ray direction and an output path");
  GeometryRegisters<P> geometry;
  [[no_unique_address]] UnitState<U.perspective, RsqrtRom<P>> rsqrt;
  [[no_unique_address]] UnitState<U.classification, ClassificationTable<P>> class_table;
  [[no_unique_address]] UnitState<U.reflectance_map, ReflectanceRegisters<P>> reflectance_regs;
  [[no_unique_address]] UnitState<U.reflectance_map, ReflectanceMap<P>> reflectance;
  CompositorRegisters<P> compositor;
  FrameMode mode;  // among the modes the units allow (can_mip, can_composite, can_shade)
  // Space leaping (hls/space_leaping_unit.hpp): registers, prefix table and the
  // min-max block memory, loaded when the volume is (the blocks) and with the
  // classification table (the prefix counts).
  [[no_unique_address]] UnitState<U.space_leaping, LeapRegisters<P>> leap;
  [[no_unique_address]] UnitState<U.space_leaping, MinMaxMemory<P>> minmax;
};

// §1 for the cameras the design has: a one-camera design instantiates only its
// set-up (a parallel design has no direction or rsqrt unit).
template <PrecisionProfile P, Units U>
RaySetup<P> ray_setup_for(const FrameState<P, U>& f, int px, int py) {
  if constexpr (!U.perspective) {
    return ray_setup_parallel<P>(f.geometry, px, py);
  } else if constexpr (!U.parallel_origin) {
    return ray_setup_perspective<P>(f.geometry, f.rsqrt.seed, px, py);
  } else {
    return ray_setup<P>(f.geometry, f.rsqrt.seed, px, py);
  }
}

// Tracing hook: the default does nothing and compiles away. The cosim harness
// passes a tracer that records every unit's output (cosim/hls_engine.cpp).
struct NullTracer {
  template <class Ray>
  void ray(const Ray&) {}
  template <class... Args>
  void sample(const Args&...) {}
  void skip(std::uint64_t) {}
};

// Counts the samples space leaping skipped (render_rows' statistics).
struct SkipCounter : NullTracer {
  std::uint64_t skipped = 0;
  void skip(std::uint64_t run) { skipped += run; }
};

// One ray through the whole pipeline; `samples` counts the samples it took
// (tracer.skip those space leaping skipped). Units the design lacks are cut at
// compile time: a MIP-only design has no classification, shading or
// compositing here, a design without MIP no maximum register, one without ERT
// no comparator, one without space leaping no min-max memory or leap search.
template <PrecisionProfile P, Units U, class Banks, class Tracer = NullTracer>
OutputPixel<P> cast_ray(const FrameState<P, U>& f, const Banks& banks, int px, int py,
                        std::uint64_t& samples, Tracer& tracer) {
  VOXCAST_HLS_PRAGMA(HLS INLINE off)
  const RaySetup<P> ray = ray_setup_for<P, U>(f, px, py);
  tracer.ray(ray);
  Accumulator<P> acc;
  if (!ray.hit) return output<P>(acc);
  // The mode register decides only between modes the units allow.
  [[maybe_unused]] const bool mip = can_mip(U) && (!can_composite(U) || f.mode == FrameMode::Mip);
  [[maybe_unused]] const bool shaded = can_shade(U) && f.mode == FrameMode::Shaded;
  typename CompositorParams<P>::value_t peak = 0;
  auto per_sample = [&](std::uint64_t, const auto& p, const Sample<P>& s) -> bool {
    ++samples;
    if constexpr (can_mip(U)) {
      if (mip) {
        mip_update<P>(peak, s.value);
        tracer.sample(p, s, peak);
        return true;
      }
    }
    if constexpr (can_composite(U)) {
      const ClassEntry<P> e = classify<P>(f.class_table, s.value);
      if (e.alpha == 0) {  // transparent: no change, no ERT test (§7)
        tracer.sample(p, s, e, Reflect<P>{0, 0}, ShadedColor<P>{}, acc);
        return true;
      }
      Reflect<P> r{0, 0};
      if constexpr (can_shade(U)) {
        if (shaded) r = reflect<P>(f.reflectance, f.reflectance_regs, s.g);
        const ShadedColor<P> c = shade<P>(e, r, shaded);
        composite<P>(acc, c, e.alpha);
        tracer.sample(p, s, e, r, c, acc);
      } else {  // c = U(colour) (§6): shaded is the constant false, so the
                // intensity products inside shade() have no fan-out
        const ShadedColor<P> c = shade<P>(e, r, false);
        composite<P>(acc, c, e.alpha);
        tracer.sample(p, s, e, r, c, acc);
      }
      if constexpr (U.ert) return !ert_reached<P>(acc, f.compositor);
    }
    return true;
  };
  bool leaped = false;
  if constexpr (U.space_leaping) {
    if (f.leap.enabled && !mip) {
      auto skip = [&tracer](std::uint64_t run) { tracer.skip(run); };
      march_ray_leaping<P>(f.geometry, f.leap, f.minmax, banks, ray, per_sample, skip);
      leaped = true;
    }
  }
  if (!leaped) march_ray<P>(f.geometry, banks, ray, per_sample);
  if constexpr (can_mip(U)) {
    if (mip) acc = mip_pixel<P>(peak, f.compositor);
  }
  return output<P>(acc);
}

// The frame loop over rows [y0, y1) of a width-pixel image: one pixel per
// iteration, written to fb[y * width + x]. The cosim harness calls it for row
// ranges on several host threads; the synthesized top calls it for the frame.
template <PrecisionProfile P, Units U, class Banks>
void render_rows(const FrameState<P, U>& f, const Banks& banks, int width, int y0, int y1,
                 OutputPixel<P>* fb, std::uint64_t* samples, std::uint64_t* skipped = nullptr) {
  SkipCounter none;
  std::uint64_t taken = 0;
  [[maybe_unused]] row_loop : for (int y = y0; y < y1; ++y) {
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 8192 avg = 256)
    [[maybe_unused]] pixel_loop : for (int x = 0; x < width; ++x) {
      VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 8192 avg = 256)
      fb[y * width + x] = cast_ray<P, U>(f, banks, x, y, taken, none);
    }
  }
  *samples = taken;
  if (skipped) *skipped = none.skipped;
}

// The synthesizable top: the frame state and the 8 voxel banks in external
// memory (one AXI master each, as the card's DIMM channels), the frame buffer
// out. Generated wrappers (docs/synthesis.md) instantiate it for one profile
// and one elaborated set of units.
template <PrecisionProfile P, Units U = kAllUnits>
void vizard2_frame(const FrameState<P, U>* frame,
                   const typename InterpolationParams<P>::packed_word_t* bank0,
                   const typename InterpolationParams<P>::packed_word_t* bank1,
                   const typename InterpolationParams<P>::packed_word_t* bank2,
                   const typename InterpolationParams<P>::packed_word_t* bank3,
                   const typename InterpolationParams<P>::packed_word_t* bank4,
                   const typename InterpolationParams<P>::packed_word_t* bank5,
                   const typename InterpolationParams<P>::packed_word_t* bank6,
                   const typename InterpolationParams<P>::packed_word_t* bank7, int width,
                   int height, OutputPixel<P>* fb, std::uint64_t* samples) {
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = width)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = height)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE s_axilite port = return)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = frame offset = slave bundle = gmem_frame)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank0 offset = slave bundle = dimm0)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank1 offset = slave bundle = dimm0)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank2 offset = slave bundle = dimm1)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank3 offset = slave bundle = dimm1)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank4 offset = slave bundle = dimm2)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank5 offset = slave bundle = dimm2)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank6 offset = slave bundle = dimm3)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = bank7 offset = slave bundle = dimm3)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = fb offset = slave bundle = gmem_fb)
  VOXCAST_HLS_PRAGMA(HLS INTERFACE m_axi port = samples offset = slave bundle = gmem_fb)
  const PackedBanks<P> banks{{bank0, bank1, bank2, bank3, bank4, bank5, bank6, bank7}};
  render_rows<P, U>(*frame, banks, width, 0, height, fb, samples);
}

}  // namespace voxcast::hls
