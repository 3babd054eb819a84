// Compositor: front-to-back "over" with early ray termination (VIZARD II
// section 2.1), maximum intensity projection, and the output quantisation. The
// datapath is docs/pipeline.md §7-8; its float twins are ref::composite,
// ref::opacity_correct (baked into the classification table) and the ERT / MIP
// branches of ref::cast_ray.
//
// Layout of this header:
//   1. CompositorParams<P>: every width and type of the unit, derived from P.
//   2. The synthesizable unit: the accumulator state, composite() (§7.1-7.2),
//      ert_reached() (§7.3), the MIP max and grey (§7), and output() (§8).
//   3. host:: — the unit's registers from the frame set-up. Not synthesized.
#pragma once

#include <cstdint>

#include "hls/classification_table.hpp"
#include "hls/shader.hpp"
#include "hls/pragma.hpp"
#include "hls/types.hpp"
#include "hls/widths.hpp"

#if VOXCAST_HLS_HOST_CODE
#include <ostream>

#include "refmodel/bittrue/frame_setup.hpp"
#endif


namespace voxcast {
namespace hls {

// ---- 1. Parameters ------------------------------------------------------------------------
// The widths are hls/widths.hpp's functions of the profile.
template <class P>
struct CompositorParams {
  static constexpr int acc_bits = P::acc_bits;
  static constexpr int out_bits = P::out_bits;
  // C[3] and A: acc_bits fraction bits, one integer bit, in [0, 1] (§7).
  static constexpr int acc_word_bits = widths::acc_word_bits(profile_fields<P>());
  using acc_t = ufixed<acc_word_bits, 1>;
  // w = Q_RND((1 - A)·alpha_c, acc_bits) and Q_RND(w·c, acc_bits), both in [0, 1].
  using weight_t = ufixed<acc_word_bits, 1, RND>;
  using alpha_t = typename ClassificationParams<P>::alpha_t;
  using shade_t = typename ShaderParams<P>::shade_t;
  // MIP: the interpolated value (vb.sf), the RM register Q_RND(1/max_stored, df) <= 1, and
  // Q_RND(M·RM, acc_bits) before its clamp to 1 (M·RM < 2^vb as RM <= 1).
  using value_t = typename ClassificationParams<P>::value_t;
  using rm_t = ufixed<widths::mip_scale_bits(profile_fields<P>()), 1>;
  using grey_t = ufixed<widths::grey_bits(profile_fields<P>()),
                        widths::grey_int_bits(profile_fields<P>()), RND>;
  // §8: Q_RND(x·(2^out_bits - 1), 0) of x in [0, 1] (the SAT never acts, x <= 1).
  using out_round_t = ufixed<out_bits, out_bits, RND, SAT>;
  using out_t = uint_t<out_bits>;
  static constexpr unsigned out_max = widths::out_max(profile_fields<P>());

  // The widest products: (1 - A)·alpha_c, w·c, M·RM, x·(2^out_bits - 1).
  static_assert(acc_bits + 1 + P::alpha_bits <= 64, "(1 - A) x alpha exceeds 64 bits");
  static_assert(acc_bits + 1 + P::shade_bits <= 64, "w x c exceeds 64 bits");
  static_assert(P::value_bits + P::sample_frac_bits + P::dir_frac_bits + 1 <= 64,
                "M x RM exceeds 64 bits");
  static_assert(out_bits >= 1 && out_bits <= 16, "out_bits out of range");
};

// Pipeline depths (clocks; see hls/geometry_processor.hpp, "Pipeline depths").
// §7.1-7.2 the over operator is a one-clock recurrence: the next sample of the
// same ray reads the A it writes. §7.3 the ERT comparator tests the new A in
// that clock. §7 MIP: the maximum register, one clock. §8 the output
// quantization, one clock. These functions are inlined (HLS INLINE), and Vitis
// ignores an inlined function's pragmas (UG1399, "Inline"): no LATENCY pragmas.
constexpr int compositor_depth = 1;
constexpr int ert_depth = 0;
constexpr int mip_depth = 1;
constexpr int output_quantization_depth = 1;

// ---- 2. The unit ----------------------------------------------------------------------------

// The per-frame registers of the unit (§0, §7).
template <class P>
struct CompositorRegisters {
  bool ert_enabled = false;                               // threshold below 1
  typename CompositorParams<P>::acc_t ert_threshold = 0;  // Q_RND(threshold, acc_bits)
  typename CompositorParams<P>::rm_t RM = 0;              // Q_RND(1/max_stored, df)
};

// The accumulator state of one ray: premultiplied colour and opacity, both 0 at
// the ray's start. Registers: the top-level kernel partitions C completely.
template <class P>
struct Accumulator {
  using acc_t = typename CompositorParams<P>::acc_t;
  acc_t C[3] = {acc_t(0), acc_t(0), acc_t(0)};
  acc_t A = 0;
};

// §7.1-7.2: one front-to-back step,
//   w = Q_RND((1 - A)·alpha_c, acc_bits),
//   C[k] = SAT(C[k] + Q_RND(w·c[k], acc_bits), 0, 1),  A = SAT(A + w, 0, 1).
// A sample with alpha_c = 0 is skipped: returns false, state unchanged, and the
// caller must not test ERT after it (§7).
template <class P>
VOXCAST_HLS_HOST_INLINE bool composite(Accumulator<P>& acc, const ShadedColor<P>& c,
                                       const typename CompositorParams<P>::alpha_t& alpha_c) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using Params = CompositorParams<P>;
  using acc_t = typename Params::acc_t;
  using weight_t = typename Params::weight_t;
  if (alpha_c == 0) return false;
  const acc_t one = 1;
  const acc_t transparency = one - acc.A;  // exact: A <= 1
  const weight_t w = transparency * alpha_c;
  [[gnu::unused]] composite_channels : VOXCAST_HLS_HOST_UNROLL for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const weight_t contribution = w * c.c[k];
    const auto sum = acc.C[k] + contribution;
    acc.C[k] = sum > one ? one : acc_t(sum);
  }
  const auto sum_a = acc.A + w;
  acc.A = sum_a > one ? one : acc_t(sum_a);
  return true;
}

