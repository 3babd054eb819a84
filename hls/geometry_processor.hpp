// Geometry processor: ray setup and stepping, VIZARD II section 2.1 ("for each
// point P(i,j) of the view plane a ray is cast ... the ray is clipped against the
// volume ... sample positions are computed incrementally"). The datapath is
// docs/pipeline.md §0-2, bit by bit; its float twins are ref::primary_ray,
// ref::clip, ref::sample_count and ray.at(t_enter + k·step) / world_scale; its
// bit-true twin is bittrue::bt_ray_setup (refmodel/bittrue/geometry.hpp).
//
// Layout of this header:
//   1. GeometryParams<P>: every width and type of the unit, derived from P.
//   2. GeometryRegisters<P> (§0) and the rsqrt seed ROM (§1.2).
//   3. The synthesizable unit: pixel_direction (§1.1), rsqrt_newton and
//      normalize_direction (§1.2, the rsqrt unit), step_vector (§1.3),
//      pixel_origin (§1.4), clip_ray (§1.5-1.6), ray_setup_perspective /
//      ray_setup_parallel / ray_setup, and step_position (§2).
//   4. host:: — loading the registers and the ROM from the raw integers the
//      driver computes (bittrue::make_frame_registers / make_rsqrt_seed). Not
//      synthesized.
#pragma once

#include <cstdint>

#include "hls/pragma.hpp"
#include "hls/types.hpp"
#include "hls/widths.hpp"
#include "refmodel/render/jitter.hpp"

#if VOXCAST_HLS_HOST_CODE
#include <vector>

#include "refmodel/bittrue/frame_setup.hpp"
#endif


namespace voxcast {
namespace hls {

// ---- 1. Parameters ------------------------------------------------------------------------
// a = addr_bits, pf = pos_frac_bits, df = dir_frac_bits, tf = t_frac_bits,
// sb = rsqrt_seed_bits. Every width is one of hls/widths.hpp's functions of the
// profile, where the value range that sets it is stated; every product and sum
// between rounding points is exact in the operator's widened result type
// (docs/pipeline.md, "Notation").
template <class P>
struct GeometryParams {
  static constexpr int a = P::addr_bits;
  static constexpr int pf = P::pos_frac_bits;
  static constexpr int df = P::dir_frac_bits;
  static constexpr int tf = P::t_frac_bits;
  static constexpr int sb = P::rsqrt_seed_bits;
  static constexpr int seed_entries = widths::rsqrt_seed_entries(profile_fields<P>());

  static constexpr int pixel_bits = widths::pixel_bits;
  static constexpr int dir_bits = widths::dir_bits(profile_fields<P>());
  static constexpr int origin_int_bits = widths::origin_int_bits(profile_fields<P>());
  static constexpr int origin_bits = widths::origin_bits(profile_fields<P>());
  static constexpr int kreg_bits = widths::kreg_bits(profile_fields<P>());
  static constexpr int word_addr_bits = widths::word_addr_bits(profile_fields<P>());
  static constexpr int unit_bits = widths::unit_bits(profile_fields<P>());
  static constexpr int step_bits = widths::step_bits(profile_fields<P>());
  static constexpr int clip_int_bits = widths::clip_int_bits(profile_fields<P>());
  static constexpr int clip_num_bits = widths::clip_num_bits(profile_fields<P>());
  static constexpr int pos_int_bits = widths::pos_int_bits(profile_fields<P>());
  static constexpr int pos_bits = widths::pos_bits(profile_fields<P>());
  static constexpr int count_bits = widths::count_bits(profile_fields<P>());

  static_assert(sb <= df,
                "rsqrt_seed_bits must not exceed dir_frac_bits (the seed index is a "
                "bit select of m, docs/pipeline.md §0)");
  static_assert(a + pf + tf <= 49,
                "addr_bits + pos_frac_bits + t_frac_bits must be <= 49 "
                "(clip quotients below 2^53 LSBs, docs/pipeline.md §0)");

