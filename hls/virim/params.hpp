// VIRIM's fixed-point datapath: every width and type of the rotator and the
// slice processor, derived from a Heidelberg profile as a traits type (VirimTraits,
// refmodel/precision/profile_traits.hpp) (docs/heidelberg.md §7).
// One struct read by every unit in hls/virim/, so their widths cannot drift.
#pragma once

#include "hls/types.hpp"

namespace voxcast {
namespace hls {
namespace virim {

template <class HP>
struct VirimParams {
  static constexpr int a = HP::addr_bits;
  static constexpr int vbits = HP::view_bits;
  static constexpr int cf = HP::coord_frac_bits;
  static constexpr int vb = HP::value_bits;
  static constexpr int wb = HP::weight_bits;
  static constexpr int wf = HP::weight_frac_bits;
  static constexpr int db = HP::density_bits;
  static constexpr int gb = HP::gradient_bits;
  static constexpr int lf = HP::light_frac_bits;
  static constexpr int cof = HP::cos_frac_bits;
  static constexpr int uw = HP::user_weight_bits;
  static constexpr int ob = HP::out_bits;
  static constexpr int max_view = 1 << vbits;
  static constexpr int rom_entries = 1 << (3 * wb);
  static constexpr int lut_entries = 1 << vb;
  static constexpr int bus_bits = db + 2 * gb;  // VIRIM: 48 (section "Rotator Board")
  static constexpr int fade_log2 = 6;  // Phong terms fade in below |g| = 2^-6 (docs/heidelberg.md §5.3)

  static_assert(vb <= 16, "gray values are held in 16-bit RAM words");
  static_assert(wb <= cf, "the weight address is the position rounded to wb fraction bits");
  static_assert(cof <= gb, "the surface probability is a bit select of |g|");
  static_assert(2 * gb + 1 <= 63, "|g|^2 must fit the 64-bit square root");

  // §7.1 geometry: view offsets i - (W-1)/2 (one fraction bit, |.| < 2^vbits),
  // plane scales s_j in (0, 2), M = R^T/zoom with |M| <= 16, base and positions
  // within ±2^(a+2) (saturating: far outside stays outside).
  using view_t = int_t<vbits + 2>;
  using offset_t = fixed<vbits + 3, vbits + 2>;
  using scale_t = ufixed<cf + 2, 2>;
  using matrix_t = fixed<cf + 6, 6>;
  using pos_t = fixed<a + 3 + cf, a + 3, TRN, SAT>;
  using floor_t = fixed<a + 3, a + 3, TRN, SAT>;  // floor(p)
  using rom_pos_t = fixed<a + 3 + wb, a + 3, RND, SAT>;  // p on the ROM's grid
  using coord_t = int_t<a + 4>;
  using box_t = int_t<a + 4>;
  using half_t = uint_t<a + 1>;        // hy = ceil(Ny/2), hx2 = ceil(Nx/4)
  using word_addr_t = uint_t<3 * a>;   // address within one bank
  // §7.3 interpolation: LUT densities and ROM weights (the 8 sum to 1 exactly).
  using density_t = ufixed<db, 0>;
  using weight_t = ufixed<wf + 1, 1>;
  // §7.4 gradients: Sobel/8 of densities in [0, 1) lies in (-1/2, 1/2).
  using grad_t = fixed<gb, 0>;
  using mag2_t = ufixed<2 * gb, 0>;  // gx^2 + gy^2 < 1/2
  using mag_t = ufixed<gb, 0>;       // floor(|g|) < 0.71
  using bus_t = uint_t<bus_bits>;
  // §7.5 slice processor.
  using cos_t = fixed<cof + 2, 2, TRN_ZERO>;  // cosines, clamped to [-1, 1]
  using ucos_t = ufixed<cof + 1, 1>;          // [0, 1]: rv+, spec, surface, r0
  using refl_t = ufixed<cof + 2, 2>;          // r45 <= 2
  using light_t = ufixed<lf + 1, 1>;          // L, T0, T45, I, E in [0, 1]
  using energy_t = ufixed<lf + 2, 2>;         // E0 + E45 and e, <= 2
  using acc_t = ufixed<lf + 2, 2, TRN, SAT>;  // < 2 (docs/heidelberg.md §7.5)
  using uweight_t = ufixed<uw + 1, 1>;        // user weights in [0, 1]
  using level_t = ufixed<ob + 2, ob + 2, RND>;
};

}  // namespace virim
}  // namespace hls
}  // namespace voxcast
