// Reflectance-map unit: table-based Phong shading, VIZARD II section 2.1 (the
// diffuse and specular intensities for lights and viewer at infinity are
// "stored in tables which only need to be computed when the illumination
// parameters change"). The datapath is docs/pipeline.md §5; its float twin is
// ref::surface_normal + ref::reflectance.
//
// Layout of this header:
//   1. ReflectanceParams<P>: every width and type of the unit, derived from P.
//   2. The synthesizable unit: the IS registers, the two tables, rm_cell() (the
//      cube-map cell of a gradient, §5.1-5.3, and with rm_bilinear its in-cell
//      position, §5.5) and reflect() (one read per table, or four and a bilinear
//      blend, §5.5).
//   3. host:: — loading the tables (bittrue::make_reflectance_maps, §5.4 / §5.5)
//      and the registers. Not synthesized.
#pragma once

#include <cstdint>

#include "hls/pragma.hpp"
#include "hls/types.hpp"
#include "hls/units.hpp"
#include "hls/widths.hpp"

#if VOXCAST_HLS_HOST_CODE
#include <vector>

#include "refmodel/bittrue/frame_setup.hpp"
#endif


namespace voxcast {
namespace hls {

// ---- 1. Parameters ------------------------------------------------------------------------
// The widths are hls/widths.hpp's functions of the profile (rm_*).
template <class P>
struct ReflectanceParams {
  static constexpr int res = P::rm_res;  // cells per cube-face edge
  static constexpr int cells = widths::rm_cells(profile_fields<P>());
  // §5.5: rm_bilinear reads the entries at the cell's corners, (res + 1)^2 per face;
  // nearest mode (VIZARD II) one entry per cell.
  static constexpr bool bilinear = widths::rm_bilinear(profile_fields<P>());
  static constexpr int side = widths::rm_side(profile_fields<P>());        // entries per face row
  static constexpr int entries = widths::rm_entries(profile_fields<P>());  // per table
  // Fraction bits of the in-cell position (0 in nearest mode: the division gives the cell).
  static constexpr int wb = widths::rm_pos_frac_bits(profile_fields<P>());
  static constexpr int sf = P::sample_frac_bits;
  static constexpr int df = P::dir_frac_bits;

  // Interpolated gradient component (§3.5), the interpolation unit's format.
  static constexpr int grad_int_bits = widths::sample_grad_int_bits(profile_fields<P>());
  using gradient_t = fixed<widths::sample_grad_bits(profile_fields<P>()), grad_int_bits>;
  // §5.1 IS[a] <= 1.
  using scale_t = ufixed<widths::rm_scale_bits(profile_fields<P>()), 1>;
  // gw = Q_RND(g · IS, sf): |gw| <= |g| (IS <= 1, g on the sf grid), so g's format holds it.
  using world_gradient_t = fixed<widths::sample_grad_bits(profile_fields<P>()), grad_int_bits, RND>;
  // N = -gw, |N|, and N[a] + |N[m]| in [0, 2 |N[m]|].
  static constexpr int normal_int_bits = widths::rm_normal_int_bits(profile_fields<P>());
  using normal_t = fixed<widths::rm_normal_bits(profile_fields<P>()), normal_int_bits>;
  using magnitude_t = ufixed<widths::rm_magnitude_bits(profile_fields<P>()), grad_int_bits>;
  using offset_t = ufixed<widths::rm_normal_bits(profile_fields<P>()), normal_int_bits>;

  // §5.3's (§5.5's) integer division on raw values (units of 2^-sf).
  static constexpr int res_bits = widths::rm_res_bits(profile_fields<P>());
  static constexpr int den_bits = widths::rm_den_bits(profile_fields<P>());
  static constexpr int num_bits = widths::rm_num_bits(profile_fields<P>());
  using den_t = uint_t<den_bits>;
  using num_t = uint_t<num_bits>;
  using pos_t = uint_t<widths::rm_pos_bits(profile_fields<P>())>;  // t
  static constexpr int cell_bits = widths::rm_cell_bits(profile_fields<P>());
  using cell_t = uint_t<cell_bits>;  // iu, iv
  static constexpr int index_bits = widths::rm_index_bits(profile_fields<P>());
  using index_t = uint_t<index_bits>;
  // §5.5: the in-cell position f = t·2^-wb - i in [0, 1].
  using weight_t = ufixed<widths::rm_blend_weight_bits(profile_fields<P>()), 1>;

