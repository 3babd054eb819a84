#include "refmodel/render/heidelberg/slice_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace voxcast::ref::heidelberg {

SliceParams slice_params(const HeidelbergDesc& h) {
  return {h.light, h.diffuse_0, h.diffuse_45, h.specular_45, h.luminosity, h.shininess,
          h.background_threshold};
}

PhongFactors phong_factors(double gx, double gy, double gz) {
  PhongFactors ph;
  const double m = std::sqrt(gx * gx + gy * gy + gz * gz);
  ph.surface = std::min(1.0, 2.0 * m);
  ph.fade = std::min(1.0, m / kNormalFade);
  if (m == 0.0) return ph;  // no direction at all
  const double r = 1.0 / std::numbers::sqrt2;
  ph.c0 = gy / m;
  ph.c45 = (gx + gy) * r / m;
  ph.rv = 2.0 * ph.c45 * ph.c0 - r;
  return ph;
}

double scattered(const SliceParams& s, double I0, double I45, double rho, const PhongFactors& ph) {
  // §5.2: the energy each light deposits in the voxel bounds what it scatters.
  const double e0 = I0 * rho, e45 = I45 * rho;
  const double spec = std::pow(std::max(0.0, ph.rv), s.shininess) * ph.surface * ph.fade;
  const double e = e0 * s.diffuse_0 * std::max(0.0, ph.c0) * ph.fade +
                   e45 * (s.diffuse_45 * std::max(0.0, ph.c45) * ph.fade + s.specular_45 * spec) +
                   s.luminosity * 0.5 * (e0 + e45);
  return std::min(e0 + e45, e);
}

Line trace_slice(const SliceParams& s, int W, int D, const double* rho, const double* gx,
                 const double* gy, const double* gz) {
  // T0[x]: the 0 deg light's transmittance down column x, which is also the
  // way back to the viewer; T45[x]: the 45 deg light arriving at (x, j).
  std::vector<double> t0(static_cast<std::size_t>(W), 1.0), t45(static_cast<std::size_t>(W), 1.0);
  std::vector<double> acc(static_cast<std::size_t>(W), 0.0);
  std::vector<double> next45(static_cast<std::size_t>(W), 1.0);
  for (int j = 0; j < D; ++j) {
    for (int x = 0; x < W; ++x) {
      const std::size_t n = static_cast<std::size_t>(j) * W + x, ux = static_cast<std::size_t>(x);
      const double r = rho[n];
      const PhongFactors ph = phong_factors(gx[n], gy[n], gz ? gz[n] : 0.0);
      acc[ux] += scattered(s, s.light * t0[ux], s.light * t45[ux], r, ph) * t0[ux];
      t0[ux] *= 1.0 - r;
      // The 45 deg light leaving (x, j) arrives at (x + 1, j + 1); light enters
      // unattenuated at x = 0 (the cube's side).
      if (x + 1 < W) next45[ux + 1] = t45[ux] * (1.0 - r);
    }
    next45[0] = 1.0;
    std::swap(t45, next45);
  }
  Line line;
  line.value.resize(static_cast<std::size_t>(W));
  line.background.resize(static_cast<std::size_t>(W));
  line.transmitted = t0;
  for (std::size_t x = 0; x < acc.size(); ++x) {
    line.value[x] = std::min(1.0, acc[x]);
    line.background[x] = t0[x] > s.background_threshold ? 1 : 0;
  }
  return line;
}

}  // namespace voxcast::ref::heidelberg
