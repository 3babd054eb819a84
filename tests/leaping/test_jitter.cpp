// Jittered ray starts (docs/leaping.md): every engine delays pixel (x, y)'s
// first sample by the same hashed fraction J·2^-tf of a step, for any thread
// count.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cosim/engines/engines.hpp"
#include "hls/host_frame.hpp"
#include "refmodel/bittrue/geometry.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/render/jitter.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/engine.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

ref::Scene scene(bool jitter, const std::string& extra = "render.mode=shaded") {
  return ref::default_scene({"render.width=20", "render.height=20",
                             std::string("render.jitter=") + (jitter ? "true" : "false"), extra});
}

TEST(Jitter, OffsetsAreUniformFractionsOfAStep) {
  // J < 2^tf always; over 64 x 64 pixels the mean of J·2^-tf is 1/2 within a
  // few standard errors (1/sqrt(12·4096) = 0.0045), and each quarter of [0, 1)
  // gets a quarter of the pixels within 3 standard errors (sqrt(4096·3/16) = 27.7).
  const int tf = kBalanced.t_frac_bits;
  double sum = 0.0;
  int quarter[4] = {0, 0, 0, 0};
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const std::uint32_t j = ref::jitter_raw(x, y, tf);
      ASSERT_LT(j, 1u << tf);
      const double f = std::ldexp(j, -tf);
      sum += f;
      ++quarter[static_cast<int>(f * 4.0)];
    }
  EXPECT_NEAR(sum / 4096.0, 0.5, 0.015);
  for (int q : quarter) EXPECT_NEAR(q, 1024, 84);
  EXPECT_EQ(ref::jitter_raw(3, 5, 0), 0u);
}

TEST(Jitter, EveryEngineStartsEachRayAtTheSameOffset) {
  const ref::Scene on = scene(true), off = scene(false);
  const cosim::SceneVolume sv = cosim::load_scene_volume(on);
  const auto setup = [&](const ref::Scene& s) {
    return bittrue::make_frame_setup(
        s.precision, s, ref::make_render_inputs(s, sv.volume, sv.gradients, s.camera.pose));
  };
  const bittrue::FrameSetup fs_on = setup(on), fs_off = setup(off);
  const ref::RenderInputs in_on = ref::make_render_inputs(on, sv.volume, sv.gradients, on.camera.pose);
  constexpr PrecisionProfile P = kBalanced;
  ASSERT_EQ(on.precision, P);
  const auto frame = hls::host::load_frame_state<ProfileTraits<P>>(fs_on, "test");
  const int tf = P.t_frac_bits;
  int moved = 0, hits = 0;
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 20; ++x) {
      const double j = std::ldexp(ref::jitter_raw(x, y, tf), -tf);
      // The double reference uses the same fraction.
      EXPECT_EQ(ref::pixel_jitter(in_on.settings, x, y), j);
      const bittrue::BtRay a = bittrue::bt_ray_setup(fs_off, x, y);
      const bittrue::BtRay b = bittrue::bt_ray_setup(fs_on, x, y);
      if (!a.hit) {
        EXPECT_FALSE(b.hit);
        continue;
      }
      // Bit-true: the entry moves by J·2^-tf samples, in [0, 1); a ray whose
      // first sample moves past its exit takes none.
      if (b.hit) {
        EXPECT_EQ(b.k_in - a.k_in, j);
        EXPECT_GE(b.k_in - a.k_in, 0.0);
        EXPECT_LT(b.k_in - a.k_in, 1.0);
        EXPECT_EQ(b.n, static_cast<std::uint64_t>(std::floor(a.k_out - b.k_in)) + 1u);
        moved += b.p0 != a.p0;
        ++hits;
      } else {
        EXPECT_GT(a.k_in + j, a.k_out);
      }
      // hls: the same ray set-up bits.
      const hls::RaySetup<ProfileTraits<P>> h = hls::ray_setup<ProfileTraits<P>>(frame->geometry, frame->rsqrt.seed, x, y);
      ASSERT_EQ(h.hit, b.hit);
      if (!b.hit) continue;
      EXPECT_EQ(h.k_in.to_double(), b.k_in);
      EXPECT_EQ(h.n.to_uint64(), b.n);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(h.p0[k].to_double(), b.p0[static_cast<std::size_t>(k)]);
    }
  // A first sample stays put only if J·s rounds to 0 at pos_frac_bits: rare.
  EXPECT_GT(hits, 100);
  EXPECT_GE(moved, hits * 9 / 10);
}

