// The VIZARD II pipeline as the card streams it: the units of cast_ray
// (hls/vizard2_top.hpp) as six processes of a DATAFLOW region, joined by FIFOs
// (hls/stream.hpp), one image row per run of the region:
//
//   ray_setup_stage -> rays -> march_stage -> accesses -> interpolation_stage
//     -> samples -> classification_stage -> classified -> shading_stage
//     -> shaded -> compositor_stage -> frame buffer
//
// Each process is one flat loop with PIPELINE II=1 that takes or gives one
// token per iteration, so an HLS scheduler can run every unit at one sample
// per clock, as the 2001 paper's pipeline does (§2: "one sample per clock
// cycle"; docs/pipeline.md). The loops' trip counts are data (the rays'
// lengths), so each carries a LOOP_TRIPCOUNT and ends on a count of end-of-ray
// tokens: exactly one per pixel leaves every stage.
//
// Memory. The tables are read from on-chip copies (the top's load phase,
// hls/vizard2_synth_top.cpp); in the per-sample loops the only external
// memory is the eight voxel banks, each read at its own port in every access
// (interpolation_stage, §3.3), and the frame buffer, written once per pixel by
// the compositor.
//
// Early ray termination (§7.3). The processes form a feed-forward chain, which
// is what a canonical DATAFLOW region allows; the compositor drops the samples
// of a ray after its termination (the cycle model drops them the same way when
// they are already in flight, rtl_model/pipeline/ray_pipeline.hpp). The march
// stage, without a channel back from the compositor, marches every ray to its
// end: the image and the count of composited samples are cast_ray's, bit for
// bit, but ERT saves no clocks in this top. The card's feedback from the
// compositor to the address generator (the cycle model's ray slots) needs a
// backward channel, which Vitis HLS supports only between hls::task processes
// (UG1399, "Tasks and Dataflow"): docs/synthesis.md, "The streamed top".
//
// The host engines run cast_ray/render_rows (the same unit functions, one ray
// at a time, faster on a CPU); tests/hls/test_streamed_top.cpp proves this
// region gives the same pixels and sample counts. C++14.
#pragma once

#include <cstdint>

#include "hls/pragma.hpp"
#include "hls/stream.hpp"
#include "hls/vizard2_top.hpp"

