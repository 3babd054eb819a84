// Pareto marking on constructed tables: dominance, exact ties, objectives
// that are not available, rows that could not run, and minimised objectives.
#include <gtest/gtest.h>

#include <limits>

#include "cosim/explore/sweep_table.hpp"
#include "refmodel/error.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast::cosim::sweep;
using Opt = std::optional<double>;

TEST(Pareto, MarksTheNonDominatedPointsIncludingExactTies) {
  // (PSNR, frames/s), both maximised.
  const std::vector<std::vector<Opt>> pts = {
      {40.0, 100.0},          // 0: on (tied with 1: neither dominates the other)
      {40.0, 100.0},          // 1: on
      {45.0, 50.0},           // 2: on (tied with 7)
      {40.0, 90.0},           // 3: off: 0 is as accurate and faster
      {30.0, 200.0},          // 4: on: the fastest
      {30.0, 150.0},          // 5: off: 4 is as accurate and faster
      {std::nullopt, 300.0},  // 6: not available
      {45.0, 50.0},           // 7: on
      {46.0, 49.0},           // 8: on: the most accurate
      {39.0, 100.0},          // 9: off: 0 is as fast and more accurate
  };
  const auto on = pareto_front(pts, {true, true});
  const std::vector<std::optional<bool>> expected = {true,  true,         true, false, true,
                                                     false, std::nullopt, true, true,  false};
  ASSERT_EQ(on.size(), expected.size());
  for (std::size_t i = 0; i < on.size(); ++i) EXPECT_EQ(on[i], expected[i]) << "point " << i;
}

TEST(Pareto, AMinimisedObjectiveReversesTheOrder) {
  // (PSNR max, LUTs min).
  const std::vector<std::vector<Opt>> pts = {
      {40.0, 1000.0}, {40.0, 900.0}, {50.0, 2000.0}, {35.0, 900.0}};
  const auto on = pareto_front(pts, {true, false});
  EXPECT_EQ(on[0], false);  // 1 is as accurate and smaller
  EXPECT_EQ(on[1], true);
  EXPECT_EQ(on[2], true);
  EXPECT_EQ(on[3], false);  // 1 is as small and more accurate
}

TEST(Pareto, OnePointAloneIsOnTheFront) {
  EXPECT_EQ(pareto_front({{1.0, 2.0}}, {true, true})[0], true);
}

Table constructed() {
  Table t;
  t.columns = {{"status", Column::Kind::Text, "", ""},
               {"psnr_db", Column::Kind::Number, "dB", ""},
               {"rtl_fps", Column::Kind::Number, "frames/s", ""}};
  const auto row = [](std::size_t i, const char* status, Cell psnr, Cell fps) {
    return Row{i, {Cell::txt(status), psnr, fps}};
  };
  t.rows = {row(0, "ok", Cell::num(40), Cell::num(100)),
            row(1, "infeasible: value_bits", Cell::na("x"), Cell::na("x")),
            row(2, "ok", Cell::num(50), Cell::na("rtl runs only the compiled presets")),
            row(3, "ok", Cell::num(35), Cell::num(100)),
            row(4, "ok", Cell::num(40), Cell::num(100))};
  return t;
}

TEST(Pareto, MarkFrontWritesYesNoAndReasons) {
  Table t = constructed();
  mark_front(t, {{"front", Column::Kind::Text, "", ""}, {{"psnr_db", true}, {"rtl_fps", true}}});
  const std::size_t c = t.column("front");
  EXPECT_EQ(t.rows[0].cells[c], Cell::txt("yes"));
  EXPECT_EQ(t.rows[1].cells[c].kind, Cell::Kind::NotAvailable);
  EXPECT_EQ(t.rows[2].cells[c].kind, Cell::Kind::NotAvailable);  // no fps: neither on nor blocking
  EXPECT_NE(t.rows[2].cells[c].text.find("rtl_fps"), std::string::npos) << t.rows[2].cells[c].text;
  EXPECT_EQ(t.rows[3].cells[c], Cell::txt("no"));
  EXPECT_EQ(t.rows[4].cells[c], Cell::txt("yes"));
  // Marking again (sweep-merge over merged rows) replaces the column, not adds one.
  mark_front(t, {{"front", Column::Kind::Text, "", ""}, {{"psnr_db", true}, {"rtl_fps", true}}});
  EXPECT_EQ(t.columns.size(), 4u);
}

TEST(SweepTable, JsonRoundTripKeepsEveryCell) {
  Table t = constructed();
  t.meta = {{"points_total", 5}};
  t.rows[3].cells[1] = Cell::num(std::numeric_limits<double>::infinity());
  t.rows[0].cells[1] = Cell::num(0.1 + 0.2);  // a double with no short decimal form
  const Table back = table_from_json(to_json(t), "test");
  EXPECT_EQ(back.rows, t.rows);
  EXPECT_EQ(back.meta, t.meta);
}

TEST(SweepTable, MergeRejectsOverlapsGapsAndOtherSweeps) {
  Table a = constructed(), b = constructed();
  a.meta = b.meta = {{"points_total", 5}, {"scene", "s.toml"}};
  a.rows = {a.rows[0], a.rows[2], a.rows[4]};
  b.rows = {b.rows[1], b.rows[3]};
  a.meta["shard"] = "0/2";
  b.meta["shard"] = "1/2";
  const Table m = merge_tables({b, a}, {"b", "a"});
  ASSERT_EQ(m.rows.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i) EXPECT_EQ(m.rows[i].index, i);
  EXPECT_FALSE(m.meta.contains("shard"));
  EXPECT_THROW(merge_tables({a}, {"a"}), voxcast::Error);                   // points 1, 3 missing
  EXPECT_THROW(merge_tables({a, a, b}, {"a", "a2", "b"}), voxcast::Error);  // twice
  Table other = b;
  other.meta["scene"] = "other.toml";
  EXPECT_THROW(merge_tables({a, other}, {"a", "other"}), voxcast::Error);
}

}  // namespace
