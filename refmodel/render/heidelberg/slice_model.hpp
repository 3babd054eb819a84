// The Heidelberg Raytracing Model on one constant-z plane of the rotated cube
// (virim-1994.txt, "Algorithm"; Meinzer et al. 1991), in double precision: the
// ground truth of hls/virim/slice_processor.hpp. Every formula is in
// docs/heidelberg.md §5.
#pragma once

#include <cstdint>
#include <vector>

#include "refmodel/scene/scene.hpp"

namespace voxcast::ref::heidelberg {

struct SliceParams {
  double light = 1.0;  // L: both lights' intensity where they enter the cube
  double diffuse_0 = 0.6, diffuse_45 = 0.4, specular_45 = 0.4, luminosity = 0.2;
  int shininess = 8;
  double background_threshold = 0.95;
};
SliceParams slice_params(const HeidelbergDesc& h);

// Below this gradient norm the Phong terms fade linearly to 0 (docs/heidelberg.md
// §5.3): a weak gradient's direction is noise (a homogeneous region's resampled
// densities differ in their last bits), and a hard cut would make the image
// jump where |g| crosses it. hls/virim uses the same 2^-6.
inline constexpr double kNormalFade = 1.0 / 64.0;

// Phong factors of one voxel from its gradient (§5.3): the normal n = −g/|g|,
// lights towards (0,−1,0) (0 deg) and (−1,−1,0)/√2 (45 deg), viewer (0,−1,0).
struct PhongFactors {
  double c0 = 0.0;    // n · L0 (= n · V)
  double c45 = 0.0;   // n · L45
  double rv = 0.0;    // R45 · V = 2 c45 c0 − 1/√2
  double surface = 0.0;  // surface probability min(1, 2|g|)
  double fade = 0.0;     // min(1, |g| / kNormalFade): weight of every Phong term
};
PhongFactors phong_factors(double gx, double gy, double gz);

// What one voxel sends towards the viewer (§5.4), given the light arriving
// from each source (I0, I45) and its density.
double scattered(const SliceParams& s, double I0, double I45, double rho, const PhongFactors& ph);

struct Line {
  std::vector<double> value;              // per x: light reaching the viewer, clamped to [0, 1]
  std::vector<std::uint8_t> background;   // per x: 1 where the 0 deg light leaving the far end
                                          // exceeds the threshold (§5.6)
  std::vector<double> transmitted;        // per x: the 0 deg light's transmittance T0 there
};

// The model on one plane: rho, gx, gy, gz are W x D, x fastest; row j = 0 is
// nearest the viewer. gz may be null (2D gradients).
Line trace_slice(const SliceParams& s, int W, int D, const double* rho, const double* gx,
                 const double* gy, const double* gz);

}  // namespace voxcast::ref::heidelberg
