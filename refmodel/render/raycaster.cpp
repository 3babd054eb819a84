#include "refmodel/render/raycaster.hpp"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "refmodel/parallel.hpp"
#include "refmodel/volume/preintegration.hpp"

namespace voxcast::ref {

Vec3 normalised_spacing(const Volume& volume) {
  const double smallest = std::min({volume.spacing.x, volume.spacing.y, volume.spacing.z});
  return volume.spacing / smallest;
}

RenderVolume make_render_volume(const Volume& volume, const GradientField& gradients,
                                const std::optional<Crop>& crop) {
  RenderVolume rv;
  rv.volume = &volume;
  rv.gradients = &gradients;
  rv.world_scale = normalised_spacing(volume);
  Vec3 lo{0.0}, hi{volume.dims[0] - 1.0, volume.dims[1] - 1.0, volume.dims[2] - 1.0};
  if (crop) {
    lo = Vec3(crop->lo[0], crop->lo[1], crop->lo[2]);
    hi = Vec3(crop->hi[0], crop->hi[1], crop->hi[2]);
  }
  rv.index_box = Box{lo, hi};
  rv.world_box = Box{lo * rv.world_scale, hi * rv.world_scale};
  return rv;
}

// --- Interpolation ------------------------------------------------------------

namespace {
// Lower neighbour index and weight along one axis; a one-voxel axis has both
// neighbours at 0, and a position on the last voxel uses the last cell with
// weight 1, so no index ever leaves the grid.
struct AxisWeight {
  int i0, i1;
  double f;
};
AxisWeight axis_weight(double x, int n) {
  if (n == 1) return {0, 0, 0.0};
  const double c = std::clamp(x, 0.0, n - 1.0);
  const int i0 = std::min(static_cast<int>(std::floor(c)), n - 2);
  return {i0, i0 + 1, c - i0};
}
}  // namespace

template <typename T>
T lerp(const T& a, const T& b, double f) {
  return a + f * (b - a);  // exactly a when a == b: constant data stay constant
}

Sample interpolate(const Volume& volume, const GradientField& gradients, const Vec3& p) {
  const AxisWeight ax = axis_weight(p.x, volume.dims[0]);
  const AxisWeight ay = axis_weight(p.y, volume.dims[1]);
  const AxisWeight az = axis_weight(p.z, volume.dims[2]);
  // Seven lerps, x then y then z (the interpolation processor's order).
  double v[2][2];
  Vec3 g[2][2];
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy) {
      const int y = dy ? ay.i1 : ay.i0, z = dz ? az.i1 : az.i0;
      const std::size_t i0 = volume.index(ax.i0, y, z), i1 = volume.index(ax.i1, y, z);
      v[dz][dy] = lerp<double>(volume.data[i0], volume.data[i1], ax.f);
      g[dz][dy] = lerp(Vec3(gradients.g[i0]), Vec3(gradients.g[i1]), ax.f);
    }
  Sample s;
  s.value = lerp(lerp(v[0][0], v[0][1], ay.f), lerp(v[1][0], v[1][1], ay.f), az.f);
  s.gradient = lerp(lerp(g[0][0], g[0][1], ay.f), lerp(g[1][0], g[1][1], ay.f), az.f);
  return s;
}

// --- Shading ------------------------------------------------------------------

ShadingSetup make_shading_setup(const std::vector<Light>& lights, const Vec3& view_direction,
                                double shininess) {
  ShadingSetup s;
  s.shininess = shininess;
  const Vec3 v = -glm::normalize(view_direction);  // towards the viewer
  for (const Light& l : lights) {
    const Vec3 dir = l.type == LightType::Headlight ? v : glm::normalize(l.direction);
    const Vec3 h = dir + v;
    // A light exactly behind the viewer's line of sight has no halfway vector;
    // its specular lobe then faces away from every visible normal.
    const Vec3 halfway = glm::length(h) > 0.0 ? glm::normalize(h) : Vec3(0.0);
    s.lights.push_back({dir, halfway, l.intensity});
  }
  return s;
}

Reflectance reflectance(const ShadingSetup& setup, const Vec3& n) {
  Reflectance r;
  for (const ShadingSetup::Term& t : setup.lights) {
    const double nl = glm::dot(n, t.light);
    if (nl <= 0.0) continue;
    r.diffuse += t.intensity * nl;
    const double nh = glm::dot(n, t.halfway);
    if (nh > 0.0) r.specular += t.intensity * std::pow(nh, setup.shininess);
  }
  return r;
}

