#include "cosim/engines/warnings.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <iomanip>
#include <limits>
#include <ostream>
#include <sstream>
#include <utility>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/geometry.hpp"
#include "refmodel/bittrue/geometry_bound.hpp"
#include "refmodel/bittrue/heidelberg.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/bittrue/shading.hpp"
#include "refmodel/render/camera.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/volume/preintegration.hpp"

namespace voxcast::cosim {
namespace {

double full_scale(const PrecisionProfile& p) { return std::ldexp(1.0, p.out_bits) - 1.0; }
// The smallest worst case reported, in output LSB.
double hazard_threshold(const PrecisionProfile& p) { return kHazardFraction * full_scale(p); }

std::string guard_fmt(double x, int digits = 3) {
  std::ostringstream s;
  s << std::setprecision(digits) << x;
  return s.str();
}

// The most samples one ray takes: the volume's world diagonal at the scene's
// step (world = index · normalised spacing, step = 1/oversampling).
double max_ray_samples(const ref::Scene& scene, const ref::Volume& volume) {
  const glm::dvec3 extent = glm::dvec3(volume.dims[0], volume.dims[1], volume.dims[2]) *
                            ref::normalised_spacing(volume);
  return std::ceil(glm::length(extent) * scene.render.oversampling);
}

// The largest difference of the opacity a ray accumulates over L consecutive
// samples of one material, 1 - (1 - a)^L, between step opacities a and b, over
// L = 1 .. n: what one material's rounding can move a ray at most. The
// difference is unimodal in L (maximum at L* = ln(ln(1-b)/ln(1-a)) /
// ln((1-a)/(1-b))), so the maximum is at floor(L*) or ceil(L*), clamped to [1, n].
double slab_opacity_difference(double a, double b, double n) {
  auto opacity = [](double x, double l) { return 1.0 - std::pow(1.0 - x, l); };
  auto diff = [&](double l) { return std::abs(opacity(a, l) - opacity(b, l)); };
  if (a == b) return 0.0;
  if (a >= 1.0 || b >= 1.0 || a <= 0.0 || b <= 0.0) return diff(1.0) > diff(n) ? diff(1.0) : diff(n);
  const double la = std::log1p(-a), lb = std::log1p(-b);
  const double star = std::log(lb / la) / (la - lb);
  double best = std::max(diff(1.0), diff(n));
  for (double l : {std::floor(star), std::ceil(star)})
    if (l >= 1.0 && l <= n) best = std::max(best, diff(l));
  return best;
}

Hazard make_hazard(std::string kind, std::string key, double value, std::string width,
                   double worst_lsb) {
  Hazard h;
  h.kind = std::move(kind);
  h.key = std::move(key);
  h.value = value;
  h.width = std::move(width);
  h.worst_lsb = worst_lsb;
  return h;
}

// ---- Opacity (§4.2) and its accumulation (§7.1) -----------------------------------------
//
// A slab of one material, L samples deep: the float reference accumulates
// F(L) = 1 - (1 - x)^L with x = 1 - (1 - alpha)^step; the table holds
// q = Q_RND(x, alpha_bits), and the compositor adds w = Q_RND((1 - A)·q,
// acc_bits) per sample (bittrue::bt_composite, simulated here sample by
// sample). Over L = 1 .. n (n: the longest ray's samples) the largest
// |fixed - F| is the worst case one channel can show (the alpha channel
// carries it whole; a colour channel times the colour).
//   alpha-vanishes: q = 0 (x below half an LSB; always reported).
//   alpha-rounding: the table's rounding dominates, max |(1-q)^L - (1-x)^L|.
//   acc-rounding:   the accumulator's dominates: (1 - A)·q falls below half an
//                   LSB of acc_bits and A stalls short of 1 - (1-q)^L.
struct SlabErrors {
  double table = 0.0, accumulator = 0.0, total = 0.0;
};

SlabErrors slab_errors(const PrecisionProfile& p, double x, double q, double n) {
  SlabErrors e;
  bittrue::BtAccumulator acc;
  const std::array<double, 3> white{1.0, 1.0, 1.0};
  const auto samples = static_cast<long>(n);
  for (long l = 1; l <= samples; ++l) {
    bittrue::bt_composite(p, acc, white, q);
    const double f = 1.0 - std::pow(1.0 - x, static_cast<double>(l));
    const double t = 1.0 - std::pow(1.0 - q, static_cast<double>(l));
    e.table = std::max(e.table, std::abs(t - f));
    e.accumulator = std::max(e.accumulator, std::abs(acc.A - t));
    e.total = std::max(e.total, std::abs(acc.A - f));
  }
  return e;
}

void alpha_hazards(const ref::Scene& scene, const ref::Volume& volume, std::vector<Hazard>& out) {
  const PrecisionProfile& p = scene.precision;
  const int ab = p.alpha_bits;
  const double step = 1.0 / scene.render.oversampling;
  const double half_lsb = std::ldexp(1.0, -(ab + 1));
  const double n = max_ray_samples(scene, volume);
  for (std::size_t i = 0; i < scene.tf_points.size(); ++i) {
    const ref::TfPoint& pt = scene.tf_points[i];
    const double alpha = pt.alpha;
    if (!(alpha > 0.0) || alpha >= 1.0) continue;
    const double x = ref::opacity_correct(alpha, step);
    const double q = bittrue::u_frac(x, ab);
    const SlabErrors e = slab_errors(p, x, q, n);
    const double worst = full_scale(p) * e.total;
    if (q != 0.0 && worst < hazard_threshold(p)) continue;
    const bool accumulator = q != 0.0 && e.accumulator > e.table;
    Hazard h = make_hazard("", "classification.points[" + std::to_string(i) + "].alpha", alpha,
                           accumulator ? "precision.acc_bits = " + std::to_string(p.acc_bits)
                                       : "precision.alpha_bits = " + std::to_string(ab),
                           worst);
    std::ostringstream w;
    if (q == 0.0) {
      h.kind = "alpha-vanishes";
      w << h.key << " " << alpha << " vanishes at oversampling " << scene.render.oversampling
        << ": its step opacity " << std::setprecision(2) << x
        << " is below half an LSB of precision.alpha_bits = " << ab << " (" << std::setprecision(3)
        << half_lsb << ")";
    } else if (!accumulator) {
      h.kind = "alpha-rounding";
      w << h.key << " " << alpha << " at oversampling " << scene.render.oversampling
        << ": its step opacity " << std::setprecision(3) << x << " rounds to " << q << " ("
        << std::setprecision(2) << (q / x - 1.0) * 100.0 << " %) in precision.alpha_bits = " << ab;
    } else {
      h.kind = "acc-rounding";
      w << h.key << " " << alpha << " at oversampling " << scene.render.oversampling
        << ": its step opacity " << std::setprecision(3) << q << " times the remaining "
        << "transparency falls below half an LSB of precision.acc_bits = " << p.acc_bits
        << ", and a ray's opacity stalls short of the float reference's";
    }
    w << "; worst case " << guard_fmt(worst) << " LSB of an output channel";
    h.message = w.str();
    out.push_back(std::move(h));
  }
}

// ---- Classification table (§4.1-4.2): entry k at stored value k·spacing ----------------------
struct TableGeometry {
  double spacing;     // stored values between entries
  double last_entry;  // the last entry's stored value
  double data_hi;     // the volume's largest stored value
};

TableGeometry table_geometry(const PrecisionProfile& p, const ref::Volume& volume) {
  const double spacing =
      std::ldexp(1.0, p.value_bits - p.tf_addr_bits - bittrue::value_shift(p, volume));
  return {spacing, (std::ldexp(1.0, p.tf_addr_bits) - 1.0) * spacing,
          static_cast<double>(volume.max_stored())};
}

// The stored value of the entry a sample of stored value v reads: the nearest
// (ties up), clamped to the last entry (class_address, §4.1).
double entry_of(const TableGeometry& g, double v) {
  return std::min(std::floor(v / g.spacing + 0.5) * g.spacing, g.last_entry);
}

// The scene's point index of stored point i (in_stored_units reverses the
// order for a negative slope).
std::size_t scene_index(const ref::Volume& volume, std::size_t i, std::size_t count) {
  return volume.slope < 0 ? count - 1 - i : i;
}

// tf-no-entry (binary interpolation): point i classifies the values in [lo_i,
// hi_i) (from its value up to the next point's; the first point also
// everything below, the last everything above); a sample reads the nearest
// entry, so when no entry lies in that range inside the data, every such
// sample reads a neighbour's material: the point vanishes (worst case: its
// whole opacity).
void table_hazards(const ref::Scene& scene, const ref::Volume& volume, std::vector<Hazard>& out) {
  if (scene.tf_interpolation != ref::TfInterpolation::Binary) return;
  const PrecisionProfile& p = scene.precision;
  const ref::TransferFunction tf = ref::stored_transfer_function(scene, volume);
  const std::vector<ref::TfPoint>& pts = tf.points();  // stored units, sorted
  const TableGeometry g = table_geometry(p, volume);
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (!(pts[i].alpha > 0.0)) continue;
    const double lo = i == 0 ? -inf : pts[i].value;
    const double hi = i + 1 == pts.size() ? inf : pts[i + 1].value;  // exclusive
    // Not in the float image either: an empty interval, or none of it in the data range.
    if (!(lo < hi) || lo > g.data_hi || hi <= 0.0) continue;
    // The first entry at or above lo: readable, and below hi?
    const double entry = std::max(0.0, std::ceil(lo / g.spacing)) * g.spacing;
    if (entry <= g.last_entry && entry < hi && entry <= g.data_hi + g.spacing / 2) continue;
    const std::size_t index = scene_index(volume, i, pts.size());
    const std::size_t next = volume.slope < 0 ? index - 1 : index + 1;
    const ref::TfPoint& sp = scene.tf_points[index];
    Hazard h = make_hazard("tf-no-entry", "classification.points[" + std::to_string(index) + "].value",
                           sp.value, "precision.tf_addr_bits = " + std::to_string(p.tf_addr_bits),
                           full_scale(p) * std::min(1.0, sp.alpha));  // the alpha channel: the whole opacity
    std::ostringstream w;
    w << h.key << " " << sp.value << " vanishes: no classification-table entry lies between it and ";
    if (hi <= g.data_hi)
      w << "classification.points[" << next << "] value " << scene.tf_points[next].value;
    else
      w << "the data's largest value " << volume.to_physical(g.data_hi);
    w << " (precision.tf_addr_bits = " << p.tf_addr_bits << ": entries every " << g.spacing
      << " stored values, the last at " << volume.to_physical(g.last_entry) << "); worst case "
      << guard_fmt(h.worst_lsb) << " LSB of an output channel";
    h.message = w.str();
    out.push_back(std::move(h));
  }
}

// tf-between-entries (ramp interpolation): the float reference classifies the
// continuous value v, the table the entry nearest to it. Along a ramp the
// difference is at most the slope times half a spacing: the ordinary
// quantization of the table, not reported. A feature narrower than the
// spacing — a spike or a notch whose control points fall strictly between
// two entries — is a shape the table cannot hold: the entries on either side
// see only the chord between them. For each control point strictly between
// entries k and k+1, the hazard is how far the transfer function there is
// from that chord; its worst case is what a ray that stays at the point's
// value loses against the entry it reads, over the samples it spends there
// (slab_opacity_difference of the step opacities, and the colour).
void between_entry_hazards(const ref::Scene& scene, const ref::Volume& volume,
                           std::vector<Hazard>& out) {
  if (scene.tf_interpolation != ref::TfInterpolation::Ramp) return;
  const PrecisionProfile& p = scene.precision;
  const ref::TransferFunction tf = ref::stored_transfer_function(scene, volume);
  const std::vector<ref::TfPoint>& pts = tf.points();
  const TableGeometry g = table_geometry(p, volume);
  const double step = 1.0 / scene.render.oversampling;
  const double n = max_ray_samples(scene, volume);
  // What a ray loses at value v reading `got` instead of `want`, in output LSB.
  auto loss = [&](const ref::Classified& want, const ref::Classified& got) {
    const double a = ref::opacity_correct(want.alpha, step);
    const double b = ref::opacity_correct(got.alpha, step);
    // The alpha channel carries the opacity difference itself; a colour
    // channel that, or the colour difference times the opacity.
    const glm::dvec3 dc = glm::abs(want.color - got.color);
    const double tint = std::max({dc.r, dc.g, dc.b}) * std::max(want.alpha, got.alpha);
    return full_scale(p) * std::max(slab_opacity_difference(a, b, n), tint);
  };
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double vp = pts[i].value;
    if (vp < 0.0 || vp > g.data_hi || vp >= g.last_entry) continue;
    const double k0 = std::floor(vp / g.spacing) * g.spacing, k1 = k0 + g.spacing;
    if (vp == k0) continue;  // on an entry: the table holds it
    const ref::Classified lo = tf.classify(k0), hi = tf.classify(k1), at = tf.classify(vp);
    const double f = (vp - k0) / g.spacing;
    ref::Classified chord = at;
    chord.alpha = lo.alpha + f * (hi.alpha - lo.alpha);
    chord.color = lo.color + f * (hi.color - lo.color);
    if (loss(at, chord) < hazard_threshold(p)) continue;  // the ramp's own slope: ordinary
    const double worst = loss(at, tf.classify(entry_of(g, vp)));
    if (worst < hazard_threshold(p)) continue;
    const std::size_t index = scene_index(volume, i, pts.size());
    const ref::TfPoint& sp = scene.tf_points[index];
    Hazard h = make_hazard("tf-between-entries",
                           "classification.points[" + std::to_string(index) + "].value", sp.value,
                           "precision.tf_addr_bits = " + std::to_string(p.tf_addr_bits), worst);
    std::ostringstream w;
    w << h.key << " " << sp.value
      << " lies between classification-table entries (precision.tf_addr_bits = "
      << p.tf_addr_bits << ": entries every "
      << std::abs(volume.to_physical(g.spacing) - volume.to_physical(0.0))
      << " data units), which see only the chord across it: a feature narrower than an entry "
         "is lost; worst case "
      << guard_fmt(worst) << " LSB of an output channel";
    h.message = w.str();
    out.push_back(std::move(h));
  }
}

