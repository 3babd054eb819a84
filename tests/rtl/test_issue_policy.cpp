// Row-hit issue (IssuePolicy::kRowHit, rtl_model/pipeline/ray_pipeline.hpp,
// docs/performance.md §7): the address generator takes the next sample from
// the oldest ready ray whose sample lies in the rows it last requested, so
// rays in flight share each row opening. It reorders samples between rays,
// never within one, so the image is the bit-true reference's; what it changes
// is how often a DIMM changes rows.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "rtl_frames.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/layout/vizard2_layout.hpp"

namespace voxcast::test {
namespace VOXCAST_UNITY_ID {

using rtl::pipeline::IssuePolicy;

// Samples per row opening: every sample reads one word from each DIMM.
double samples_per_activate(const rtl::RtlStats& st) {
  return static_cast<double>(st.samples_issued) * rtl::layout::kDimms /
         static_cast<double>(st.activates());
}

// The organisation that lets rays share rows: bricks whose neighbours lie in
// other banks, look-ahead activation, tiles of rays.
rtl::RtlConfig shared_rows(IssuePolicy issue, int ray_slots) {
  rtl::RtlConfig c = rtl::vizard2_baseline();
  c.mapping.name = "bricked-swizzled";
  c.scheduler = "lookahead";
  c.pipeline.traversal = rtl::pipeline::Traversal::kTiles;
  c.pipeline.ray_slots = ray_slots;
  c.pipeline.issue = issue;
  c.pipeline.issue_bypass_limit = 1 << 20;
  return c;
}

// A perspective frame (make_rtl_frame's oblique 45-degree eye): with whole
// rays issued in turn every brick a ray crosses is opened again for the next
// ray; row-hit issue serves the rays in flight from one opening.
TEST(RowHitIssue, RaysInFlightShareRowOpeningsInPerspective) {
  const RtlFrame f = make_rtl_frame("shepp-logan", 64, 48,
                                    {"precision.profile=vizard2", "render.oversampling=1",
                                     "render.ert_threshold=1.0"});
  const ref::QuantImage bt = bittrue::bt_render_image(f.setup, f.memory, 1);
  const rtl::RtlResult oldest = rtl::rtl_render(f.setup, f.memory, shared_rows(IssuePolicy::kOldest, 64));
  const rtl::RtlResult row_hit = rtl::rtl_render(f.setup, f.memory, shared_rows(IssuePolicy::kRowHit, 64));
  EXPECT_EQ(oldest.image.pixels, bt.pixels);
  EXPECT_EQ(row_hit.image.pixels, bt.pixels);
  ASSERT_EQ(row_hit.stats.samples_issued, oldest.stats.samples_issued);
  const double r_oldest = samples_per_activate(oldest.stats);
  const double r_row_hit = samples_per_activate(row_hit.stats);
  RecordProperty("samples_per_activate_oldest", std::to_string(r_oldest));
  RecordProperty("samples_per_activate_row_hit", std::to_string(r_row_hit));
  // A 64-slot tile of rays crosses each 8x8x8-word brick together: at least
  // twice the samples per opening of whole rays issued in turn.
  EXPECT_GT(r_row_hit, 2.0 * r_oldest) << oldest.stats << row_hit.stats;
  EXPECT_LT(row_hit.stats.cycles, oldest.stats.cycles);
  EXPECT_GT(row_hit.stats.issue_bypasses, 0u);
  // One READ per DIMM per sample on a command bus of one command a clock:
  // no policy can beat a sample per clock.
  EXPECT_GE(row_hit.stats.cycles, row_hit.stats.samples_issued);
}

// The oldest ready ray is bypassed at most issue_bypass_limit times in a row;
// limit 0 is oldest-ready-ray issue.
TEST(RowHitIssue, TheBypassLimitBindsTheOldestRay) {
  const RtlFrame f = make_rtl_frame("shepp-logan", 32, 24, {"precision.profile=vizard2"});
  const ref::QuantImage bt = bittrue::bt_render_image(f.setup, f.memory, 1);
  for (const int limit : {1 << 20, 0, 2, 7}) {
    rtl::RtlConfig c = shared_rows(IssuePolicy::kRowHit, 32);
    c.pipeline.issue_bypass_limit = limit;
    const rtl::RtlResult r = rtl::rtl_render(f.setup, f.memory, c);
    EXPECT_EQ(r.image.pixels, bt.pixels) << "limit " << limit;
    if (limit == 1 << 20) {
      ASSERT_GT(r.stats.issue_longest_bypass, 7u) << "the frame never bypasses the oldest ray for long";
    } else {
      EXPECT_EQ(r.stats.issue_longest_bypass, static_cast<std::uint64_t>(limit)) << r.stats;
    }
  }
}

// Early ray termination ends rays anywhere in the collapsing issue queue: each
// leaves it, frees its slot, and its samples still in flight are dropped.
TEST(RowHitIssue, EarlyTerminatedRaysLeaveFromAnyPlaceInTheQueue) {
  const RtlFrame f = make_rtl_frame("shepp-logan", 32, 24,
                                    {"precision.profile=vizard2", "render.ert_threshold=0.3"});
  const ref::QuantImage bt = bittrue::bt_render_image(f.setup, f.memory, 1);
  const rtl::RtlResult oldest = rtl::rtl_render(f.setup, f.memory, shared_rows(IssuePolicy::kOldest, 32));
  const rtl::RtlResult row_hit = rtl::rtl_render(f.setup, f.memory, shared_rows(IssuePolicy::kRowHit, 32));
  EXPECT_EQ(row_hit.image.pixels, bt.pixels);
  ASSERT_GT(row_hit.stats.rays_ert, 0u);
  EXPECT_EQ(row_hit.stats.rays_ert, oldest.stats.rays_ert);
  EXPECT_EQ(row_hit.stats.samples, oldest.stats.samples);  // the composited samples: the image's
  EXPECT_EQ(row_hit.stats.samples_issued,
            row_hit.stats.samples + row_hit.stats.samples_discarded);
}

}  // namespace
}  // namespace voxcast::test