  using pixel_t = uint_t<pixel_bits>;
  // §0 registers: A, B, C, U and the pixel direction d; E, O, P, R and o; K; the box.
  using dir_t = fixed<dir_bits, widths::dir_int_bits>;
  using origin_t = fixed<origin_bits, origin_int_bits>;  // E, O, P, R, o
  using kreg_t = ufixed<kreg_bits, widths::kreg_int_bits>;
  using box_t = int_t<widths::box_bits(profile_fields<P>())>;      // LO, HI
  using coord_t = uint_t<widths::coord_bits(profile_fields<P>())>;  // voxel index, LAST
  using dim_t = uint_t<widths::dim_bits(profile_fields<P>())>;      // dims
  using half_t = uint_t<widths::half_bits(profile_fields<P>())>;    // HX
  using slice_t = uint_t<widths::slice_bits(profile_fields<P>())>;  // HXY
  using word_addr_t = uint_t<word_addr_bits>;

  // §1.2 rsqrt unit.
  using n2_t = ufixed<widths::n2_bits(profile_fields<P>()), widths::n2_int_bits>;  // d·d
  using n2_norm_t = ufixed<widths::n2_norm_bits(profile_fields<P>()), widths::n2_int_bits>;
  using dnorm_t = fixed<widths::dnorm_bits(profile_fields<P>()), widths::dnorm_int_bits>;
  using m_t = ufixed<widths::m_bits(profile_fields<P>()), widths::m_int_bits, RND>;
  using y_t = ufixed<widths::y_bits(profile_fields<P>()), widths::y_int_bits, RND>;  // seeds, y
  using sq_t = ufixed<widths::sq_bits(profile_fields<P>()), widths::sq_int_bits, RND>;
  using three_t = ufixed<2, 2>;  // the constant 3
  using halving_t = fixed<widths::halving_bits(profile_fields<P>()), widths::halving_int_bits>;
  using unit_t = fixed<unit_bits, widths::unit_int_bits, RND>;  // u

