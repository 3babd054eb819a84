// The VIZARD II ray-casting pipeline in double precision (paper section 2.1):
//
//   ray setup -> clip -> stepping -> interpolation (value and gradient)
//             -> classification -> shading -> compositing (+ early ray termination)
//
// Each stage is a small pure function so that the fixed-point kernels in hls/
// mirror them one to one, and the tests can check each stage against a closed
// form. This is the ground truth every accuracy figure of the tool is measured
// against.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <vector>

#include "refmodel/math/geometry.hpp"
#include "refmodel/render/camera.hpp"
#include "refmodel/render/image.hpp"
#include "refmodel/render/space_leaping.hpp"
#include "refmodel/scene/scene.hpp"
#include "refmodel/volume/gradients.hpp"
#include "refmodel/volume/transfer_function.hpp"
#include "refmodel/volume/volume.hpp"

namespace voxcast::ref {

// The volume as the pipeline sees it: values, the precomputed gradient voxel
// property, and where it sits in world space.
struct RenderVolume {
  const Volume* volume = nullptr;
  const GradientField* gradients = nullptr;
  Vec3 world_scale{1.0};  // normalised spacing: world = index * world_scale
  Box index_box;          // voxel-centre box rendered (crop or whole), index space
  Box world_box;          // the same in world space
};

RenderVolume make_render_volume(const Volume& volume, const GradientField& gradients,
                                const std::optional<Crop>& crop);
Vec3 normalised_spacing(const Volume& volume);

// --- Stage: interpolation --------------------------------------------------------
struct Sample {
  double value = 0.0;   // stored units
  Vec3 gradient{0.0};   // stored units per index step (index space)
};

// Trilinear interpolation of the eight neighbours of `p` (index space, clamped
// to the grid): value and gradient alike (VIZARD II: "in a similar fashion, the
// gradient at sample location is computed").
Sample interpolate(const Volume& volume, const GradientField& gradients, const Vec3& p);

// --- Stage: shading ------------------------------------------------------------
// Lights and viewer at infinity: the reflectance-map assumption of VIZARD II's
// table-based Phong shading (tables "only need to be computed when the
// illumination parameters change"), so L, V and H are constant over the image.
struct ShadingSetup {
  struct Term {
    Vec3 light;      // unit, towards the light
    Vec3 halfway;    // unit, (L + V)/|L + V|
    double intensity = 1.0;
  };
  std::vector<Term> lights;
  double shininess = 20.0;
};

ShadingSetup make_shading_setup(const std::vector<Light>& lights, const Vec3& view_direction,
                                double shininess);

// Diffuse and specular intensities at a surface normal N (unit, or zero):
//   D = sum_l I_l max(0, N.L_l),  S = sum_l I_l [N.L_l > 0] max(0, N.H_l)^n.
// These are exactly what the two reflectance-map tables hold.
struct Reflectance {
  double diffuse = 0.0;
  double specular = 0.0;
};
Reflectance reflectance(const ShadingSetup& setup, const Vec3& normal);

// Surface normal from the index-space gradient: N = -g_world/|g_world| (pointing
// from dense to empty, i.e. towards a viewer outside the material); zero where
// the gradient vanishes (no NaN: such a sample is lit by the ambient term only).
Vec3 surface_normal(const Vec3& gradient_index, const Vec3& world_scale);

// Shaded colour: colour * (ka + kd*D + ks*S), saturated to [0, 1] per channel
// (our reading of "intensities multiplied with the material properties and
// with the color of the classified sample").
Vec3 shade(const Classified& c, const Reflectance& r);

// --- Stage: compositing ----------------------------------------------------------
// alpha is given per unit distance; a step of `step` units has opacity
// 1 - (1 - alpha)^step, which makes the result independent of the sampling rate.
double opacity_correct(double alpha, double step);

struct Accumulator {
  Vec3 color{0.0};  // premultiplied
  double alpha = 0.0;
};
// Front-to-back "over": C += (1 - A) a c,  A += (1 - A) a.
void composite(Accumulator& acc, const Vec3& color, double alpha);

// --- The whole ray -------------------------------------------------------------
// What one ray did; the bit-true engine fills the same structure. The
// definitions, and where the engines legitimately differ, are FrameStats'.
struct RayStats {
  std::uint64_t samples = 0;
  std::uint64_t skipped = 0;  // samples space leaping skipped (not in `samples`)
  bool hit = false;
  bool terminated_early = false;
};

struct RenderSettings {
  RenderMode mode = RenderMode::Shaded;
  double step = 1.0;            // sampling distance, world units (1/oversampling)
  double ert_threshold = 0.98;  // >= 1 disables early ray termination
  int jitter_bits = 0;          // render.jitter: start offset resolution (0 = off)
  bool partial_segments = false;  // render.partial_segments: segment_weight()
  // render.classification = "preintegrated" (docs/pipeline.md §4a): each sample
  // classifies the segment from the previous one (preintegrate(), exact).
  bool preintegrated = false;
  // Float reference only, not a scene key: `voxcast paper engel2001`'s error
  // budget of pre-integration (docs/accuracy.md). Each segment is composited
  // from kStudySubsamples sub-samples instead of the exact table entry, with
  // one of the two approximations of pre-integration removed or replaced.
  enum class SegmentStudy {
    None,              // the table entry (preintegrate), lit at the front sample
    ExactLighting,     // value linear between the samples, lit with the gradient along the ray
    ExactValue,        // the trilinear value along the ray, lit at the front sample
    GradientLerp,      // value linear, lit with the lerp of the two samples' gradients
    IlluminationLerp,  // value linear, the lerp of the two samples' illumination (Lum et al. 2004)
  };
  SegmentStudy study = SegmentStudy::None;
};
inline constexpr int kStudySubsamples = 16;

// render.partial_segments (docs/pipeline.md §7a): the length, in steps, of the
// segment sample k of n stands for on a ray whose clipped length is `length`
// steps and whose first sample lies `jitter` steps after the entry. Sample k
// sits at jitter + k and stands for [max(jitter + k, 0 if k = 0), min(jitter +
// k + 1, length)]: the first sample also takes the unsampled gap before it
// (1 + jitter, or the whole length when it is the only one), the last the
// fraction length - (jitter + n - 1) in [0, 1), every other sample 1. The
// weights sum to `length`, so a constant medium of opacity a per step gives
// 1 - (1 - a)^length whatever the length.
double segment_weight(std::uint32_t k, std::uint32_t n, double length, double jitter);

// Space leaping in the reference (docs/leaping.md): the volume's min-max
// blocks and, per block, whether the transfer function is transparent over
// the block's value range (TransferFunction::max_alpha == 0).
struct LeapBlocks {
  std::shared_ptr<const MinMaxBlocks> blocks;
  std::vector<std::uint8_t> empty;

