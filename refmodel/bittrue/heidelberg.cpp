#include "refmodel/bittrue/heidelberg.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/error.hpp"
#include "refmodel/parallel.hpp"
#include "refmodel/render/heidelberg/rotator.hpp"
#include "refmodel/render/heidelberg/slice_model.hpp"

namespace voxcast::bittrue {

HeidelbergProfile heidelberg_profile(const ref::Scene& scene) {
  HeidelbergProfile p = kVirimProfile;
  p.weight_bits = scene.heidelberg.weight_bits;
  return p;
}

void check_heidelberg_fits(const HeidelbergProfile& p, const ref::Volume& volume, int W, int D,
                           int H) {
  for (int a = 0; a < 3; ++a)
    if (volume.dims[static_cast<std::size_t>(a)] > (1 << p.addr_bits))
      throw Error(volume.source + ": " + std::to_string(volume.dims[static_cast<std::size_t>(a)]) +
                  " voxels along axis " + std::to_string(a) +
                  " exceed the rotator memory's addr_bits = " + std::to_string(p.addr_bits) +
                  " (at most " + std::to_string(1 << p.addr_bits) + ")");
  const std::pair<const char*, int> view[] = {{"render.width", W}, {"heidelberg.depth", D},
                                              {"render.height", H}};
  for (const auto& [key, n] : view)
    if (n > (1 << p.view_bits))
      throw Error(std::string(key) + " = " + std::to_string(n) + " exceeds the view cube's " +
                  std::to_string(1 << p.view_bits) + " voxels (view_bits = " +
                  std::to_string(p.view_bits) + ")");
  if (volume.bits > p.value_bits)
    throw Error(volume.source + ": " + std::to_string(volume.bits) +
                "-bit voxels exceed the LUT's value_bits = " + std::to_string(p.value_bits));
}

namespace {
// Register types (docs/heidelberg.md §7.1): M in fixed<cf+6, 6>, base and
// positions in fixed<a+3+cf, a+3>, both saturating.
double sat_signed(double x, int int_bits, int frac_bits) {
  const double hi = std::ldexp(1.0, int_bits - 1) - std::ldexp(1.0, -frac_bits);
  return sat(x, -std::ldexp(1.0, int_bits - 1), hi);
}
}  // namespace

std::array<std::uint32_t, 8> rom_entry(const HeidelbergProfile& p,
                                       ref::HeidelbergInterpolation interp, double sigma, int qx,
                                       int qy, int qz) {
  const glm::dvec3 f = glm::dvec3(qx, qy, qz) / std::ldexp(1.0, p.weight_bits);
  const std::array<double, 8> w = interp == ref::HeidelbergInterpolation::Trilinear
                                      ? ref::heidelberg::trilinear_weights(f)
                                      : ref::heidelberg::gaussian_weights(f, sigma);
  // Largest remainder: floor every weight, then give the missing LSBs to the
  // largest remainders (lowest corner first on ties), so the sum is exactly 1.
  const double one = std::ldexp(1.0, p.weight_frac_bits);
  std::array<std::uint32_t, 8> raw{};
  std::array<double, 8> rem{};
  std::int64_t sum = 0;
  for (std::size_t c = 0; c < 8; ++c) {
    const double v = w[c] * one;
    raw[c] = static_cast<std::uint32_t>(std::floor(v));
    rem[c] = v - std::floor(v);
    sum += raw[c];
  }
  for (std::int64_t missing = static_cast<std::int64_t>(one) - sum; missing > 0; --missing) {
    std::size_t best = 0;
    for (std::size_t c = 1; c < 8; ++c)
      if (rem[c] > rem[best]) best = c;
    ++raw[best];
    rem[best] = -1.0;
  }
  return raw;
}

VirimSetup make_virim_setup(const HeidelbergProfile& p, const ref::Scene& scene,
                            const ref::Volume& volume, double eye_offset_deg) {
  namespace hb = ref::heidelberg;
  const ref::HeidelbergDesc& h = scene.heidelberg;
  const hb::ViewDims vd = hb::view_dims(scene, volume);
  check_heidelberg_fits(p, volume, vd.W, vd.D, vd.H);
  const hb::ViewTransform vt = hb::make_view_transform(h, volume, vd, eye_offset_deg);
  const hb::DensityVolume dv_bounds = [&] {
    hb::DensityVolume d;
    d.hi = {volume.dims[0] - 1, volume.dims[1] - 1, volume.dims[2] - 1};
    if (scene.volume.crop) d.lo = scene.volume.crop->lo, d.hi = scene.volume.crop->hi;
    return d;
  }();
  const int cf = p.coord_frac_bits;
  VirimSetup s;
  s.profile = p;
  s.W = vd.W, s.D = vd.D, s.H = vd.H;
  s.dims = volume.dims;
  s.lo = dv_bounds.lo;
  s.hi = dv_bounds.hi;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c)
      s.M[static_cast<std::size_t>(r * 3 + c)] = sat_signed(q_rnd(vt.to_data[c][r] / vt.zoom, cf), 6, cf);
  const glm::dvec3 base = vt.volume_center - vt.to_data * vt.translation;
  for (int a = 0; a < 3; ++a)
    s.base[static_cast<std::size_t>(a)] = sat_signed(q_rnd(base[a], cf), p.addr_bits + 3, cf);
  s.plane_scale.resize(static_cast<std::size_t>(s.D));
  for (int j = 0; j < s.D; ++j) s.plane_scale[static_cast<std::size_t>(j)] = q_rnd(hb::plane_scale(vt, j), cf);
  const std::vector<double> lut = hb::density_lut(scene, volume);
  s.lut.assign(std::size_t{1} << p.value_bits, 0.0);
  for (std::size_t v = 0; v < lut.size(); ++v) s.lut[v] = u_frac(lut[v], p.density_bits);
  s.interpolation = h.interpolation;
  s.sigma = h.gaussian_sigma;
  if (p.weight_bits <= 6) {
    const int n = 1 << p.weight_bits;
    s.rom.resize(static_cast<std::size_t>(n) * n * n * 8);
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const auto e = rom_entry(p, s.interpolation, s.sigma, x, y, z);
          const std::size_t at = ((static_cast<std::size_t>(z) * n + y) * n + x) * 8;
          for (std::size_t c = 0; c < 8; ++c) s.rom[at + c] = static_cast<std::uint16_t>(e[c]);
        }
  }
  const int lf = p.light_frac_bits, uw = p.user_weight_bits;
  s.light = q_rnd(h.light, lf);
  s.wd0 = q_rnd(h.diffuse_0, uw);
  s.wd45 = q_rnd(h.diffuse_45, uw);
  s.ws45 = q_rnd(h.specular_45, uw);
  s.wlum = q_rnd(h.luminosity, uw);
  s.threshold = q_rnd(h.background_threshold, lf);
  s.shininess = h.shininess;
  return s;
}