// §7.3: early ray termination after a composited sample.
template <class P>
VOXCAST_HLS_HOST_INLINE bool ert_reached(const Accumulator<P>& acc,
                                         const CompositorRegisters<P>& regs) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  return regs.ert_enabled && acc.A >= regs.ert_threshold;
}

// §7 MIP: M = max_j value_j (M starts at 0).
template <class P>
VOXCAST_HLS_HOST_INLINE void mip_update(typename CompositorParams<P>::value_t& M,
                                        const typename CompositorParams<P>::value_t& value) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  if (value > M) M = value;
}

// §7 MIP: grey = SAT(Q_RND(M·RM, acc_bits), 0, 1); the pixel is (grey, grey, grey, 1).
template <class P>
Accumulator<P> mip_pixel(const typename CompositorParams<P>::value_t& M,
                         const CompositorRegisters<P>& regs) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using Params = CompositorParams<P>;
  using acc_t = typename Params::acc_t;
  const acc_t one = 1;
  const typename Params::grey_t grey = M * regs.RM;
  const acc_t g = grey > one ? one : acc_t(grey);
  Accumulator<P> px;
  px.C[0] = g;
  px.C[1] = g;
  px.C[2] = g;
  px.A = one;
  return px;
}

// §8: one channel, out = Q_RND(x·(2^out_bits - 1), 0).
template <class P>
typename CompositorParams<P>::out_t quantize_output(const typename CompositorParams<P>::acc_t& x) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using Params = CompositorParams<P>;
  const typename Params::out_round_t q = x * uint_t<Params::out_bits>(Params::out_max);
  return int_cast<typename Params::out_t>(q);
}

// §8: the pixel (r, g, b, alpha) of a finished ray. A miss is (0, 0, 0, 0), the
// output of a fresh Accumulator.
template <class P>
struct OutputPixel {
  typename CompositorParams<P>::out_t ch[4];
};

template <class P>
OutputPixel<P> output(const Accumulator<P>& acc) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  OutputPixel<P> px;
  [[gnu::unused]] output_channels : VOXCAST_HLS_HOST_UNROLL for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    px.ch[k] = quantize_output<P>(acc.C[k]);
  }
  px.ch[3] = quantize_output<P>(acc.A);
  return px;
}

#if VOXCAST_HLS_HOST_CODE
template <class P>
std::ostream& operator<<(std::ostream& os, const Accumulator<P>& acc) {
  return os << "Accumulator{C=(" << acc.C[0].to_double() << ", " << acc.C[1].to_double() << ", "
            << acc.C[2].to_double() << "), A=" << acc.A.to_double() << "}";
}
#endif

// ---- 3. Host side (not synthesized) -------------------------------------------------------
#if VOXCAST_HLS_HOST_CODE
namespace host {

template <class P>
CompositorRegisters<P> compositor_registers(const bittrue::FrameRegisters& regs) {
  CompositorRegisters<P> r;
  r.ert_enabled = regs.ert_enabled;
  write_bits(r.ert_threshold, static_cast<std::uint64_t>(regs.ert_threshold));
  write_bits(r.RM, static_cast<std::uint64_t>(regs.RM));
  return r;
}

}  // namespace host
#endif
}  // namespace hls
}  // namespace voxcast