namespace voxcast {
namespace hls {

// ---- Tokens ---------------------------------------------------------------------------------

// What every token after ray set-up carries besides its payload: `valid` a
// sample (false: an end-of-ray token with no sample, for a ray that missed,
// has no samples, or whose last samples were leapt over), `last` the ray's
// last token, `hit` the ray entered the volume (a missed ray's pixel is the
// background; a hit ray's is the accumulator's, MIP included, even with no
// sample taken).
struct TokenFlags {
  bool valid = false;
  bool last = false;
  bool hit = false;
};

// A sample's segment weight (§7a) rides with it from the march stage to the
// classification stage, where the segment-opacity unit weighs its opacity.
template <class P, class U>
struct AccessToken {
  BankAccess<P> access;
  SampleWeight<P, U> w;
  TokenFlags flags;
};

template <class P, class U>
struct SampleToken {
  Sample<P> s;
  SampleWeight<P, U> w;
  TokenFlags flags;
};

template <class P, class U>
struct ClassifiedToken {
  Sample<P> s;
  UnitState<can_composite(units_of<U>()), ClassEntry<P>> e;
  TokenFlags flags;
};

template <class P, class U>
struct ShadedToken {
  typename InterpolationParams<P>::value_t value;  // for MIP
  UnitState<can_composite(units_of<U>()), ShadedColor<P>> c;
  UnitState<can_composite(units_of<U>()), typename ClassificationParams<P>::alpha_t> alpha;
  TokenFlags flags;
};

// Trip counts: a row has at most 8192 pixels (GeometryParams::pixel_bits) and
// a ray at most 444 samples in a 256^3 volume at one sample per voxel
// (march_ray's bound), so the per-sample loops run at most 8192 x 444 =
// 3637248 iterations per row; the average is 256 rays of 256 samples.

// The FIFO depths between the stages: each absorbs the latency of the stage
// after it (the declared unit depths, hls/*.hpp) plus a small skid; the
// region's throughput does not depend on them once they cover the latency.
constexpr int kRayFifoDepth = 4;
constexpr int kSampleFifoDepth = 16;

// ---- 1. Ray set-up (§1) ---------------------------------------------------------------------
template <class P, class U>
void ray_setup_stage(const GeometryRegisters<P>& geometry,
                     const UnitState<U::perspective, RsqrtRom<P>>& rsqrt, int width, int y,
                     fifo<RaySetup<P>>& rays) {
  [[gnu::unused]] ray_setup_loop : for (int x = 0; x < width; ++x) {
    VOXCAST_HLS_PRAGMA(HLS PIPELINE II = 1)
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 8192 avg = 256)
    rays.write(ray_setup_for<P, U>(geometry, rsqrt, x, y));
  }
}

// ---- 2. Stepping and address generation (§2-3.3), space leaping ------------------------------

// Whether the sample at p lies in an empty block (docs/leaping.md): then `run`
// is the number of samples leapt (p left at the last of them). Always false
// in a design without space leaping, or when the frame disables it.
template <class P, class U>
bool leap_here(const GeometryRegisters<P>& g, const UnitState<U::space_leaping, LeapRegisters<P>>& lr,
               const UnitState<U::space_leaping, MinMaxMemory<P>>& mm, bool leaping,
               typename GeometryParams<P>::pos_t p[3], const typename GeometryParams<P>::step_t s[3],
               std::uint64_t remaining, std::uint64_t& run, Has<true>) {
  if (!leaping) return false;
  typename LeapParams<P>::bcoord_t b[3];
  if (!sample_block_empty<P>(g, lr, mm, p, b)) return false;
  run = leap_run<P>(g, lr, p, s, remaining, b);
  return true;
}
template <class P, class U, class Lr, class Mm>
bool leap_here(const GeometryRegisters<P>&, const Lr&, const Mm&, bool,
               typename GeometryParams<P>::pos_t[3], const typename GeometryParams<P>::step_t[3],
               std::uint64_t, std::uint64_t&, Has<false>) {
  return false;
}

// One flat loop over the row's samples: an iteration either takes the next
// ray (and issues its first sample) or issues the current ray's next sample
// (one bank access) or one leap; a ray's last token ends it. `width` rays in,
// one end-of-ray token per ray out. Each sample carries its segment weight
// (§7a, from the ray's set-up and pixel (x, y)'s jitter).
template <class P, class U>
void march_stage(const GeometryRegisters<P>& geometry,
                 const UnitState<U::space_leaping, LeapRegisters<P>>& leap,
                 const UnitState<U::space_leaping, MinMaxMemory<P>>& minmax,
                 const UnitState<U::partial_segments, SegmentOpacityTables<P>>& segments, bool mip,
                 int width, int y, fifo<RaySetup<P>>& rays, fifo<AccessToken<P, U>>& accesses) {
  using G = GeometryParams<P>;
  using HasLeap = Has<U::space_leaping>;
  using HasSegments = Has<U::partial_segments>;
  const bool leaping = leaping_enabled<P, U>(leap, mip, HasLeap{});
  RaySetup<P> ray;
  RayWeights<P, U> weights;
  typename G::pos_t p[3];
  std::uint64_t k = 0, n = 0;
  bool active = false;
  int taken = 0;
  [[gnu::unused]] march_loop : while (active || taken < width) {
    VOXCAST_HLS_PRAGMA(HLS PIPELINE II = 1)
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 3637248 avg = 65536)
    AccessToken<P, U> t;
    if (!active) {
      ray = rays.read();
      weights = ray_weights<P>(segments, geometry, ray, taken, y, HasSegments{});
      ++taken;
      n = ray.hit ? ray.n.to_uint64() : 0;
      if (n == 0) {  // missed, or no sample inside: the end token alone
        t.flags.last = true;
        t.flags.hit = ray.hit;
        accesses.write(t);
        continue;
      }
      [[gnu::unused]] march_start_loop : for (int a = 0; a < 3; ++a) {
        VOXCAST_HLS_PRAGMA(HLS UNROLL)
        p[a] = ray.p0[a];
      }
      k = 0;
      active = true;
    }
    std::uint64_t run = 0;
    const bool leapt = leap_here<P, U>(geometry, leap, minmax, leaping, p, ray.s, n - k, run, HasLeap{});
    if (leapt) {
      k += run;
    } else {
      t.access = address_generator<P>(geometry, p);
      t.w = weight_of_sample<P>(weights, k, n, HasSegments{});
      t.flags.valid = true;
      ++k;
    }
    step_position<P>(p, ray.s);
    t.flags.hit = true;
    t.flags.last = k >= n;
    if (t.flags.valid || t.flags.last) accesses.write(t);
    if (t.flags.last) active = false;
  }
}