  // Table entries (§5.4): rm_int_bits.rm_frac_bits unsigned.
  static constexpr int ri = P::rm_int_bits;
  static constexpr int entry_bits = widths::rm_entry_bits(profile_fields<P>());
  using entry_t = ufixed<entry_bits, ri>;
  // §5.5's exact blend, as lerps e0 + (e1 - e0)·f; the result rounds once (RND).
  using lerp1_t = ufixed<widths::rm_lerp_bits(profile_fields<P>(), 1), ri>;
  using lerp2_t = ufixed<widths::rm_lerp_bits(profile_fields<P>(), 2), ri>;
  using entry_rnd_t = ufixed<entry_bits, ri, RND>;

  // g · IS is the widest product: (grad_int_bits + sf) + (df + 1) bits.
  static_assert(grad_int_bits + sf + df + 1 <= 64, "gradient x IS product exceeds 64 bits");
  static_assert(num_bits <= 64, "cube-map division exceeds 64 bits");
  // The blend's widest intermediate, the second lerp's sum: its product (lerp1 difference x
  // weight) has (entry_bits + wb + 1) + (wb + 1) bits, the sum one more.
  static_assert(!bilinear || entry_bits + 2 * wb + 3 <= 64, "bilinear blend exceeds 64 bits");
  static_assert(res >= 1 && res <= 256, "rm_res out of range");
  static_assert(!bilinear || (wb >= 1 && wb <= 12), "rm_weight_bits out of range");
};

// Pipeline depth (clocks; see hls/geometry_processor.hpp, "Pipeline depths"):
// §5.1-5.3 the cell (g·IS, N, the major axis, the two divisions, the index) and
// the table reads (§5.5: with the blend), 3 clocks: the cycle model's assumption
// (like the ray set-up's divisions, the report prices each division as a
// pipelined restoring divider, one stage per quotient bit). reflect() is
// inlined (HLS INLINE), and Vitis ignores an inlined function's pragmas
// (UG1399, "Inline"): no LATENCY pragma until the unit has a hierarchy level of
// its own.
constexpr int reflectance_map_depth = 3;

// ---- 2. The unit ----------------------------------------------------------------------------

// The per-frame registers of the unit (§0): 1/world_scale per axis.
template <class P>
struct ReflectanceRegisters {
  typename ReflectanceParams<P>::scale_t IS[3];
};

// Diffuse and specular tables, `entries` each. Nearest mode: 6 rm_res^2 entries,
// indexed face·rm_res² + iv·rm_res + iu (§5.3). Bilinear mode: 6 (rm_res+1)^2
// corner entries, indexed face·(rm_res+1)² + j·(rm_res+1) + i (§5.5). Two
// independent memories, both read in the same cycle, written by the load phase
// between frames; the synthesized top (hls/vizard2_synth_top.cpp) binds each
// to its own dual-port block RAM.
//
// Bilinear mode reads four entries of each table per sample, k, k+1, k+side and
// k+side+1 (the corners of one cell, k = its (i, j) corner). Split cyclically
// in two halves by the parity of the index, two of the four fall in each half
// whatever side's parity (side even: k, k+side in one, k+1, k+side+1 in the
// other; side odd: k, k+side+1 and k+1, k+side), so two dual-port halves serve
// the four reads in one clock: the top's `ARRAY_PARTITION cyclic factor=2` and
// `BIND_STORAGE ram_2p` (factor 1 in nearest mode, one read per table).
template <class P>
struct ReflectanceMap {
  typename ReflectanceParams<P>::entry_t diffuse[ReflectanceParams<P>::entries];
  typename ReflectanceParams<P>::entry_t specular[ReflectanceParams<P>::entries];
};

// The cube-map cell of a gradient; valid = false when N = 0 (§5.2). Nearest
// mode: index is the entry to read. Bilinear mode: index is the cell's corner
// (i, j), fu and fv its in-cell position (§5.5); 0 in nearest mode.
template <class P>
struct RmCell {
  bool valid;
  typename ReflectanceParams<P>::index_t index;
  typename ReflectanceParams<P>::weight_t fu, fv;
};

// The unit's result: D and S of §5 (both 0 without a normal).
template <class P>
struct Reflect {
  typename ReflectanceParams<P>::entry_t D, S;
};

// §5.1-5.3: world scaling, N = -gw, zero test, major axis, the two exact
// integer divisions and the cell index.
template <class P>
VOXCAST_HLS_HOST_INLINE RmCell<P> rm_cell(const typename ReflectanceParams<P>::gradient_t (&g)[3],
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
  [[gnu::unused]] rm_world_scale : VOXCAST_HLS_HOST_UNROLL for (int k = 0; k < 3; ++k) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const typename Params::world_gradient_t gw = g[k] * regs.IS[k];
    n[k] = -gw;
    mag[k] = (n[k] < 0) ? magnitude_t(gw) : magnitude_t(n[k]);
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
  // on the raw integers (both operands in units of 2^-sf). §5.5 (bilinear): the
  // same division with wb more quotient bits, t = floor(·· 2^wb); the cell is
  // min(t >> wb, res - 1) and the in-cell position f = t - (cell << wb) in units
  // of 2^-wb (f = 2^wb, i.e. 1, only at the clamp).
  typename Params::den_t den = read_bits(mag[m]);
  den = den << 1;
  if (!valid) den = 1;  // no division by zero; the index is unused then
  const typename Params::cell_t last = Params::res - 1;
  typename Params::cell_t cell[2];
  typename Params::weight_t frac[2];
  const int uv_axis[2] = {a, b};
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = cell complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = frac complete)
  [[gnu::unused]] rm_cell_divide : VOXCAST_HLS_HOST_UNROLL for (int j = 0; j < 2; ++j) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const typename Params::offset_t off = n[uv_axis[j]] + mag[m];
    const typename Params::den_t off_raw = read_bits(off);
    typename Params::num_t num = off_raw * uint_t<Params::res_bits>(Params::res);
    num = num << Params::wb;
    const typename Params::pos_t t = num / den;  // <= res·2^wb
    const typename Params::pos_t whole = t >> Params::wb;
    cell[j] = whole > last ? last : typename Params::cell_t(whole);
    const typename Params::pos_t f = t - (typename Params::pos_t(cell[j]) << Params::wb);
    write_bits(frac[j], f.to_uint64());  // f <= 2^wb: fits wb + 1 bits
  }

