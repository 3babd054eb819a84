#include "refmodel/volume/transfer_function.hpp"

#include <algorithm>
#include <utility>

#include "refmodel/error.hpp"

namespace voxcast::ref {

TransferFunction::TransferFunction(std::vector<TfPoint> points, TfInterpolation interpolation,
                                   Material material)
    : points_(std::move(points)), interpolation_(interpolation), material_(material) {
  if (points_.empty()) throw Error("transfer function needs at least one control point");
  for (std::size_t i = 1; i < points_.size(); ++i)
    if (points_[i].value < points_[i - 1].value)
      throw Error("transfer function control point " + std::to_string(i) + " (value " +
                  std::to_string(points_[i].value) + ") is below the one before it (" +
                  std::to_string(points_[i - 1].value) + "): points must be sorted by value");
}

TransferFunction TransferFunction::in_stored_units(const Volume& volume) const {
  std::vector<TfPoint> stored = points_;
  for (TfPoint& p : stored) p.value = volume.to_stored(p.value);
  // A negative slope reverses the order; keep the points sorted.
  if (volume.slope < 0) std::reverse(stored.begin(), stored.end());
  return TransferFunction(std::move(stored), interpolation_, material_);
}

Classified TransferFunction::classify(double value) const {
  // First point strictly above `value`: [lo, hi) brackets it.
  const auto hi = std::upper_bound(points_.begin(), points_.end(), value,
                                   [](double v, const TfPoint& p) { return v < p.value; });
  glm::dvec3 color;
  double alpha;
  if (hi == points_.begin()) {
    color = hi->color;
    alpha = hi->alpha;
  } else if (hi == points_.end() || interpolation_ == TfInterpolation::Binary) {
    const TfPoint& p = *(hi - 1);
    color = p.color;
    alpha = p.alpha;
  } else {
    const TfPoint& a = *(hi - 1);
    const TfPoint& b = *hi;
    const double f = (value - a.value) / (b.value - a.value);  // b.value > a.value here
    color = a.color + f * (b.color - a.color);
    alpha = a.alpha + f * (b.alpha - a.alpha);
  }
  return Classified{color, alpha, material_.ka, material_.kd, material_.ks};
}

double TransferFunction::max_alpha(double lo, double hi) const {
  double m = std::max(classify(lo).alpha, classify(hi).alpha);
  for (const TfPoint& p : points_)
    if (p.value >= lo && p.value <= hi) m = std::max({m, p.alpha, classify(p.value).alpha});
  return m;
}

TfInterpolation parse_tf_interpolation(const std::string& name) {
  if (name == "ramp") return TfInterpolation::Ramp;
  if (name == "binary") return TfInterpolation::Binary;
  throw Error("unknown transfer-function interpolation \"" + name +
              "\" (expected \"ramp\" or \"binary\")");
}

const char* to_string(TfInterpolation i) {
  return i == TfInterpolation::Ramp ? "ramp" : "binary";
}

}  // namespace voxcast::ref
