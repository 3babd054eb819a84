// Built-in phantoms: volumes defined analytically in continuous coordinates and
// sampled once at every voxel centre (no supersampling), so each voxel value is
// an exact closed form of its indices. docs/volumes.md states every definition.
//
// Normalised coordinates: on an axis of n voxels, voxel index i sits at
//   u(i) = (2*i - (n-1)) / (n-1)   in [-1, 1],
// so the first and last voxel centres are at -1 and +1 and the grid centre at 0.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "refmodel/error.hpp"
#include "refmodel/math/geometry.hpp"
#include "refmodel/parallel.hpp"
#include "refmodel/volume/loaders.hpp"

namespace voxcast::ref {
namespace {

constexpr int kMinSize = 2;
constexpr int kMaxSize = 1024;
constexpr const char* kPhantomNames = "shepp-logan, shells, tube, box, grating";

// `offset` (in voxels, within the voxel) is 0 for the voxel centre; partial
// volume averages several offsets (make_phantom's `aa`).
double normalised(int i, int n, double offset = 0.0) {
  return (2.0 * (i + offset) - static_cast<double>(n - 1)) / static_cast<double>(n - 1);
}

struct SubVoxel {
  double x = 0.0, y = 0.0, z = 0.0;
};

// --- shepp-logan ------------------------------------------------------------
// Kak & Slaney's 3-D Shepp-Logan head (Principles of Computerized Tomographic
// Imaging, 1988, p. 102) with the high-contrast densities of Yu, Ye & Wang
// (Proc. SPIE 5535, 2004). Each ellipsoid adds its density where
//   (x'/a)^2 + (y'/b)^2 + (dz/c)^2 <= 1,  d = u - centre,
//   x' = dx cos(phi) + dy sin(phi),  y' = -dx sin(phi) + dy cos(phi)
// (the ellipsoid is turned by phi about the z axis through its own centre).
// Densities are kept in tenths so that sums are exact integers.
struct Ellipsoid {
  double cx, cy, cz;  // centre
  double a, b, c;     // semi-axes along x', y', z
  double phi_deg;     // rotation about z
  int density_tenths;
};

constexpr std::array<Ellipsoid, 10> kSheppLogan{{
    {0.00, 0.000, 0.000, 0.6900, 0.920, 0.900, 0.0, 10},      // skull (outer surface)
    {0.00, 0.000, 0.000, 0.6624, 0.874, 0.880, 0.0, -8},      // brain
    {-0.22, 0.000, -0.250, 0.4100, 0.160, 0.210, 108.0, -2},  // ventricle
    {0.22, 0.000, -0.250, 0.3100, 0.110, 0.220, 72.0, -2},    // ventricle
    {0.00, 0.350, -0.250, 0.2100, 0.250, 0.500, 0.0, 2},
    {0.00, 0.100, -0.250, 0.0460, 0.046, 0.046, 0.0, 2},
    {-0.08, -0.650, -0.250, 0.0460, 0.023, 0.020, 0.0, 1},
    {0.06, -0.650, -0.250, 0.0460, 0.023, 0.020, 90.0, 1},
    {0.06, -0.105, 0.625, 0.0560, 0.040, 0.100, 90.0, 2},
    {0.00, 0.100, 0.625, 0.0560, 0.056, 0.100, 0.0, -2},
}};
// Density d in tenths to stored value round(255 * d / 10), half up. The table's
// sums stay within 0..10 tenths (0 outside the head, 10 in the skull); the
// tests check every voxel's value at several sizes.
std::uint16_t shepp_logan_grey(int tenths) {
  return static_cast<std::uint16_t>((tenths * 255 + 5) / 10);
}

void fill_shepp_logan(Volume& v, SubVoxel o) {
  const int n = v.dims[0];
  struct Prepared {
    Ellipsoid e;
    double cos_phi, sin_phi;
    double half_y;  // half extent of the rotated ellipse along y
  };
  std::array<Prepared, kSheppLogan.size()> prepared{};
  for (std::size_t k = 0; k < kSheppLogan.size(); ++k) {
    const Ellipsoid& e = kSheppLogan[k];
    const double phi = e.phi_deg * std::numbers::pi / 180.0;
    const double c = std::cos(phi), s = std::sin(phi);
    prepared[k] = {e, c, s, std::hypot(e.a * s, e.b * c)};
  }
  // Slices are filled in parallel, each voxel on its own, so the result does not
  // depend on the thread count. Row bounds only skip work; the exact test below
  // decides membership, and the margin keeps rounding in the bounds from ever
  // dropping a voxel.
  constexpr double kMargin = 1e-9;
  parallel_for(n, [&](int z) {
    const double uz = normalised(z, n, o.z);
    std::array<std::size_t, kSheppLogan.size()> row_active{};
    for (int y = 0; y < n; ++y) {
      const double uy = normalised(y, n, o.y);
      std::size_t active = 0;
      for (std::size_t k = 0; k < prepared.size(); ++k) {
        const Prepared& p = prepared[k];
        if (std::abs(uz - p.e.cz) <= p.e.c + kMargin && std::abs(uy - p.e.cy) <= p.half_y + kMargin)
          row_active[active++] = k;
      }
      std::uint16_t* row = &v.data[v.index(0, y, z)];
      for (int x = 0; x < n; ++x) {
        const double ux = normalised(x, n, o.x);
        int tenths = 0;
        for (std::size_t r = 0; r < active; ++r) {
          const Prepared& p = prepared[row_active[r]];
          const double dx = ux - p.e.cx, dy = uy - p.e.cy, dz = uz - p.e.cz;
          const double xr = dx * p.cos_phi + dy * p.sin_phi;
          const double yr = -dx * p.sin_phi + dy * p.cos_phi;
          const double q = (xr / p.e.a) * (xr / p.e.a) + (yr / p.e.b) * (yr / p.e.b) +
                           (dz / p.e.c) * (dz / p.e.c);
          if (q <= 1.0) tenths += p.e.density_tenths;
        }
        row[x] = shepp_logan_grey(tenths);
      }
    }
  });
}

// --- shells -------------------------------------------------------------------
// Value w where r_in <= |u| <= r_out (compared as squares), 0 elsewhere.
struct Shell {
  double r_out, r_in;
  std::uint16_t value;
};
constexpr std::array<Shell, 3> kShells{{
    {0.9, 0.82, 80},
    {0.6, 0.52, 160},
    {0.3, 0.22, 240},
}};

void fill_shells(Volume& v, SubVoxel o) {
  const int n = v.dims[0];
  parallel_for(n, [&](int z) {
    const double uz = normalised(z, n, o.z);
    for (int y = 0; y < n; ++y) {
      const double uy = normalised(y, n, o.y);
      std::uint16_t* row = &v.data[v.index(0, y, z)];
      for (int x = 0; x < n; ++x) {
        const double ux = normalised(x, n, o.x);
        const double r2 = ux * ux + uy * uy + uz * uz;
        std::uint16_t value = 0;
        for (const Shell& s : kShells)
          if (r2 >= s.r_in * s.r_in && r2 <= s.r_out * s.r_out) value = s.value;
        row[x] = value;
      }
    }
  });
}

// --- tube -----------------------------------------------------------------------
// A bent tube with two side branches (a virtual-endoscopy target). Distances
// are measured in voxels: p = (i, j, k) - (n-1)/2, and a normalised length L
// is L * h voxels with h = (n-1)/2.
constexpr double kTubeLumen = 0.16;    // main tube lumen radius (normalised)
constexpr double kBranchLumen = 0.08;  // side branch lumen radius (normalised)
constexpr double kWallVoxels = 1.5;    // wall thickness in voxels, at every size
constexpr std::uint16_t kTubeLumenValue = 0;
constexpr std::uint16_t kTubeWallValue = 200;
constexpr std::uint16_t kTubeTissueValue = 40;

// Squared distance from p to the segment [a, b].
double segment_distance2(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab{b.x - a.x, b.y - a.y, b.z - a.z};
  const Vec3 ap{p.x - a.x, p.y - a.y, p.z - a.z};
  const double len2 = ab.x * ab.x + ab.y * ab.y + ab.z * ab.z;
  const double t = std::clamp((ap.x * ab.x + ap.y * ab.y + ap.z * ab.z) / len2, 0.0, 1.0);
  const Vec3 d{ap.x - t * ab.x, ap.y - t * ab.y, ap.z - t * ab.z};
  return d.x * d.x + d.y * d.y + d.z * d.z;
}

// Squared distance from p to the quarter circle in the plane y = 0 with centre
// c and radius r that runs from c + (-r, 0, 0) to c + (0, 0, r).
double arc_distance2(const Vec3& p, const Vec3& c, double r) {
  const double qx = p.x - c.x, qz = p.z - c.z;
  if (qx <= 0.0 && qz >= 0.0) {
    const double radial = std::sqrt(qx * qx + qz * qz) - r;
    return radial * radial + p.y * p.y;
  }
  const double d_start = (qx + r) * (qx + r) + p.y * p.y + qz * qz;
  const double d_end = qx * qx + p.y * p.y + (qz - r) * (qz - r);
  return std::min(d_start, d_end);
}

void fill_tube(Volume& v, SubVoxel o) {
  const int n = v.dims[0];
  const double h = static_cast<double>(n - 1) / 2.0;  // voxels per normalised unit
  auto at = [h](double x, double y, double z) { return Vec3{x * h, y * h, z * h}; };
  // Centreline pieces (normalised): straight along +z, quarter bend towards +x,
  // straight along +x; branches along +y and -y.
  const Vec3 s1a = at(-0.3, 0.0, -0.9), s1b = at(-0.3, 0.0, 0.0);
  const Vec3 arc_c = at(0.2, 0.0, 0.0);
  const double arc_r = 0.5 * h;
  const Vec3 s2a = at(0.2, 0.0, 0.5), s2b = at(0.9, 0.0, 0.5);
  const Vec3 b1a = at(-0.3, 0.0, -0.45), b1b = at(-0.3, 0.7, -0.45);
  const Vec3 b2a = at(0.55, 0.0, 0.5), b2b = at(0.55, -0.7, 0.5);
  const double tube_r = kTubeLumen * h, branch_r = kBranchLumen * h;
  const double tube_lumen2 = tube_r * tube_r, branch_lumen2 = branch_r * branch_r;
  const double tube_outer2 = (tube_r + kWallVoxels) * (tube_r + kWallVoxels);
  const double branch_outer2 = (branch_r + kWallVoxels) * (branch_r + kWallVoxels);
  // Row culling (only skips work): the main tube and its wall lie within
  // tube_r + 1.5 voxels of the plane y = 0, each branch and its wall within
  // branch_r + 1.5 voxels of its plane z = const; other rows are pure tissue.
  const double reach = tube_r + kWallVoxels + 1.0;
  parallel_for(n, [&](int z) {
    const double pz = static_cast<double>(z) + o.z - h;
    for (int y = 0; y < n; ++y) {
      const double py = static_cast<double>(y) + o.y - h;
      std::uint16_t* row = &v.data[v.index(0, y, z)];
      const bool near_plane = std::abs(py) <= reach;
      const bool near_branch1 = std::abs(pz - b1a.z) <= reach;
      const bool near_branch2 = std::abs(pz - b2a.z) <= reach;
      if (!near_plane && !near_branch1 && !near_branch2) {
        std::fill(row, row + n, kTubeTissueValue);
        continue;
      }
      for (int x = 0; x < n; ++x) {
        const Vec3 p{static_cast<double>(x) + o.x - h, py, pz};
        const double d_s1 = segment_distance2(p, s1a, s1b);
        const double d_arc = arc_distance2(p, arc_c, arc_r);
        const double d_s2 = segment_distance2(p, s2a, s2b);
        const double d_b1 = segment_distance2(p, b1a, b1b);
        const double d_b2 = segment_distance2(p, b2a, b2b);
        const double d_main = std::min({d_s1, d_arc, d_s2});
        const double d_branch = std::min(d_b1, d_b2);
        std::uint16_t value = kTubeTissueValue;
        if (d_main <= tube_lumen2 || d_branch <= branch_lumen2)
          value = kTubeLumenValue;
        else if (d_main <= tube_outer2 || d_branch <= branch_outer2)
          value = kTubeWallValue;
        row[x] = value;
      }
    }
  });
}

// --- box --------------------------------------------------------------------------
// 200 where all three indices are in [n/4, n-1-n/4] (integer division), 0 elsewhere.
constexpr std::uint16_t kBoxValue = 200;

// The box is axis-aligned on voxel boundaries: partial volume leaves it as is.
void fill_box(Volume& v, SubVoxel) {
  const int n = v.dims[0];
  const int lo = n / 4, hi = n - 1 - n / 4;
  parallel_for(n, [&](int z) {
    for (int y = 0; y < n; ++y) {
      std::uint16_t* row = &v.data[v.index(0, y, z)];
      const bool inside_yz = y >= lo && y <= hi && z >= lo && z <= hi;
      for (int x = 0; x < n; ++x)
        row[x] = (inside_yz && x >= lo && x <= hi) ? kBoxValue : std::uint16_t{0};
    }
  });
}

// --- grating ------------------------------------------------------------------
// Planes of constant x: 128 + 100 cos(2 pi x / 3), x the voxel index (plus the
// sub-voxel offset). A period of 3 voxels (1/3 cycle per voxel, two thirds of
// Nyquist) is where a two-tap interpolation's shift variance shows most: a
// rotated view resamples it at every fractional offset, and the beat between
// the grating and the sampling grid is the Moire pattern the VIRIM paper
// compares the Gaussian mask and trilinear interpolation on (docs/accuracy.md).
constexpr double kGratingPeriod = 3.0;
constexpr double kGratingMean = 128.0;
constexpr double kGratingAmplitude = 100.0;

void fill_grating(Volume& v, SubVoxel o) {
  const int n = v.dims[0];
  std::vector<std::uint16_t> row(static_cast<std::size_t>(n));
  for (int x = 0; x < n; ++x)
    row[static_cast<std::size_t>(x)] = static_cast<std::uint16_t>(std::lround(
        kGratingMean + kGratingAmplitude * std::cos(2.0 * std::numbers::pi * (x + o.x) / kGratingPeriod)));
  parallel_for(n, [&](int z) {
    for (int y = 0; y < n; ++y) std::copy(row.begin(), row.end(), &v.data[v.index(0, y, z)]);
  });
}

// Partial volume: the mean of aa^3 point samples on a regular sub-grid of each
// voxel (what a scanner's finite voxel integrates), rounded to the nearest
// stored value. aa = 1 samples the voxel centre only.
void fill_partial_volume(Volume& v, void (*fill)(Volume&, SubVoxel), int aa) {
  if (aa == 1) {
    fill(v, SubVoxel{});
    return;
  }
  std::vector<std::uint32_t> sum(v.voxel_count(), 0);
  Volume sub = v;
  for (int k = 0; k < aa; ++k)
    for (int j = 0; j < aa; ++j)
      for (int i = 0; i < aa; ++i) {
        const auto offset = [aa](int t) { return (t + 0.5) / aa - 0.5; };
        fill(sub, SubVoxel{offset(i), offset(j), offset(k)});
        for (std::size_t n = 0; n < sum.size(); ++n) sum[n] += sub.data[n];
      }
  const std::uint32_t count = static_cast<std::uint32_t>(aa * aa * aa);
  for (std::size_t n = 0; n < sum.size(); ++n)
    v.data[n] = static_cast<std::uint16_t>((sum[n] + count / 2) / count);
}

}  // namespace

Volume make_phantom(const std::string& name, int size, int aa) {
  void (*fill)(Volume&, SubVoxel) = nullptr;
  if (name == "shepp-logan")
    fill = fill_shepp_logan;
  else if (name == "shells")
    fill = fill_shells;
  else if (name == "tube")
    fill = fill_tube;
  else if (name == "box")
    fill = fill_box;
  else if (name == "grating")
    fill = fill_grating;
  else
    throw Error("phantom '" + name + "' is unknown (the built-in phantoms are " + kPhantomNames +
                ")");
  if (size < kMinSize || size > kMaxSize)
    throw Error("phantom:" + name + ": size " + std::to_string(size) + " is outside " +
                std::to_string(kMinSize) + ".." + std::to_string(kMaxSize));
  if (aa < 1 || aa > 8)
    throw Error("phantom:" + name + ": aa " + std::to_string(aa) +
                " is outside 1..8 (sub-samples per voxel edge)");

  Volume v;
  v.dims = {size, size, size};
  v.spacing = glm::dvec3(1.0);
  v.bits = 8;
  v.slope = 1.0;
  v.intercept = 0.0;
  v.source = "phantom:" + name + "?size=" + std::to_string(size) +
             (aa > 1 ? "&aa=" + std::to_string(aa) : "");
  v.data.assign(v.voxel_count(), 0);
  fill_partial_volume(v, fill, aa);
  validate(v, v.source);
  return v;
}

}  // namespace voxcast::ref