// ---- 3. Interpolation (§3.3-3.5): the eight bank ports and the crossbar --------------------------

// The eight voxel banks, each its own AXI port of the top (two per DIMM
// bundle): the region's only external memory besides the frame buffer.
template <class P>
struct BankPorts {
  using word_t = typename InterpolationParams<P>::packed_word_t;
  const word_t* bank0;
  const word_t* bank1;
  const word_t* bank2;
  const word_t* bank3;
  const word_t* bank4;
  const word_t* bank5;
  const word_t* bank6;
  const word_t* bank7;
};

// §3.3: every bank read at its own port, at its own address, in every access.
template <class P>
void read_bank_ports(const BankPorts<P>& ports, const BankAccess<P>& a, VoxelWordFx<P> word[8]) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  word[0] = unpack_voxel_word<P>(ports.bank0[a.addr[0].to_uint64()]);
  word[1] = unpack_voxel_word<P>(ports.bank1[a.addr[1].to_uint64()]);
  word[2] = unpack_voxel_word<P>(ports.bank2[a.addr[2].to_uint64()]);
  word[3] = unpack_voxel_word<P>(ports.bank3[a.addr[3].to_uint64()]);
  word[4] = unpack_voxel_word<P>(ports.bank4[a.addr[4].to_uint64()]);
  word[5] = unpack_voxel_word<P>(ports.bank5[a.addr[5].to_uint64()]);
  word[6] = unpack_voxel_word<P>(ports.bank6[a.addr[6].to_uint64()]);
  word[7] = unpack_voxel_word<P>(ports.bank7[a.addr[7].to_uint64()]);
}

template <class P, class U>
void interpolation_stage(const BankPorts<P>& ports, int width, fifo<AccessToken<P, U>>& accesses,
                         fifo<SampleToken<P, U>>& samples) {
  int ended = 0;
  [[gnu::unused]] interpolation_loop : while (ended < width) {
    VOXCAST_HLS_PRAGMA(HLS PIPELINE II = 1)
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 3637248 avg = 65536)
    const AccessToken<P, U> t = accesses.read();
    SampleToken<P, U> o;
    o.flags = t.flags;
    o.w = t.w;
    if (t.flags.valid) {
      VoxelWordFx<P> word[8], corner[8];
      read_bank_ports<P>(ports, t.access, word);
      crossbar<P>(word, t.access.parity, corner);
      o.s = interpolation_processor<P>(corner, t.access.fq);
    }
    samples.write(o);
    if (t.flags.last) ++ended;
  }
}

// ---- 4. Classification (§4) and segment opacity (§7a) ----------------------------------------------
// `front` is the previous sample's value on the ray, the front of the segment
// the pre-integration table classifies (§4a).
template <class P, class U, class Segments, class Preint>
void classify_token(const ClassificationTable<P>& table, const Preint& preint,
                    const Segments& segments, const SampleWeight<P, U>& w, bool first,
                    const typename ClassificationParams<P>::value_t& front,
                    ClassifiedToken<P, U>& o, Has<true>) {
  if (o.flags.valid)
    o.e = weigh_entry<P>(
        segments, w, o.s.value,
        classify_entry<P>(table, preint, first, front, o.s.value, Has<U::preintegration>{}),
        Has<U::partial_segments>{});
}
template <class P, class U, class Table, class Preint, class Segments>
void classify_token(const Table&, const Preint&, const Segments&, const SampleWeight<P, U>&, bool,
                    const typename ClassificationParams<P>::value_t&, ClassifiedToken<P, U>&,
                    Has<false>) {}

