// The synthesizable top with the scene's units (issue 6, part 5): the
// elaborated_config.hpp `voxcast synth-script` writes has the flags the
// elaboration rules give for MIP, unshaded and parallel scenes; the top
// compiled with two such headers (tests/CMakeLists.txt: scenes/mip.toml, and
// scenes/default.toml unshaded with ERT off) is linked here and renders the
// hls engine's image bit for bit; its frame state has no storage for the units
// it lacks.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "cosim/engines/engines.hpp"
#include "cosim/hardware/synth_script.hpp"
#include "hls/host_frame.hpp"
#include "hls/units.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/error.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/board/board.hpp"

namespace {  // the top's declarations below name these from the global namespace

namespace hls = voxcast::hls;
using voxcast::kBalanced;

// The units the elaboration rules give (docs/resources.md, "Elaboration").
// None of these scenes asks for render.space_leaping: no min-max memory. They
// keep render.partial_segments' default (on): the segment-opacity unit where
// there is an opacity to weight (not in MIP).
// MIP with a parallel camera: the maximum register only; no direction or
// rsqrt unit, classification, gradients, reflectance map, shader, over
// operator or ERT comparator.
constexpr hls::Units kMipParallel{.perspective = false,
                                  .parallel_direction = true,
                                  .gradients = false,
                                  .classification = false,
                                  .reflectance_map = false,
                                  .shader = false,
                                  .compositor = false,
                                  .ert = false,
                                  .mip = true,
                                  .space_leaping = false,
                                  .partial_segments = false,
                                  .preintegration = false};
// Perspective, unshaded, ERT off: no view-direction register, gradients,
// reflectance map, ERT comparator or MIP unit.
constexpr hls::Units kUnshadedNoErt{.perspective = true,
                                    .parallel_direction = false,
                                    .gradients = false,
                                    .classification = true,
                                    .reflectance_map = false,
                                    .shader = true,
                                    .compositor = true,
                                    .ert = false,
                                    .mip = false,
                                    .space_leaping = false,
                                    .partial_segments = true,
                                    .preintegration = false};
// Parallel, shaded, ERT on: everything but the perspective units and MIP.
constexpr hls::Units kShadedParallel{.perspective = false,
                                     .parallel_direction = true,
                                     .gradients = true,
                                     .classification = true,
                                     .reflectance_map = true,
                                     .shader = true,
                                     .compositor = true,
                                     .ert = true,
                                     .mip = false,
                                     .space_leaping = false,
                                     .partial_segments = true,
                                    .preintegration = false};

using Word = hls::InterpolationParams<voxcast::BalancedTraits>::packed_word_t;

}  // namespace

// hls/vizard2_synth_top.cpp compiled with each scene's elaborated_config.hpp.
// The units are part of the parameter type, so these link only if the
// generated headers carry exactly these flags (and the balanced profile).
void vizard2_frame_top(const hls::FrameState<voxcast::BalancedTraits, hls::host::UnitsType<kMipParallel>>* frame, const Word* bank0,
                       const Word* bank1, const Word* bank2, const Word* bank3, const Word* bank4,
                       const Word* bank5, const Word* bank6, const Word* bank7, int width,
                       int height, hls::OutputPixel<voxcast::BalancedTraits>* fb, std::uint64_t* samples);
void vizard2_frame_top(const hls::FrameState<voxcast::BalancedTraits, hls::host::UnitsType<kUnshadedNoErt>>* frame, const Word* bank0,
                       const Word* bank1, const Word* bank2, const Word* bank3, const Word* bank4,
                       const Word* bank5, const Word* bank6, const Word* bank7, int width,
                       int height, hls::OutputPixel<voxcast::BalancedTraits>* fb, std::uint64_t* samples);

namespace voxcast {
namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;

const std::string kPhantom = "volume.source=phantom:shepp-logan?size=128";

// The flags of a generated header: the "    /* name = */ true|false," lines of
// its UnitSet<...> (the last one ends ">;").
std::map<std::string, bool> header_flags(const std::string& text) {
  std::map<std::string, bool> flags;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) {
    const auto eq = l.find(" = */ ");
    if (l.rfind("    /* ", 0) != 0 || eq == std::string::npos) continue;
    const std::string value = l.substr(eq + 6);
    EXPECT_TRUE(value == "true," || value == "false," || value == "true>;" ||
                value == "false>;")
        << l;
    flags[l.substr(7, eq - 7)] = value.rfind("true", 0) == 0;
  }
  return flags;
}