// ---- Narrow features at steep data (§3.5, §4) ------------------------------------------
//
// The fixed-point sample value differs from the float one by up to
//   e = 3·D·2^-(wb+1) + 2^-(sf+1+shift)   stored values:
// each weight fq = Q_RND(f, weight_bits) moves the sample by at most half an
// LSB of a voxel along its axis, across which the data changes by at most D
// (the steepest step between neighbouring voxels), and the value is rounded
// to sample_frac_bits of the field (stored << value_shift). A material whose
// band of values is narrower than 2e (binary: from its point to the next;
// ramp: between its neighbouring points) is, at the data's steep edges, hit
// by a sample in one engine and missed in the other: a ray differs by one
// sample of the material's step opacity (and colour). A wide band only moves
// its edges by e, as any sampling does; that is not reported.
double steepest_step(const ref::Volume& v) {
  double d = 0.0;
  for (int z = 0; z < v.dims[2]; ++z)
    for (int y = 0; y < v.dims[1]; ++y)
      for (int x = 0; x < v.dims[0]; ++x) {
        const double c = v.data[v.index(x, y, z)];
        if (x + 1 < v.dims[0]) d = std::max(d, std::abs(c - v.data[v.index(x + 1, y, z)]));
        if (y + 1 < v.dims[1]) d = std::max(d, std::abs(c - v.data[v.index(x, y + 1, z)]));
        if (z + 1 < v.dims[2]) d = std::max(d, std::abs(c - v.data[v.index(x, y, z + 1)]));
      }
  return d;
}

