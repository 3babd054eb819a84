// The streamed top (hls/vizard2_dataflow.hpp: load phase, six processes joined
// by FIFOs, one DATAFLOW run per row, the eight bank ports read at fixed
// ports) renders the hls engine's image bit for bit, with the same count of
// composited samples, in every mode and on the cases where the stream has to
// carry something unusual: end tokens of missed rays, rays whose last samples
// are leapt over, samples dropped after early ray termination, one-pixel rows.
// The engine itself is cast_ray (one ray at a time); both are composed from
// the same unit functions, so this proves the composition, not the units.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "cosim/engines/engines.hpp"
#include "hls/host_frame.hpp"
#include "hls/vizard2_dataflow.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/scene/scene_toml.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

// The eight banks as the top's ports see them: packed words (§3.4).
template <class P>
struct PackedPorts {
  using word_t = typename hls::InterpolationParams<P>::packed_word_t;
  std::array<std::vector<word_t>, 8> words;
  explicit PackedPorts(const bittrue::VoxelMemory& mem) {
    const hls::host::BitTrueBanks<P> view(mem);
    for (int b = 0; b < 8; ++b) {
      const auto ib = static_cast<std::size_t>(b);
      words[ib].reserve(mem.banks[ib].size());
      for (std::size_t w = 0; w < mem.banks[ib].size(); ++w)
        words[ib].push_back(hls::pack_voxel_word<P>(
            view.read(b, typename hls::InterpolationParams<P>::word_addr_t(w))));
    }
  }
  const word_t* operator[](int b) const { return words[static_cast<std::size_t>(b)].data(); }
};

struct Streamed {
  ref::QuantImage image{1, 1, 8};
  std::uint64_t samples = 0;
};

