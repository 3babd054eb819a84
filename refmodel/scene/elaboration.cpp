#include "refmodel/scene/elaboration.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

#include "refmodel/render/space_leaping.hpp"

namespace voxcast::ref {

namespace {

// Bits of an unsigned integer holding 0..n (at least 1).
int unsigned_bits(double n) {
  if (n < 1.0) return 1;
  return static_cast<int>(std::bit_width(static_cast<unsigned long long>(n)));
}

void leave_out(Elaboration& e, bool& unit, const char* name, const std::string& reason) {
  unit = false;
  e.omitted.push_back({name, reason});
}

// Does one channel of the transfer function vary over its points? A constant
// field of the classification entry is a register, not table bits.
template <class F>
bool varies(const TransferFunction& tf, F field) {
  const auto& pts = tf.points();
  for (const TfPoint& p : pts)
    if (field(p) != field(pts.front())) return true;
  return false;
}

void size_from_data(Elaboration& e, const TransferFunction& tf, const DataRange& r) {
  const PrecisionProfile& p = e.profile;
  // §3.4: value = stored << shift, so the value field stores only the data's
  // real range; the low `shift` bits are constant zeros (wires).
  const int shift = std::max(0, p.value_bits - r.volume_bits);
  e.value_store_bits = std::min(p.value_bits, unsigned_bits(r.max_stored));
  // §3.4: g_stored = SAT(Q_RND(g · 2^shift, gfb)); its raw integer plus a sign bit.
  const double g_raw = std::round(std::ldexp(r.max_gradient, shift + p.gradient_frac_bits));
  e.gradient_store_bits = std::min(p.gradient_bits, unsigned_bits(g_raw) + 1);
  // §4.1: interpolated values never exceed the largest stored value, so the
  // addresses above round(max · 2^(tf_addr_bits - vb)) are never read.
  const double top = std::ldexp(static_cast<double>(r.max_stored), shift + p.tf_addr_bits -
                                                                       p.value_bits);
  const double last = std::min(std::ldexp(1.0, p.tf_addr_bits) - 1.0, std::floor(top + 0.5));
  e.class_entries = static_cast<int>(last) + 1;
  // §4a.1: the same bound at the pre-integration table's resolution, per segment end.
  const double preint_top = std::ldexp(static_cast<double>(r.max_stored),
                                       shift + p.preint_addr_bits - p.value_bits);
  e.preint_side = static_cast<int>(
                      std::min(std::ldexp(1.0, p.preint_addr_bits) - 1.0,
                               std::floor(preint_top + 0.5))) +
                  1;
  e.class_color_fields = (varies(tf, [](const TfPoint& q) { return q.color.x; }) ? 1 : 0) +
                         (varies(tf, [](const TfPoint& q) { return q.color.y; }) ? 1 : 0) +
                         (varies(tf, [](const TfPoint& q) { return q.color.z; }) ? 1 : 0);
  e.class_alpha_varies = varies(tf, [](const TfPoint& q) { return q.alpha; });
  e.class_k_fields = 0;  // one material per scene (ref::Material): ka, kd, ks are registers
}

}  // namespace

DataRange data_range(const Volume& volume, const GradientField& gradients) {
  DataRange r;
  r.volume_bits = volume.bits;
  r.max_stored = 0;
  for (const std::uint16_t v : volume.data) r.max_stored = std::max<unsigned>(r.max_stored, v);
  for (const auto& g : gradients.g)
    r.max_gradient = std::max({r.max_gradient, std::abs(static_cast<double>(g.x)),
                               std::abs(static_cast<double>(g.y)),
                               std::abs(static_cast<double>(g.z))});
  return r;
}

Elaboration elaborate(const PrecisionProfile& profile, RenderMode mode, Projection projection,
                      double ert_threshold, const TransferFunction& stored_tf,
                      const DataRange& range) {
  Elaboration e;
  e.profile = profile;
  if (projection == Projection::Parallel) {
    leave_out(e, e.perspective, "ray_direction+rsqrt",
              "camera.projection = parallel: one view direction (register U), no per-pixel "
              "direction or normalisation (docs/pipeline.md §1.2)");
    e.parallel_direction = true;
  } else {
    e.omitted.push_back({"parallel_direction", "camera.projection = perspective: every ray has "
                                               "its own direction, no view-direction register U "
                                               "(§1.1)"});
  }
  if (mode == RenderMode::Mip) {
    e.mip = true;
    leave_out(e, e.classification, "classification",
              "render.mode = mip: the pixel is the maximum value, no transfer function (§7)");
    leave_out(e, e.gradients, "gradient_memory",
              "render.mode = mip: gradients are read only by the reflectance map (§5)");
    leave_out(e, e.reflectance_map, "reflectance_map", "render.mode = mip: no shading");
    leave_out(e, e.shader, "shader", "render.mode = mip: no shading");
    leave_out(e, e.compositor, "compositor", "render.mode = mip: no over operator (§7)");
    leave_out(e, e.ert, "ert", "render.mode = mip: every ray runs to its end (§7)");
  } else {
    e.omitted.push_back({"mip", "render.mode = " + std::string(to_string(mode)) +
                                    ": no maximum-intensity projection"});
    if (mode == RenderMode::Unshaded) {
      leave_out(e, e.reflectance_map, "reflectance_map",
                "render.mode = unshaded: c = U(colour), no Phong intensity (§6)");
      leave_out(e, e.gradients, "gradient_memory",
                "render.mode = unshaded: gradients are read only by the reflectance map (§5)");
      e.omitted.push_back({"shader.intensity", "render.mode = unshaded: no ka + kd·D + ks·S and "
                                               "colour·I products, only U(colour) (§6)"});
    }
    if (ert_threshold >= 1.0)
      leave_out(e, e.ert, "ert",
                "render.ert_threshold >= 1: early ray termination disabled (§7.3)");
  }
  size_from_data(e, stored_tf, range);
  if (!e.gradients) e.gradient_store_bits = 0;
  if (!e.classification) e.class_entries = 0;
  return e;
}

Elaboration elaborate(const Scene& scene, const Volume& volume, const GradientField& gradients) {
  Elaboration e = elaborate(scene.precision, scene.render.mode, scene.camera.projection,
                            scene.render.ert_threshold, stored_transfer_function(scene, volume),
                            data_range(volume, gradients));
  elaborate_options(e, scene.render, volume.dims);
  return e;
}

void elaborate_options(Elaboration& e, const RenderDesc& render, const std::array<int, 3>& dims) {
  e.leap_block = render.leap_block;
  if (!render.space_leaping) {
    e.omitted.push_back({"space_leaping", "render.space_leaping = false: every sample is read, "
                                          "no min-max block memory (docs/leaping.md)"});
  } else if (render.mode == RenderMode::Mip) {
    e.omitted.push_back({"space_leaping", "render.mode = mip: every sample can be the maximum, "
                                          "none is skipped (docs/leaping.md)"});
  } else {
    e.space_leaping = true;
    e.leap_blocks = 1;
    const int lb = leap_block_log2(render.leap_block);
    for (const int n : dims) e.leap_blocks *= (std::max(n - 2, 0) >> lb) + 1;
  }
  e.jitter = render.jitter;
  if (!e.jitter)
    e.omitted.push_back({"jitter", "render.jitter = false: every ray starts at its entry, no "
                                   "pixel hash in the ray set-up (docs/leaping.md)"});
  if (!render.partial_segments) {
    e.omitted.push_back({"segment_opacity", "render.partial_segments = false: every sample has "
                                            "the table's opacity, no optical-depth table or 2^-x "
                                            "ROM (docs/pipeline.md §7a)"});
  } else if (render.mode == RenderMode::Mip) {
    e.omitted.push_back({"segment_opacity", "render.mode = mip: no opacity to weight "
                                            "(docs/pipeline.md §7a)"});
  } else {
    e.partial_segments = true;
  }
  if (!render.preintegrated()) {
    e.omitted.push_back({"preintegration", "render.classification = \"post\": one table read "
                                           "per sample value, no 2-D segment table "
                                           "(docs/pipeline.md §4a)"});
  } else if (render.mode == RenderMode::Mip) {
    e.omitted.push_back({"preintegration", "render.mode = mip: the maximum of the values needs "
                                           "no classification (docs/pipeline.md §4a)"});
  } else {
    e.preintegration = true;
  }
}

}  // namespace voxcast::ref