  // Face 2m + (N[m] < 0); index face·side² + iv·side + iu (side = res, or res + 1 for the
  // corner grid).
  constexpr int side = Params::side;
  const typename Params::index_t face = 2 * m + ((n[m] < 0) ? 1 : 0);
  RmCell<P> out;
  out.valid = valid;
  out.index = face * typename Params::index_t(side * side) +
              cell[1] * typename Params::index_t(side) + cell[0];
  out.fu = Params::bilinear ? frac[0] : typename Params::weight_t(0);
  out.fv = Params::bilinear ? frac[1] : typename Params::weight_t(0);
  return out;
}

// §5.5: the bilinear blend of one table's four corner entries e[0..3] = (i, j),
// (i+1, j), (i, j+1), (i+1, j+1): exact lerps e0 + (e1 - e0)·fu along u, then
// along v (= the weighted sum with (1-fu)(1-fv), fu(1-fv), (1-fu)fv, fu·fv; any
// exact order gives the same bits), one Q_RND to rm_frac_bits.
template <class P>
VOXCAST_HLS_HOST_INLINE typename ReflectanceParams<P>::entry_t rm_bilerp(
    const typename ReflectanceParams<P>::entry_t (&e)[4],
    const typename ReflectanceParams<P>::weight_t& fu,
    const typename ReflectanceParams<P>::weight_t& fv) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using Params = ReflectanceParams<P>;
  typename Params::lerp1_t l1[2];
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = l1 complete)
  [[gnu::unused]] rm_lerp_u : VOXCAST_HLS_HOST_UNROLL for (int j = 0; j < 2; ++j) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    l1[j] = e[2 * j] + (e[2 * j + 1] - e[2 * j]) * fu;
  }
  const typename Params::lerp2_t l2 = l1[0] + (l1[1] - l1[0]) * fv;
  const typename Params::entry_rnd_t r = l2;  // Q_RND(·, rm_frac_bits); <= the largest entry
  return r;
}