TEST(Jitter, ImagesAgreeAcrossEnginesAndThreadCounts) {
  for (const char* mode : {"render.mode=shaded", "render.mode=mip"}) {
    SCOPED_TRACE(mode);
    const ref::Scene s = scene(true, mode);
    const cosim::SceneVolume sv = cosim::load_scene_volume(s);
    const ref::RenderInputs in = ref::make_render_inputs(s, sv.volume, sv.gradients, s.camera.pose);
    const bittrue::FrameSetup fs = bittrue::make_frame_setup(s.precision, s, in);
    const bittrue::VoxelMemory mem =
        bittrue::make_voxel_memory(s.precision, sv.volume, sv.gradients);
    const ref::QuantImage bt1 = bittrue::bt_render_image(fs, mem, 1);
    const ref::QuantImage bt2 = bittrue::bt_render_image(fs, mem, 2);
    const ref::QuantImage h1 = cosim::hls_render_image(fs, mem, 1);
    const ref::QuantImage h2 = cosim::hls_render_image(fs, mem, 2);
    EXPECT_EQ(bt1.pixels, bt2.pixels);
    EXPECT_EQ(h1.pixels, h2.pixels);
    EXPECT_EQ(h1.pixels, bt1.pixels);
    EXPECT_EQ(rtl::rtl_render(fs, mem, rtl::vizard2_baseline()).image.pixels, h1.pixels);
    const ref::Image r1 = ref::render_image(in, 1), r2 = ref::render_image(in, 2);
    EXPECT_EQ(r1.pixels, r2.pixels);
    // ... and jitter does change the picture.
    const ref::Scene plain = scene(false, mode);
    const ref::RenderInputs in0 =
        ref::make_render_inputs(plain, sv.volume, sv.gradients, plain.camera.pose);
    EXPECT_NE(bittrue::bt_render_image(bittrue::make_frame_setup(plain.precision, plain, in0), mem)
                  .pixels,
              bt1.pixels);
  }
}

TEST(Jitter, WithSpaceLeapingEveryEngineStillAgrees) {
  const ref::Scene s = ref::default_scene({"render.width=20", "render.height=20",
                                           "render.jitter=true", "render.space_leaping=true"});
  const ref::Scene s0 = ref::default_scene({"render.width=20", "render.height=20",
                                            "render.jitter=true"});
  const cosim::SceneVolume sv = cosim::load_scene_volume(s);
  const ref::RenderInputs in = ref::make_render_inputs(s, sv.volume, sv.gradients, s.camera.pose);
  const ref::RenderInputs in0 = ref::make_render_inputs(s0, sv.volume, sv.gradients, s0.camera.pose);
  const bittrue::FrameSetup fs = bittrue::make_frame_setup(s.precision, s, in);
  const bittrue::FrameSetup fs0 = bittrue::make_frame_setup(s0.precision, s0, in0);
  const bittrue::VoxelMemory mem = bittrue::make_voxel_memory(s.precision, sv.volume, sv.gradients);
  const ref::QuantImage h = cosim::hls_render_image(fs, mem, 2);
  EXPECT_EQ(h.pixels, bittrue::bt_render_image(fs, mem, 2).pixels);
  EXPECT_EQ(h.pixels, bittrue::bt_render_image(fs0, mem, 2).pixels);
  EXPECT_EQ(rtl::rtl_render(fs, mem, rtl::vizard2_baseline()).image.pixels, h.pixels);
  EXPECT_EQ(ref::render_image(in, 2).pixels, ref::render_image(in0, 2).pixels);
}

}  // namespace
}  // namespace voxcast::test
