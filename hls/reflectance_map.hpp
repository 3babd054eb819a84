// Reflectance-map unit: table-based Phong shading, VIZARD II section 2.1 (the
// diffuse and specular intensities for lights and viewer at infinity are
// "stored in tables which only need to be computed when the illumination
// parameters change"). The datapath is docs/pipeline.md §5; its float twin is
// ref::surface_normal + ref::reflectance.
//
// Layout of this header:
//   1. ReflectanceParams<P>: every width and type of the unit, derived from P.
//   2. The synthesizable unit: the IS registers, the two tables, rm_cell() (the
//      cube-map cell of a gradient, §5.1-5.3) and reflect() (the two reads).
//   3. host:: — loading the tables (bittrue::make_reflectance_maps, §5.4) and the
//      registers. Not synthesized.
#pragma once

#include <bit>
#include <cstdint>

#include "hls/pragma.hpp"
#include "hls/types.hpp"
#include "refmodel/precision/profile.hpp"

#ifndef __SYNTHESIS__
#include <vector>

#include "refmodel/bittrue/frame_setup.hpp"
#endif


namespace voxcast::hls {

namespace rm_detail {
// Bits of an unsigned integer that holds every value 0..n (n >= 0; at least 1).
constexpr int bits_for(long long n) {
  return n < 1 ? 1 : static_cast<int>(std::bit_width(static_cast<unsigned long long>(n)));
}
}  // namespace rm_detail

// ---- 1. Parameters ------------------------------------------------------------------------
template <PrecisionProfile P>
struct ReflectanceParams {
  static constexpr int res = P.rm_res;  // cells per cube-face edge
  static constexpr int cells = 6 * res * res;
  static constexpr int sf = P.sample_frac_bits;
  static constexpr int df = P.dir_frac_bits;

  // Interpolated gradient component (§3.5), the interpolation unit's format: the
  // stored field has gradient_bits - gradient_frac_bits integer bits (sign
  // included); one more when sf < gradient_frac_bits, where rounding to sf bits can
  // carry the largest stored value up to 2^(gradient_bits - gradient_frac_bits - 1).
  static constexpr int grad_int_bits =
      P.gradient_bits - P.gradient_frac_bits + (sf < P.gradient_frac_bits ? 1 : 0);
  using gradient_t = fixed<grad_int_bits + sf, grad_int_bits>;
  // IS[a] = Q_RND(1/world_scale[a], df) <= 1 (§5.1).
  using scale_t = ufixed<df + 1, 1>;
  // gw = Q_RND(g · IS, sf): |gw| <= |g| (IS <= 1, g on the sf grid), so g's format holds it.
  using world_gradient_t = fixed<grad_int_bits + sf, grad_int_bits, RND>;
  // N = -gw needs one integer bit more; |N| <= 2^(grad_int_bits - 1) fits unsigned.
  using normal_t = fixed<grad_int_bits + 1 + sf, grad_int_bits + 1>;
  using magnitude_t = ufixed<grad_int_bits + sf, grad_int_bits>;
  // N[a] + |N[m]| in [0, 2 |N[m]|].
  using offset_t = ufixed<grad_int_bits + 1 + sf, grad_int_bits + 1>;

  // §5.3's integer division on raw values (units of 2^-sf):
  // numerator (N[a] + |N[m]|) · res, denominator 2 |N[m]|.
  static constexpr int res_bits = rm_detail::bits_for(res);
  static constexpr int den_bits = grad_int_bits + 1 + sf;
  static constexpr int num_bits = den_bits + res_bits;
  using den_t = uint_t<den_bits>;
  using num_t = uint_t<num_bits>;
  static constexpr int cell_bits = rm_detail::bits_for(res - 1);
  using cell_t = uint_t<cell_bits>;  // iu, iv
  static constexpr int index_bits = rm_detail::bits_for(cells - 1);
  using index_t = uint_t<index_bits>;

  // Table entries (§5.4): rm_int_bits.rm_frac_bits unsigned.
  static constexpr int entry_bits = P.rm_int_bits + P.rm_frac_bits;
  using entry_t = ufixed<entry_bits, P.rm_int_bits>;

  // g · IS is the widest product: (grad_int_bits + sf) + (df + 1) bits.
  static_assert(grad_int_bits + sf + df + 1 <= 64, "gradient x IS product exceeds 64 bits");
  static_assert(num_bits <= 64, "cube-map division exceeds 64 bits");
  static_assert(res >= 1 && res <= 256, "rm_res out of range");
};

// ---- 2. The unit ----------------------------------------------------------------------------

// The per-frame registers of the unit (§0): 1/world_scale per axis.
template <PrecisionProfile P>
struct ReflectanceRegisters {
  typename ReflectanceParams<P>::scale_t IS[3];
};

// Diffuse and specular tables, 6 rm_res^2 entries each, indexed
// face·rm_res² + iv·rm_res + iu (§5.3). Two independent memories, both read in
// the same cycle: the top-level kernel binds each to its own single-port RAM
// (`#pragma HLS BIND_STORAGE variable=<map>.diffuse type=ram_1p impl=bram`, and
// likewise .specular), written by the host only between frames.
template <PrecisionProfile P>
struct ReflectanceMap {
  typename ReflectanceParams<P>::entry_t diffuse[ReflectanceParams<P>::cells];
  typename ReflectanceParams<P>::entry_t specular[ReflectanceParams<P>::cells];
};

// The cube-map cell of a gradient; valid = false when N = 0 (§5.2).
template <PrecisionProfile P>
struct RmCell {
  bool valid;
  typename ReflectanceParams<P>::index_t index;
};

// The unit's result: D and S of §5 (both 0 without a normal).
template <PrecisionProfile P>
struct Reflect {
  typename ReflectanceParams<P>::entry_t D, S;
};

// §5.1-5.3: world scaling, N = -gw, zero test, major axis, the two exact
// integer divisions and the cell index.
template <PrecisionProfile P>
RmCell<P> rm_cell(const typename ReflectanceParams<P>::gradient_t (&g)[3],
                  const ReflectanceRegisters<P>& regs) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using Params = ReflectanceParams<P>;
  using normal_t = typename Params::normal_t;
  using magnitude_t = typename Params::magnitude_t;

