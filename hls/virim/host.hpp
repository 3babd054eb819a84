// Host side of VIRIM's kernels (not synthesized): the profiles they are
// compiled for, and loading a frame's registers, LUT and weight ROM from the
// host set-up the bit-true twin uses (bittrue::VirimSetup), so both engines
// read one set of numbers.
#pragma once

#include "hls/pragma.hpp"

#if VOXCAST_HLS_HOST_CODE
#include <memory>
#include <string>

#include "hls/virim/virim_top.hpp"
#include "refmodel/bittrue/heidelberg.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/preset_profiles.hpp"

namespace voxcast {
namespace hls {
namespace virim {
namespace host {

inline constexpr const char* kCompiledHeidelbergProfiles =
    "VIRIM's (6-bit weight addressing, heidelberg.weight_bits = 6)";

template <class Fn>
bool dispatch_heidelberg_profile(const HeidelbergProfile& p, Fn&& fn) {
  if (p == heidelberg_value<VirimTraits>()) {
    fn.template operator()<VirimTraits>();
    return true;
  }
  return false;
}

template <class T>
T on_grid(double v) {
  T t = v;  // exact: the set-up already rounded v to T's grid
  return t;
}

template <class HP>
std::unique_ptr<VirimFrame<HP>> load_virim_frame(const bittrue::VirimSetup& s) {
  using V = VirimParams<HP>;
  if (s.rom.size() != static_cast<std::size_t>(V::rom_entries) * 8 ||
      s.lut.size() != static_cast<std::size_t>(V::lut_entries))
    throw Error("hls engine: the Heidelberg set-up's ROM or LUT does not match the profile");
  auto f = std::make_unique<VirimFrame<HP>>();
  GeometryRegisters<HP>& g = f->geometry;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) g.M[r][c] = on_grid<typename V::matrix_t>(s.M[static_cast<std::size_t>(r * 3 + c)]);
    g.base[r] = on_grid<typename V::pos_t>(s.base[static_cast<std::size_t>(r)]);
  }
  g.cx = on_grid<typename V::offset_t>(0.5 * (s.W - 1));
  g.cy = on_grid<typename V::offset_t>(0.5 * (s.D - 1));
  g.cz = on_grid<typename V::offset_t>(0.5 * (s.H - 1));
  for (int j = 0; j < s.D; ++j) g.scale[j] = on_grid<typename V::scale_t>(s.plane_scale[static_cast<std::size_t>(j)]);
  g.W = s.W, g.D = s.D, g.H = s.H;
  for (int a = 0; a < 3; ++a) {
    f->memory.lo[a] = s.lo[static_cast<std::size_t>(a)];
    f->memory.hi[a] = s.hi[static_cast<std::size_t>(a)];
  }
  f->memory.hy = (s.dims[1] + 1) / 2;
  f->memory.hx2 = (s.dims[0] + 3) / 4;
  for (std::size_t v = 0; v < s.lut.size(); ++v) f->tables.lut[v] = on_grid<typename V::density_t>(s.lut[v]);
  for (std::size_t e = 0; e < static_cast<std::size_t>(V::rom_entries); ++e)
    for (std::size_t c = 0; c < 8; ++c)
      write_bits(f->tables.rom[e][c], V::wf, 0, s.rom[e * 8 + c]);
  SliceRegisters<HP>& sr = f->slice;
  sr.light = on_grid<typename V::light_t>(s.light);
  sr.wd0 = on_grid<typename V::uweight_t>(s.wd0);
  sr.wd45 = on_grid<typename V::uweight_t>(s.wd45);
  sr.ws45 = on_grid<typename V::uweight_t>(s.ws45);
  sr.wlum = on_grid<typename V::uweight_t>(s.wlum);
  sr.threshold = on_grid<typename V::light_t>(s.threshold);
  sr.inv_sqrt2 = on_grid<typename V::ucos_t>(bittrue::inv_sqrt2(HP::cos_frac_bits));
  sr.shininess = s.shininess;
  return f;
}

inline void bank_pointers(const bittrue::VirimMemory& m, const std::uint16_t* out[16]) {
  for (std::size_t b = 0; b < 16; ++b) out[b] = m.banks[b].data();
}

}  // namespace host
}  // namespace virim
}  // namespace hls
}  // namespace voxcast
#endif