  // §1.3-1.6.
  using step_t = fixed<step_bits, widths::step_int_bits, RND>;  // s = Q_RND(u·K, pf)
  using num_t = fixed<clip_num_bits, clip_int_bits, TRN>;       // Q_TRN(LO - o, tf)
  // ap's quotient type (semantics §5-6): tf fraction bits, truncated toward zero.
  using k_t = decltype(num_t() / step_t());
  static_assert(k_t::width == widths::clip_quotient_bits(profile_fields<P>()),
                "hls/widths.hpp's clip_quotient_bits is the quotient type's width");
  using kstep_t = fixed<widths::kstep_bits(profile_fields<P>()), clip_int_bits, RND>;  // k_in·s
  using pos_t = fixed<pos_bits, pos_int_bits>;  // sample positions
  using count_t = uint_t<count_bits>;
};

// ---- 2. Registers and ROM -------------------------------------------------------------------
// docs/pipeline.md §0, loaded once per frame by host::load_geometry_registers.
// (P and R of the spec are Pcol and Rrow here: P is the profile.)
template <class P>
struct GeometryRegisters {
  using G = GeometryParams<P>;
  bool perspective = true;
  bool jitter = false;                          // render.jitter
  typename G::dir_t A[3], B[3], C[3];           // perspective directions
  typename G::origin_t O[3], Pcol[3], Rrow[3];  // origin plane: origin, increments
  typename G::dir_t U[3];                       // parallel unit direction
  typename G::kreg_t K[3];                      // step / world_scale
  typename G::box_t LO[3], HI[3];               // voxel-centre box (crop)
  typename G::dim_t dims[3];                    // volume dims
  typename G::coord_t LAST[3];                  // dims - 1
  typename G::half_t HX;                        // ceil(dx/2), words per bank row
  typename G::slice_t HXY;                      // HX·ceil(dy/2), words per bank slice
};

// The rsqrt seed ROM (§1.2), 2^rsqrt_seed_bits entries.
template <class P>
struct RsqrtRom {
  typename GeometryParams<P>::y_t seed[GeometryParams<P>::seed_entries];
};

// The result of ray setup for one pixel (§1.5-1.6). k_in, k_out (in samples) are
// kept for the tests and for mismatch reports; a miss has n = 0 and p0 = k_in =
// k_out = 0.
template <class P>
struct RaySetup {
  using G = GeometryParams<P>;
  bool hit = false;
  typename G::count_t n;
  typename G::pos_t p0[3];
  typename G::step_t s[3];
  typename G::k_t k_in, k_out;
};

// ---- 3. The unit ----------------------------------------------------------------------------

// §1.1: perspective pixel direction d = A + px·B + py·C (exact).
template <class P>
void pixel_direction(const GeometryRegisters<P>& r, typename GeometryParams<P>::pixel_t px,
                     typename GeometryParams<P>::pixel_t py,
                     typename GeometryParams<P>::dir_t d[3]) {
  [[gnu::unused]] dir_loop : for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    d[k] = r.A[k] + px * r.B[k] + py * r.C[k];
  }
}

// §1.2: seed look-up and two Newton steps of y <- y·(3 - m·y²)/2; y ~ 1/sqrt(m).
template <class P>
typename GeometryParams<P>::y_t rsqrt_newton(
    const typename GeometryParams<P>::m_t& m,
    const typename GeometryParams<P>::y_t seed[GeometryParams<P>::seed_entries]) {
  using G = GeometryParams<P>;
  // floor(m·2^sb): bits [df, df - sb] of m (its integer bit and the top sb
  // fraction bits); 2^sb only when m rounded up to 1.
  unsigned idx = static_cast<unsigned>(read_bits(m, G::df, G::df - G::sb));
  if (idx > static_cast<unsigned>(G::seed_entries - 1)) idx = G::seed_entries - 1;
  typename G::y_t y = seed[idx];
  const typename G::three_t three = 3;
  [[gnu::unused]] newton_loop : for (int it = 0; it < 2; ++it) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    typename G::sq_t t = y * y;                 // Q_RND(y·y, df)
    t = m * t;                                  // Q_RND(m·t, df)
    typename G::halving_t h = y * (three - t);  // exact
    h >>= 1;                                    // exact: h has one spare fraction bit
    y = h;                                      // Q_RND(·, df)
  }
  return y;
}

// ---- Pipeline depths ------------------------------------------------------------------------
// Each unit's depth in clocks at the 100 MHz core clock, one sample (or ray) per
// clock (VIZARD II runs its core at the SDRAM clock, 2001 paper §2.3), is a
// constant declared once, next to the unit's kernel (here for the geometry
// processor, in the other units' headers for theirs; docs/pipeline.md,
// "Pipeline depths", lists them). The kernel's LATENCY pragma, the cycle model's
// UnitLatencies (rtl_model/pipeline/config.hpp) and the resource report
// (cosim/hardware/report.cpp) read the constant; tests/report/test_unit_depths.cpp checks
// that the three agree. The pragmas name plain namespace-scope constants:
// UG1399 ("Using Constants with Pragmas") allows a const int or constexpr
// variable as a pragma's value, and says nothing of qualified or
// template-dependent names. min = max: the tool neither stretches nor shortens
// the unit, so the cycle model's timing is the design's.
//
// The rsqrt unit (docs/pipeline.md §1.2), one multiply or add per clock: d·d
// (multiply, sum) 2, leading-zero count and shifts 1, seed ROM 1, two Newton
// steps of three products 6, d'·y 1. A parallel camera has no rsqrt unit: its
// ray set-up is shorter by these stages.
constexpr int rsqrt_depth = 11;

