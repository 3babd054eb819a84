// Host set-up of the classification table (docs/pipeline.md §4.2) and the two
// reflectance maps (§5.4): computed in double from the float reference's own
// functions, stored as the raw integers the card loads.
#include <cmath>
#include <cstddef>
#include <deque>
#include <mutex>
#include <utility>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/parallel.hpp"
#include "refmodel/volume/preintegration.hpp"

namespace voxcast::bittrue {

namespace {

// Raw integer of U(x, F) (an unsigned fraction of 1).
std::uint32_t raw_u(double x, int F) { return static_cast<std::uint32_t>(to_raw(u_frac(x, F), F)); }

}  // namespace

ref::TransferFunction field_transfer_function(const PrecisionProfile& p,
                                              const ref::TransferFunction& tf_stored,
                                              const ref::Volume& v) {
  const double scale = std::ldexp(1.0, value_shift(p, v));
  std::vector<ref::TfPoint> points = tf_stored.points();
  for (ref::TfPoint& pt : points) pt.value *= scale;
  return ref::TransferFunction(points, tf_stored.interpolation(), tf_stored.material());
}

std::vector<ClassEntry> make_class_table(const PrecisionProfile& profile,
                                         const ref::TransferFunction& tf_stored, double step) {
  const int n = 1 << profile.tf_addr_bits;
  std::vector<ClassEntry> table(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    // Entry i: the transfer function at stored value i · 2^(vb - tf_addr_bits).
    const double value =
        std::ldexp(static_cast<double>(i), profile.value_bits - profile.tf_addr_bits);
    const ref::Classified c = tf_stored.classify(value);
    ClassEntry& e = table[static_cast<std::size_t>(i)];
    e.r = raw_u(c.color.r, profile.color_bits);
    e.g = raw_u(c.color.g, profile.color_bits);
    e.b = raw_u(c.color.b, profile.color_bits);
    // Opacity correction for the frame's step baked in; alpha >= 1 gives 1, which saturates.
    e.alpha = raw_u(ref::opacity_correct(c.alpha, step), profile.alpha_bits);
    e.ka = raw_u(c.ka, profile.k_bits);
    e.kd = raw_u(c.kd, profile.k_bits);
    e.ks = raw_u(c.ks, profile.k_bits);
  }
  return table;
}

namespace {

// The inputs a pre-integration table is a function of.
struct PreintKey {
  PrecisionProfile profile;
  std::vector<ref::TfPoint> points;
  ref::TfInterpolation interpolation;
  ref::Material material;
  double step;
  bool operator==(const PreintKey&) const = default;
};

std::vector<ClassEntry> build_preint_table(const PrecisionProfile& profile,
                                           const ref::TransferFunction& tf, double step) {
  const int b = profile.preint_addr_bits;
  const int side = 1 << b;
  std::vector<ClassEntry> table(static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
  const auto value = [&](int a) {
    return std::ldexp(static_cast<double>(a), profile.value_bits - b);
  };
  // Each entry on its own: the same bits for any thread count.
  ref::parallel_for(
      side,
      [&](int f) {
        for (int k = 0; k < side; ++k) {
          const ref::SegmentClass seg = ref::preintegrate(tf, value(f), value(k), step);
          const ref::Classified back = tf.classify(value(k));
          const glm::dvec3 c = glm::clamp(seg.color(), 0.0, 1.0);
          ClassEntry& e = table[static_cast<std::size_t>(f) * static_cast<std::size_t>(side) +
                                static_cast<std::size_t>(k)];
          e.r = raw_u(c.r, profile.color_bits);
          e.g = raw_u(c.g, profile.color_bits);
          e.b = raw_u(c.b, profile.color_bits);
          e.alpha = raw_u(seg.alpha, profile.alpha_bits);
          e.ka = raw_u(back.ka, profile.k_bits);
          e.kd = raw_u(back.kd, profile.k_bits);
          e.ks = raw_u(back.ks, profile.k_bits);
        }
      },
      0);
  return table;
}

}  // namespace

std::shared_ptr<const std::vector<ClassEntry>> make_preint_table(
    const PrecisionProfile& profile, const ref::TransferFunction& tf_stored, double step) {
  // A few recent tables: the frames of a flythrough and the points of a sweep
  // share their transfer function and step (0.1-0.3 s a table at 8 bits).
  static std::mutex mutex;
  static std::deque<std::pair<PreintKey, std::shared_ptr<const std::vector<ClassEntry>>>> cache;
  constexpr std::size_t kCached = 4;
  PreintKey key{profile, tf_stored.points(), tf_stored.interpolation(), tf_stored.material(), step};
  {
    const std::lock_guard<std::mutex> lock(mutex);
    for (const auto& [k, t] : cache)
      if (k == key) return t;
  }
  auto table = std::make_shared<const std::vector<ClassEntry>>(
      build_preint_table(profile, tf_stored, step));
  const std::lock_guard<std::mutex> lock(mutex);
  cache.emplace_front(std::move(key), table);
  if (cache.size() > kCached) cache.pop_back();
  return table;
}

SegmentTables make_segment_tables(const PrecisionProfile& profile,
                                  const std::vector<ClassEntry>& class_table) {
  const int ab = profile.alpha_bits;
  const int F = segment_frac_bits(profile);
  SegmentTables t;
  // §7a.2: from the table's rounded alpha, so that w = 1 gives alpha_c back; alpha_c <= 1 - 2^-ab
  // (U saturates), so tau2 <= ab is finite.
  t.tau.reserve(class_table.size());
  for (const ClassEntry& e : class_table)
    t.tau.push_back(to_raw(q_rnd(-std::log2(1.0 - from_raw(e.alpha, ab)), F), F));
  // §7a.4: 2^-x at x = i·2^-r, i = 0 .. 2^r.
  const int r = segment_rom_index_bits(profile);
  const int n = (1 << r) + 1;
  t.rom.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    t.rom.push_back(to_raw(q_rnd(std::exp2(-std::ldexp(static_cast<double>(i), -r)), F), F));
  return t;
}

void make_reflectance_maps(const PrecisionProfile& profile, const ref::ShadingSetup& shading,
                           std::vector<std::uint32_t>& diffuse,
                           std::vector<std::uint32_t>& specular) {
  const int res = profile.rm_res;
  const int rf = profile.rm_frac_bits;
  // Nearest (§5.4): one entry per cell, at the cell centre. Bilinear (§5.5): one entry per
  // cell corner, (res + 1)^2 per face; corner (i, j) at u = i·2/res - 1, v = j·2/res - 1.
  const bool corners = profile.rm_bilinear != 0;
  const int side = corners ? res + 1 : res;
  const double offset = corners ? 0.0 : 0.5;
  const auto entries = static_cast<std::size_t>(6 * side * side);
  const double hi = std::ldexp(1.0, profile.rm_int_bits) - std::ldexp(1.0, -rf);
  auto store = [&](double x) {
    return static_cast<std::uint32_t>(to_raw(sat(q_rnd(x, rf), 0.0, hi), rf));
  };
  diffuse.assign(entries, 0);
  specular.assign(entries, 0);
  std::size_t index = 0;
  for (int face = 0; face < 6; ++face) {
    // Face 2m + s: major axis m with sign +1 (s = 0) or -1 (s = 1); the other axes a < b.
    const int m = face / 2;
    const double sign = (face & 1) ? -1.0 : 1.0;
    const int a = m == 0 ? 1 : 0;
    const int b = m == 2 ? 1 : 2;
    for (int iv = 0; iv < side; ++iv) {
      for (int iu = 0; iu < side; ++iu, ++index) {
        ref::Vec3 n(0.0);
        n[m] = sign;
        n[a] = (iu + offset) * 2.0 / res - 1.0;
        n[b] = (iv + offset) * 2.0 / res - 1.0;
        const ref::Reflectance r = ref::reflectance(shading, glm::normalize(n));
        diffuse[index] = store(r.diffuse);
        specular[index] = store(r.specular);
      }
    }
  }
}

}  // namespace voxcast::bittrue
