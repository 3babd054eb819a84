// VIRIM's rotator in double precision (the ground truth of hls/virim/): the
// gray-value LUT, rotation about any axis, translation, zoom and perspective,
// and the resampling of the data cube into view space, where the viewer looks
// along +y (virim-1994.txt, "Algorithm" and "Rotator Board"; docs/heidelberg.md §1-3).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "refmodel/scene/scene.hpp"
#include "refmodel/volume/volume.hpp"

namespace voxcast::ref::heidelberg {

// The view cube's size: W = image width (x), D = depth (y, along the view),
// H = image height (z; one constant-z plane is one image line).
struct ViewDims {
  int W = 0, D = 0, H = 0;
};
ViewDims view_dims(const Scene& scene, const Volume& volume);

// Where the output voxel (i, j, k) of the view cube samples the data cube
// (docs/heidelberg.md §2): p = c + R^T (s_j · v / zoom − t), v the offset of
// (i, j, k) from the view cube's centre with its x and z scaled by the plane's
// perspective factor s_j.
struct ViewTransform {
  glm::dmat3 to_data{1.0};  // R^T: view axes -> data axes
  glm::dvec3 volume_center{0.0};
  glm::dvec3 translation{0.0};
  double zoom = 1.0;
  double eye_distance = 0.0;  // 0: parallel
  ViewDims dims;
};

// Rotation by `angle_deg` about `axis` (right-handed, Rodrigues' formula).
glm::dmat3 rotation_matrix(const glm::dvec3& axis, double angle_deg);

// `eye_offset_deg`: the stereo eye's extra rotation about the view's z axis.
ViewTransform make_view_transform(const HeidelbergDesc& h, const Volume& volume, ViewDims dims,
                                  double eye_offset_deg);

// Perspective (§2.3): the factor by which plane j's x and z offsets are
// scaled, (E + y_j) / E, so the pyramid of the view maps onto the cube.
double plane_scale(const ViewTransform& vt, int j);
glm::dvec3 data_position(const ViewTransform& vt, int i, int j, int k);

// The eight interpolation weights at fractional offset f in [0, 1)^3, corner
// c = cx + 2 cy + 4 cz at offset c from the lower neighbour. Both sum to 1.
std::array<double, 8> trilinear_weights(const glm::dvec3& f);
// Gaussian mask (§3.2): per axis a(d) = g(d) / (g(d) + g(1 − d)), g(d) =
// exp(−d²/σ²) for d < 1 and g(1) = 0 (the paper's footnote 3: a neighbour a
// whole voxel away is handled separately and gets nothing).
double gaussian_axis_weight(double d, double sigma);
std::array<double, 8> gaussian_weights(const glm::dvec3& f, double sigma);

// The data cube after the gray-value LUT (§1): density in [0, 1] per voxel,
// with the software-set bounds outside which reads give 0.
struct DensityVolume {
  std::array<int, 3> dims{0, 0, 0};
  std::array<int, 3> lo{0, 0, 0}, hi{0, 0, 0};  // inclusive bounds (volume.crop)
  std::vector<double> rho;                       // x fastest
  double at(int x, int y, int z) const;          // 0 outside [lo, hi]
};

// The gray-value LUT: the classification's alpha at each stored value,
// 2^volume.bits entries (our reading: density = the transfer function's alpha).
std::vector<double> density_lut(const Scene& scene, const Volume& volume);
DensityVolume make_density_volume(const Scene& scene, const Volume& volume);

double resample(const DensityVolume& dv, const glm::dvec3& p, HeidelbergInterpolation interp,
                double sigma);

// One constant-z plane of the view cube, W x D, x fastest.
struct Plane {
  int W = 0, D = 0;
  std::vector<double> v;
  Plane() = default;
  Plane(int w, int d) : W(w), D(d), v(static_cast<std::size_t>(w) * static_cast<std::size_t>(d), 0.0) {}
  double at(int i, int j) const {
    return (i < 0 || j < 0 || i >= W || j >= D) ? 0.0
                                                : v[static_cast<std::size_t>(j) * W + i];
  }
  double& at(int i, int j) { return v[static_cast<std::size_t>(j) * W + i]; }
};

// Plane k of the view cube (all zeros for k outside [0, H)).
Plane rotate_plane(const DensityVolume& dv, const ViewTransform& vt, HeidelbergInterpolation interp,
                   double sigma, int k);

// Sobel gradients (§4): 2D in the plane (x, y), as on VIRIM's gradient
// processor, normalized by 1/8 so a ramp of slope 1 gives 1; with `below` and
// `above` (3D option) the 3x3x3 Sobel normalized by 1/32, gz included.
struct PlaneGradients {
  Plane gx, gy, gz;  // gz is all zeros for the 2D operator
};
PlaneGradients sobel(const Plane& mid, const Plane* below, const Plane* above);

}  // namespace voxcast::ref::heidelberg