VirimMemory make_virim_memory(const ref::Volume& volume) {
  VirimMemory m;
  m.dims = volume.dims;
  m.hy = (volume.dims[1] + 1) / 2;
  m.hx2 = (volume.dims[0] + 3) / 4;
  const std::size_t per_bank =
      static_cast<std::size_t>((volume.dims[2] + 1) / 2) * static_cast<std::size_t>(m.hy) *
      static_cast<std::size_t>(m.hx2);
  for (auto& b : m.banks) b.assign(per_bank, 0);
  for (int z = 0; z < volume.dims[2]; ++z)
    for (int y = 0; y < volume.dims[1]; ++y)
      for (int x = 0; x < volume.dims[0]; ++x) {
        const int unit = (x & 1) + 2 * (y & 1) + 4 * (z & 1);
        const int bank = (x >> 1) & 1;
        const std::size_t addr = (static_cast<std::size_t>(z >> 1) * m.hy + (y >> 1)) * m.hx2 + (x >> 2);
        m.banks[static_cast<std::size_t>(unit * 2 + bank)][addr] = volume.at(x, y, z);
      }
  return m;
}

std::uint16_t memory_value(const VirimMemory& m, int x, int y, int z) {
  const int unit = (x & 1) + 2 * (y & 1) + 4 * (z & 1);
  const std::size_t addr = (static_cast<std::size_t>(z >> 1) * m.hy + (y >> 1)) * m.hx2 + (x >> 2);
  return m.banks[static_cast<std::size_t>(unit * 2 + ((x >> 1) & 1))][addr];
}

BtPosition bt_position(const VirimSetup& s, int i, int j, int k) {
  const int cf = s.profile.coord_frac_bits;
  const double sj = s.plane_scale[static_cast<std::size_t>(j)];
  const double u[3] = {(i - 0.5 * (s.W - 1)) * sj, j - 0.5 * (s.D - 1), (k - 0.5 * (s.H - 1)) * sj};
  BtPosition out;
  for (int r = 0; r < 3; ++r) {
    double acc = s.base[static_cast<std::size_t>(r)];  // exact: every term on the 2^-(2cf+1) grid
    for (int c = 0; c < 3; ++c) acc += s.M[static_cast<std::size_t>(r * 3 + c)] * u[c];
    out.p[static_cast<std::size_t>(r)] = sat_signed(q_trn(acc, cf), s.profile.addr_bits + 3, cf);
  }
  return out;
}

