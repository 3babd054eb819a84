// The subcommands of `voxcast`, callable from main() and from tests.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene.hpp"
#include "cosim/engines/warnings.hpp"

namespace voxcast::cosim {

enum class Engine { Ref, BitTrue, Hls, Rtl };
Engine parse_engine(const std::string& name);  // "ref" | "bittrue" | "hls" | "rtl"
const char* to_string(Engine e);

struct RenderOptions {
  std::vector<std::string> outputs;  // each .png or .exr; the same frames go to each
  std::string report_json;           // optional JSON report path
  Engine engine = Engine::Ref;
  // rtl engine: a VCD trace of each view (rtl_model/trace/; a stereo pair or
  // a path adds the image's suffix to the name), and its window of cycles
  // "START:END" of each frame (empty: the whole frame).
  std::string vcd_path = {};
  std::string vcd_window = {};
  // --strict: refuse a scene the precision guard finds hazards in
  // (cosim/engines/warnings.hpp; PrecisionHazardError, exit status 6).
  bool strict = false;
};

// What one `render` did, for the summary line and the JSON report.
struct RenderSummary {
  std::string volume_source;
  std::array<int, 3> dims{};
  int bits = 0;
  double load_seconds = 0.0;
  double render_seconds = 0.0;
  int threads = 0;
  Engine engine = Engine::Ref;
  ref::FrameStats stats;            // summed over views; a VIRIM scene counts only rays
  double rtl_cycles = 0.0;         // summed over frames (rtl engine)
  double rtl_ns_per_sample = 0.0;  // of the last frame
  double rtl_fps = 0.0;
  double rtl_row_hit_rate = 0.0;  // summed over every frame and eye
  double rtl_clock_mhz = 0.0;     // the card's core clock
  // The DDR4 card (rtl_pipelines > 0), of the last frame: samples per second,
  // the channels' bandwidth, the brick caches' hit rate, what bounds it.
  int rtl_pipelines = 0;
  double rtl_samples_per_second = 0.0;
  double rtl_bandwidth_gbs = 0.0;
  double rtl_bandwidth_share = 0.0;
  double rtl_cache_hit_rate = 0.0;
  std::string rtl_bound;
  std::uint64_t rtl_samples_issued = 0;  // composited + issued beyond an early termination
  double rtl_pipeline_busy = 0.0;        // the busiest pipeline's issue clocks / core clocks
  double rtl_channel_busy = 0.0;         // the busiest channel's data-bus clocks / memory clocks
  std::uint64_t vcd_commands = 0;  // SDRAM commands inside the VCD window
  std::vector<Hazard> hazards;     // the precision guard's (fixed-point engines)
  std::vector<std::string> written;
};

// Loads the scene's volume, renders every frame (camera.path) and eye
// (camera.stereo_deg) with the chosen engine and writes the images.
// Frame f of a path gets "_NNNN" before the extension, stereo eyes "_left" and
// "_right".
RenderSummary run_render(const ref::Scene& scene, const RenderOptions& options);

void print_summary(std::ostream& os, const ref::Scene& scene, const RenderSummary& s);

// "out/a.png" with "_left" -> "out/a_left.png": the name of a view's or a
// frame's file (stereo eyes, path frames, their VCD traces).
std::string with_suffix(const std::string& path, const std::string& suffix);

}  // namespace voxcast::cosim
