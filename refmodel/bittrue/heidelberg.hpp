// VIRIM's fixed-point datapath as plain doubles rounded at the same points as
// hls/virim/ (the bit-true twin; docs/heidelberg.md §7), and the host set-up
// both engines share: the registers the host writes (matrix, plane scales,
// LUT, weight ROM, slice parameters) already on their fixed-point grids, and
// the 8-unit parity memory.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "refmodel/precision/heidelberg_profile.hpp"
#include "refmodel/render/quant_image.hpp"
#include "refmodel/scene/scene.hpp"
#include "refmodel/volume/volume.hpp"

namespace voxcast::bittrue {

// The profile of a scene: VIRIM's, with heidelberg.weight_bits.
HeidelbergProfile heidelberg_profile(const ref::Scene& scene);

// Throws voxcast::Error naming the limit if the volume or the view cube does
// not fit the profile (addr_bits, view_bits, value_bits).
void check_heidelberg_fits(const HeidelbergProfile& p, const ref::Volume& volume, int W, int D,
                           int H);

struct VirimSetup {
  HeidelbergProfile profile;
  int W = 0, D = 0, H = 0;               // view cube
  std::array<int, 3> dims{}, lo{}, hi{}; // data cube and its software-set bounds (inclusive)
  // Geometry (§7.1): data position p = base + M u, u = (x offset · s_j, y offset,
  // z offset · s_j); M = R^T / zoom row-major, base = c − R^T t, s_j per plane.
  std::array<double, 9> M{};
  std::array<double, 3> base{};
  std::vector<double> plane_scale;       // D entries
  std::vector<double> lut;               // 2^value_bits densities
  ref::HeidelbergInterpolation interpolation = ref::HeidelbergInterpolation::Gaussian;
  double sigma = 0.5;
  std::vector<std::uint16_t> rom;        // 2^(3 weight_bits) x 8 raw weights, or empty (> 6 bits)
  // Slice processor (§7.5).
  double light = 1.0, wd0 = 0.0, wd45 = 0.0, ws45 = 0.0, wlum = 0.0, threshold = 1.0;
  int shininess = 1;
};

VirimSetup make_virim_setup(const HeidelbergProfile& p, const ref::Scene& scene,
                            const ref::Volume& volume, double eye_offset_deg);

// The ROM's entry at address (qx, qy, qz): the 8 weights at fractional offset
// q / 2^weight_bits, as integers in units of 2^-weight_frac_bits that sum to
// exactly 2^weight_frac_bits (largest-remainder rounding, §7.3).
std::array<std::uint32_t, 8> rom_entry(const HeidelbergProfile& p,
                                       ref::HeidelbergInterpolation interp, double sigma, int qx,
                                       int qy, int qz);

// The data cube in 8 RAM units by the parities of (x, y, z), each in two banks
// (§7.2): unit u = (x&1) + 2(y&1) + 4(z&1), bank (x>>1)&1, address
// ((z>>1) hy + (y>>1)) hx2 + (x>>2), hy = ceil(Ny/2), hx2 = ceil(Nx/4).
struct VirimMemory {
  std::array<int, 3> dims{};
  int hy = 0, hx2 = 0;
  std::array<std::vector<std::uint16_t>, 16> banks;  // [unit * 2 + bank]
};
VirimMemory make_virim_memory(const ref::Volume& volume);
std::uint16_t memory_value(const VirimMemory& m, int x, int y, int z);  // in the cube

// --- The units, for tests that compare with hls/virim/ one unit at a time ---
struct BtPosition {
  std::array<double, 3> p{};  // on the coord_frac_bits grid
};
BtPosition bt_position(const VirimSetup& s, int i, int j, int k);
// Density after LUT, 0 outside [lo, hi] (§7.2).
double bt_read_density(const VirimSetup& s, const VirimMemory& m, int x, int y, int z);
std::array<double, 8> bt_weights(const VirimSetup& s, int qx, int qy, int qz);
double bt_density(const VirimSetup& s, const VirimMemory& m, int i, int j, int k);

struct BtBusWord {
  double density = 0.0, gx = 0.0, gy = 0.0;
};
// Sobel x, y of a W-wide row from three density rows (null rows read 0).
BtBusWord bt_sobel(const VirimSetup& s, const double* above_y, const double* row,
                   const double* below_y, int x);

// RND(1/√2, cos_frac_bits): the 45 deg light's direction cosine constant.
double inv_sqrt2(int cos_frac_bits);

struct BtPhong {
  double c0 = 0.0, c45 = 0.0, spec = 0.0, surface = 0.0, fade = 0.0;
  double d0 = 0.0, d45 = 0.0;  // faded diffuse factors
};
BtPhong bt_phong(const VirimSetup& s, double gx, double gy);

// One voxel of the slice processor: updates T0, accumulates, returns T45 out.
struct BtVoxelState {
  double t0 = 1.0, acc = 0.0;
};
double bt_slice_voxel(const VirimSetup& s, const BtBusWord& w, double t45_in, BtVoxelState& st);
std::uint32_t bt_output_level(const VirimSetup& s, double acc);

// One image line (plane k): out[x] = gray level, bg[x] = background flag.
void bt_line(const VirimSetup& s, const VirimMemory& m, int k, std::uint32_t* out,
             std::uint8_t* bg);
// The whole image as the ray caster's engines deliver it: r = g = b = level,
// alpha full scale, or all 0 on background pixels.
ref::QuantImage bt_render_heidelberg(const VirimSetup& s, const VirimMemory& m, int threads = 0);

}  // namespace voxcast::bittrue