Vec3 surface_normal(const Vec3& gradient_index, const Vec3& world_scale) {
  const Vec3 g = gradient_index / world_scale;  // d/dworld = d/dindex / scale
  const double len = glm::length(g);
  if (len == 0.0) return Vec3(0.0);
  return -g / len;
}

Vec3 shade(const Classified& c, const Reflectance& r) {
  const double intensity = c.ka + c.kd * r.diffuse + c.ks * r.specular;
  return glm::clamp(c.color * intensity, 0.0, 1.0);
}

// --- Compositing --------------------------------------------------------------

double opacity_correct(double alpha, double step) {
  if (alpha >= 1.0) return 1.0;
  return 1.0 - std::pow(1.0 - alpha, step);
}

void composite(Accumulator& acc, const Vec3& color, double alpha) {
  const double w = (1.0 - acc.alpha) * alpha;
  acc.color += w * color;
  acc.alpha += w;
}

// --- The whole ray ------------------------------------------------------------

std::uint32_t sample_count(const Segment& s, double step) {
  return static_cast<std::uint32_t>(std::floor(s.length() / step)) + 1u;
}

// --- Beyond the papers: space leaping and jitter (docs/leaping.md) ------------

LeapBlocks make_leap_blocks(std::shared_ptr<const MinMaxBlocks> blocks,
                            const TransferFunction& tf_stored) {
  LeapBlocks l;
  l.empty.resize(blocks->count());
  for (std::size_t i = 0; i < l.empty.size(); ++i)
    l.empty[i] = tf_stored.max_alpha(blocks->vmin[i], blocks->vmax[i]) <= 0.0 ? 1 : 0;
  l.blocks = std::move(blocks);
  return l;
}

bool LeapBlocks::skips(const Vec3& p) const {
  const MinMaxBlocks& b = *blocks;
  const int lb = b.block_log2;
  return empty[b.index(cell_base(p.x, b.dims[0]) >> lb, cell_base(p.y, b.dims[1]) >> lb,
                       cell_base(p.z, b.dims[2]) >> lb)] != 0;
}

double pixel_jitter(const RenderSettings& settings, int x, int y) {
  return std::ldexp(static_cast<double>(jitter_raw(x, y, settings.jitter_bits)),
                    -settings.jitter_bits);
}

namespace {
// Samples at t_enter + (k + jitter)·step for k = 0 .. floor((length - jitter·step)/step);
// none when the jitter moves the first past the exit. jitter = 0: sample_count.
std::uint32_t jittered_count(const Segment& s, double step, double jitter) {
  if (jitter == 0.0) return sample_count(s, step);
  const double rest = s.length() - jitter * step;
  if (rest < 0.0) return 0;
  return static_cast<std::uint32_t>(std::floor(rest / step)) + 1u;
}
}  // namespace

double segment_weight(std::uint32_t k, std::uint32_t n, double length, double jitter) {
  if (k == 0) return n == 1 ? length : 1.0 + jitter;
  if (k + 1 == n) return length - (jitter + static_cast<double>(n - 1));
  return 1.0;
}

