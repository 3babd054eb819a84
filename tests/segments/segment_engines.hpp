// What the tests of the units that classify a ray's segments share
// (render.partial_segments, docs/pipeline.md §7a; render.classification =
// "preintegrated", §4a): a frame's set-up and voxel memory as every engine
// takes them, and a shaded phantom small enough for every engine, the cycle
// model included, in a unit test.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "cosim/engines/engines.hpp"
#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/render/raycaster.hpp"
#include "refmodel/volume/gradients.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/engine.hpp"

namespace voxcast::test::segments {

struct Frame {
  bittrue::FrameSetup setup;
  bittrue::VoxelMemory memory;
};

inline Frame prepare(const ref::Scene& s, const cosim::SceneVolume& sv) {
  const ref::RenderInputs in = ref::make_render_inputs(s, sv.volume, sv.gradients, s.camera.pose);
  return {bittrue::make_frame_setup(s.precision, s, in),
          bittrue::make_voxel_memory(s.precision, sv.volume, sv.gradients)};
}

// An n^3 volume of 8-bit values v(x) along x, with its gradients.
template <class F>
inline cosim::SceneVolume volume_along_x(int n, F v) {
  cosim::SceneVolume sv;
  sv.volume.dims = {n, n, n};
  sv.volume.bits = 8;
  sv.volume.source = "test volume along x";
  sv.volume.data.assign(sv.volume.voxel_count(), 0);
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x)
        sv.volume.data[static_cast<std::size_t>(x + n * (y + n * z))] =
            static_cast<std::uint16_t>(v(x));
  sv.gradients = ref::compute_gradients(sv.volume, ref::GradientOperator::Central);
  return sv;
}

// A 24^3 Shepp-Logan phantom, shaded under two lights, 20x20 at 1.5 samples
// per voxel; `overrides` as --set gives them.
inline ref::Scene small_scene(const ref::Overrides& overrides, const std::string& origin) {
  return ref::parse_scene(
      "[volume]\nsource = \"phantom:shepp-logan?size=24&aa=2\"\n"
      "[classification]\npoints = [ {value = 0, alpha = 0.0}, "
      "{value = 30, color = [0.9, 0.6, 0.4], alpha = 0.05}, "
      "{value = 200, color = [0.5, 0.8, 1.0], alpha = 0.7} ]\n"
      "[camera]\neye = [18.7, -28.8, 21.1]\ncenter = [11.5, 11.5, 11.5]\nfov_deg = 45\n"
      "[render]\nwidth = 20\nheight = 20\noversampling = 1.5\n"
      "[[lights]]\ntype = \"directional\"\ndirection = [1, -1, 1]\nintensity = 0.6\n"
      "[[lights]]\ntype = \"headlight\"\nintensity = 0.6\n",
      origin, ".", overrides);
}

// One frame through hls, bit-true and the cycle model (two host threads):
// the same pixels, and hls's and bit-true's counts the same (EXPECTs).
struct EngineRun {
  ref::QuantImage hls;
  rtl::RtlResult rtl;
};
inline EngineRun expect_engines_agree(const Frame& f) {
  ref::FrameStats hs, bs;
  EngineRun run{cosim::hls_render_image(f.setup, f.memory, 2, &hs),
                rtl::rtl_render(f.setup, f.memory)};
  const ref::QuantImage b = bittrue::bt_render_image(f.setup, f.memory, 2, &bs);
  EXPECT_EQ(run.hls.pixels, b.pixels);
  EXPECT_EQ(run.hls.pixels, run.rtl.image.pixels);
  EXPECT_EQ(hs, bs);
  return run;
}

}  // namespace voxcast::test::segments
