// VIRIM's slice processor: the Heidelberg Raytracing Model on one constant-z
// plane in fixed point (the DSP board's job in VIRIM; docs/heidelberg.md §5 for
// the model, §7.5 for the rounding points). Its double twin is
// ref::heidelberg::trace_slice, its bit-true twin bittrue::bt_slice_voxel.
#pragma once

#include <cstdint>

#include "hls/pragma.hpp"
#include "hls/virim/gradient_processor.hpp"
#include "hls/virim/params.hpp"

namespace voxcast {
namespace hls {
namespace virim {

template <class HP>
struct SliceRegisters {
  using V = VirimParams<HP>;
  typename V::light_t light;       // L
  typename V::uweight_t wd0, wd45, ws45, wlum;
  typename V::light_t threshold;   // background identification
  typename V::ucos_t inv_sqrt2;    // RND(1/√2, cof)
  int shininess;                   // 1..127
};

template <class HP>
struct Phong {
  typename VirimParams<HP>::cos_t c0, c45;
  typename VirimParams<HP>::ucos_t d0, d45;  // max(0, c) x fade
  typename VirimParams<HP>::ucos_t spec;     // max(0, R·V)^n x surface probability x fade
};

// floor(sqrt(n)) for n < 2^(2N), bit by bit.
template <int N>
std::uint64_t isqrt(std::uint64_t n) {
  std::uint64_t r = 0;
  [[gnu::unused]] isqrt_loop : for (int b = N - 1; b >= 0; --b) {
    const std::uint64_t t = r | (std::uint64_t{1} << b);
    if (t * t <= n) r = t;
  }
  return r;
}

template <class HP>
Phong<HP> phong(const SliceRegisters<HP>& r, const typename VirimParams<HP>::grad_t& gx,
                const typename VirimParams<HP>::grad_t& gy) {
  using V = VirimParams<HP>;
  using ucos_t = typename V::ucos_t;
  const typename V::mag2_t m2 = gx * gx + gy * gy;  // exact
  typename V::mag_t m;
  write_bits(m, V::gb - 1, 0, isqrt<V::gb>(read_bits(m2, 2 * V::gb - 1, 0)));
  ucos_t surface = m * 2;  // TRN to cof bits
  if (surface > 1) surface = 1;
  // The Phong terms fade in below |g| = 2^-fade_log2 (ref::heidelberg::kNormalFade).
  const ufixed<V::cof + V::fade_log2 + 1, V::fade_log2 + 1> wide_fade = m * (1 << V::fade_log2);
  const ucos_t fade = wide_fade > 1 ? ucos_t(1) : ucos_t(wide_fade);
  Phong<HP> ph;
  ph.c0 = 0;
  ph.c45 = 0;
  ph.d0 = 0;
  ph.d45 = 0;
  ph.spec = 0;
  if (m == 0) return ph;
  // Quotients truncated toward zero (ap '/'), then TRN_ZERO to cof bits; |.| < 2
  // because m = floor(|g|) is at least |g| - 1 LSB (§7.5), then clamped.
  using quot_t = fixed<V::cof + 4, 4, TRN_ZERO>;
  quot_t q0 = gy / m;
  quot_t q45 = ((gx + gy) * r.inv_sqrt2) / m;
  q0 = q0 > 1 ? quot_t(1) : (q0 < -1 ? quot_t(-1) : q0);
  q45 = q45 > 1 ? quot_t(1) : (q45 < -1 ? quot_t(-1) : q45);
  ph.c0 = q0;
  ph.c45 = q45;
  // R·V = 2 c45 c0 - 1/√2, kept in [0, 1].
  fixed<V::cof + 4, 4> rv = ph.c45 * ph.c0 * 2;  // TRN to cof bits
  rv = rv - r.inv_sqrt2;
  ucos_t base = rv < 0 ? fixed<V::cof + 4, 4>(0) : (rv > 1 ? fixed<V::cof + 4, 4>(1) : rv);
  ucos_t result = 1;
  [[gnu::unused]] power_loop : for (int b = 0; b < 7; ++b) {  // square and multiply, n < 128
    if ((r.shininess >> b) & 1) result = result * base;
    base = base * base;
  }
  const ucos_t spec = result * surface;
  ph.spec = spec * fade;
  const ucos_t p0 = ph.c0 < 0 ? typename V::cos_t(0) : ph.c0;
  const ucos_t p45 = ph.c45 < 0 ? typename V::cos_t(0) : ph.c45;
  ph.d0 = p0 * fade;
  ph.d45 = p45 * fade;
  return ph;
}

// One voxel of the model: the energy each light deposits (I rho), what the
// voxel scatters towards the viewer (bounded by it), the way back (T0), and
// the attenuation of both lights. Returns the 45 deg light leaving the voxel.
template <class HP>
typename VirimParams<HP>::light_t slice_voxel(const SliceRegisters<HP>& r, const BusWord<HP>& w,
                                              const typename VirimParams<HP>::light_t& t45,
                                              typename VirimParams<HP>::light_t& t0,
                                              typename VirimParams<HP>::acc_t& acc) {
  using V = VirimParams<HP>;
  using light_t = typename V::light_t;
  using ucos_t = typename V::ucos_t;
  const Phong<HP> ph = phong<HP>(r, w.gx, w.gy);
  const light_t i0 = r.light * t0, i45 = r.light * t45;
  const light_t e0 = i0 * w.density, e45 = i45 * w.density;
  const ucos_t r0 = r.wd0 * ph.d0;
  const typename V::refl_t r45 = r.wd45 * ph.d45 + r.ws45 * ph.spec;
  const typename V::energy_t deposited = e0 + e45;
  const ufixed<V::lf + 3, 2> wide = deposited;
  const ufixed<V::lf + 3, 2> half = wide >> 1;  // exact
  const light_t lum = r.wlum * half;
  const light_t s0 = e0 * r0, s45 = e45 * r45;
  ufixed<V::lf + 3, 3> e = s0 + s45 + lum;  // < 2 E0 + 3 E45 < 8
  if (e > deposited) e = deposited;
  const light_t back = e * t0;
  acc = acc + back;
  const light_t a0 = t0 * w.density, a45 = t45 * w.density;
  t0 = t0 - a0;
  const light_t t45_out = t45 - a45;
  return t45_out;
}

template <class HP>
std::uint32_t output_level(const typename VirimParams<HP>::acc_t& acc) {
  using V = VirimParams<HP>;
  constexpr std::uint32_t full = (1u << V::ob) - 1u;
  const typename V::level_t q = acc * full;  // RND to an integer
  return q > full ? full : static_cast<std::uint32_t>(q.to_uint64());
}

}  // namespace virim
}  // namespace hls
}  // namespace voxcast