namespace {
// RenderSettings::study: segment `front -> back` (index-space positions pf, pb;
// values and gradients of the two samples) composited from kStudySubsamples
// sub-samples at the midpoints of equal parts. Returns true when early ray
// termination stops the ray inside the segment.
bool composite_study_segment(const RenderVolume& rv, const TransferFunction& tf,
                             const ShadingSetup& shading, const RenderSettings& settings,
                             const Vec3& pf, const Vec3& pb, const Sample& front,
                             const Sample& back, Accumulator& acc) {
  using Study = RenderSettings::SegmentStudy;
  const bool shaded = settings.mode == RenderMode::Shaded;
  const auto lit = [&](const Classified& c, const Vec3& gradient) {
    return shade(c, reflectance(shading, surface_normal(gradient, rv.world_scale)));
  };
  const bool along_ray =
      settings.study == Study::ExactLighting || settings.study == Study::ExactValue;
  for (int j = 0; j < kStudySubsamples; ++j) {
    const double x = (j + 0.5) / kStudySubsamples;
    const Vec3 p = pf + (pb - pf) * x;
    const Sample ray = along_ray ? interpolate(*rv.volume, *rv.gradients, p) : Sample{};
    const double value = settings.study == Study::ExactValue
                             ? ray.value
                             : front.value + (back.value - front.value) * x;
    Classified c = tf.classify(value);
    if (c.alpha <= 0.0) continue;
    const double alpha = opacity_correct(c.alpha, settings.step / kStudySubsamples);
    Vec3 color = c.color;
    if (shaded) {
      switch (settings.study) {
        case Study::ExactLighting:
          color = lit(c, ray.gradient);
          break;
        case Study::GradientLerp:
          color = lit(c, front.gradient + (back.gradient - front.gradient) * x);
          break;
        case Study::IlluminationLerp: {
          const Vec3 cf = lit(c, front.gradient), cb = lit(c, back.gradient);
          color = cf + (cb - cf) * x;
          break;
        }
        default:
          color = lit(c, front.gradient);
          break;
      }
    }
    composite(acc, color, alpha);
    if (settings.ert_threshold < 1.0 && acc.alpha >= settings.ert_threshold) return true;
  }
  return false;
}
}  // namespace

glm::dvec4 cast_ray(const RenderVolume& rv, const TransferFunction& tf, const ShadingSetup& shading,
                    const RenderSettings& settings, const Ray& ray, RayStats* stats,
                    const LeapBlocks* leap, double jitter) {
  RayStats local;
  RayStats& st = stats ? *stats : local;
  st = RayStats{};
  const std::optional<Segment> seg = clip(ray, rv.world_box);
  if (!seg) return glm::dvec4(0.0);
  st.hit = true;
  const std::uint32_t n = jittered_count(*seg, settings.step, jitter);
  const bool ert = settings.ert_threshold < 1.0;
  // Stepping: positions from the entry point, converted to index space and
  // clamped against rounding at the box faces.
  const auto position = [&](std::uint32_t k) {
    return glm::clamp(ray.at(seg->t_enter + (k + jitter) * settings.step) / rv.world_scale,
                      rv.index_box.lo, rv.index_box.hi);
  };

  if (settings.mode == RenderMode::Mip) {
    double peak = 0.0;
    for (std::uint32_t k = 0; k < n; ++k) {
      peak = std::max(peak, interpolate(*rv.volume, *rv.gradients, position(k)).value);
      ++st.samples;
    }
    const double gray = peak / rv.volume->max_stored();
    return glm::dvec4(gray, gray, gray, 1.0);
  }

  // render.partial_segments: the clipped length in steps, for segment_weight.
  const double length = seg->length() / settings.step;
  Accumulator acc;
  // render.classification = "preintegrated": the previous sample's value and gradient.
  double front = 0.0;
  Vec3 front_gradient(0.0);
  for (std::uint32_t k = 0; k < n; ++k) {
    const Vec3 p = position(k);
    // A sample in an empty block classifies transparent: skipped unread.
    if (leap && leap->skips(p)) {
      ++st.skipped;
      continue;
    }
    const Sample s = interpolate(*rv.volume, *rv.gradients, p);
    ++st.samples;
    Classified c = tf.classify(s.value);
    if (settings.preintegrated) {
      // §4a: the segment from the previous sample to this one, integrated
      // exactly; a ray's first sample opens its first segment and ends none.
      // The segment is lit with the gradient at its front, where a ray entering
      // a surface gathers most of its opacity (docs/pipeline.md §4a).
      const double f = front;
      const Vec3 lit = front_gradient;
      front = s.value;
      front_gradient = s.gradient;
      if (k == 0) continue;
      if (settings.study != RenderSettings::SegmentStudy::None) {
        const Sample fs{f, lit};
        if (composite_study_segment(rv, tf, shading, settings, position(k - 1), p, fs, s, acc)) {
          st.terminated_early = k + 1 < n;
          break;
        }
        continue;
      }
      const SegmentClass sc = tf.max_alpha(std::min(f, s.value), std::max(f, s.value)) > 0.0
                                  ? preintegrate(tf, f, s.value, settings.step)
                                  : SegmentClass{};
      if (sc.alpha <= 0.0) continue;
      c.color = sc.color();
      const Vec3 color =
          settings.mode == RenderMode::Shaded
              ? shade(c, reflectance(shading, surface_normal(lit, rv.world_scale)))
              : c.color;
      composite(acc, color, sc.alpha);
      if (ert && acc.alpha >= settings.ert_threshold) {
        st.terminated_early = k + 1 < n;
        break;
      }
      continue;
    }
    if (c.alpha <= 0.0) continue;
    // Opacity correction for the segment the sample stands for: one step, or
    // with render.partial_segments the first and last segments' lengths.
    const double alpha = settings.partial_segments
                             ? opacity_correct(c.alpha, settings.step *
                                                            segment_weight(k, n, length, jitter))
                             : opacity_correct(c.alpha, settings.step);
    if (alpha <= 0.0) continue;  // a segment of length 0: transparent
    const Vec3 color =
        settings.mode == RenderMode::Shaded
            ? shade(c, reflectance(shading, surface_normal(s.gradient, rv.world_scale)))
            : c.color;
    composite(acc, color, alpha);
    if (ert && acc.alpha >= settings.ert_threshold) {
      st.terminated_early = k + 1 < n;
      break;
    }
  }
  return glm::dvec4(acc.color, acc.alpha);
}

