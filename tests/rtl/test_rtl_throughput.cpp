// Closed-form throughput of the rtl engine: when no sample ever changes row,
// the pipeline runs at one sample per clock once it is full, less the
// refresh cost of streaming (docs/sdram.md §5: tRP + tRFC + tRCD = 11 clocks
// per tREFI = 1,562 at PC100). A 128 x 4 x 4 volume is 128 x 2 x 2 = 512
// words per DIMM: row 0 of bank 0 in the linear layout, so every access is a
// row hit except the first and the one after each refresh.
#include <gtest/gtest.h>

#include <cmath>

#include "refmodel/bittrue/raycaster.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "refmodel/volume/gradients.hpp"
#include "rtl_model/engine.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

struct OneRowFrame {
  bittrue::FrameSetup setup;
  bittrue::VoxelMemory memory;
};

OneRowFrame one_row_frame(const std::string& mode, int image) {
  ref::Volume v;
  v.dims = {128, 4, 4};
  v.bits = 8;
  v.source = "one-row test volume";
  v.data.resize(v.voxel_count());
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 128; ++x) v.data[v.index(x, y, z)] = static_cast<std::uint16_t>((x * 3 + y * 50 + z * 20) % 256);
  const ref::GradientField g = ref::compute_gradients(v, ref::GradientOperator::Central);
  // Parallel rays along +x through the 4 x 4 cross-section, 2 samples per voxel.
  const std::string text =
      "[volume]\nsource = \"phantom:box\"\n[classification]\npoints = [ {value = 0, alpha = 0.0}, "
      "{value = 255, color = [1, 1, 1], alpha = 0.01} ]\n[camera]\nprojection = \"parallel\"\n"
      "eye = [-40.0, 1.5, 1.5]\ncenter = [63.5, 1.5, 1.5]\nup = [0.0, 0.0, 1.0]\nheight = 3.0\n"
      "[render]\nwidth = " + std::to_string(image) + "\nheight = " + std::to_string(image) +
      "\noversampling = 2\nert_threshold = 1.0\nmode = \"" + mode + "\"\n[precision]\nprofile = \"vizard2\"\n";
  const ref::Scene s = ref::parse_scene(text, "one-row", ".");
  const ref::RenderInputs in = ref::make_render_inputs(s, v, g, s.camera.pose);
  return {bittrue::make_frame_setup(s.precision, s, in), bittrue::make_voxel_memory(s.precision, v, g)};
}

TEST(RtlThroughput, OneSamplePerClockWhenRowsNeverChange) {
  for (const char* mode : {"mip", "shaded"}) {
    SCOPED_TRACE(mode);
    const OneRowFrame f = one_row_frame(mode, 12);
    ref::FrameStats fs;
    const ref::QuantImage bt = bittrue::bt_render_image(f.setup, f.memory, 1, &fs);
    const rtl::RtlResult r = rtl::rtl_render(f.setup, f.memory, rtl::vizard2_baseline());
    ASSERT_EQ(r.image.pixels, bt.pixels);
    const auto& st = r.stats;
    ASSERT_EQ(st.rays_hit, st.rays) << "every ray crosses the volume";
    ASSERT_GT(st.samples, 30'000u);
    // Closed form: S samples at one per clock, stretched by refresh, plus the
    // pipeline's fill (ray setup 24, address 2, ACT + tRCD + CL 4, then the
    // datapath 4 + 2 + 4 + 1, and the frame-buffer write: about 45 clocks).
    const double refresh = 11.0 / 1562.0;
    const double expected = static_cast<double>(st.samples) / (1.0 - refresh) + 45.0;
    RecordProperty("cycles", std::to_string(st.cycles));
    RecordProperty("closed_form", std::to_string(expected));
    EXPECT_NEAR(static_cast<double>(st.cycles), expected, 0.002 * expected)
        << "samples " << st.samples << "\n" << st;
    EXPECT_GT(st.samples_per_cycle(), 0.99);
    EXPECT_NEAR(st.ns_per_sample(), 10.0 / (1.0 - refresh), 0.05);
    for (const auto& d : st.dimms) {
      EXPECT_EQ(d.controller.row_conflicts, 0u);
      // The first access and the first after each refresh open row 0 again.
      EXPECT_EQ(d.controller.row_misses, d.dimm.refreshes + 1);
      EXPECT_EQ(d.dimm.banks[0].activates, d.dimm.refreshes + 1);
    }
    EXPECT_EQ(st.stalls.issue_buffer_full + st.stalls.interp_blocked, 0);
  }
}

// The same stream issued one sample per ray in turn (16 rays interleaved):
// still one row, still one sample per clock.
TEST(RtlThroughput, RoundRobinIssueKeepsTheRate) {
  const OneRowFrame f = one_row_frame("mip", 12);
  rtl::RtlConfig c = rtl::vizard2_baseline();
  c.pipeline.issue_burst = 1;
  const rtl::RtlResult r = rtl::rtl_render(f.setup, f.memory, c);
  EXPECT_GT(r.stats.samples_per_cycle(), 0.985) << r.stats;
}

}  // namespace
}  // namespace voxcast::test