double bt_read_density(const VirimSetup& s, const VirimMemory& m, int x, int y, int z) {
  if (x < s.lo[0] || y < s.lo[1] || z < s.lo[2] || x > s.hi[0] || y > s.hi[1] || z > s.hi[2])
    return 0.0;
  return s.lut[memory_value(m, x, y, z)];
}

std::array<double, 8> bt_weights(const VirimSetup& s, int qx, int qy, int qz) {
  std::array<double, 8> w{};
  const int n = 1 << s.profile.weight_bits;
  const std::array<std::uint32_t, 8> raw =
      s.rom.empty() ? rom_entry(s.profile, s.interpolation, s.sigma, qx, qy, qz) : [&] {
        std::array<std::uint32_t, 8> e{};
        const std::size_t at = ((static_cast<std::size_t>(qz) * n + qy) * n + qx) * 8;
        for (std::size_t c = 0; c < 8; ++c) e[c] = s.rom[at + c];
        return e;
      }();
  for (std::size_t c = 0; c < 8; ++c) w[c] = from_raw(raw[c], s.profile.weight_frac_bits);
  return w;
}

double bt_density(const VirimSetup& s, const VirimMemory& m, int i, int j, int k) {
  const HeidelbergProfile& p = s.profile;
  const BtPosition pos = bt_position(s, i, j, k);
  int i0[3], q[3];
  for (std::size_t a = 0; a < 3; ++a) {
    // RND to the ROM's grid; a fraction rounding up to 1 carries (§7.3).
    const double pr = sat_signed(q_rnd(pos.p[a], p.weight_bits), p.addr_bits + 3, p.weight_bits);
    const double fl = std::floor(pr);
    i0[a] = static_cast<int>(fl);
    q[a] = static_cast<int>(std::ldexp(pr - fl, p.weight_bits));
  }
  const std::array<double, 8> w = bt_weights(s, q[0], q[1], q[2]);
  double sum = 0.0;  // exact: 8 products on the 2^-(wf+db) grid, below 1
  for (int c = 0; c < 8; ++c)
    sum += w[static_cast<std::size_t>(c)] *
           bt_read_density(s, m, i0[0] + (c & 1), i0[1] + ((c >> 1) & 1), i0[2] + ((c >> 2) & 1));
  return q_trn(sum, p.density_bits);
}

BtBusWord bt_sobel(const VirimSetup& s, const double* above_y, const double* row,
                   const double* below_y, int x) {
  const auto at = [&](const double* r, int i) { return (!r || i < 0 || i >= s.W) ? 0.0 : r[i]; };
  const double* rows[3] = {above_y, row, below_y};  // y - 1, y, y + 1
  double sx = 0.0, sy = 0.0;
  const double w[3] = {1.0, 2.0, 1.0};
  for (int d = 0; d < 3; ++d) {
    sx += w[d] * (at(rows[d], x + 1) - at(rows[d], x - 1));
    sy += w[d] * (at(below_y, x + d - 1) - at(above_y, x + d - 1));
  }
  const int gb = s.profile.gradient_bits;
  return {at(row, x), q_trn(sx / 8.0, gb), q_trn(sy / 8.0, gb)};
}

namespace {
std::int64_t isqrt(std::int64_t n) {
  auto r = static_cast<std::int64_t>(std::sqrt(static_cast<double>(n)));
  while (r * r > n) --r;
  while ((r + 1) * (r + 1) <= n) ++r;
  return r;
}
}  // namespace

double inv_sqrt2(int cos_frac_bits) { return q_rnd(1.0 / std::numbers::sqrt2, cos_frac_bits); }

BtPhong bt_phong(const VirimSetup& s, double gx, double gy) {
  const int gb = s.profile.gradient_bits, cf = s.profile.cos_frac_bits;
  BtPhong ph;
  const std::int64_t rx = to_raw(gx, gb), ry = to_raw(gy, gb);
  const double m = from_raw(isqrt(rx * rx + ry * ry), gb);  // floor(|g|) on the gb grid
  ph.surface = std::min(1.0, q_trn(2.0 * m, cf));
  ph.fade = std::min(1.0, q_trn(m / ref::heidelberg::kNormalFade, cf));  // exact: 2^6 m
  if (m == 0.0) return ph;
  const double k = inv_sqrt2(cf);
  ph.c0 = sat(trunc0_div(gy, gb, m, gb, cf), -1.0, 1.0);
  ph.c45 = sat(trunc0_div((gx + gy) * k, gb + cf, m, gb, cf), -1.0, 1.0);
  const double rv = sat(q_trn(2.0 * ph.c45 * ph.c0, cf) - k, 0.0, 1.0);
  double result = 1.0, base = rv;
  for (int b = 0; b < 7; ++b) {  // square and multiply, shininess < 128
    if ((s.shininess >> b) & 1) result = q_trn(result * base, cf);
    base = q_trn(base * base, cf);
  }
  ph.spec = q_trn(q_trn(result * ph.surface, cf) * ph.fade, cf);
  ph.d0 = q_trn(std::max(0.0, ph.c0) * ph.fade, cf);
  ph.d45 = q_trn(std::max(0.0, ph.c45) * ph.fade, cf);
  return ph;
}

