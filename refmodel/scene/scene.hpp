// The scene: everything a render needs, as plain data. Parsed from TOML
// (scene_toml.cpp; every key is documented in docs/scenes.md) and read by every
// engine — refmodel, hls, rtl_model — so they cannot disagree on a parameter.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "refmodel/precision/profile.hpp"
#include "refmodel/volume/gradients.hpp"
#include "refmodel/volume/loaders.hpp"
#include "refmodel/volume/transfer_function.hpp"

namespace voxcast::ref {

struct Crop {
  std::array<int, 3> lo{0, 0, 0};  // inclusive voxel indices
  std::array<int, 3> hi{0, 0, 0};  // inclusive
};

struct VolumeDesc {
  std::string source = "phantom:shepp-logan";
  std::optional<RawSpec> raw;  // set when volume.dims/type are given
  std::optional<Crop> crop;    // VIRIM's cubic sub-regions; whole volume if absent
  GradientOperator gradient = GradientOperator::Central;
  bool resample = true;  // DICOM: resample a gantry-tilted or unevenly spaced series (else refuse)
};

enum class Projection { Perspective, Parallel };

struct CameraPose {
  glm::dvec3 eye{0.0}, center{0.0}, up{0.0, 0.0, 1.0};  // voxel coordinates
};

struct CameraDesc {
  Projection projection = Projection::Perspective;
  CameraPose pose;
  double fov_deg = 40.0;     // perspective: vertical field of view
  double height = 64.0;      // parallel: view height in voxels (world units)
  double stereo_deg = 0.0;   // 0 = mono; VIRIM used 4
  std::vector<CameraPose> path;  // keyframes of a flythrough (may be empty)
};

enum class RenderMode { Shaded, Unshaded, Mip };

// How a sample is classified (render.classification): "post" looks the
// interpolated value up in the 1-D table (§4, VIZARD II); "preintegrated"
// classifies the segment from the previous sample to this one through the 2-D
// pre-integration table (§4a; Engel, Kraus and Ertl 2001).
enum class ClassificationMode { Post, Preintegrated };

struct RenderDesc {
  int width = 256;
  int height = 256;
  RenderMode mode = RenderMode::Shaded;
  double oversampling = 1.0;    // samples per world unit along the ray
  double ert_threshold = 0.98;  // early ray termination; >= 1 disables it
  glm::dvec3 background{0.0};
  int frames = 1;               // frames along camera.path
  int threads = 0;              // 0 = all cores
  // Beyond the papers (docs/leaping.md): skip samples in blocks of
  // leap_block^3 cells whose values all classify transparent (min-max blocks),
  // and start each ray a per-pixel hashed fraction of a step late.
  bool space_leaping = false;
  int leap_block = 8;           // cells per block edge: 4, 8, 16, 32 or 64
  bool jitter = false;
  // Issue 19 part 2 (docs/pipeline.md §7a): weight the first and the last
  // sample of each ray by the fractional length of the segment it stands for
  // (opacity correction at the fractional step), so that the image is
  // continuous in the camera.
  bool partial_segments = true;
  // Issue 25 (docs/pipeline.md §4a): pre-integrated classification. It
  // classifies whole segments between samples, so a scene that asks for it
  // has render.partial_segments off unless it sets both (an error), and it
  // cannot leap (a leap would lose the segment's front value).
  ClassificationMode classification = ClassificationMode::Post;
  bool preintegrated() const { return classification == ClassificationMode::Preintegrated; }
};

enum class LightType { Directional, Headlight };

struct Light {
  LightType type = LightType::Headlight;
  glm::dvec3 direction{0.0, 0.0, 1.0};  // towards the light, world axes (directional only)
  double intensity = 1.0;
};

// [rtl]: the cycle model of the card (rtl_model/, docs/performance.md) as plain
// names and numbers; rtl::rtl_config() (rtl_model/scene_config.hpp) turns it
// into the model's RtlConfig. The defaults are the VIZARD II baseline. The
// accepted names are rtl_choices() (scene_toml.hpp); tests/rtl checks them
// against the model's registries.
struct RtlDesc {
  std::string scheduler = "in-order";  // row-activate scheduler (rtl_model/sched/)
  int reorder_window = 8;              // fr-fcfs: requests considered, oldest first
  int starvation_limit = 64;           // fr-fcfs: hits that may bypass the oldest request
  std::string refresh = "eager";       // refresh policy
  int refresh_postpone = 0;            // REFs that may be postponed (DimmConfig)
  // The card: clocks, DIMM geometry and SDRAM timing come from this board
  // description (constraints/boards/, docs/constraints.md), the one source the
  // timing constraints are generated from too. A shipped name or a .toml path
  // (relative paths resolved against the scene's folder by the reader).
  std::string board = "vizard2_pci";
  std::string sdram = "board";         // "board": the board's timing; else a preset overriding it
  std::string layout = "linear";       // address mapping inside the DIMMs
  std::array<int, 3> brick{8, 8, 8};   // bricked: words per brick edge (x, y/2, z/2)
  std::string traversal = "scanline";  // ray order: scanline | tiles
  int tile = 8;                        // tiles: edge in pixels
  int ray_slots = 16;                  // rays in flight
  // How the address generator picks the ray it issues from: "oldest" (the
  // oldest ready ray, issue_burst samples at a time) or "row-hit" (the oldest
  // ray whose next sample hits the rows last requested, ray-level FR-FCFS).
  std::string issue = "oldest";
  int issue_burst = 0;                 // oldest: samples per ray before the next; 0 = whole ray
  int issue_bypass_limit = 64;         // row-hit: issues that may bypass the oldest ready ray
  int sample_buffer = 64;              // samples between address generator and interpolation
  int queue_depth = 8;                 // controller request queue per DIMM
  int return_depth = 8;                // controller read-data return FIFO per DIMM
  bool auto_precharge = false;         // a row's last queued READ closes it (RDA); false: open page
  // A DDR4 board's card (rtl_model/pipeline/burst_card.hpp): ray pipelines
  // sharing the four channels; the SDR card has one.
  int pipelines = 1;
};
// --- VIRIM: the Heidelberg Raytracing Model (docs/heidelberg.md) ----------------
enum class Algorithm { Raycast, Heidelberg };
enum class HeidelbergInterpolation { Gaussian, Trilinear };
enum class HeidelbergGradient { Sobel2D, Sobel3D };

// [heidelberg]: the rotator's view transform and the slice model's parameters.
struct HeidelbergDesc {
  // The four user weights (VIRIM's reflection parameters, section "User Interface").
  double diffuse_0 = 0.6;    // diffuse scattering of the 0 deg light
  double diffuse_45 = 0.4;   // diffuse scattering of the 45 deg light
  double specular_45 = 0.4;  // specular scattering of the 45 deg light (x surface probability)
  double luminosity = 0.2;   // self-luminosity, proportional to the local light
  double light = 1.0;        // intensity of both parallel lights entering the cube
  int shininess = 8;         // Phong exponent of the specular term
  double background_threshold = 0.95;  // light leaving a line's far end above this: background
  HeidelbergInterpolation interpolation = HeidelbergInterpolation::Gaussian;
  double gaussian_sigma = 0.5;  // width of the Gaussian mask, in voxels
  int weight_bits = 6;          // weight-ROM address bits per coordinate (VIRIM: 6)
  HeidelbergGradient gradient = HeidelbergGradient::Sobel2D;
  glm::dvec3 axis{0.0, 0.0, 1.0};  // rotation axis, volume axes
  double angle_deg = 0.0;          // rotation about `axis` through the volume centre
  glm::dvec3 translation{0.0};     // view-space shift of the cube, voxels
  double zoom = 1.0;
  double perspective = 0.0;  // eye distance from the cube centre in voxels; 0 = parallel
  int depth = 0;             // voxels along the view (y); 0 = the volume's largest dimension
  double stereo_deg = 0.0;   // 0 = mono; VIRIM: 4 (two images 4 deg apart)
  // The rtl engine's VIRIM card (docs/virim-rtl.md): modules of 1 rotator + 16
  // DSPs ("Four modules are required ... 256x256x128"), and its three clocks.
  int modules = 4;
  double rotator_mhz = 40.0;  // 160 M voxels/s over 4 modules at one voxel per clock
  double dsp_mhz = 40.0;      // "Running at a speed of 40 MHz"
  double bus_mhz = 40.0;      // 240 MB/s over the 48-bit (6-byte) bus
};
const char* to_string(Algorithm a);

struct Scene {
  std::string origin = "scene";  // file path or "default scene", for messages
  std::string base_dir = ".";    // resolves relative volume paths
  VolumeDesc volume;
  std::vector<TfPoint> tf_points;
  TfInterpolation tf_interpolation = TfInterpolation::Ramp;
  Material material;
  CameraDesc camera;
  RenderDesc render;
  std::vector<Light> lights;
  // [precision]: the fixed-point design's widths (docs/pipeline.md).
  std::string precision_name = "balanced";  // the preset, plus "+overrides" if any
  PrecisionProfile precision;
  RtlDesc rtl;  // [rtl]: the cycle model's card configuration
  // VIRIM (render.algorithm, [heidelberg]).
  Algorithm algorithm = Algorithm::Raycast;
  HeidelbergDesc heidelberg;
};

const char* to_string(Projection p);
const char* to_string(RenderMode m);
const char* to_string(ClassificationMode m);
const char* to_string(LightType t);

// The transfer function of the scene in the volume's stored units.
TransferFunction stored_transfer_function(const Scene& scene, const Volume& volume);

// Checks what can only be checked against the loaded volume (crop inside the
// dims); throws voxcast::Error naming the key.
void validate_against_volume(const Scene& scene, const Volume& volume);

// The poses of an animation: the camera pose if there is no path, else
// `frames` poses linearly interpolated along the keyframes.
std::vector<CameraPose> frame_poses(const CameraDesc& camera, int frames);

}  // namespace voxcast::ref
