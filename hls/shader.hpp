// Shader: the classified colour times the Phong intensity from the reflectance
// map, VIZARD II section 2.1 ("intensities multiplied with the material
// properties and with the color of the classified sample"). The datapath is
// docs/pipeline.md §6; its float twin is ref::shade.
#pragma once

#include "hls/classification_table.hpp"
#include "hls/reflectance_map.hpp"
#include "hls/pragma.hpp"
#include "hls/types.hpp"
#include "hls/widths.hpp"


namespace voxcast {
namespace hls {

// The widths are hls/widths.hpp's functions of the profile (intensity_*).
template <class P>
struct ShaderParams {
  static constexpr int shade_bits = P::shade_bits;
  // ka + kd·D + ks·S: its integer bits and the exact sum's width.
  static constexpr int intensity_int_bits = widths::intensity_int_bits(profile_fields<P>());
  static constexpr int sum_bits = widths::intensity_sum_bits(profile_fields<P>());
  // I = Q_RND(·, shade_bits) (§6).
  using intensity_t =
      ufixed<widths::intensity_bits(profile_fields<P>()), intensity_int_bits, RND>;
  // c = U(·, shade_bits): one conversion rounds and saturates at 1 - 2^-shade_bits.
  using shade_t = ufixed<shade_bits, 0, RND, SAT>;
  // colour · I, the widest product of the unit.
  static constexpr int product_bits = widths::shade_product_bits(profile_fields<P>());

  static_assert(sum_bits <= 64 && product_bits <= 64, "shader products exceed 64 bits");
};

// Pipeline depth (clocks; see hls/geometry_processor.hpp, "Pipeline depths"):
// one clock, shaded (the intensity products kd·D, ks·S and colour·I, the sums and
// the roundings: the cycle model's assumption) or unshaded (U(colour,
// shade_bits), one rounding adder); with the reflectance map's clocks the cycle
// model's `shading` stage. shade() is inlined (HLS INLINE), and Vitis ignores an
// inlined function's pragmas (UG1399, "Inline"): no LATENCY pragma here.
constexpr int shader_depth = 1;

// The shaded colour of one sample.
template <class P>
struct ShadedColor {
  typename ShaderParams<P>::shade_t c[3];
};

// §6: I = Q_RND(ka·1 + kd·D + ks·S, shade_bits); c = U(colour · I, shade_bits) per
// channel. Unshaded (emission-absorption) mode: c = U(colour, shade_bits).
template <class P>
VOXCAST_HLS_HOST_INLINE ShadedColor<P> shade(const ClassEntry<P>& e, const Reflect<P>& r,
                                             bool shaded) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using Params = ShaderParams<P>;
  const typename Params::intensity_t intensity = e.ka + e.kd * r.D + e.ks * r.S;
  const typename ClassificationParams<P>::color_t colour[3] = {e.r, e.g, e.b};
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = colour complete)
  ShadedColor<P> out;
  [[gnu::unused]] shade_channels : VOXCAST_HLS_HOST_UNROLL for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    if (shaded) {
      out.c[k] = colour[k] * intensity;
    } else {
      out.c[k] = colour[k];
    }
  }
  return out;
}

}  // namespace hls
}  // namespace voxcast