  // Whether the sample at clamped index-space position p lies in an empty block.
  bool skips(const Vec3& p) const;
};
LeapBlocks make_leap_blocks(std::shared_ptr<const MinMaxBlocks> blocks,
                            const TransferFunction& tf_stored);

// Samples at t_k = t_enter + k*step for k = 0 .. floor((t_exit - t_enter)/step).
// With render.partial_segments the first and last weigh by segment_weight().
std::uint32_t sample_count(const Segment& s, double step);

// `leap`: skip samples in empty blocks (null: no leaping; MIP never leaps).
// `jitter`: the first sample's offset along the ray in steps, in [0, 1).
glm::dvec4 cast_ray(const RenderVolume& rv, const TransferFunction& tf, const ShadingSetup& shading,
                    const RenderSettings& settings, const Ray& ray, RayStats* stats = nullptr,
                    const LeapBlocks* leap = nullptr, double jitter = 0.0);

// The jitter of pixel (x, y) in steps for `settings` (0 without render.jitter).
double pixel_jitter(const RenderSettings& settings, int x, int y);

// --- The whole image -------------------------------------------------------------
// The counts of one frame, the same in every engine of the ray caster (ref,
// bittrue, hls, rtl; docs/pipeline.md §9 "What the engines count"):
//   rays                   pixels cast, width x height;
//   rays_hit               rays that enter the rendered box: ray set-up finds
//                          an entry no later than the exit (ref: clip() in
//                          double; the fixed-point engines: the geometry
//                          processor's hit flag, §1.5, in the profile's widths);
//   rays_terminated_early  rays whose accumulated opacity reached the ERT
//                          threshold at a sample before the ray's last sample
//                          position (samples were left, to read or to leap
//                          over); 0 in MIP and with ERT off, which have no ERT;
//   samples                samples interpolated (read from the volume); the
//                          samples space leaping skipped are not in it;
//   samples_skipped        samples space leaping skipped unread.
// Where they differ: ref decides the hit, the sample count and the ERT sample
// in double, the fixed-point engines in their widths, so a ray grazing the box
// may hit in one and not the other and a ray may end a sample earlier or
// later; the emptiness of a leaping block is decided on the double transfer
// function in ref and on the classification table in the fixed-point engines.
// bittrue, hls and rtl decide every count on the same bits and agree exactly.
struct FrameStats {
  std::uint64_t samples = 0;
  std::uint64_t rays = 0;
  std::uint64_t rays_hit = 0;
  std::uint64_t rays_terminated_early = 0;
  std::uint64_t samples_skipped = 0;  // by space leaping (not in `samples`)

  // One more ray.
  void add(const RayStats& r);
  FrameStats& operator+=(const FrameStats& o);
  bool operator==(const FrameStats&) const = default;
};
std::ostream& operator<<(std::ostream& os, const FrameStats& s);

struct RenderInputs {
  RenderVolume volume;
  TransferFunction tf;  // stored units
  ShadingSetup shading;
  RenderSettings settings;
  CameraFrame camera;
  std::optional<LeapBlocks> leap;  // render.space_leaping
};

// The scene's render settings (mode, step, ERT, jitter, partial segments).
RenderSettings make_render_settings(const Scene& scene);
RenderInputs make_render_inputs(const Scene& scene, const Volume& volume,
                                const GradientField& gradients, const CameraPose& pose);

// Renders every pixel, rows spread over `threads` workers (0 = all cores); the
// result is bit-identical for any thread count. `row_done`, when given, is
// called once per finished row from the worker that rendered it (a progress
// line counts them; it must be thread-safe).
Image render_image(const RenderInputs& in, int threads = 0, FrameStats* stats = nullptr,
                   const std::function<void()>& row_done = {});

}  // namespace voxcast::ref