// The top's two phases on the host: the frame state the host wrote, copied
// by the load phase into a second (on-chip) state, then the streamed frame.
template <class P>
Streamed render_streamed(const bittrue::FrameSetup& fs, const bittrue::VoxelMemory& memory) {
  const auto external = hls::host::load_frame_state<P>(fs, "streamed top");
  auto on_chip = std::make_unique<hls::FrameState<P>>();
  hls::load_frame_state<P, hls::AllUnits>(*external, *on_chip);
  const PackedPorts<P> ports(memory);
  const int w = fs.regs.width, h = fs.regs.height;
  std::vector<hls::OutputPixel<P>> fb(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  Streamed out;
  hls::render_frame_streamed<P, hls::AllUnits>(*on_chip, ports[0], ports[1], ports[2], ports[3],
                                               ports[4], ports[5], ports[6], ports[7], w, h,
                                               fb.data(), out.samples);
  out.image = ref::QuantImage(w, h, P::out_bits);
  for (std::size_t i = 0; i < fb.size(); ++i)
    for (int c = 0; c < 4; ++c)
      out.image.pixels[i][static_cast<std::size_t>(c)] =
          static_cast<std::uint32_t>(fb[i].ch[c].to_uint64());
  return out;
}

// The scene with `sets` over scenes/default.toml, small enough for a unit test.
ref::Scene scene_with(std::vector<std::string> sets, const std::string& file = "default.toml") {
  sets.push_back("render.width=24");
  sets.push_back("render.height=16");
  return ref::load_scene_file(std::string(VOXCAST_SOURCE_DIR) + "/scenes/" + file, sets);
}

void expect_streamed_equals_engine(const ref::Scene& scene, const std::string& what) {
  SCOPED_TRACE(what);
  // The scenes share two volumes: each loaded once.
  static std::map<std::string, std::shared_ptr<const cosim::SceneVolume>> volumes;
  auto& cached = volumes[scene.volume.source];
  if (!cached) cached = std::make_shared<const cosim::SceneVolume>(cosim::load_scene_volume(scene));
  const cosim::SceneVolume& sv = *cached;
  const ref::RenderInputs in =
      ref::make_render_inputs(scene, sv.volume, sv.gradients, scene.camera.pose);
  const bittrue::FrameSetup fs = bittrue::make_frame_setup(scene.precision, scene, in);
  const bittrue::VoxelMemory memory =
      bittrue::make_voxel_memory(scene.precision, sv.volume, sv.gradients);
  ref::FrameStats stats;
  const ref::QuantImage engine = cosim::hls_render_image(fs, memory, 2, &stats);
  Streamed streamed;
  const bool compiled = hls::host::dispatch_profile(scene.precision, [&]<class P>() {
    streamed = render_streamed<P>(fs, memory);
  });
  ASSERT_TRUE(compiled) << "the test scenes use the presets";
  ASSERT_EQ(streamed.image.pixels.size(), engine.pixels.size());
  std::size_t differ = 0, first = engine.pixels.size();
  for (std::size_t i = 0; i < engine.pixels.size(); ++i)
    if (streamed.image.pixels[i] != engine.pixels[i] && differ++ == 0) first = i;
  EXPECT_EQ(differ, 0u) << "first differing pixel: " << first;
  EXPECT_EQ(streamed.samples, stats.samples) << "composited samples";
  EXPECT_GT(stats.samples, 0u) << "a case that takes no sample proves nothing";
}

TEST(StreamedTop, ShadedPerspectiveWithErtEqualsTheEngine) {
  expect_streamed_equals_engine(scene_with({}), "default scene");
}

// A low threshold ends most rays early: the compositor must drop the rest of
// each ray's samples and not count them.
TEST(StreamedTop, EarlyTerminationDropsTheRestOfTheRay) {
  expect_streamed_equals_engine(scene_with({"render.ert_threshold=0.3"}), "ERT at 0.3");
}

TEST(StreamedTop, UnshadedAndMipEqualTheEngine) {
  expect_streamed_equals_engine(scene_with({"render.mode=\"unshaded\""}), "unshaded");
  expect_streamed_equals_engine(scene_with({"render.mode=\"mip\""}), "MIP");
  expect_streamed_equals_engine(scene_with({}, "mip.toml"), "scenes/mip.toml (parallel)");
}

// Leaps that end a ray send an end token with no sample.
TEST(StreamedTop, SpaceLeapingEqualsTheEngine) {
  expect_streamed_equals_engine(scene_with({"render.space_leaping=true", "render.leap_block=4"}),
                                "space leaping, 4^3 blocks");
}

// render.partial_segments (§7a): each sample's segment weight rides with its
// tokens to the classification stage; with jitter the first sample's weight
// absorbs the gap before it, and leaps may skip a weighted first or last sample.
TEST(StreamedTop, PartialSegmentsEqualTheEngine) {
  expect_streamed_equals_engine(scene_with({"render.partial_segments=true"}), "partial segments");
  expect_streamed_equals_engine(
      scene_with({"render.partial_segments=true", "render.jitter=true",
                  "render.space_leaping=true", "render.leap_block=4",
                  "render.mode=\"unshaded\"", "precision.profile=\"vizard2\""}),
      "partial segments, jitter, leaping, unshaded, vizard2");
}

TEST(StreamedTop, ParallelCameraAndOtherProfilesEqualTheEngine) {
  expect_streamed_equals_engine(scene_with({"camera.projection=\"parallel\""}), "parallel");
  expect_streamed_equals_engine(scene_with({"precision.profile=\"vizard2\""}), "vizard2 preset");
  expect_streamed_equals_engine(scene_with({"precision.profile=\"precise\""}), "precise preset");
}

// Rows of one pixel, and a view in which most rays miss the volume (a wide
// field of view): the region's end-of-ray counting with few or no samples.
TEST(StreamedTop, OnePixelRowsAndMissedRaysEqualTheEngine) {
  expect_streamed_equals_engine(
      ref::load_scene_file(std::string(VOXCAST_SOURCE_DIR) + "/scenes/default.toml",
                      {"render.width=1", "render.height=16"}),
      "1 x 16");
  expect_streamed_equals_engine(scene_with({"camera.fov_deg=150"}), "fov 150: most rays miss");
}

}  // namespace VOXCAST_UNITY_ID
}  // namespace voxcast::test