void edge_hazards(const ref::Scene& scene, const ref::Volume& volume, std::vector<Hazard>& out) {
  const PrecisionProfile& p = scene.precision;
  const ref::TransferFunction tf = ref::stored_transfer_function(scene, volume);
  const std::vector<ref::TfPoint>& pts = tf.points();
  const double step = 1.0 / scene.render.oversampling;
  const double e = 3.0 * steepest_step(volume) * std::ldexp(1.0, -(p.weight_bits + 1)) +
                   std::ldexp(1.0, -(p.sample_frac_bits + 1 + bittrue::value_shift(p, volume)));
  const double data_hi = volume.max_stored();
  // One sample classified at `a` in one engine and at `b` in the other.
  auto flip = [&](double a, double b) {
    const ref::Classified x = tf.classify(a), y = tf.classify(b);
    const double da = std::abs(ref::opacity_correct(x.alpha, step) - ref::opacity_correct(y.alpha, step));
    const glm::dvec3 dc = glm::abs(x.color - y.color) * std::max(x.alpha, y.alpha);
    return full_scale(p) * std::max({da, dc.r, dc.g, dc.b});
  };
  const bool binary = scene.tf_interpolation == ref::TfInterpolation::Binary;
  const double inf = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double vp = pts[i].value;
    if (!(pts[i].alpha > 0.0) || vp < 0.0 || vp > data_hi) continue;
    const double lo = binary ? vp : (i == 0 ? -inf : pts[i - 1].value);
    const double hi = i + 1 == pts.size() ? inf : pts[i + 1].value;
    if (!(hi - lo < 2.0 * e)) continue;
    // The material at its point against the values just outside its band.
    const double worst = std::max(flip(vp, std::nextafter(lo, -inf)), flip(vp, hi));
    if (worst < hazard_threshold(p)) continue;
    const std::size_t index = scene_index(volume, i, pts.size());
    const ref::TfPoint& sp = scene.tf_points[index];
    Hazard h = make_hazard("tf-narrow-feature",
                           "classification.points[" + std::to_string(index) + "].value",
                           sp.value, "precision.weight_bits = " + std::to_string(p.weight_bits),
                           worst);
    std::ostringstream w;
    w << h.key << " " << sp.value << ": its material's band of values is narrower than twice "
      << "the fixed-point sample value's error at the data's steepest edges, "
      << guard_fmt(std::abs(volume.to_physical(e) - volume.to_physical(0.0))) << " data units ("
      << h.width << ", precision.sample_frac_bits = " << p.sample_frac_bits
      << "): a sample sees it in one engine and misses it in the other; worst case " << guard_fmt(worst)
      << " LSB of an output channel per such sample";
    h.message = w.str();
    out.push_back(std::move(h));
  }
}