// §5.5: the four corners of the cell, one read per parity bank (see
// ReflectanceMap), blended; §5: the nearest cell's entries. The mode is the
// profile's (rm_bilinear), so only one of the two is instantiated.
template <class P>
VOXCAST_HLS_HOST_INLINE void rm_read(const ReflectanceMap<P>& map, const RmCell<P>& cell,
                                     Reflect<P>& r, Has<true> /*bilinear*/) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using Params = ReflectanceParams<P>;
  constexpr unsigned side = static_cast<unsigned>(Params::side);
  const unsigned offset[4] = {0u, 1u, side, side + 1u};
  typename Params::entry_t d[4], s[4];
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = d complete)
  VOXCAST_HLS_PRAGMA(HLS ARRAY_PARTITION variable = s complete)
  [[gnu::unused]] rm_corner_read : VOXCAST_HLS_HOST_UNROLL for (int c = 0; c < 4; ++c) {
    VOXCAST_HLS_PRAGMA(HLS UNROLL)
    const unsigned k = cell.index.to_uint() + offset[c];
    d[c] = map.diffuse[k];
    s[c] = map.specular[k];
  }
  r.D = rm_bilerp<P>(d, cell.fu, cell.fv);
  r.S = rm_bilerp<P>(s, cell.fu, cell.fv);
}
template <class P>
VOXCAST_HLS_HOST_INLINE void rm_read(const ReflectanceMap<P>& map, const RmCell<P>& cell,
                                     Reflect<P>& r, Has<false> /*bilinear*/) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  r.D = map.diffuse[cell.index.to_uint()];
  r.S = map.specular[cell.index.to_uint()];
}

// §5: the table reads (D = S = 0 without a normal): one per table in nearest
// mode, four and a blend in bilinear mode. G is the interpolation unit's
// gradient component type; it converts exactly into gradient_t when it has
// sample_frac_bits fraction bits (checked below) and fits.
template <class P, class G>
VOXCAST_HLS_HOST_INLINE Reflect<P> reflect(const ReflectanceMap<P>& map,
                                           const ReflectanceRegisters<P>& regs, const G (&g)[3]) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using Params = ReflectanceParams<P>;
  static_assert(G::width - fixed_iwidth<G>::value == Params::sf,
                "the gradient must have sample_frac_bits fraction bits");
  const typename Params::gradient_t gc[3] = {g[0], g[1], g[2]};
  const RmCell<P> cell = rm_cell<P>(gc, regs);
  Reflect<P> r;
  r.D = 0;
  r.S = 0;
  if (cell.valid) rm_read<P>(map, cell, r, Has<Params::bilinear>{});
  return r;
}

// ---- 3. Host side (not synthesized) -------------------------------------------------------
#if VOXCAST_HLS_HOST_CODE
namespace host {

// Loads both tables from bittrue::make_reflectance_maps' raw integers (cell
// entries, or corner entries in bilinear mode). Returns false (tables
// unchanged) if a size does not match.
template <class P>
bool load_reflectance_map(ReflectanceMap<P>& map, const std::vector<std::uint32_t>& diffuse,
                          const std::vector<std::uint32_t>& specular) {
  constexpr int n = ReflectanceParams<P>::entries;
  if (diffuse.size() != static_cast<std::size_t>(n) ||
      specular.size() != static_cast<std::size_t>(n))
    return false;
  [[gnu::unused]] load_rm_entries : for (int i = 0; i < n; ++i) {
    write_bits(map.diffuse[i], std::uint64_t{diffuse[static_cast<std::size_t>(i)]});
    write_bits(map.specular[i], std::uint64_t{specular[static_cast<std::size_t>(i)]});
  }
  return true;
}

// The IS registers from the frame's raw register values (dir_frac_bits).
template <class P>
ReflectanceRegisters<P> reflectance_registers(const bittrue::FrameRegisters& regs) {
  ReflectanceRegisters<P> r;
  [[gnu::unused]] load_is_registers : for (int k = 0; k < 3; ++k) {
    write_bits(r.IS[k], static_cast<std::uint64_t>(regs.IS[static_cast<std::size_t>(k)]));
  }
  return r;
}

}  // namespace host
#endif
}  // namespace hls
}  // namespace voxcast