template <class P, class U>
void classification_stage(const UnitState<U::classification, ClassificationTable<P>>& table,
                          const UnitState<U::preintegration, PreintegrationTable<P>>& preint,
                          const UnitState<U::partial_segments, SegmentOpacityTables<P>>& segments,
                          int width, fifo<SampleToken<P, U>>& samples,
                          fifo<ClassifiedToken<P, U>>& classified) {
  int ended = 0;
  // §4a: the front sample register (value and gradient), and whether the next
  // sample is its ray's first (which ends no segment). Rays arrive one after
  // another.
  Sample<P> front;
  bool first = true;
  [[gnu::unused]] classification_loop : while (ended < width) {
    VOXCAST_HLS_PRAGMA(HLS PIPELINE II = 1)
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 3637248 avg = 65536)
    const SampleToken<P, U> t = samples.read();
    ClassifiedToken<P, U> o;
    o.s = t.s;
    o.flags = t.flags;
    if (t.flags.valid && first) front = t.s;  // (read by nothing: the first ends no segment)
    classify_token<P, U>(table, preint, segments, t.w, first, front.value, o,
                         Has<can_composite(units_of<U>())>{});
    // The shading stage lights the sample's gradient, or the segment's front's (§4a).
    const Sample<P> lit = lit_sample<P>(preint, front, t.s, Has<U::preintegration>{});
    [[gnu::unused]] lit_gradient_loop : for (int a = 0; a < 3; ++a) {
      VOXCAST_HLS_PRAGMA(HLS UNROLL)
      o.s.g[a] = lit.g[a];
    }
    if (t.flags.valid) {
      front = t.s;
      first = false;
    }
    if (t.flags.last) {
      first = true;
      ++ended;
    }
    classified.write(o);
  }
}

// ---- 5. Reflectance map and shader (§5-6) ---------------------------------------------------------
template <class P, class U>
void shade_token(const UnitState<U::reflectance_map, ReflectanceMap<P>>& map,
                 const UnitState<U::reflectance_map, ReflectanceRegisters<P>>& regs, bool shaded,
                 const ClassifiedToken<P, U>& t, ShadedToken<P, U>& o, Has<true>) {
  o.alpha = t.e.alpha;
  if (t.flags.valid && t.e.alpha != 0) {  // transparent samples are not shaded (§7)
    Reflect<P> r;
    o.c = shade_sample<P, U>(map, regs, shaded, t.e, t.s, r);
  }
}
template <class P, class U, class Map, class Regs>
void shade_token(const Map&, const Regs&, bool, const ClassifiedToken<P, U>&, ShadedToken<P, U>&,
                 Has<false>) {}

template <class P, class U>
void shading_stage(const UnitState<U::reflectance_map, ReflectanceMap<P>>& map,
                   const UnitState<U::reflectance_map, ReflectanceRegisters<P>>& regs, bool shaded,
                   int width, fifo<ClassifiedToken<P, U>>& classified,
                   fifo<ShadedToken<P, U>>& shaded_out) {
  int ended = 0;
  [[gnu::unused]] shading_loop : while (ended < width) {
    VOXCAST_HLS_PRAGMA(HLS PIPELINE II = 1)
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 3637248 avg = 65536)
    const ClassifiedToken<P, U> t = classified.read();
    ShadedToken<P, U> o;
    o.value = t.s.value;
    o.flags = t.flags;
    shade_token<P, U>(map, regs, shaded, t, o, Has<can_composite(units_of<U>())>{});
    shaded_out.write(o);
    if (t.flags.last) ++ended;
  }
}

// ---- 6. Compositor (§7) and the frame buffer -------------------------------------------------------

// MIP (§7 MIP): the maximum register takes the sample; true if the frame is a
// MIP frame (the sample is then done).
template <class P, class U>
bool mip_token(bool mip, const ShadedToken<P, U>& t, typename CompositorParams<P>::value_t& peak,
               Has<true>) {
  if (!mip) return false;
  mip_update<P>(peak, t.value);
  return true;
}
template <class P, class U>
bool mip_token(bool, const ShadedToken<P, U>&, typename CompositorParams<P>::value_t&, Has<false>) {
  return false;
}