// ---- Geometry processor (§0-2): the samples' positions ------------------------------------
//
// The frame's registers, loaded as the host would, give every ray's samples
// p_j = p0 + j·s exactly; bittrue::frame_sample_position_error measures the
// largest distance per axis, delta, of any sample from the float reference's
// point at the same parameter (the origin plane's rounding, the step vector's
// error times the entry's lever and the ray's length, p0's rounding: not a
// bound but this frame's figure). Across the data's steepest step D between
// neighbouring voxels a position error of delta per axis moves the trilinear
// sample value by up to 3·delta·D; as a share of the data's range, in output
// LSB, that is the worst case reported (the change of a transfer function that
// maps the data's range linearly onto the output). The origin plane keeps delta
// independent of the eye's distance; it grows with the image (the origin and
// direction registers' rounding times the pixel index), the box's depth, and
// narrow pos_frac_bits and dir_frac_bits.
void geometry_hazards(const ref::Scene& scene, const ref::Volume& volume,
                      std::vector<Hazard>& out) {
  const PrecisionProfile& p = scene.precision;
  const double data_hi = volume.max_stored();
  if (!(data_hi > 0.0)) return;
  const ref::GradientField none;
  ref::RenderInputs in;
  in.volume = ref::make_render_volume(volume, none, scene.volume.crop);
  in.camera = ref::make_camera_frame(scene.camera, scene.camera.pose, scene.render.width,
                                     scene.render.height, in.volume.world_scale);
  in.settings = ref::make_render_settings(scene);
  bittrue::FrameRegisters regs;
  try {
    regs = bittrue::make_frame_registers(p, scene, in);
  } catch (const Error&) {
    return;  // the render refuses the camera itself, with this error
  }
  const std::vector<bittrue::Raw> seed =
      regs.perspective ? bittrue::make_rsqrt_seed(p) : std::vector<bittrue::Raw>{};
  const bittrue::SamplePositionError e = bittrue::frame_sample_position_error(
      p, regs, seed, in.camera, in.volume.world_scale, in.settings.step);
  const double delta = e.voxels;
  const double worst = full_scale(p) * std::min(1.0, 3.0 * delta * steepest_step(volume) / data_hi);
  if (worst < hazard_threshold(p)) return;
  const double distance = glm::length(scene.camera.pose.eye - scene.camera.pose.center);
  Hazard h = make_hazard("geometry-position", "camera.eye", distance,
                         "precision.pos_frac_bits = " + std::to_string(p.pos_frac_bits) +
                             ", precision.dir_frac_bits = " + std::to_string(p.dir_frac_bits),
                         worst);
  std::ostringstream w;
  w << "camera.eye " << guard_fmt(distance) << " voxels from camera.center, "
    << scene.render.width << "x" << scene.render.height << " pixels: a sample of pixel ("
    << e.x << ", " << e.y << ") lies " << guard_fmt(delta)
    << " voxels along an axis from the float reference's (" << h.width
    << "; the weight addressing resolves " << guard_fmt(std::ldexp(1.0, -p.weight_bits))
    << "), which the data's steepest edges turn into a sample value error of up to "
    << guard_fmt(100.0 * worst / full_scale(p)) << " % of its range; worst case "
    << guard_fmt(worst) << " LSB of an output channel";
  h.message = w.str();
  out.push_back(std::move(h));
}

