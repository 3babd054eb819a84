#include "refmodel/render/heidelberg/rotator.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

#include "refmodel/error.hpp"

namespace voxcast::ref::heidelberg {

ViewDims view_dims(const Scene& scene, const Volume& volume) {
  const int depth = scene.heidelberg.depth > 0
                        ? scene.heidelberg.depth
                        : std::max({volume.dims[0], volume.dims[1], volume.dims[2]});
  return {scene.render.width, depth, scene.render.height};
}

glm::dmat3 rotation_matrix(const glm::dvec3& axis, double angle_deg) {
  const glm::dvec3 u = glm::normalize(axis);
  const double a = angle_deg * std::numbers::pi / 180.0;
  // Exact for multiples of 90 degrees, so such rotations permute voxels exactly.
  const double turns = angle_deg / 90.0;
  double c = std::cos(a), s = std::sin(a);
  if (turns == std::round(turns)) {
    const long q = ((static_cast<long>(std::round(turns)) % 4) + 4) % 4;
    c = q == 0 ? 1.0 : q == 2 ? -1.0 : 0.0;
    s = q == 1 ? 1.0 : q == 3 ? -1.0 : 0.0;
  }
  const double t = 1.0 - c;
  // Column-major (glm): m[col][row].
  glm::dmat3 m;
  m[0] = {t * u.x * u.x + c, t * u.x * u.y + s * u.z, t * u.x * u.z - s * u.y};
  m[1] = {t * u.x * u.y - s * u.z, t * u.y * u.y + c, t * u.y * u.z + s * u.x};
  m[2] = {t * u.x * u.z + s * u.y, t * u.y * u.z - s * u.x, t * u.z * u.z + c};
  return m;
}

ViewTransform make_view_transform(const HeidelbergDesc& h, const Volume& volume, ViewDims dims,
                                  double eye_offset_deg) {
  if (h.perspective > 0.0 && h.perspective <= 0.5 * (dims.D - 1))
    throw Error("heidelberg.perspective = " + std::to_string(h.perspective) +
                " must exceed half the view cube's depth (" + std::to_string(dims.D) +
                " voxels): the eye must be outside the cube");
  ViewTransform vt;
  // The stereo eye turns the rotated cube about the view's z axis (§6).
  const glm::dmat3 r = rotation_matrix({0.0, 0.0, 1.0}, eye_offset_deg) *
                       rotation_matrix(h.axis, h.angle_deg);
  vt.to_data = glm::transpose(r);
  vt.volume_center = 0.5 * glm::dvec3(volume.dims[0] - 1, volume.dims[1] - 1, volume.dims[2] - 1);
  vt.translation = h.translation;
  vt.zoom = h.zoom;
  vt.eye_distance = h.perspective;
  vt.dims = dims;
  return vt;
}

double plane_scale(const ViewTransform& vt, int j) {
  if (vt.eye_distance <= 0.0) return 1.0;
  const double y = j - 0.5 * (vt.dims.D - 1);
  return (vt.eye_distance + y) / vt.eye_distance;
}

glm::dvec3 data_position(const ViewTransform& vt, int i, int j, int k) {
  const double s = plane_scale(vt, j);
  const glm::dvec3 v{(i - 0.5 * (vt.dims.W - 1)) * s, j - 0.5 * (vt.dims.D - 1),
                     (k - 0.5 * (vt.dims.H - 1)) * s};
  return vt.volume_center + vt.to_data * (v / vt.zoom - vt.translation);
}

namespace {
std::array<double, 8> separable(const std::array<double, 3>& lo) {
  std::array<double, 8> w{};
  for (int c = 0; c < 8; ++c) {
    double p = 1.0;
    for (int a = 0; a < 3; ++a)
      p *= ((c >> a) & 1) ? 1.0 - lo[static_cast<std::size_t>(a)] : lo[static_cast<std::size_t>(a)];
    w[static_cast<std::size_t>(c)] = p;
  }
  return w;
}
}  // namespace

std::array<double, 8> trilinear_weights(const glm::dvec3& f) {
  return separable({1.0 - f.x, 1.0 - f.y, 1.0 - f.z});
}

double gaussian_axis_weight(double d, double sigma) {
  const auto g = [sigma](double x) { return x >= 1.0 ? 0.0 : std::exp(-(x * x) / (sigma * sigma)); };
  return g(d) / (g(d) + g(1.0 - d));
}

std::array<double, 8> gaussian_weights(const glm::dvec3& f, double sigma) {
  return separable({gaussian_axis_weight(f.x, sigma), gaussian_axis_weight(f.y, sigma),
                    gaussian_axis_weight(f.z, sigma)});
}

double DensityVolume::at(int x, int y, int z) const {
  if (x < lo[0] || y < lo[1] || z < lo[2] || x > hi[0] || y > hi[1] || z > hi[2]) return 0.0;
  return rho[(static_cast<std::size_t>(z) * static_cast<std::size_t>(dims[1]) +
              static_cast<std::size_t>(y)) * static_cast<std::size_t>(dims[0]) +
             static_cast<std::size_t>(x)];
}

std::vector<double> density_lut(const Scene& scene, const Volume& volume) {
  const TransferFunction tf = stored_transfer_function(scene, volume);
  std::vector<double> lut(static_cast<std::size_t>(volume.max_stored()) + 1);
  for (std::size_t v = 0; v < lut.size(); ++v)
    lut[v] = std::clamp(tf.classify(static_cast<double>(v)).alpha, 0.0, 1.0);
  return lut;
}

DensityVolume make_density_volume(const Scene& scene, const Volume& volume) {
  DensityVolume dv;
  dv.dims = volume.dims;
  dv.hi = {volume.dims[0] - 1, volume.dims[1] - 1, volume.dims[2] - 1};
  if (scene.volume.crop) {
    dv.lo = scene.volume.crop->lo;
    dv.hi = scene.volume.crop->hi;
  }
  const std::vector<double> lut = density_lut(scene, volume);
  dv.rho.resize(volume.data.size());
  for (std::size_t n = 0; n < volume.data.size(); ++n) dv.rho[n] = lut[volume.data[n]];
  return dv;
}

double resample(const DensityVolume& dv, const glm::dvec3& p, HeidelbergInterpolation interp,
                double sigma) {
  const glm::dvec3 i0 = glm::floor(p);
  const glm::dvec3 f = p - i0;
  const std::array<double, 8> w = interp == HeidelbergInterpolation::Trilinear
                                      ? trilinear_weights(f)
                                      : gaussian_weights(f, sigma);
  // Far outside the cube every neighbour reads 0; skip the int conversion.
  for (int a = 0; a < 3; ++a)
    if (i0[a] < -2.0 || i0[a] > dv.dims[static_cast<std::size_t>(a)] + 1.0) return 0.0;
  const int x = static_cast<int>(i0.x), y = static_cast<int>(i0.y), z = static_cast<int>(i0.z);
  double sum = 0.0;
  for (int c = 0; c < 8; ++c)
    sum += w[static_cast<std::size_t>(c)] * dv.at(x + (c & 1), y + ((c >> 1) & 1), z + ((c >> 2) & 1));
  return sum;
}

Plane rotate_plane(const DensityVolume& dv, const ViewTransform& vt, HeidelbergInterpolation interp,
                   double sigma, int k) {
  Plane pl(vt.dims.W, vt.dims.D);
  if (k < 0 || k >= vt.dims.H) return pl;
  for (int j = 0; j < vt.dims.D; ++j)
    for (int i = 0; i < vt.dims.W; ++i) pl.at(i, j) = resample(dv, data_position(vt, i, j, k), interp, sigma);
  return pl;
}

PlaneGradients sobel(const Plane& mid, const Plane* below, const Plane* above) {
  PlaneGradients g{Plane(mid.W, mid.D), Plane(mid.W, mid.D), Plane(mid.W, mid.D)};
  constexpr double s[3] = {1.0, 2.0, 1.0};
  const bool three_d = below && above;
  const Plane* planes[3] = {below, &mid, above};
  for (int j = 0; j < mid.D; ++j)
    for (int i = 0; i < mid.W; ++i) {
      double gx = 0.0, gy = 0.0, gz = 0.0;
      if (!three_d) {
        for (int d = -1; d <= 1; ++d) {
          gx += s[d + 1] * (mid.at(i + 1, j + d) - mid.at(i - 1, j + d));
          gy += s[d + 1] * (mid.at(i + d, j + 1) - mid.at(i + d, j - 1));
        }
        g.gx.at(i, j) = gx / 8.0;
        g.gy.at(i, j) = gy / 8.0;
        continue;
      }
      for (int dk = -1; dk <= 1; ++dk)
        for (int d = -1; d <= 1; ++d) {
          const Plane& p = *planes[dk + 1];
          gx += s[d + 1] * s[dk + 1] * (p.at(i + 1, j + d) - p.at(i - 1, j + d));
          gy += s[d + 1] * s[dk + 1] * (p.at(i + d, j + 1) - p.at(i + d, j - 1));
        }
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
          gz += s[di + 1] * s[dj + 1] * (above->at(i + di, j + dj) - below->at(i + di, j + dj));
      g.gx.at(i, j) = gx / 32.0;
      g.gy.at(i, j) = gy / 32.0;
      g.gz.at(i, j) = gz / 32.0;
    }
  return g;
}

}  // namespace voxcast::ref::heidelberg