// --- The whole image ------------------------------------------------------------

RenderSettings make_render_settings(const Scene& scene) {
  RenderSettings s;
  s.mode = scene.render.mode;
  s.step = 1.0 / scene.render.oversampling;
  s.ert_threshold = scene.render.ert_threshold;
  if (scene.render.jitter) s.jitter_bits = scene.precision.t_frac_bits;
  s.partial_segments = scene.render.partial_segments;
  s.preintegrated = scene.render.preintegrated() && scene.render.mode != RenderMode::Mip;
  return s;
}

RenderInputs make_render_inputs(const Scene& scene, const Volume& volume,
                                const GradientField& gradients, const CameraPose& pose) {
  RenderInputs in;
  in.volume = make_render_volume(volume, gradients, scene.volume.crop);
  in.tf = stored_transfer_function(scene, volume);
  in.camera = make_camera_frame(scene.camera, pose, scene.render.width, scene.render.height,
                                in.volume.world_scale);
  in.shading = make_shading_setup(scene.lights, in.camera.forward, scene.material.shininess);
  in.settings = make_render_settings(scene);
  if (scene.render.space_leaping && scene.render.mode != RenderMode::Mip)
    in.leap = make_leap_blocks(std::make_shared<const MinMaxBlocks>(make_min_max_blocks(
                                   volume, leap_block_log2(scene.render.leap_block))),
                               in.tf);
  return in;
}

Image render_image(const RenderInputs& in, int threads, FrameStats* stats,
                   const std::function<void()>& row_done) {
  Image img(in.camera.width, in.camera.height);
  std::vector<FrameStats> rows(static_cast<std::size_t>(img.height));
  parallel_for(
      img.height,
      [&](int y) {
        FrameStats& fs = rows[static_cast<std::size_t>(y)];
        for (int x = 0; x < img.width; ++x) {
          RayStats rs;
          img.at(x, y) = cast_ray(in.volume, in.tf, in.shading, in.settings,
                                  primary_ray(in.camera, x, y), &rs,
                                  in.leap ? &*in.leap : nullptr, pixel_jitter(in.settings, x, y));
          fs.add(rs);
        }
        if (row_done) row_done();
      },
      threads);
  if (stats) {
    *stats = FrameStats{};
    for (const FrameStats& r : rows) *stats += r;
  }
  return img;
}

void FrameStats::add(const RayStats& r) {
  rays += 1;
  samples += r.samples;
  samples_skipped += r.skipped;
  rays_hit += r.hit ? 1 : 0;
  rays_terminated_early += r.terminated_early ? 1 : 0;
}

FrameStats& FrameStats::operator+=(const FrameStats& o) {
  samples += o.samples;
  rays += o.rays;
  rays_hit += o.rays_hit;
  rays_terminated_early += o.rays_terminated_early;
  samples_skipped += o.samples_skipped;
  return *this;
}

std::ostream& operator<<(std::ostream& os, const FrameStats& s) {
  return os << "{rays " << s.rays << ", hit " << s.rays_hit << ", terminated early "
            << s.rays_terminated_early << ", samples " << s.samples << ", skipped "
            << s.samples_skipped << "}";
}

}  // namespace voxcast::ref