// ---- Reflectance map (§5.4): entries U(D), U(S) saturate at 2^rm_int_bits - 2^-rm_frac_bits ----
//
// D(N) = sum of I·max(0, N·L) over the lights, S(N) = sum of I·max(0, N·H)^n:
// their largest values over the normals are at the lights' own directions (for
// D, at the normalised sum of the lights that face a common normal: checked on
// every table entry's normal and at each light and halfway vector). Where D or
// S exceeds the largest entry, the shaded intensity ka + kd·D + ks·S is short
// by kd·(D - max) + ks·(S - max), and a channel by colour times that (both
// sides clamped to 1 as the shader does), for an opaque sample.
void reflectance_hazards(const ref::Scene& scene, std::vector<Hazard>& out) {
  if (scene.render.mode != ref::RenderMode::Shaded || scene.lights.empty()) return;
  const PrecisionProfile& p = scene.precision;
  const double cap = std::ldexp(1.0, p.rm_int_bits) - std::ldexp(1.0, -p.rm_frac_bits);
  // The camera only turns headlights; the worst case over views is the
  // worst case over normals, which every view direction gives alike.
  const ref::ShadingSetup shading =
      ref::make_shading_setup(scene.lights, glm::dvec3(0.0, 0.0, -1.0), scene.material.shininess);
  std::vector<glm::dvec3> normals;
  for (const auto& t : shading.lights) {
    normals.push_back(t.light);
    if (glm::length(t.halfway) > 0.0) normals.push_back(t.halfway);
  }
  glm::dvec3 sum(0.0);
  for (const auto& t : shading.lights) sum += t.intensity * t.light;
  if (glm::length(sum) > 0.0) normals.push_back(glm::normalize(sum));
  const int res = 64;  // a fine cube map of normals besides
  for (int face = 0; face < 6; ++face)
    for (int iv = 0; iv < res; ++iv)
      for (int iu = 0; iu < res; ++iu) {
        glm::dvec3 nrm(0.0);
        const int m = face / 2, a = m == 0 ? 1 : 0, b = m == 2 ? 1 : 2;
        nrm[m] = (face & 1) ? -1.0 : 1.0;
        nrm[a] = (iu + 0.5) * 2.0 / res - 1.0;
        nrm[b] = (iv + 0.5) * 2.0 / res - 1.0;
        normals.push_back(glm::normalize(nrm));
      }
  double d_max = 0.0, s_max = 0.0, worst = 0.0;
  const ref::Material& mat = scene.material;
  // The colours the materials have (each channel of each visible point): the
  // clamp at 1 hides the loss for a bright colour and not for a dim one.
  std::vector<double> colours;
  for (const ref::TfPoint& pt : scene.tf_points)
    if (pt.alpha > 0.0) colours.insert(colours.end(), {pt.color.r, pt.color.g, pt.color.b});
  for (const glm::dvec3& nrm : normals) {
    const ref::Reflectance r = ref::reflectance(shading, nrm);
    d_max = std::max(d_max, r.diffuse);
    s_max = std::max(s_max, r.specular);
    const double exact = mat.ka + mat.kd * r.diffuse + mat.ks * r.specular;
    const double held = mat.ka + mat.kd * std::min(r.diffuse, cap) + mat.ks * std::min(r.specular, cap);
    for (double c : colours)
      worst = std::max(worst, full_scale(p) * (std::min(1.0, c * exact) - std::min(1.0, c * held)));
  }
  if (worst < hazard_threshold(p)) return;
  // The key: the light that adds most to the largest diffuse (or specular) term.
  std::size_t brightest = 0;
  for (std::size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].intensity > scene.lights[brightest].intensity) brightest = i;
  double total = 0.0;
  for (const ref::Light& l : scene.lights) total += l.intensity;
  Hazard h = make_hazard("rm-saturation", "lights[" + std::to_string(brightest) + "].intensity",
                         scene.lights[brightest].intensity,
                         "precision.rm_int_bits = " + std::to_string(p.rm_int_bits), worst);
  std::ostringstream w;
  w << h.key << " " << h.value << " (" << scene.lights.size() << " light"
    << (scene.lights.size() == 1 ? "" : "s") << ", intensities summing to " << total
    << "): the reflectance map reaches diffuse " << guard_fmt(d_max) << ", specular " << guard_fmt(s_max)
    << ", but precision.rm_int_bits = " << p.rm_int_bits << " and rm_frac_bits = "
    << p.rm_frac_bits << " hold at most " << guard_fmt(cap, 6) << ": shading saturates; worst case "
    << guard_fmt(worst) << " LSB of an output channel";
  h.message = w.str();
  out.push_back(std::move(h));
}