// §7.1-7.3: the over operator; false once ERT ends the ray.
template <class P, class U>
bool composite_token(const CompositorRegisters<P>& regs, const ShadedToken<P, U>& t,
                     Accumulator<P>& acc, Has<true>) {
  if (t.alpha == 0) return true;  // transparent: no change, no ERT test (§7)
  return composite_step<P, U>(regs, t.c, t.alpha, acc);
}
template <class P, class U>
bool composite_token(const CompositorRegisters<P>&, const ShadedToken<P, U>&, Accumulator<P>&,
                     Has<false>) {
  return true;
}

// Writes pixel (x, y) of each ray as its last token arrives; `samples` counts
// the samples composited (those after an early termination are dropped).
template <class P, class U>
void compositor_stage(const CompositorRegisters<P>& regs, bool mip, int width, int y,
                      fifo<ShadedToken<P, U>>& shaded, OutputPixel<P>* fb,
                      std::uint64_t& samples) {
  using HasMip = Has<can_mip(units_of<U>())>;
  Accumulator<P> acc;
  typename CompositorParams<P>::value_t peak = 0;
  bool live = true;  // no early termination yet
  std::uint64_t taken = 0;
  int x = 0;
  [[gnu::unused]] compositor_loop : while (x < width) {
    VOXCAST_HLS_PRAGMA(HLS PIPELINE II = 1)
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 3637248 avg = 65536)
    const ShadedToken<P, U> t = shaded.read();
    if (t.flags.valid && live) {
      ++taken;
      if (!mip_token<P, U>(mip, t, peak, HasMip{}))
        live = composite_token<P, U>(regs, t, acc, Has<can_composite(units_of<U>())>{});
    }
    if (t.flags.last) {
      if (t.flags.hit) mip_finish<P>(mip, peak, regs, acc, HasMip{});
      fb[y * width + x] = output<P>(acc);
      ++x;
      acc = Accumulator<P>();
      peak = 0;
      live = true;
    }
  }
  samples = taken;
}

// ---- 0. The load phase: the frame's registers and tables into on-chip memory -------------------
//
// Once per frame, before the region runs, the top copies the frame state the
// host wrote (one m_axi bundle, as the card's PCI upload wrote the SRAMs and
// registers between frames) into its on-chip copy: each table by a pipelined
// loop, one entry per clock (a burst on the bus); the registers by
// assignment. An absent unit's table is not copied: it does not exist.

template <class T, int N>
void load_table(const T (&src)[N], T (&dst)[N]) {
  [[gnu::unused]] load_table_loop : for (int i = 0; i < N; ++i) {
    VOXCAST_HLS_PRAGMA(HLS PIPELINE II = 1)
    dst[i] = src[i];
  }
}

template <class P>
void load_unit(const RsqrtRom<P>& src, RsqrtRom<P>& dst) {
  load_table(src.seed, dst.seed);
}
template <class P>
void load_unit(const ClassificationTable<P>& src, ClassificationTable<P>& dst) {
  load_table(src.entry, dst.entry);
}
template <class P>
void load_unit(const ReflectanceMap<P>& src, ReflectanceMap<P>& dst) {
  load_table(src.diffuse, dst.diffuse);
  load_table(src.specular, dst.specular);
}
template <class P>
void load_unit(const MinMaxMemory<P>& src, MinMaxMemory<P>& dst) {
  load_table(src.block, dst.block);
}
template <class P>
void load_unit(const SegmentOpacityTables<P>& src, SegmentOpacityTables<P>& dst) {
  dst.enabled = src.enabled;
  load_table(src.tau, dst.tau);
  load_table(src.rom, dst.rom);
}
template <class P>
void load_unit(const PreintegrationTable<P>& src, PreintegrationTable<P>& dst) {
  dst.enabled = src.enabled;
  load_table(src.entry, dst.entry);
}
inline void load_unit(const AbsentUnit&, AbsentUnit&) {}

