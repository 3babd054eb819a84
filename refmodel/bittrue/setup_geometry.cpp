// Host set-up of the geometry processor and the voxel memory (docs/pipeline.md
// §0, §1.2, §3.3-3.4): doubles from the float reference's camera and volume,
// quantized to the raw integers the hls engine and the bit-true model load.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <glm/geometric.hpp>
#include <limits>
#include <string>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/error.hpp"

namespace voxcast::bittrue {

// Raw of Q_RND(x, F) = floor(x·2^F + 1/2), ties towards +inf. Exact for every
// finite x with |x·2^F| < 2^52: the scaling is a power of two, floor is exact
// and y - floor(y) is exact, so no addition rounds (quantize.hpp, q_rnd). Above
// 2^52 every double is an integer and the result is x·2^F itself; beyond 2^62
// (or a non-finite x) it throws.
Raw quantize_rnd(double x, int frac_bits) {
  const double y = std::ldexp(x, frac_bits);
  if (!std::isfinite(y) || std::fabs(y) >= 0x1p62)
    throw Error("quantize_rnd: " + std::to_string(x) + " at " + std::to_string(frac_bits) +
                " fraction bits does not fit a 64-bit register");
  const double t = std::floor(y);
  return static_cast<Raw>(y - t >= 0.5 ? t + 1.0 : t);
}

namespace {

using ref::Vec3;

Raw3 quantize3(const Vec3& v, int frac_bits) {
  return {quantize_rnd(v.x, frac_bits), quantize_rnd(v.y, frac_bits), quantize_rnd(v.z, frac_bits)};
}

void check_profile(const PrecisionProfile& p) {
  if (p.rsqrt_seed_bits > p.dir_frac_bits)
    throw Error("precision.rsqrt_seed_bits = " + std::to_string(p.rsqrt_seed_bits) +
                " exceeds precision.dir_frac_bits = " + std::to_string(p.dir_frac_bits) +
                " (docs/pipeline.md §0)");
  if (p.addr_bits + p.pos_frac_bits + p.t_frac_bits > 49)
    throw Error("precision.addr_bits + pos_frac_bits + t_frac_bits = " +
                std::to_string(p.addr_bits + p.pos_frac_bits + p.t_frac_bits) +
                " exceeds 49 (docs/pipeline.md §0)");
}

// The origin format fixed<a+4+pf, a+4> holds [-2^(a+3), 2^(a+3)); the plane's
// corners are kept one voxel inside, so their rounding cannot leave it.
double origin_limit(const PrecisionProfile& p) { return std::ldexp(1.0, p.addr_bits + 3) - 1.0; }

void check_origin(const PrecisionProfile& p, const Raw3& o) {
  const Raw limit = Raw{1} << (p.addr_bits + 3 + p.pos_frac_bits);
  for (Raw v : o)
    if (v < -limit || v >= limit)
      throw Error("camera: the ray origin lies outside the geometry processor's origin register "
                  "range of +-" + std::to_string(1 << (p.addr_bits + 3)) +
                  " voxels per axis (docs/pipeline.md §0)");
}

}  // namespace

// The origin plane (docs/pipeline.md §0, "The origin plane"): the rays start
// on the plane normal to the view direction at depth D from the eye, as close
// to the volume as it can be without passing into it. A ray's first sample is
// then o + k_in·s with k_in bounded by the box's depth, not by the eye's
// distance, so the step vector's rounding (2^-(pf+1) per component, multiplied
// by k_in) no longer grows with the distance (issue 19).
//   * D_box = min over the box's corners of forward·(corner - eye): every point
//     of the box lies at depth >= D_box, so every entry is at k >= 0 from the
//     plane and k_in's clamp at 0 never moves an entry (it still places the
//     first sample at the eye when the eye is inside the box: D = 0).
//   * The plane's corner pixels must fit the origin register: each component of
//     a corner, (eye + D·dir_c)/ws, is affine in D, so each gives an interval of
//     D; D is the largest value in [0, D_box] inside all of them.
double origin_plane_depth(const PrecisionProfile& p, const ref::CameraFrame& cam, const Vec3& ws,
                          const ref::Box& index_box) {
  const double u0 = (1.0 / cam.width - 1.0) * cam.half_width;
  const double v0 = (1.0 - 1.0 / cam.height) * cam.half_height;
  const double u1 = -u0, v1 = -v0;  // the last column's and row's centres
  const bool perspective = cam.projection == ref::Projection::Perspective;
  const double d_box =
      ref::box_depth_range(cam, ref::Box{index_box.lo * ws, index_box.hi * ws}).near;
  double lo = 0.0, hi = std::max(0.0, d_box);
  const double limit = origin_limit(p);
  for (const double u : {u0, u1})
    for (const double v : {v0, v1}) {
      // Corner position at depth D: base + D·rate, index space.
      const Vec3 lateral = u * cam.right + v * cam.up;
      const Vec3 base = (perspective ? cam.eye : cam.eye + lateral) / ws;
      const Vec3 rate = (perspective ? cam.forward + lateral : cam.forward) / ws;
      for (int k = 0; k < 3; ++k) {
        if (rate[k] == 0.0) {
          if (std::fabs(base[k]) > limit) return -1.0;
          continue;
        }
        const double a = (-limit - base[k]) / rate[k], b = (limit - base[k]) / rate[k];
        lo = std::max(lo, std::min(a, b));
        hi = std::min(hi, std::max(a, b));
      }
    }
  return lo <= hi ? hi : -1.0;
}

FrameRegisters make_frame_registers(const PrecisionProfile& p,
                                    [[maybe_unused]] const ref::Scene& scene,
                                    const ref::RenderInputs& in) {
  check_profile(p);
  const int pf = p.pos_frac_bits, df = p.dir_frac_bits;
  const ref::CameraFrame& cam = in.camera;
  const ref::RenderVolume& rv = in.volume;
  const Vec3 ws = rv.world_scale;
  const ref::Volume& volume = *rv.volume;

  FrameRegisters r;
  r.perspective = cam.projection == ref::Projection::Perspective;
  r.width = cam.width;
  r.height = cam.height;
  r.mode = in.settings.mode;

  // Image-plane coordinates of pixel (0,0)'s centre and the per-pixel increments,
  // as ref::primary_ray computes them.
  const double u0 = (1.0 / cam.width - 1.0) * cam.half_width;
  const double v0 = (1.0 - 1.0 / cam.height) * cam.half_height;
  const double du = 2.0 * cam.half_width / cam.width;
  const double dv = -2.0 * cam.half_height / cam.height;
  const int corners[4][2] = {
      {0, 0}, {cam.width - 1, 0}, {0, cam.height - 1}, {cam.width - 1, cam.height - 1}};

  // The origin plane at depth D (origin_plane_depth): O is the plane's point
  // on pixel (0,0)'s ray, P and R its increments per column and row; the same
  // three registers for both projections.
  const double depth = origin_plane_depth(p, cam, ws, rv.index_box);
  if (depth < 0.0)
    throw Error("camera: no plane normal to the view direction between camera.eye and the "
                "volume keeps the rays' origins inside the geometry processor's origin register "
                "range of +-" + std::to_string(1 << (p.addr_bits + 3)) +
                " voxels per axis (docs/pipeline.md §0); narrow camera.fov_deg or camera.height, "
                "or move camera.eye closer");
  r.origin_depth = depth;
  if (r.perspective) {
    const Vec3 d00 = cam.forward + u0 * cam.right + v0 * cam.up;
    const double M = glm::length(d00);
    r.A = quantize3(d00 / M, df);
    r.B = quantize3(du * cam.right / M, df);
    r.C = quantize3(dv * cam.up / M, df);
    r.O = quantize3((cam.eye + depth * d00) / ws, pf);
    r.P = quantize3(depth * du * cam.right / ws, pf);
    r.R = quantize3(depth * dv * cam.up / ws, pf);
    // |d| < 2 at every pixel: d·d is convex in (px, py), so the corners bound it.
    for (const auto& c : corners) {
      Raw n2 = 0;
      for (std::size_t k = 0; k < 3; ++k) {
        const Raw d = r.A[k] + c[0] * r.B[k] + c[1] * r.C[k];
        n2 += d * d;
      }
      if (n2 >= (Raw{4} << (2 * df)))
        throw Error("camera: precision.dir_frac_bits = " + std::to_string(df) +
                    " is too narrow for a " + std::to_string(cam.width) + "x" +
                    std::to_string(cam.height) + " image (pixel directions overflow)");
    }
  } else {
    r.O = quantize3((cam.eye + u0 * cam.right + v0 * cam.up + depth * cam.forward) / ws, pf);
    r.P = quantize3(du * cam.right / ws, pf);
    r.R = quantize3(dv * cam.up / ws, pf);
    r.U = quantize3(cam.forward, df);
  }
  for (const auto& c : corners) {
    Raw3 o{};
    for (std::size_t k = 0; k < 3; ++k) o[k] = r.O[k] + c[0] * r.P[k] + c[1] * r.R[k];
    check_origin(p, o);
  }
  r.K = quantize3(in.settings.step / ws, df);
  r.IS = quantize3(1.0 / ws, df);

  for (std::size_t k = 0; k < 3; ++k) {
    r.dims[k] = volume.dims[k];
    if (volume.dims[k] > (1 << p.addr_bits))
      throw Error("precision.addr_bits = " + std::to_string(p.addr_bits) + " cannot address " +
                  std::to_string(volume.dims[k]) + " voxels along an axis");
    r.LO[k] = static_cast<int>(rv.index_box.lo[static_cast<int>(k)]);
    r.HI[k] = static_cast<int>(rv.index_box.hi[static_cast<int>(k)]);
  }
  // MIP grey = M / full scale of the (shifted) value field's data range.
  r.RM = quantize_rnd(1.0 / std::ldexp(volume.max_stored(), value_shift(p, volume)), df);
  r.ert_enabled = in.settings.ert_threshold < 1.0;
  r.ert_threshold = quantize_rnd(std::min(in.settings.ert_threshold, 1.0), p.acc_bits);
  r.jitter = in.settings.jitter_bits > 0;  // render.jitter, at this profile's t_frac_bits
  return r;
}

std::vector<Raw> make_rsqrt_seed(const PrecisionProfile& p) {
  check_profile(p);
  const int sb = p.rsqrt_seed_bits;
  std::vector<Raw> seed(std::size_t{1} << sb, 0);
  // Entries below 2^(sb-2) are never addressed (m >= 1/4) and stay 0 (§1.2).
  for (std::size_t i = std::size_t{1} << (sb - 2); i < seed.size(); ++i)
    seed[i] = quantize_rnd(1.0 / std::sqrt(std::ldexp(static_cast<double>(i) + 0.5, -sb)),
                           p.dir_frac_bits);
  return seed;
}

std::shared_ptr<const std::vector<PackedVoxelWord>> pack_banks(const VoxelMemory& mem) {
  const std::size_t words = mem.banks[0].size();
  for (std::size_t b = 1; b < 8; ++b)
    if (mem.banks[b].size() != words)
      throw Error("voxel memory: bank " + std::to_string(b) + " holds " +
                  std::to_string(mem.banks[b].size()) + " words, bank 0 " + std::to_string(words) +
                  ": the banks cannot be interleaved");
  auto packed = std::make_shared<std::vector<PackedVoxelWord>>(8 * words);
  for (std::size_t b = 0; b < 8; ++b)
    for (std::size_t a = 0; a < words; ++a) {
      const VoxelWord& w = mem.banks[b][a];
      PackedVoxelWord& q = (*packed)[8 * a + b];
      q.value = static_cast<std::uint16_t>(w.value);
      for (std::size_t c = 0; c < 3; ++c) q.gradient[c] = static_cast<std::int16_t>(w.gradient[c]);
    }
  return packed;
}

VoxelMemory make_voxel_memory(const PrecisionProfile& p, const ref::Volume& volume,
                              const ref::GradientField& gradients) {
  VoxelMemory mem;
  mem.dims = volume.dims;
  for (int k = 0; k < 3; ++k)
    if (volume.dims[static_cast<std::size_t>(k)] > (1 << p.addr_bits))
      throw Error("precision.addr_bits = " + std::to_string(p.addr_bits) + " cannot address " +
                  std::to_string(volume.dims[static_cast<std::size_t>(k)]) +
                  " voxels along an axis");
  const int hx = (volume.dims[0] + 1) / 2, hy = (volume.dims[1] + 1) / 2,
            hz = (volume.dims[2] + 1) / 2;
  const std::size_t words =
      static_cast<std::size_t>(hx) * static_cast<std::size_t>(hy) * static_cast<std::size_t>(hz);
  for (auto& bank : mem.banks) bank.assign(words, VoxelWord{});  // padding words are zero
  const std::uint32_t vmax = (std::uint32_t{1} << p.value_bits) - 1u;
  const Raw gmax = (Raw{1} << (p.gradient_bits - 1)) - 1, gmin = -(Raw{1} << (p.gradient_bits - 1));
  const int shift = value_shift(p, volume);
  for (int z = 0; z < volume.dims[2]; ++z)
    for (int y = 0; y < volume.dims[1]; ++y)
      for (int x = 0; x < volume.dims[0]; ++x) {
        const std::size_t i = volume.index(x, y, z);
        const int bank = (x & 1) | (y & 1) << 1 | (z & 1) << 2;
        const std::size_t word = static_cast<std::size_t>((x >> 1) + (y >> 1) * hx) +
                                 static_cast<std::size_t>(z >> 1) * static_cast<std::size_t>(hx) *
                                     static_cast<std::size_t>(hy);
        VoxelWord& w = mem.banks[static_cast<std::size_t>(bank)][word];
        const std::uint32_t value = std::uint32_t{volume.data[i]} << shift;
        if (value > vmax)
          throw Error("precision.value_bits = " + std::to_string(p.value_bits) +
                      " cannot hold the voxel value " + std::to_string(volume.data[i]) + " (" +
                      volume.source + ")");
        w.value = value;
        for (int c = 0; c < 3; ++c) {
          const Raw g = quantize_rnd(std::ldexp(gradients.g[i][c], shift), p.gradient_frac_bits);
          w.gradient[static_cast<std::size_t>(c)] =
              static_cast<std::int32_t>(g < gmin ? gmin : (g > gmax ? gmax : g));
        }
      }
  mem.leap_blocks = std::make_shared<const ref::MinMaxBlocks>(
      ref::make_min_max_blocks(volume, kEngineLeapBlockLog2));
  mem.value_shift = shift;
  if (p.value_bits <= 16 && p.gradient_bits <= 16) mem.packed = pack_banks(mem);
  return mem;
}

}  // namespace voxcast::bittrue