// ---- The Heidelberg path (docs/heidelberg.md §7.4-7.5) ------------------------------------
//
// The density of a voxel is the transfer function's alpha, carried as
// TRN(rho, density_bits); the slice processor updates T0 -= TRN(T0·rho,
// light_frac_bits). Each of the n voxels of a line thus loses at most one LSB
// of each (§7.5: (1-rho)^n <= T0 <= (1-rho)^n + n·2^-lf, and the density's
// floor adds n·2^-db), and the light a line deposits — which the output
// shows — is off by at most n·(2^-db + 2^-lf): a bound proved from the
// widths, reported only where it reaches the threshold (deep view cubes). A
// density below one LSB of density_bits vanishes: its material absorbs and
// deposits nothing, up to 1 - (1 - rho)^n of the light.
void heidelberg_hazards(const ref::Scene& scene, const ref::Volume& volume,
                        std::vector<Hazard>& out) {
  const HeidelbergProfile hp = bittrue::heidelberg_profile(scene);
  const double full = std::ldexp(1.0, hp.out_bits) - 1.0;
  const double limit = kHazardFraction * full;
  const int largest = std::max({volume.dims[0], volume.dims[1], volume.dims[2]});
  const double n = scene.heidelberg.depth > 0 ? scene.heidelberg.depth : largest;
  const double lsb = std::ldexp(1.0, -hp.density_bits);
  for (std::size_t i = 0; i < scene.tf_points.size(); ++i) {
    const double rho = scene.tf_points[i].alpha;
    if (!(rho > 0.0) || rho >= lsb) continue;
    const double worst = full * (1.0 - std::pow(1.0 - rho, n));
    Hazard h = make_hazard("heidelberg-density-vanishes",
                           "classification.points[" + std::to_string(i) + "].alpha", rho,
                           "density_bits = " + std::to_string(hp.density_bits), worst);
    h.message = h.key + " " + guard_fmt(rho) + " is a density below one LSB of the Heidelberg " +
                "path's " + h.width + " (" + guard_fmt(lsb) +
                "): its material vanishes from the fixed-point image; worst case " +
                guard_fmt(worst) + " LSB of the output over " + guard_fmt(n) + " voxels";
    out.push_back(std::move(h));
  }
  const double bound = full * std::min(1.0, n * (lsb + std::ldexp(1.0, -hp.light_frac_bits)));
  if (bound < limit) return;
  Hazard h = make_hazard("heidelberg-transmittance", "heidelberg.depth", n,
                         "density_bits = " + std::to_string(hp.density_bits) +
                             ", light_frac_bits = " + std::to_string(hp.light_frac_bits),
                         bound);
  h.message = "heidelberg.depth " + guard_fmt(n) + ": over that many voxels the floors of the " +
              "density and of the transmittance update (" + h.width + ") may cost up to " +
              guard_fmt(bound) + " LSB of the output (n·(2^-db + 2^-lf), docs/heidelberg.md §7.5)";
  out.push_back(std::move(h));
}