double bt_slice_voxel(const VirimSetup& s, const BtBusWord& w, double t45_in, BtVoxelState& st) {
  const int lf = s.profile.light_frac_bits, cf = s.profile.cos_frac_bits;
  const BtPhong ph = bt_phong(s, w.gx, w.gy);
  const double rho = w.density;
  const double i0 = q_trn(s.light * st.t0, lf), i45 = q_trn(s.light * t45_in, lf);
  const double e0 = q_trn(i0 * rho, lf), e45 = q_trn(i45 * rho, lf);
  const double r0 = q_trn(s.wd0 * ph.d0, cf);
  const double r45 = q_trn(s.wd45 * ph.d45 + s.ws45 * ph.spec, cf);
  const double lum = q_trn(s.wlum * ((e0 + e45) / 2.0), lf);
  const double e = std::min(e0 + e45, q_trn(e0 * r0, lf) + q_trn(e45 * r45, lf) + lum);
  st.acc = sat(st.acc + q_trn(e * st.t0, lf), 0.0, 4.0 - std::ldexp(1.0, -lf));
  st.t0 = st.t0 - q_trn(st.t0 * rho, lf);
  return t45_in - q_trn(t45_in * rho, lf);
}

std::uint32_t bt_output_level(const VirimSetup& s, double acc) {
  const double full = std::ldexp(1.0, s.profile.out_bits) - 1.0;
  return static_cast<std::uint32_t>(std::min(full, q_rnd(acc * full, 0)));
}

void bt_line(const VirimSetup& s, const VirimMemory& m, int k, std::uint32_t* out,
             std::uint8_t* bg) {
  const std::size_t W = static_cast<std::size_t>(s.W);
  std::vector<double> rho(W * static_cast<std::size_t>(s.D));
  for (int j = 0; j < s.D; ++j)
    for (int i = 0; i < s.W; ++i) rho[static_cast<std::size_t>(j) * W + static_cast<std::size_t>(i)] = bt_density(s, m, i, j, k);
  std::vector<BtVoxelState> st(W);
  std::vector<double> t45(W, 1.0), next45(W, 1.0);
  for (int j = 0; j < s.D; ++j) {
    const double* row = &rho[static_cast<std::size_t>(j) * W];
    const double* above = j > 0 ? row - W : nullptr;
    const double* below = j + 1 < s.D ? row + W : nullptr;
    for (int x = 0; x < s.W; ++x) {
      const std::size_t ux = static_cast<std::size_t>(x);
      const double t45_out = bt_slice_voxel(s, bt_sobel(s, above, row, below, x), t45[ux], st[ux]);
      if (ux + 1 < W) next45[ux + 1] = t45_out;
    }
    next45[0] = 1.0;
    std::swap(t45, next45);
  }
  for (std::size_t x = 0; x < W; ++x) {
    out[x] = bt_output_level(s, st[x].acc);
    bg[x] = st[x].t0 > s.threshold ? 1 : 0;
  }
}

ref::QuantImage bt_render_heidelberg(const VirimSetup& s, const VirimMemory& m, int threads) {
  ref::QuantImage img(s.W, s.H, s.profile.out_bits);
  const auto full = static_cast<std::uint32_t>(img.full_scale());
  ref::parallel_for(
      s.H,
      [&](int k) {
        std::vector<std::uint32_t> out(static_cast<std::size_t>(s.W));
        std::vector<std::uint8_t> bg(static_cast<std::size_t>(s.W));
        bt_line(s, m, k, out.data(), bg.data());
        for (int x = 0; x < s.W; ++x) {
          const std::uint32_t v = out[static_cast<std::size_t>(x)];
          img.at(x, s.H - 1 - k) = bg[static_cast<std::size_t>(x)]
                                       ? std::array<std::uint32_t, 4>{0, 0, 0, 0}
                                       : std::array<std::uint32_t, 4>{v, v, v, full};
        }
      },
      threads);
  return img;
}

}  // namespace voxcast::bittrue