// The load phase. `src` is the frame state in external memory, `dst` the
// top's on-chip copy.
template <class P, class U>
void load_frame_state(const FrameState<P, U>& src, FrameState<P, U>& dst) {
  dst.geometry = src.geometry;
  dst.reflectance_regs = src.reflectance_regs;
  dst.compositor = src.compositor;
  dst.mode = src.mode;
  dst.leap = src.leap;  // registers and the prefix table (entries + 1 counts)
  load_unit(src.rsqrt, dst.rsqrt);
  load_unit(src.class_table, dst.class_table);
  load_unit(src.reflectance, dst.reflectance);
  load_unit(src.minmax, dst.minmax);
  load_unit(src.segments, dst.segments);
  load_unit(src.preint, dst.preint);
}

// ---- The region ----------------------------------------------------------------------------------

// One image row through the six processes. `f` is the on-chip state (the
// top's load phase filled it); the banks and fb are the top's AXI ports.
template <class P, class U>
void render_row_streamed(const FrameState<P, U>& f, const BankPorts<P>& ports, int width, int y,
                         OutputPixel<P>* fb, std::uint64_t& samples) {
  VOXCAST_HLS_PRAGMA(HLS DATAFLOW)
  const bool mip = frame_is_mip<U>(f.mode);
  const bool shaded = frame_is_shaded<U>(f.mode);
  fifo<RaySetup<P>> rays;
  fifo<AccessToken<P, U>> accesses;
  fifo<SampleToken<P, U>> interpolated;
  fifo<ClassifiedToken<P, U>> classified;
  fifo<ShadedToken<P, U>> shaded_samples;
  VOXCAST_HLS_PRAGMA(HLS STREAM variable = rays depth = kRayFifoDepth)
  VOXCAST_HLS_PRAGMA(HLS STREAM variable = accesses depth = kSampleFifoDepth)
  VOXCAST_HLS_PRAGMA(HLS STREAM variable = interpolated depth = kSampleFifoDepth)
  VOXCAST_HLS_PRAGMA(HLS STREAM variable = classified depth = kSampleFifoDepth)
  VOXCAST_HLS_PRAGMA(HLS STREAM variable = shaded_samples depth = kSampleFifoDepth)
  ray_setup_stage<P, U>(f.geometry, f.rsqrt, width, y, rays);
  march_stage<P, U>(f.geometry, f.leap, f.minmax, f.segments, mip, width, y, rays, accesses);
  interpolation_stage<P, U>(ports, width, accesses, interpolated);
  classification_stage<P, U>(f.class_table, f.preint, f.segments, width, interpolated,
                             classified);
  shading_stage<P, U>(f.reflectance, f.reflectance_regs, shaded, width, classified,
                      shaded_samples);
  compositor_stage<P, U>(f.compositor, mip, width, y, shaded_samples, fb, samples);
}

// The frame: one run of the region per row; `samples` is the frame's count of
// composited samples (cast_ray's count). Its only pointers are the eight bank
// ports and the frame buffer, which the top passes as they are
// (tools/synth_lint --region checks that it passes nothing else).
template <class P, class U>
void render_frame_streamed(const FrameState<P, U>& f, const typename InterpolationParams<P>::packed_word_t* bank0,
                           const typename InterpolationParams<P>::packed_word_t* bank1,
                           const typename InterpolationParams<P>::packed_word_t* bank2,
                           const typename InterpolationParams<P>::packed_word_t* bank3,
                           const typename InterpolationParams<P>::packed_word_t* bank4,
                           const typename InterpolationParams<P>::packed_word_t* bank5,
                           const typename InterpolationParams<P>::packed_word_t* bank6,
                           const typename InterpolationParams<P>::packed_word_t* bank7, int width,
                           int height, OutputPixel<P>* fb, std::uint64_t& samples) {
  const BankPorts<P> ports = {bank0, bank1, bank2, bank3, bank4, bank5, bank6, bank7};
  std::uint64_t total = 0;
  [[gnu::unused]] streamed_row_loop : for (int y = 0; y < height; ++y) {
    VOXCAST_HLS_PRAGMA(HLS LOOP_TRIPCOUNT min = 1 max = 8192 avg = 256)
    std::uint64_t row = 0;
    render_row_streamed<P, U>(f, ports, width, y, fb, row);
    total += row;
  }
  samples = total;
}

}  // namespace hls
}  // namespace voxcast