// ---- Pre-integration table (§4a.3) ----------------------------------------------------------
//
// The table's entry (f, b) holds the segment's opacity x (ref::preintegrate)
// as q = U(x, alpha_bits): q = 0 for x below half an LSB, q = 1 - 2^-ab for x
// above 1 - 2^-(ab+1). Over a ray of n such segments the float reference
// accumulates 1 - (1 - x)^n, the card 1 - (1 - q)^n (slab_errors, the
// accumulator's roundings included).
//   preint-alpha-vanishes: the largest segment opacity, at least the faintest
//                          declared material's, that the table stores as 0 (a
//                          faint or thin layer between two samples lost),
//                          always reported;
//   preint-alpha-saturates: the opacity of a segment the table cannot make
//                          opaque (1 - 2^-ab stored for x up to 1), reported
//                          when its worst case reaches the guard's threshold.
void preintegration_hazards(const ref::Scene& scene, const ref::Volume& volume,
                            std::vector<Hazard>& out) {
  if (!scene.render.preintegrated()) return;
  const PrecisionProfile& p = scene.precision;
  const int ab = p.alpha_bits;
  const double step = 1.0 / scene.render.oversampling;
  // The table over the value field's units, as the frame set-up builds it
  // (bittrue::make_frame_setup): the same cached table.
  const ref::TransferFunction tf = bittrue::field_transfer_function(
      p, ref::stored_transfer_function(scene, volume), volume);
  const auto table = bittrue::make_preint_table(p, tf, step);
  const int side = 1 << p.preint_addr_bits;
  const std::uint32_t full = (std::uint32_t{1} << ab) - 1;
  // The faintest material the scene declares (a control point's step opacity):
  // fainter segments lie inside ramps from transparency, whose rounding is the
  // table's ordinary quantization (as for the 1-D table, table_hazards).
  double faintest = 1.0;
  for (const ref::TfPoint& pt : scene.tf_points)
    if (pt.alpha > 0.0) faintest = std::min(faintest, ref::opacity_correct(pt.alpha, step));
  double vanishing = 0.0, saturating = 1.0;  // the worst x of each kind
  for (int f = 0; f < side; ++f)
    for (int b = 0; b < side; ++b) {
      const std::uint32_t q = (*table)[static_cast<std::size_t>(f * side + b)].alpha;
      if (q != 0 && q != full) continue;
      const double x = ref::preintegrate(tf, std::ldexp(f, p.value_bits - p.preint_addr_bits),
                                         std::ldexp(b, p.value_bits - p.preint_addr_bits), step)
                           .alpha;
      if (q == 0 && x >= faintest * (1.0 - 1e-9)) vanishing = std::max(vanishing, x);
      if (q == full && x > 1.0 - std::ldexp(1.0, -ab)) saturating = std::max(saturating, x);
    }
  const double n = max_ray_samples(scene, volume);
  const std::string width = "precision.alpha_bits = " + std::to_string(ab);
  if (vanishing > 0.0) {
    const double worst = full_scale(p) * slab_errors(p, vanishing, 0.0, n).total;
    {  // always reported, as alpha-vanishes: a layer the table cannot see
      Hazard h = make_hazard("preint-alpha-vanishes", "render.classification", vanishing, width,
                             worst);
      std::ostringstream w;
      w << "render.classification = \"preintegrated\": segments of opacity up to "
        << std::setprecision(3) << vanishing << " are stored as 0 in " << width
        << " (below half an LSB, " << std::ldexp(1.0, -(ab + 1))
        << "); worst case " << guard_fmt(worst) << " LSB of an output channel";
      h.message = w.str();
      out.push_back(std::move(h));
    }
  }
  if (saturating > 1.0 - std::ldexp(1.0, -ab)) {
    const double q = 1.0 - std::ldexp(1.0, -ab);
    const double worst = full_scale(p) * slab_errors(p, saturating, q, n).total;
    if (worst >= hazard_threshold(p)) {
      Hazard h = make_hazard("preint-alpha-saturates", "render.classification", saturating, width,
                             worst);
      std::ostringstream w;
      w << "render.classification = \"preintegrated\": segments of opacity up to "
        << std::setprecision(6) << saturating << " are stored as " << q << " in " << width
        << ", never opaque; worst case " << guard_fmt(worst) << " LSB of an output channel";
      h.message = w.str();
      out.push_back(std::move(h));
    }
  }
}

}  // namespace

