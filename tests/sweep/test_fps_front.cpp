// The front of frames/s against resources (issue 23, part 4): its
// objectives, the points it marks on a constructed table, and a sweep over
// rtl.pipelines on the U250 whose resource columns are `voxcast report`'s card
// totals and whose front marks exactly the non-dominated points.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "cosim/explore/sweep.hpp"
#include "tests/sweep/cli.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast::cosim::sweep;
using namespace sweep_test;
namespace fs = std::filesystem;

const Front& fps_front() {
  for (const Front& f : pareto_fronts())
    if (f.column.name == "pareto_fps_resources") return f;
  throw std::logic_error("no pareto_fps_resources front");
}

TEST(FpsFront, MaximisesFramesPerSecondAndMinimisesTheScarcestShare) {
  const Front& f = fps_front();
  ASSERT_EQ(f.objectives.size(), 2u);
  EXPECT_EQ(f.objectives[0].column, "rtl_fps");
  EXPECT_TRUE(f.objectives[0].maximize);
  EXPECT_EQ(f.objectives[1].column, "part_max_pct");
  EXPECT_FALSE(f.objectives[1].maximize);
}

TEST(FpsFront, MarksExactlyTheNonDominatedPoints) {
  Table t;
  t.columns = {{"rtl.pipelines", Column::Kind::Text, "", ""},
               {"status", Column::Kind::Text, "", ""},
               {"rtl_fps", Column::Kind::Number, "frames/s", ""},
               {"part_max_pct", Column::Kind::Number, "%", ""}};
  const auto row = [](std::size_t i, const char* n, Cell fps, Cell share) {
    return Row{i, {Cell::txt(n), Cell::txt("ok"), fps, share}};
  };
  t.rows = {row(0, "1", Cell::num(92), Cell::num(3)),      // on: the smallest
            row(1, "2", Cell::num(183), Cell::num(5)),     // on
            row(2, "4", Cell::num(308), Cell::num(9)),     // on
            row(3, "8", Cell::num(300), Cell::num(17)),    // off: 4 is faster and smaller
            row(4, "16", Cell::num(1381), Cell::num(33)),  // on: the fastest
            row(5, "16b", Cell::num(1381), Cell::num(40)),  // off: as fast, larger
            row(6, "x", Cell::na("rtl: refused"), Cell::num(1))};  // neither on nor blocking
  mark_front(t, fps_front());
  const std::size_t c = t.column("pareto_fps_resources");
  const char* expected[] = {"yes", "yes", "yes", "no", "yes", "no"};
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(t.rows[i].cells[c], Cell::txt(expected[i])) << i;
  EXPECT_EQ(t.rows[6].cells[c].kind, Cell::Kind::NotAvailable);
}

// The tiny tube on the U250 at 1 and 2 pipelines: the resource columns are
// the card's (report's card.total on the board's part), frames/s grows with
// the pipelines, and the front marks exactly the point no other dominates:
// both take the same share of the scarcest resource (the four channels'
// caches' URAM, whatever N), so 2 pipelines dominate 1.
TEST(FpsFront, SweepOverPipelinesOnTheU250PricesTheCard) {
  const auto d = temp_dir("u250_pipelines");
  const std::string sets = " --set precision.profile=vizard2 --set rtl.board=alveo_u250";
  const Command s = run("sweep " + tiny_scene() + sets +
                        " --vary rtl.pipelines=1,2 --part xcu250 --no-plots --out " + d.string());
  ASSERT_EQ(s.status, 0) << s.output;
  const nlohmann::json j = json_of(d / "results.json");
  ASSERT_EQ(j.at("rows").size(), 2u);
  double fps[2] = {0, 0}, share[2] = {0, 0};
  std::string front[2];
  for (std::size_t i = 0; i < 2; ++i) {
    const nlohmann::json& c = j.at("rows")[i].at("cells");
    ASSERT_EQ(c.at("status"), "ok") << c.dump();
    const std::string n = c.at("rtl.pipelines").get<std::string>();
    const Command r = run("report " + tiny_scene() + sets + " --set rtl.pipelines=" + n +
                          " --json " + (d / "report.json").string());
    ASSERT_EQ(r.status, 0) << r.output;
    const nlohmann::json rep = json_of(d / "report.json");
    const nlohmann::json& total = rep.at("card").at("total");
    EXPECT_EQ(c.at("luts"), total.at("lut"));
    EXPECT_EQ(c.at("urams"), total.at("uram"));
    EXPECT_EQ(c.at("brams"), total.at("bram"));
    EXPECT_NEAR(c.at("part_max_pct").get<double>(),
                100.0 * rep.at("card").at("binding_share").get<double>(), 1e-9);
    fps[i] = c.at("rtl_fps").get<double>();
    share[i] = c.at("part_max_pct").get<double>();
    front[i] = c.at("pareto_fps_resources").get<std::string>();
  }
  EXPECT_GT(fps[1], fps[0]);
  EXPECT_EQ(share[0], share[1]);  // URAM binds: 144 of 1,280 for the caches
  EXPECT_NEAR(share[0], 100.0 * 144 / 1280, 1e-9);
  EXPECT_EQ(front[0], "no");
  EXPECT_EQ(front[1], "yes");
}

// The shipped sweep spec (docs/performance.md §14): regress does not read
// scenes/sweeps/, so this keeps it parsing, on the U250, for every point of
// its documented --vary (parsing only: the sweep itself takes seconds).
TEST(FpsFront, ShippedU250SweepSpecParses) {
  const Plan plan = make_plan(VOXCAST_SOURCE_DIR "/scenes/sweeps/u250-pipelines.toml", {},
                              {"rtl.pipelines=1,2,4,8,16,32,64"}, {});
  ASSERT_EQ(plan.size(), 7u);
  for (std::size_t i = 0; i < plan.size(); ++i) {
    const voxcast::ref::Scene s = plan.scene(i);
    EXPECT_EQ(s.rtl.board, "alveo_u250");
    EXPECT_EQ(s.rtl.pipelines, 1 << i);
    EXPECT_EQ(s.precision_name, "vizard2");
  }
}

}  // namespace
