// Vendor synthesis scripts (voxcast synth-script SCENE --board BOARD --tool
// vitis --out DIR): for each top-level kernel, a Vitis HLS Tcl script built
// from the board (part, core clock) and the scene's elaborated configuration
// (its precision profile selects the compiled preset; elaborated_config.hpp,
// written beside the script, selects the units), naming the real top function
// and source files (docs/synthesis.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cosim/engines/engines.hpp"
#include "hls/units.hpp"
#include "refmodel/scene/elaboration.hpp"
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
// vendor fixed-point types, and -include the elaborated configuration when
// config_header is not empty).
std::string synth_cflags(const SynthTop& top, const std::string& source_root,
                         const std::string& config_header = "");

// The units of the top for an elaboration (ref::Elaboration's flags, one to one).
hls::Units elaborated_units(const ref::Elaboration& e);

// elaborated_config.hpp for the scene, C++14 like the design: the profile
// (Profile, one of the compiled presets' traits types), the units (Units, an
// hls::UnitSet) and the sizes ref::elaborate derived from the data and the
// transfer function, with the omissions and their reasons as comments.
// Defines VOXCAST_ELABORATED_CONFIG.
inline constexpr const char* kElaboratedConfigFile = "elaborated_config.hpp";
std::string elaborated_config_header(const ref::Scene& scene, const ref::Elaboration& e,
                                     const std::string& scene_name);

// Vitis HLS Tcl for each top. Throws voxcast::Error when a named file does not
// exist under source_root. `scene_name` goes into the comments only.
// config_dir: the folder of elaborated_config.hpp (added to the files and
// passed with -include); empty: the full design (AllUnits).
std::vector<SynthScript> vitis_scripts(const ref::Scene& scene, const std::string& scene_name,
                                       const rtl::board::Board& board,
                                       const std::string& source_root,
                                       const std::string& config_dir = "");

// The C simulation testbench (hls/tb/vizard2_frame_tb.cpp) and its data: the
// frame state for `units` (hls/frame_image.hpp), the 8 packed voxel banks, the
// sample count and the image the hls engine renders for the scene, as
// little-endian 64-bit words after the tag kCsimDataTag ("VXFRAME1") and the
// chunks per voxel word, width, height.
inline constexpr const char* kCsimTestbench = "hls/tb/vizard2_frame_tb.cpp";
inline constexpr const char* kCsimDataFile = "csim_frame.bin";
inline constexpr std::uint64_t kCsimDataTag = 0x31454d4152465856ull;
std::vector<std::uint8_t> csim_data(const ref::Scene& scene, const SceneVolume& sv,
                                    const hls::Units& units);

// The source tree this binary was built from (compiled in).
std::string default_source_root();

// "vitis" (the only tool so far): elaborates the scene (loads its volume for
// the data's range), writes elaborated_config.hpp, the scripts and the csim
// data (kCsimDataFile) into out_dir (created) and returns their paths, the
// header first, the data last.
std::vector<std::string> write_synth_scripts(const ref::Scene& scene, const std::string& scene_name,
                                             const rtl::board::Board& board,
                                             const std::string& tool, const std::string& out_dir,
                                             const std::string& source_root);

}  // namespace voxcast::cosim
