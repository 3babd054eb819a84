#include "cosim/warnings.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iomanip>
#include <limits>
#include <sstream>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/render/raycaster.hpp"

namespace voxcast::cosim {
namespace {

// The table entry holds U(opacity_correct(alpha, step), alpha_bits)
// (bittrue::make_class_table): 0 exactly when the step opacity is below half an
// LSB, 2^-(alpha_bits + 1) (Q_RND rounds a tie up, to one LSB).
void alpha_warnings(const ref::Scene& scene, std::vector<std::string>& out) {
  const int ab = scene.precision.alpha_bits;
  const double step = 1.0 / scene.render.oversampling;
  const double half_lsb = std::ldexp(1.0, -(ab + 1));
  for (std::size_t i = 0; i < scene.tf_points.size(); ++i) {
    const double alpha = scene.tf_points[i].alpha;
    if (!(alpha > 0.0)) continue;
    const double step_opacity = ref::opacity_correct(alpha, step);
    if (bittrue::u_frac(step_opacity, ab) > 0.0) continue;
    std::ostringstream w;
    w << "classification.points[" << i << "] alpha " << alpha << " vanishes at oversampling "
      << scene.render.oversampling << ": its step opacity " << std::setprecision(2) << step_opacity
      << " is below half an LSB of precision.alpha_bits = " << ab << " (" << std::setprecision(3)
      << half_lsb << ")";
    out.push_back(w.str());
  }
}

// Binary classification: point i classifies the values in [lo_i, hi_i) (from its
// value up to the next point's; the first point also everything below, the last
// everything above). The float reference classifies the continuous interpolated
// values, 0 .. max_stored; the table sees only its entries, at stored values
// k·spacing, k = 0 .. 2^tf_addr_bits - 1, spacing = 2^(value_bits - tf_addr_bits -
// value_shift) (§3.4, §4.2), and a sample reads the nearest one (ties up), so the
// entries a sample can read lie below max_stored + spacing/2.
void table_warnings(const ref::Scene& scene, const ref::Volume& volume,
                    std::vector<std::string>& out) {
  if (scene.tf_interpolation != ref::TfInterpolation::Binary) return;
  const PrecisionProfile& p = scene.precision;
  const ref::TransferFunction tf = ref::stored_transfer_function(scene, volume);
  const std::vector<ref::TfPoint>& pts = tf.points();  // stored units, sorted
  const double spacing =
      std::ldexp(1.0, p.value_bits - p.tf_addr_bits - bittrue::value_shift(p, volume));
  const double last_entry = (std::ldexp(1.0, p.tf_addr_bits) - 1.0) * spacing;
  const double data_hi = volume.max_stored();
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!(pts[i].alpha > 0.0)) continue;
    const double lo = i == 0 ? -inf : pts[i].value;
    const double hi = i + 1 == pts.size() ? inf : pts[i + 1].value;  // exclusive
    // Not in the float image either: an empty interval, or none of it in the data range.
    if (!(lo < hi) || lo > data_hi || hi <= 0.0) continue;
    // The first entry at or above lo: readable, and below hi?
    const double entry = std::max(0.0, std::ceil(lo / spacing)) * spacing;
    if (entry <= last_entry && entry < hi && entry <= data_hi + spacing / 2) continue;
    // The scene's point index (in_stored_units reverses the order for a negative slope).
    const std::size_t index = volume.slope < 0 ? pts.size() - 1 - i : i;
    const std::size_t next = volume.slope < 0 ? index - 1 : index + 1;
    std::ostringstream w;
    w << "classification.points[" << index << "] value " << scene.tf_points[index].value
      << " vanishes: no classification-table entry lies between it and ";
    if (hi <= data_hi)
      w << "classification.points[" << next << "] value " << scene.tf_points[next].value;
    else
      w << "the data's largest value " << volume.to_physical(data_hi);
    w << " (precision.tf_addr_bits = " << p.tf_addr_bits << ": entries every " << spacing
      << " stored values, the last at " << volume.to_physical(last_entry) << ")";
    out.push_back(w.str());
  }
}

}  // namespace

std::vector<std::string> fixed_point_warnings(const ref::Scene& scene, const ref::Volume& volume) {
  std::vector<std::string> out;
  if (scene.render.mode == ref::RenderMode::Mip) return out;
  alpha_warnings(scene, out);
  table_warnings(scene, volume, out);
  return out;
}

}  // namespace voxcast::cosim