std::vector<Hazard> precision_hazards(const ref::Scene& scene, const ref::Volume& volume) {
  std::vector<Hazard> out;
  if (scene.algorithm == ref::Algorithm::Heidelberg) {
    heidelberg_hazards(scene, volume, out);
    return out;
  }
  geometry_hazards(scene, volume, out);
  if (scene.render.mode == ref::RenderMode::Mip) return out;
  // A pre-integrated frame reads its opacities from the 2-D table, whose own
  // rounding preintegration_hazards judges; the 1-D table's alphas are unused.
  if (!scene.render.preintegrated()) alpha_hazards(scene, volume, out);
  table_hazards(scene, volume, out);
  between_entry_hazards(scene, volume, out);
  edge_hazards(scene, volume, out);
  reflectance_hazards(scene, out);
  preintegration_hazards(scene, volume, out);
  return out;
}

std::vector<std::string> fixed_point_warnings(const ref::Scene& scene, const ref::Volume& volume) {
  std::vector<std::string> out;
  for (const Hazard& h : precision_hazards(scene, volume)) out.push_back(h.message);
  return out;
}

double largest_worst_lsb(const std::vector<Hazard>& hazards) {
  double worst = 0.0;
  for (const Hazard& h : hazards) worst = std::max(worst, h.worst_lsb);
  return worst;
}

std::string hazard_keys(const std::vector<Hazard>& hazards) {
  std::string keys;
  for (const Hazard& h : hazards) keys += (keys.empty() ? "" : " ") + h.key;
  return keys;
}

nlohmann::json hazards_json(const std::vector<Hazard>& hazards) {
  nlohmann::json j = nlohmann::json::array();
  for (const Hazard& h : hazards)
    j.push_back({{"kind", h.kind},
                 {"key", h.key},
                 {"value", h.value},
                 {"width", h.width},
                 {"worst_lsb", h.worst_lsb},
                 {"message", h.message}});
  return j;
}

void report_hazards(const std::vector<Hazard>& hazards, bool strict, std::ostream& err) {
  if (strict && !hazards.empty()) {
    std::string what = "--strict: " + std::to_string(hazards.size()) + " precision hazard" +
                       (hazards.size() == 1 ? "" : "s") + ":";
    for (const Hazard& h : hazards) what += "\n  " + h.message;
    throw PrecisionHazardError(what);
  }
  for (const Hazard& h : hazards) err << "voxcast: warning: " << h.message << "\n";
}

}  // namespace voxcast::cosim