// §1.2: u = Q_RND(d·2^e · y, df), the unit direction (u = 0 if d = 0).
template <class P>
void normalize_direction(
    const typename GeometryParams<P>::dir_t d[3],
    const typename GeometryParams<P>::y_t seed[GeometryParams<P>::seed_entries],
    typename GeometryParams<P>::unit_t u[3]) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = rsqrt_depth max = rsqrt_depth)
  using G = GeometryParams<P>;
  const typename G::n2_t n2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  // Leading-zero count: a priority encoder over the 2df + 2 bits of n2, the type's own
  // (a loop over the bits cost the software engines 4 % of their instructions).
  const int lz = leading_zeros(n2);
  if (lz == G::n2_t::width) {
    [[gnu::unused]] zero_loop : for (int k = 0; k < 3; ++k) {
      VOXCAST_HLS_PRAGMA(HLS UNROLL)
      u[k] = 0;
    }
    return;
  }
  // The top set bit of n2 has weight 2^(1 - lz); n2·4^e in [1/4, 1) for
  // e = floor((-1 - (1 - lz))/2) = lz/2 - 1, in [-1, df - 1].
  const int e = lz / 2 - 1;
  typename G::n2_norm_t nn = n2;
  typename G::dnorm_t dn[3];
  [[gnu::unused]] norm_loop : for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    dn[k] = d[k];
    if (e < 0) {
      dn[k] >>= 1;  // exact: dnorm_t has one more fraction bit than dir_t
    } else {
      dn[k] <<= e;  // exact: |d·2^e| < 1
    }
  }
  if (e < 0) {
    nn >>= 2;  // exact: two spare fraction bits
  } else {
    nn <<= 2 * e;  // exact: n2·4^e < 1
  }
  const typename G::m_t m = nn;  // Q_RND(n2·4^e, df)
  const typename G::y_t y = rsqrt_newton<P>(m, seed);
  [[gnu::unused]] unit_loop : for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    u[k] = dn[k] * y;  // Q_RND(d'·y, df)
  }
}

// §1.3: s[a] = Q_RND(u[a]·K[a], pf).
template <class P>
void step_vector(const GeometryRegisters<P>& r, const typename GeometryParams<P>::unit_t u[3],
                 typename GeometryParams<P>::step_t s[3]) {
  [[gnu::unused]] step_loop : for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    s[k] = u[k] * r.K[k];
  }
}

// §1.4: o = O + px·P + py·R (exact; the host keeps it in range), the pixel's
// point on the origin plane, for either camera.
template <class P>
void pixel_origin(const GeometryRegisters<P>& r, typename GeometryParams<P>::pixel_t px,
                  typename GeometryParams<P>::pixel_t py,
                  typename GeometryParams<P>::origin_t o[3]) {
  [[gnu::unused]] origin_loop : for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    o[k] = r.O[k] + px * r.Pcol[k] + py * r.Rrow[k];
  }
}

// §1.5-1.6: clip in units of samples, sample count and first position.
// `jitter` (render.jitter, else 0): the first sample's delay in samples, in [0, 1).
template <class P>
RaySetup<P> clip_ray(const GeometryRegisters<P>& r, const typename GeometryParams<P>::origin_t o[3],
                     const typename GeometryParams<P>::step_t s[3],
                     const typename GeometryParams<P>::k_t& jitter = 0) {
  using G = GeometryParams<P>;
  using k_t = typename G::k_t;
  RaySetup<P> ray;
  k_t k_in = 0;
  k_t k_out = 0;
  bool any = false;    // an axis with s != 0
  bool inside = true;  // every axis with s = 0 has LO <= o <= HI
  [[gnu::unused]] clip_loop : for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    ray.s[k] = s[k];
    if (s[k] == 0) {
      if (o[k] < r.LO[k] || o[k] > r.HI[k]) inside = false;
    } else {
      const typename G::num_t num_lo = r.LO[k] - o[k];  // Q_TRN(LO - o, tf)
      const typename G::num_t num_hi = r.HI[k] - o[k];
      const k_t k_lo = num_lo / s[k];  // TRUNC0(·, tf)
      const k_t k_hi = num_hi / s[k];
      const k_t k_near = k_lo < k_hi ? k_lo : k_hi;
      const k_t k_far = k_lo < k_hi ? k_hi : k_lo;
      if (!any || k_near > k_in) k_in = k_near;
      if (!any || k_far < k_out) k_out = k_far;
      any = true;
    }
  }
  if (k_in < 0) k_in = 0;
  k_in += jitter;  // exact: tf fraction bits, k_in + 1 within k_t's range
  ray.hit = any && inside && !(k_in > k_out);
  if (ray.hit) {
    ray.k_in = k_in;
    ray.k_out = k_out;
    ray.n = int_cast<typename G::count_t>(k_out - k_in);  // floor (non-negative: toward zero)
    ray.n++;
  } else {
    ray.k_in = 0;
    ray.k_out = 0;
    ray.n = 0;
  }
  [[gnu::unused]] p0_loop : for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const typename G::kstep_t d = k_in * s[k];  // Q_RND(k_in·s, pf)
    if (ray.hit) {
      ray.p0[k] = o[k] + d;
    } else {
      ray.p0[k] = 0;
    }
  }
  return ray;
}

