// Classification: the transfer function from a sample value to
// (r, g, b, alpha, ka, kd, ks) — the tuple VIZARD II's classification table
// delivers (section 2.1, "two 32 bit SRAMs").
//
// Control points are given in the data's physical unit (HU, scanner intensity)
// and converted to stored units once, so the reference evaluates the transfer
// function at the continuous interpolated value (the truth); the hardware table
// quantises that value to its address width.
//
// alpha is opacity per world unit of distance (one voxel of the smallest
// spacing); the compositor corrects it for the actual sampling distance.
#pragma once

#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "refmodel/volume/volume.hpp"

namespace voxcast::ref {

enum class TfInterpolation {
  Ramp,    // piecewise linear between control points
  Binary,  // zero-order hold: a point's values hold up to the next point (a step)
};

struct TfPoint {
  double value = 0.0;               // physical unit
  glm::dvec3 color{1.0, 1.0, 1.0};  // each in [0, 1]
  double alpha = 0.0;               // [0, 1], per unit distance
  friend bool operator==(const TfPoint&, const TfPoint&) = default;
};

struct Material {
  double ka = 0.1;          // ambient
  double kd = 0.7;          // diffuse
  double ks = 0.2;          // specular
  double shininess = 20.0;  // Phong exponent
  friend bool operator==(const Material&, const Material&) = default;
};

struct Classified {
  glm::dvec3 color{0.0};
  double alpha = 0.0;
  double ka = 0.0, kd = 0.0, ks = 0.0;
};

class TransferFunction {
 public:
  TransferFunction() = default;
  // Points must be sorted by value (equal values allowed: a vertical step).
  TransferFunction(std::vector<TfPoint> points, TfInterpolation interpolation, Material material);

  // Re-expresses the control points in the stored units of `volume`.
  TransferFunction in_stored_units(const Volume& volume) const;

  // Evaluates at a value in the units the points are in. Outside the points'
  // range the end points' values hold.
  Classified classify(double value) const;

  // The largest opacity classify() gives over [lo, hi] (lo <= hi): the end
  // values and every control point inside, where a piecewise linear or step
  // function takes its extremes. Space leaping's emptiness test.
  double max_alpha(double lo, double hi) const;

  const std::vector<TfPoint>& points() const { return points_; }
  TfInterpolation interpolation() const { return interpolation_; }
  const Material& material() const { return material_; }

 private:
  std::vector<TfPoint> points_;
  TfInterpolation interpolation_ = TfInterpolation::Ramp;
  Material material_;
};

TfInterpolation parse_tf_interpolation(const std::string& name);  // "ramp" | "binary"
const char* to_string(TfInterpolation i);

}  // namespace voxcast::ref