std::map<std::string, bool> flags_of(const hls::Units& u) {
  return {{"perspective", u.perspective},       {"parallel_direction", u.parallel_direction},
          {"gradients", u.gradients},           {"classification", u.classification},
          {"reflectance_map", u.reflectance_map}, {"shader", u.shader},
          {"compositor", u.compositor},         {"ert", u.ert},
          {"mip", u.mip},                       {"space_leaping", u.space_leaping},
          {"partial_segments", u.partial_segments}, {"preintegration", u.preintegration}};
}

std::string read(const fs::path& p) {
  std::ifstream f(p);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

TEST(ElaboratedTop, SynthScriptWritesTheElaboratedUnits) {
  const fs::path dir = fs::temp_directory_path() / "voxcast_elaborated_header";
  fs::remove_all(dir);
  const auto board = rtl::board::shipped_board("vizard2_pci");
  const struct {
    ref::Overrides sets;
    hls::Units expected;
  } cases[] = {
      {{"render.mode=mip", "camera.projection=parallel"}, kMipParallel},
      {{"render.mode=unshaded", "render.ert_threshold=1"}, kUnshadedNoErt},
      {{"render.mode=shaded", "camera.projection=parallel", "render.ert_threshold=0.95"},
       kShadedParallel},
  };
  for (const auto& c : cases) {
    ref::Overrides sets = c.sets;
    sets.push_back(kPhantom);
    sets.push_back("precision.profile=balanced");
    sets.push_back("render.width=32");  // the csim data renders the frame: keep it small
    sets.push_back("render.height=24");
    SCOPED_TRACE(sets.front() + " " + sets[1]);
    const ref::Scene scene = ref::default_scene(sets);
    const auto paths =
        cosim::write_synth_scripts(scene, "test", board, "vitis", dir.string(), VOXCAST_SOURCE_DIR);
    ASSERT_EQ(paths.size(), 3u);
    EXPECT_EQ(fs::path(paths[0]).filename(), "elaborated_config.hpp");
    const std::string header = read(paths[0]);
    EXPECT_EQ(header_flags(header), flags_of(c.expected)) << header;
    EXPECT_NE(header.find("using Profile = BalancedTraits;"), std::string::npos);
    // Every omission is listed with its reason.
    const cosim::SceneVolume sv = cosim::load_scene_volume(scene);
    const ref::Elaboration e = ref::elaborate(scene, sv.volume, sv.gradients);
    EXPECT_TRUE(hls::same_units(cosim::elaborated_units(e), c.expected));
    for (const ref::Omission& o : e.omitted)
      EXPECT_NE(header.find("//   " + o.unit + ": " + o.reason), std::string::npos) << o.unit;
    // The data's range: 8-bit phantom, so 8 stored value bits.
    EXPECT_NE(header.find("kValueStoreBits = " + std::to_string(e.value_store_bits) + ";"),
              std::string::npos);
    // The Tcl adds the header and passes it with -include.
    const std::string tcl = read(paths[1]);
    EXPECT_NE(tcl.find("-include " + fs::path(paths[0]).lexically_normal().string() + "}"),
              std::string::npos)
        << tcl;
    EXPECT_NE(tcl.find("add_files {" + fs::path(paths[0]).lexically_normal().string() + "}"),
              std::string::npos);
  }
  fs::remove_all(dir);
}

// An absent unit has no storage in the frame state: the MIP design holds
// neither the rsqrt ROM, the classification table nor the reflectance map.
TEST(ElaboratedTop, AbsentUnitsHaveNoState) {
  using Full = hls::FrameState<voxcast::BalancedTraits>;
  using Mip = hls::FrameState<voxcast::BalancedTraits, hls::host::UnitsType<kMipParallel>>;
  using Unshaded = hls::FrameState<voxcast::BalancedTraits, hls::host::UnitsType<kUnshadedNoErt>>;
  const std::size_t rsqrt = sizeof(hls::RsqrtRom<voxcast::BalancedTraits>);
  const std::size_t table = sizeof(hls::ClassificationTable<voxcast::BalancedTraits>);
  const std::size_t rm =
      sizeof(hls::ReflectanceMap<voxcast::BalancedTraits>) + sizeof(hls::ReflectanceRegisters<voxcast::BalancedTraits>);
  EXPECT_LE(sizeof(Mip) + rsqrt + table + rm, sizeof(Full));
  EXPECT_LE(sizeof(Unshaded) + rm, sizeof(Full));
  EXPECT_GE(sizeof(Unshaded), table + rsqrt);
}

// The 8 banks as the top reads them: packed voxel words (§3.4).
struct PackedVolume {
  std::array<std::vector<Word>, 8> words;
  explicit PackedVolume(const bittrue::VoxelMemory& mem) {
    const hls::host::BitTrueBanks<voxcast::BalancedTraits> view(mem);
    for (int b = 0; b < 8; ++b)
      for (std::size_t w = 0; w < mem.banks[static_cast<std::size_t>(b)].size(); ++w)
        words[static_cast<std::size_t>(b)].push_back(hls::pack_voxel_word<voxcast::BalancedTraits>(
            view.read(b, hls::InterpolationParams<voxcast::BalancedTraits>::word_addr_t(w))));
  }
};

struct Frame {
  ref::Scene scene;
  cosim::SceneVolume sv;
  bittrue::FrameSetup setup;
  bittrue::VoxelMemory memory;
};

Frame make_frame(const std::string& scene_file, ref::Overrides sets) {
  sets.push_back("render.width=40");
  sets.push_back("render.height=32");
  Frame f{ref::load_scene_file(std::string(VOXCAST_SOURCE_DIR) + "/scenes/" + scene_file, sets),
          {}, {}, {}};
  f.sv = cosim::load_scene_volume(f.scene);
  const ref::CameraPose pose = ref::frame_poses(f.scene.camera, 1).front();
  const ref::RenderInputs in = ref::make_render_inputs(f.scene, f.sv.volume, f.sv.gradients, pose);
  f.setup = bittrue::make_frame_setup(f.scene.precision, f.scene, in);
  f.memory = bittrue::make_voxel_memory(f.scene.precision, f.sv.volume, f.sv.gradients);
  return f;
}

// Runs the linked top for units U on the frame; compares with the hls engine.
template <hls::Units U>
void expect_top_equals_hls(const Frame& f) {
  ASSERT_EQ(f.scene.precision, kBalanced);
  const auto state = hls::host::load_frame_state<voxcast::BalancedTraits, hls::host::UnitsType<U>>(f.setup, "elaborated top");
  const PackedVolume v(f.memory);
  const int w = f.setup.regs.width, h = f.setup.regs.height;
  std::vector<hls::OutputPixel<voxcast::BalancedTraits>> fb(static_cast<std::size_t>(w * h));
  std::uint64_t samples = 0;
  vizard2_frame_top(state.get(), v.words[0].data(), v.words[1].data(), v.words[2].data(),
                    v.words[3].data(), v.words[4].data(), v.words[5].data(), v.words[6].data(),
                    v.words[7].data(), w, h, fb.data(), &samples);
  ref::FrameStats stats;
  const ref::QuantImage hls_image = cosim::hls_render_image(f.setup, f.memory, 1, &stats);
  std::size_t differ = 0, lit = 0;
  for (std::size_t i = 0; i < fb.size(); ++i) {
    const std::array<std::uint32_t, 4> px = {
        static_cast<std::uint32_t>(fb[i].ch[0].to_uint64()),
        static_cast<std::uint32_t>(fb[i].ch[1].to_uint64()),
        static_cast<std::uint32_t>(fb[i].ch[2].to_uint64()),
        static_cast<std::uint32_t>(fb[i].ch[3].to_uint64())};
    differ += px != hls_image.pixels[i] ? 1 : 0;
    lit += px[0] != 0 ? 1 : 0;
  }
  EXPECT_EQ(differ, 0u);
  EXPECT_GT(lit, fb.size() / 8);  // the volume is in view: not a blank frame
  EXPECT_EQ(samples, stats.samples);
}

TEST(ElaboratedTop, MipParallelTopEqualsTheHlsEngine) {
  const Frame f = make_frame("mip.toml", {});
  expect_top_equals_hls<kMipParallel>(f);
}

TEST(ElaboratedTop, UnshadedTopEqualsTheHlsEngine) {
  const Frame f = make_frame("default.toml", {"render.mode=unshaded", "render.ert_threshold=1"});
  expect_top_equals_hls<kUnshadedNoErt>(f);
}

// A frame the design was not elaborated for is a one-line error, not a
// wrong image.
TEST(ElaboratedTop, AFrameOfAnotherSceneIsRefused) {
  const auto message = [](auto&& load) {
    try {
      (void)load();
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const Frame mip = make_frame("mip.toml", {});
  EXPECT_EQ(message([&] {
              return hls::host::load_frame_state<voxcast::BalancedTraits, hls::host::UnitsType<kUnshadedNoErt>>(mip.setup, "top");
            }),
            "top: the design has no units for this camera and no path for render.mode = mip "
            "(it was elaborated for another scene)");
  const Frame shaded = make_frame("mip.toml", {"render.mode=shaded"});
  EXPECT_EQ(message([&] {
              return hls::host::load_frame_state<voxcast::BalancedTraits, hls::host::UnitsType<kMipParallel>>(shaded.setup, "top");
            }),
            "top: the design has no path for render.mode = shaded (it was elaborated for "
            "another scene)");
}

}  // namespace
}  // namespace voxcast
