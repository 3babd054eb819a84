// Vendor synthesis scripts (voxcast synth-script SCENE --board BOARD --tool
// vitis --out DIR): for each top-level kernel, a Vitis HLS Tcl script built
// from the board (part, core clock) and the scene's elaborated configuration
// (its precision profile selects the compiled preset), naming the real top
// function and source files (docs/synthesis.md).
#pragma once

#include <string>
#include <vector>

#include "refmodel/scene/scene.hpp"
#include "rtl_model/board/board.hpp"

namespace voxcast::cosim {

// One top-level kernel as a vendor tool compiles it.
struct SynthTop {
  std::string function;              // set_top: "vizard2_frame_top"
  std::string source;                // relative to the source root: "hls/vizard2_synth_top.cpp"
  std::vector<std::string> headers;  // the top's interface header(s), relative
  std::string profile_macro;         // "-DVOXCAST_SYNTH_PROFILE=kVizard2"
  std::string profile_name;          // "vizard2"
};

struct SynthScript {
  std::string file_name;  // "vizard2_frame_top_vitis.tcl"
  std::string text;
};

// The tops of the design for a scene: throws voxcast::Error naming the
// compiled presets when the scene's profile is not one of them.
std::vector<SynthTop> synth_tops(const ref::Scene& scene);

// The compiler flags the vendor tool gets for a top (-std, -I, the profile, the
// vendor fixed-point types).
std::string synth_cflags(const SynthTop& top, const std::string& source_root);

// Vitis HLS Tcl for each top. Throws voxcast::Error when a named file does not
// exist under source_root. `scene_name` goes into the comments only.
std::vector<SynthScript> vitis_scripts(const ref::Scene& scene, const std::string& scene_name,
                                       const rtl::board::Board& board,
                                       const std::string& source_root);

// The source tree this binary was built from (compiled in).
std::string default_source_root();

// "vitis" (the only tool so far): writes the scripts into out_dir (created)
// and returns their paths.
std::vector<std::string> write_synth_scripts(const ref::Scene& scene, const std::string& scene_name,
                                             const rtl::board::Board& board,
                                             const std::string& tool, const std::string& out_dir,
                                             const std::string& source_root);

}  // namespace voxcast::cosim