// render.jitter: the ray parameter offset J·2^-tf of pixel (px, py), J the top
// tf bits of ref::pixel_hash (an integer hash, refmodel/render/space_leaping.hpp).
template <class P>
typename GeometryParams<P>::k_t pixel_jitter(const GeometryRegisters<P>& r, int px, int py) {
  using G = GeometryParams<P>;
  typename G::k_t j = 0;
  if (r.jitter) write_bits(j, G::tf - 1, 0, ref::jitter_raw(px, py, G::tf));
  return j;
}

// The ray set-up without the rsqrt unit (§1.1 or §1.4, §1.3, §1.5-1.6): the
// pixel's direction or origin, the step vector, the six clip divisions, the
// comparisons, the sample count and p0. 13 clocks is the cycle model's
// assumption, not a schedule: the resource report prices each clip division as
// a fully pipelined restoring divider of k_t's width in quotient bits (48 at
// kBalanced), one stage per bit, so a vendor tool held to this LATENCY has to
// use a faster divider or misses it (it then warns and schedules longer,
// UG1399 "pragma HLS latency"). A new ray every clock either way.
constexpr int ray_setup_depth = 13;
constexpr int perspective_ray_setup_depth = ray_setup_depth + rsqrt_depth;

// §1, perspective camera: direction, rsqrt unit, step vector, clip.
template <class P>
RaySetup<P> ray_setup_perspective(
    const GeometryRegisters<P>& r,
    const typename GeometryParams<P>::y_t seed[GeometryParams<P>::seed_entries], int px, int py) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = perspective_ray_setup_depth
                         max = perspective_ray_setup_depth)
  using G = GeometryParams<P>;
  const typename G::pixel_t x = px;
  const typename G::pixel_t y = py;
  typename G::dir_t d[3];
  typename G::unit_t u[3];
  typename G::step_t s[3];
  typename G::origin_t o[3];
  pixel_direction<P>(r, x, y, d);
  normalize_direction<P>(d, seed, u);
  step_vector<P>(r, u, s);
  pixel_origin<P>(r, x, y, o);  // in parallel with the rsqrt unit: no added depth
  return clip_ray<P>(r, o, s, pixel_jitter<P>(r, px, py));
}

// §1, parallel camera: no rsqrt unit (u = U).
template <class P>
RaySetup<P> ray_setup_parallel(const GeometryRegisters<P>& r, int px, int py) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = ray_setup_depth max = ray_setup_depth)
  using G = GeometryParams<P>;
  const typename G::pixel_t x = px;
  const typename G::pixel_t y = py;
  typename G::unit_t u[3];
  typename G::step_t s[3];
  typename G::origin_t o[3];
  [[gnu::unused]] unit_copy_loop : for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    u[k] = r.U[k];
  }
  step_vector<P>(r, u, s);
  pixel_origin<P>(r, x, y, o);
  return clip_ray<P>(r, o, s, pixel_jitter<P>(r, px, py));
}