  // §5.1: gw = Q_RND(g · IS, sf) (exact product, one rounding), N = -gw, |N|.
  normal_t n[3];
  magnitude_t mag[3];
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = n complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = mag complete)
  [[maybe_unused]] rm_world_scale : for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const typename Params::world_gradient_t gw = g[k] * regs.IS[k];
    n[k] = -gw;
    mag[k] = n[k].is_neg() ? magnitude_t(gw) : magnitude_t(n[k]);
  }

  // §5.3: major axis, ties to the lower axis; the other two axes a < b.
  int m = 0;
  if (mag[1] > mag[0]) m = 1;
  if (mag[2] > mag[m]) m = 2;
  const int a = m == 0 ? 1 : 0;
  const int b = m == 2 ? 1 : 2;

  // §5.2: N = 0 exactly when its largest magnitude is 0.
  const bool valid = !(mag[m] == 0);

  // §5.3: iu = min(floor((N[a] + |N[m]|)·res / (2|N[m]|)), res - 1), iv likewise,
  // on the raw integers (both operands in units of 2^-sf).
  typename Params::den_t den = mag[m].range().to_uint64();
  den = den << 1;
  if (!valid) den = 1;  // no division by zero; the index is unused then
  const typename Params::num_t last = Params::res - 1;
  typename Params::cell_t cell[2];
  const int uv_axis[2] = {a, b};
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = cell complete)
  [[maybe_unused]] rm_cell_divide : for (int j = 0; j < 2; ++j) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const typename Params::offset_t off = n[uv_axis[j]] + mag[m];
    const typename Params::den_t off_raw = off.range().to_uint64();
    const typename Params::num_t num = off_raw * uint_t<Params::res_bits>(Params::res);
    const typename Params::num_t q = num / den;
    cell[j] = q > last ? last : q;
  }

  // Face 2m + (N[m] < 0); index face·res² + iv·res + iu.
  const typename Params::index_t face = 2 * m + (n[m].is_neg() ? 1 : 0);
  RmCell<P> out;
  out.valid = valid;
  out.index = face * typename Params::index_t(Params::res * Params::res) +
              cell[1] * typename Params::index_t(Params::res) + cell[0];
  return out;
}

// §5: the two table reads (D = S = 0 without a normal). G is the interpolation
// unit's gradient component type; it converts exactly into gradient_t when it has
// sample_frac_bits fraction bits (checked below) and fits.
template <PrecisionProfile P, class G>
Reflect<P> reflect(const ReflectanceMap<P>& map, const ReflectanceRegisters<P>& regs,
                   const G (&g)[3]) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using Params = ReflectanceParams<P>;
  static_assert(G::width - G::iwidth == Params::sf,
                "the gradient must have sample_frac_bits fraction bits");
  const typename Params::gradient_t gc[3] = {g[0], g[1], g[2]};
  const RmCell<P> cell = rm_cell<P>(gc, regs);
  Reflect<P> r;
  r.D = 0;
  r.S = 0;
  if (cell.valid) {
    r.D = map.diffuse[cell.index.to_uint()];
    r.S = map.specular[cell.index.to_uint()];
  }
  return r;
}

// ---- 3. Host side (not synthesized) -------------------------------------------------------
#ifndef __SYNTHESIS__
namespace host {

// Loads both tables from bittrue::make_reflectance_maps' raw integers. Returns
// false (tables unchanged) if a size does not match.
template <PrecisionProfile P>
bool load_reflectance_map(ReflectanceMap<P>& map, const std::vector<std::uint32_t>& diffuse,
                          const std::vector<std::uint32_t>& specular) {
  constexpr int n = ReflectanceParams<P>::cells;
  if (diffuse.size() != static_cast<std::size_t>(n) ||
      specular.size() != static_cast<std::size_t>(n))
    return false;
  [[maybe_unused]] load_rm_entries : for (int i = 0; i < n; ++i) {
    map.diffuse[i].range() = std::uint64_t{diffuse[static_cast<std::size_t>(i)]};
    map.specular[i].range() = std::uint64_t{specular[static_cast<std::size_t>(i)]};
  }
  return true;
}

// The IS registers from the frame's raw register values (dir_frac_bits).
template <PrecisionProfile P>
ReflectanceRegisters<P> reflectance_registers(const bittrue::FrameRegisters& regs) {
  ReflectanceRegisters<P> r;
  [[maybe_unused]] load_is_registers : for (int k = 0; k < 3; ++k) {
    r.IS[k].range() = static_cast<std::uint64_t>(regs.IS[static_cast<std::size_t>(k)]);
  }
  return r;
}

}  // namespace host
#endif
}  // namespace voxcast::hls
