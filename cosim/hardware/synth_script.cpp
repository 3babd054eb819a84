#include "cosim/hardware/synth_script.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cosim/engines/engines.hpp"
#include "cosim/hardware/constraints.hpp"
#include "hls/frame_image.hpp"
#include "hls/host_frame.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene.hpp"
#include "refmodel/error.hpp"
#include "refmodel/precision/preset_profiles.hpp"
#include "refmodel/precision/presets.hpp"

namespace voxcast::cosim {
namespace {

namespace fs = std::filesystem;

// The presets compiled into hls/vizard2_synth_top.cpp, by the name of their
// traits type (the -D value, refmodel/precision/profile_traits.hpp) and their
// preset name.
struct CompiledPreset {
  const char* constant;
  const char* name;
  PrecisionProfile profile;
};
constexpr CompiledPreset kCompiled[] = {{"Vizard2Traits", "vizard2", kVizard2},
                                        {"BalancedTraits", "balanced", kBalanced},
                                        {"PreciseTraits", "precise", kPrecise}};

// Tcl braces quote a word literally; a path with braces or newlines could not be.
std::string tcl_word(const std::string& s) {
  if (s.find_first_of("{}\\\n") != std::string::npos)
    throw Error("synth-script: cannot quote '" + s + "' as a Tcl word");
  return "{" + s + "}";
}

}  // namespace

std::vector<SynthTop> synth_tops(const ref::Scene& scene) {
  for (const CompiledPreset& c : kCompiled) {
    if (scene.precision == c.profile)
      return {SynthTop{.function = "vizard2_frame_top",
                       .source = "hls/vizard2_synth_top.cpp",
                       .headers = {"hls/vizard2_top.hpp"},
                       .profile_macro = std::string("-DVOXCAST_SYNTH_PROFILE=") + c.constant,
                       .profile_name = c.name}};
  }
  throw Error(
      "synth-script: the scene's precision profile is not a compiled preset (the synthesizable "
      "top is compiled for the presets vizard2, balanced, precise; set precision.profile)");
}

std::string synth_cflags(const SynthTop& top, const std::string& source_root,
                         const std::string& config_header) {
  // C++14: the vendor front ends' dialect (UG1399), which the design is
  // written in (the dialect tests check it). VOXCAST_VENDOR_TYPES: the tool's
  // own ap_fixed/ap_int (hls/types.hpp). VOXCAST_HLS_KERNELS_ONLY: the host
  // loaders stay out of a C simulation too, where __SYNTHESIS__ is not
  // defined (hls/pragma.hpp). -include: the scene's units
  // (hls/vizard2_synth_top.cpp).
  std::string f = "-std=c++14 -I" + source_root +
                  " -DVOXCAST_VENDOR_TYPES -DVOXCAST_HLS_KERNELS_ONLY " + top.profile_macro;
  if (!config_header.empty()) f += " -include " + config_header;
  return f;
}

hls::Units elaborated_units(const ref::Elaboration& e) {
  return hls::Units{.perspective = e.perspective,
                    .parallel_direction = e.parallel_direction,
                    .gradients = e.gradients,
                    .classification = e.classification,
                    .reflectance_map = e.reflectance_map,
                    .shader = e.shader,
                    .compositor = e.compositor,
                    .ert = e.ert,
                    .mip = e.mip,
                    .space_leaping = e.space_leaping,
                    .partial_segments = e.partial_segments,
                    .preintegration = e.preintegration};
}

// One `/* name = */ true,` line per unit of hls::UnitSet, in its parameter order.
static std::string unit_set_arguments(const hls::Units& u) {
  const std::pair<const char*, bool> flags[] = {
      {"perspective", u.perspective},       {"parallel_direction", u.parallel_direction},
      {"gradients", u.gradients},           {"classification", u.classification},
      {"reflectance_map", u.reflectance_map}, {"shader", u.shader},
      {"compositor", u.compositor},         {"ert", u.ert},
      {"mip", u.mip},                       {"space_leaping", u.space_leaping},
      {"partial_segments", u.partial_segments}, {"preintegration", u.preintegration}};
  std::string out;
  for (std::size_t i = 0; i < std::size(flags); ++i)
    out += std::string("    /* ") + flags[i].first + " = */ " + (flags[i].second ? "true" : "false") +
           (i + 1 < std::size(flags) ? ",\n" : ">;\n");
  return out;
}

std::string elaborated_config_header(const ref::Scene& scene, const ref::Elaboration& e,
                                     const std::string& scene_name) {
  const SynthTop top = synth_tops(scene).front();  // refuses a profile that is not compiled
  const std::string constant = top.profile_macro.substr(top.profile_macro.find('=') + 1);
  const hls::Units u = elaborated_units(e);
  if (!hls::consistent(u))
    throw Error("synth-script: the elaborated units of " + scene_name + " are inconsistent");
  auto b = [](bool v) { return v ? "true" : "false"; };
  auto b01 = [](bool v) { return v ? "1" : "0"; };
  std::ostringstream os;
  os << "// The elaborated configuration of the VIZARD II top for " << scene_name << ":\n"
     << "// the units the scene needs and their sizes, from ref::elaborate\n"
     << "// (refmodel/scene/elaboration.hpp). Generated by `voxcast synth-script`;\n"
     << "// hls/vizard2_synth_top.cpp reads it (-include), docs/synthesis.md.\n"
     << "//\n// Left out:\n";
  for (const ref::Omission& o : e.omitted) os << "//   " << o.unit << ": " << o.reason << "\n";
  os << "#pragma once\n\n#define VOXCAST_ELABORATED_CONFIG 1\n"
     << "// The units with on-chip tables, for the top's storage pragmas (the\n"
     << "// preprocessor cannot read Units below; the top checks they agree).\n"
     << "#define VOXCAST_ELABORATED_HAS_PERSPECTIVE " << b01(u.perspective) << "\n"
     << "#define VOXCAST_ELABORATED_HAS_CLASSIFICATION " << b01(u.classification) << "\n"
     << "#define VOXCAST_ELABORATED_HAS_REFLECTANCE_MAP " << b01(u.reflectance_map) << "\n"
     << "#define VOXCAST_ELABORATED_HAS_SPACE_LEAPING " << b01(u.space_leaping) << "\n"
     << "#define VOXCAST_ELABORATED_HAS_PARTIAL_SEGMENTS " << b01(u.partial_segments) << "\n"
     << "#define VOXCAST_ELABORATED_HAS_PREINTEGRATION " << b01(u.preintegration) << "\n\n"
     << "#include \"hls/units.hpp\"\n#include \"refmodel/precision/profile_traits.hpp\"\n\n"
     << "// C++14, as the design (the vendor front ends' dialect).\n"
     << "namespace voxcast {\nnamespace elaborated {\n\n"
     << "// precision.profile = \"" << top.profile_name << "\"\n"
     << "using Profile = " << constant << ";\n\n"
     << "// The units present (hls/units.hpp, UnitSet).\n"
     << "using Units = hls::UnitSet<\n"
     << unit_set_arguments(u) << "\n"
     << "// Sizes from the data and the transfer function (what `voxcast report`\n"
     << "// prices); the kernels' fields keep the profile's widths, the top checks\n"
     << "// that these fit them.\n"
     << "constexpr int kValueStoreBits = " << e.value_store_bits << ";\n"
     << "constexpr int kGradientStoreBits = " << e.gradient_store_bits << ";\n"
     << "constexpr int kClassEntries = " << e.class_entries << ";\n"
     << "constexpr int kClassColorFields = " << e.class_color_fields << ";\n"
     << "constexpr bool kClassAlphaVaries = " << b(e.class_alpha_varies) << ";\n\n"
     << "}  // namespace elaborated\n}  // namespace voxcast\n";
  return os.str();
}

std::vector<SynthScript> vitis_scripts(const ref::Scene& scene, const std::string& scene_name,
                                       const rtl::board::Board& board,
                                       const std::string& source_root,
                                       const std::string& config_dir) {
  const fs::path root = fs::absolute(source_root).lexically_normal();
  std::string root_str = root.string();
  if (root_str.size() > 1 && root_str.back() == '/') root_str.pop_back();
  // The tool splits -cflags at blanks: an include path with one cannot be passed.
  if (root_str.find_first_of(" \t") != std::string::npos)
    throw Error("synth-script: the source path '" + root_str +
                "' contains a blank, which -cflags cannot carry");
  std::string config;  // the elaborated configuration's absolute path, if any
  if (!config_dir.empty()) {
    config = (fs::absolute(config_dir).lexically_normal() / kElaboratedConfigFile).string();
    if (config.find_first_of(" \t") != std::string::npos)
      throw Error("synth-script: the output path '" + config +
                  "' contains a blank, which -cflags cannot carry");
  }
  std::vector<SynthScript> out;
  for (const SynthTop& top : synth_tops(scene)) {
    const std::string cflags = tcl_word(synth_cflags(top, root_str, config));
    std::vector<std::string> files{top.source, kCsimTestbench};
    files.insert(files.end(), top.headers.begin(), top.headers.end());
    for (const std::string& f : files)
      if (!fs::is_regular_file(root / f))
        throw Error("synth-script: " + (root / f).string() +
                    " does not exist (give the voxcast source tree with --source-dir)");
    const auto& core = board.core();
    std::ostringstream os;
    os << "# Vitis HLS script: top " << top.function << " (precision profile " << top.profile_name
       << ")\n"
       << "# for board " << board.name << " (" << board.description << ")\n"
       << "# Generated by `voxcast synth-script " << scene_name << " --board " << board.name
       << " --tool vitis`; docs/synthesis.md.\n"
       << "# Run: vitis_hls -f " << top.function << "_vitis.tcl   (the project is created beside "
       << "this script)\n"
       << "#\n"
       << "# Interface (hls/vizard2_synth_top.cpp): s_axilite width, height, return;\n"
       << "# m_axi bundles gmem_frame (frame state), dimm0..dimm3 (two voxel banks each, the\n"
       << "# card's four DIMM channels), gmem_fb (frame buffer, sample count).\n"
       << "# Part: " << board.fpga.tool_part << " (the card's part: " << board.fpga.part << ")\n"
       << "#   source: " << board.fpga.source << "\n"
       << "# Clock: " << core.name << ", " << ns3(core.period_ns()) << " ns\n"
       << "#   source: " << core.source << "\n"
       << "\n"
       << "set voxcast_root " << tcl_word(root_str) << "\n"
       << "set script_dir [file dirname [file normalize [info script]]]\n"
       << "open_project -reset [file join $script_dir " << top.function << "_" << board.name
       << "]\n"
       << "set_top " << top.function << "\n"
       << "add_files [file join $voxcast_root " << top.source << "] -cflags " << cflags << "\n";
    for (const std::string& h : top.headers)
      os << "add_files [file join $voxcast_root " << h << "] -cflags " << cflags << "\n";
    if (!config.empty())
      os << "# The scene's units (" << kElaboratedConfigFile << ", written with this script)\n"
         << "add_files " << tcl_word(config) << " -cflags " << cflags << "\n";
    os << "# C simulation testbench: the frame, the voxel banks and the expected image\n"
       << "# voxcast rendered (" << kCsimDataFile << ", written with this script); every\n"
       << "# pixel must match (hls/tb/vizard2_frame_tb.cpp, docs/synthesis.md).\n"
       << "add_files -tb [file join $voxcast_root " << kCsimTestbench << "] -cflags " << cflags
       << "\n"
       << "set csim_data $script_dir\n"
       << "# RTL co-simulation of a whole frame takes hours: set to 1 to run it.\n"
       << "set run_cosim 0\n"
       << "open_solution -reset -flow_target vivado " << board.name << "\n"
       << "set_part " << tcl_word(board.fpga.tool_part) << "\n"
       << "create_clock -period " << ns3(core.period_ns()) << " -name " << core.name << "\n"
       << "csim_design -argv $csim_data\n"
       << "csynth_design\n"
       << "if {$run_cosim} { cosim_design -argv $csim_data }\n"
       << "export_design -format ip_catalog\n"
       << "exit\n";
    out.push_back({top.function + "_vitis.tcl", os.str()});
  }
  return out;
}

std::string default_source_root() { return VOXCAST_SOURCE_ROOT; }

namespace {

// hls/frame_image.hpp's visitor on the writing side: every field's pattern.
struct WordSink {
  std::vector<std::uint64_t>& out;
  template <class T>
  void bits(const T& x) {
    for (int k = 0; k < hls::image::chunks(T::width); ++k) out.push_back(hls::image::chunk_of(x, k));
  }
  void flag(bool b) { out.push_back(b ? 1 : 0); }
  void mode(hls::FrameMode m) { out.push_back(static_cast<std::uint64_t>(m)); }
};

// The frame state for the units `u` and the 8 packed banks, in the order
// hls/tb/vizard2_frame_tb.cpp reads them.
template <class P>
void append_frame_and_banks(const bittrue::FrameSetup& setup, const bittrue::VoxelMemory& memory,
                            const hls::Units& u, std::vector<std::uint64_t>& out) {
  const auto frame = hls::host::load_frame_state<P>(setup, "synth-script");
  WordSink sink{out};
  hls::image::visit_frame(*frame, u, sink);
  const hls::host::BitTrueBanks<P> view(memory);
  using Addr = typename hls::InterpolationParams<P>::word_addr_t;
  for (int b = 0; b < 8; ++b) {
    const std::size_t n = memory.banks[static_cast<std::size_t>(b)].size();
    out.push_back(n);
    for (std::size_t w = 0; w < n; ++w) sink.bits(hls::pack_voxel_word<P>(view.read(b, Addr(w))));
  }
}

}  // namespace

std::vector<std::uint8_t> csim_data(const ref::Scene& scene, const SceneVolume& sv,
                                    const hls::Units& units) {
  const ref::CameraPose pose = ref::frame_poses(scene.camera, 1).front();
  const ref::RenderInputs in = ref::make_render_inputs(scene, sv.volume, sv.gradients, pose);
  const bittrue::FrameSetup setup = bittrue::make_frame_setup(scene.precision, scene, in);
  const bittrue::VoxelMemory memory =
      bittrue::make_voxel_memory(scene.precision, sv.volume, sv.gradients);
  ref::FrameStats stats;
  const ref::QuantImage expected = hls_render_image(setup, memory, 0, &stats);

  std::vector<std::uint64_t> words{kCsimDataTag, 0, static_cast<std::uint64_t>(setup.regs.width),
                                   static_cast<std::uint64_t>(setup.regs.height)};
  const bool compiled = hls::host::dispatch_profile(scene.precision, [&]<class P>() {
    words[1] = static_cast<std::uint64_t>(
        hls::image::chunks(hls::InterpolationParams<P>::packed_word_t::width));
    append_frame_and_banks<P>(setup, memory, units, words);
  });
  if (!compiled) throw Error("synth-script: the csim data needs a compiled preset profile");
  words.push_back(stats.samples);
  for (const auto& px : expected.pixels)
    for (std::uint32_t c : px) words.push_back(c);

  std::vector<std::uint8_t> bytes;
  bytes.reserve(words.size() * 8);
  for (std::uint64_t w : words)
    for (int b = 0; b < 8; ++b) bytes.push_back(static_cast<std::uint8_t>(w >> (8 * b)));
  return bytes;
}

std::vector<std::string> write_synth_scripts(const ref::Scene& scene, const std::string& scene_name,
                                             const rtl::board::Board& board,
                                             const std::string& tool, const std::string& out_dir,
                                             const std::string& source_root) {
  if (tool != "vitis") throw Error("synth-script: unknown tool '" + tool + "' (known: vitis)");
  (void)synth_tops(scene);  // a profile that is not compiled: refused before the volume loads
  const auto scripts = vitis_scripts(scene, scene_name, board, source_root, out_dir);
  const SceneVolume sv = load_scene_volume(scene);
  const ref::Elaboration e = ref::elaborate(scene, sv.volume, sv.gradients);
  const std::string header = elaborated_config_header(scene, e, scene_name);
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw Error("synth-script: cannot create " + out_dir + ": " + ec.message());
  std::vector<std::string> paths;
  std::vector<SynthScript> files{{kElaboratedConfigFile, header}};
  files.insert(files.end(), scripts.begin(), scripts.end());
  const std::vector<std::uint8_t> data = csim_data(scene, sv, elaborated_units(e));
  files.push_back({kCsimDataFile, std::string(data.begin(), data.end())});
  for (const SynthScript& s : files) {
    const std::string path = (fs::path(out_dir) / s.file_name).string();
    std::ofstream f(path, std::ios::binary);
    f << s.text;
    if (!f) throw Error("synth-script: cannot write " + path);
    paths.push_back(path);
  }
  return paths;
}

}  // namespace voxcast::cosim