// §1, either camera (the register file says which).
template <class P>
RaySetup<P> ray_setup(const GeometryRegisters<P>& r,
                      const typename GeometryParams<P>::y_t seed[GeometryParams<P>::seed_entries],
                      int px, int py) {
  if (r.perspective) return ray_setup_perspective<P>(r, seed, px, py);
  return ray_setup_parallel<P>(r, px, py);
}

// Stepping (§2): one adder per axis, one clock. With the address generator's
// clock (interpolation_processor.hpp) it is the cycle model's `address` stage.
constexpr int stepping_depth = 1;

// §2: p += s (exact in pf bits).
template <class P>
VOXCAST_HLS_HOST_INLINE void step_position(typename GeometryParams<P>::pos_t p[3],
                                           const typename GeometryParams<P>::step_t s[3]) {
  VOXCAST_HLS_PRAGMA(HLS LATENCY min = stepping_depth max = stepping_depth)
  [[gnu::unused]] advance_loop : VOXCAST_HLS_HOST_UNROLL for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    p[k] += s[k];
  }
}

// ---- 4. Host side: register and ROM loading (not synthesized) ------------------------------
#if VOXCAST_HLS_HOST_CODE
namespace host {

// A fixed or integer type holding the raw two's-complement integer `raw` (its low W bits).
template <class T>
T from_raw_bits(std::int64_t raw) {
  T x;
  write_bits(x, T::width - 1, 0, static_cast<std::uint64_t>(raw));
  return x;
}

template <class P>
GeometryRegisters<P> load_geometry_registers(const bittrue::FrameRegisters& f) {
  using G = GeometryParams<P>;
  GeometryRegisters<P> r;
  r.perspective = f.perspective;
  r.jitter = f.jitter;
  [[gnu::unused]] register_loop : for (int k = 0; k < 3; ++k) {
    const auto i = static_cast<std::size_t>(k);
    r.A[k] = from_raw_bits<typename G::dir_t>(f.A[i]);
    r.B[k] = from_raw_bits<typename G::dir_t>(f.B[i]);
    r.C[k] = from_raw_bits<typename G::dir_t>(f.C[i]);
    r.O[k] = from_raw_bits<typename G::origin_t>(f.O[i]);
    r.Pcol[k] = from_raw_bits<typename G::origin_t>(f.P[i]);
    r.Rrow[k] = from_raw_bits<typename G::origin_t>(f.R[i]);
    r.U[k] = from_raw_bits<typename G::dir_t>(f.U[i]);
    r.K[k] = from_raw_bits<typename G::kreg_t>(f.K[i]);
    r.LO[k] = from_raw_bits<typename G::box_t>(f.LO[i]);
    r.HI[k] = from_raw_bits<typename G::box_t>(f.HI[i]);
    r.dims[k] = from_raw_bits<typename G::dim_t>(f.dims[i]);
    r.LAST[k] = from_raw_bits<typename G::coord_t>(f.dims[i] - 1);
  }
  r.HX = from_raw_bits<typename G::half_t>((f.dims[0] + 1) / 2);
  r.HXY =
      from_raw_bits<typename G::slice_t>(std::int64_t{(f.dims[0] + 1) / 2} * ((f.dims[1] + 1) / 2));
  return r;
}

template <class P>
void load_rsqrt_rom(const std::vector<bittrue::Raw>& seed, RsqrtRom<P>& rom) {
  using G = GeometryParams<P>;
  [[gnu::unused]] rom_loop : for (int i = 0; i < G::seed_entries; ++i) rom.seed[i] =
      from_raw_bits<typename G::y_t>(seed[static_cast<std::size_t>(i)]);
}

}  // namespace host
#endif

}  // namespace hls
}  // namespace voxcast
