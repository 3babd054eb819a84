// The precision guard: the hazards a scene's profile causes, predicted at load
// time from the scene, the volume and the widths, before anything renders.
// Each is an input that is valid, and that the float reference renders, but
// that the fixed-point design renders far from it without failing: a material
// that vanishes, a feature of the transfer function that no table entry
// holds, a step opacity that rounds by a large factor, a reflectance map that
// saturates. Unlike the errors of check_fixed_point (a width that cannot hold a
// value at all), the render proceeds; each hazard is one line on stderr,
// "voxcast: warning: ...", and is carried in the JSON reports; with --strict
// the command refuses the scene instead (PrecisionHazardError, exit status 6).
//
// A hazard names the scene key that causes it, the key's value, the width that
// cannot hold it and the predicted worst-case error of an output channel in
// LSB of precision.out_bits: what one ray can lose at most, from the closed
// forms below (docs/extremes.md, "The precision guard"). A hazard is reported
// when that worst case reaches kHazardFraction of the output range; below it
// the effect is within the ordinary quantization error of the widths.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "refmodel/error.hpp"
#include "refmodel/scene/scene.hpp"
#include "refmodel/volume/volume.hpp"

namespace voxcast::cosim {

// The smallest predicted worst case that is reported: a sixteenth of the
// output range (16 LSB at out_bits = 8). Below it lie the ordinary rounding
// effects of a narrow profile (vizard2's 8-bit opacities round a step opacity
// by up to a few tens of percent), which docs/accuracy.md measures per scene;
// the cases the guard exists for cost from tens of LSB to the whole channel.
inline constexpr double kHazardFraction = 1.0 / 8.0;

struct Hazard {
  // "alpha-vanishes" | "alpha-rounding" | "tf-no-entry" | "tf-between-entries" |
  // "tf-narrow-feature" | "rm-saturation" | "acc-rounding" | "heidelberg-density-vanishes" |
  // "heidelberg-transmittance" | "geometry-position" | "preint-alpha-vanishes" |
  // "preint-alpha-saturates"
  std::string kind;
  std::string key;       // the scene key, e.g. "classification.points[2].alpha", "lights[1].intensity"
  double value = 0.0;    // the key's value
  std::string width;     // the width, e.g. "precision.alpha_bits = 8"
  double worst_lsb = 0;  // predicted worst-case error of one output channel, LSB of out_bits
  std::string message;   // the whole warning, one line
};

// Every hazard of the scene's profile, in the order: the camera (the sample
// positions), control points (alpha, table entries), then lights. A MIP scene
// has only the camera's (no classification, shading or opacity).
std::vector<Hazard> precision_hazards(const ref::Scene& scene, const ref::Volume& volume);

// The hazards' messages (the lines the commands print).
std::vector<std::string> fixed_point_warnings(const ref::Scene& scene, const ref::Volume& volume);

// The largest predicted worst case among the hazards (0 when there is none),
// and their keys, space-separated: the summary line, the sweep's columns and
// the scene fuzzer's bound.
double largest_worst_lsb(const std::vector<Hazard>& hazards);
std::string hazard_keys(const std::vector<Hazard>& hazards);

// [{kind, key, value, width, worst_lsb, message}, ...] for report.json and the sweep.
nlohmann::json hazards_json(const std::vector<Hazard>& hazards);

// --strict: a scene with hazards is refused.
class PrecisionHazardError : public Error {
 public:
  using Error::Error;
};

// Prints each hazard as "voxcast: warning: <message>" on `err`; with `strict`
// and at least one hazard, throws PrecisionHazardError listing them instead.
void report_hazards(const std::vector<Hazard>& hazards, bool strict, std::ostream& err);

}  // namespace voxcast::cosim
