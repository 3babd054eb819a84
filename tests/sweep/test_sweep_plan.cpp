// --vary, --shard and the order of a sweep's points.
#include <gtest/gtest.h>

#include <set>

#include "cosim/explore/sweep_plan.hpp"
#include "refmodel/error.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast::cosim::sweep;

// One literal (no operator+: GCC 12 misreads it as out of bounds, -Warray-bounds).
std::string scene() { return VOXCAST_SOURCE_DIR "/tests/sweep/tube_tiny.toml"; }

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const voxcast::Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SweepAxis, ListsRangesAndBracketedValues) {
  EXPECT_EQ(parse_axis("precision.weight_bits=3..6").values,
            (std::vector<std::string>{"3", "4", "5", "6"}));
  EXPECT_EQ(parse_axis("render.oversampling=1,2.5, 4").values,
            (std::vector<std::string>{"1", "2.5", "4"}));
  EXPECT_EQ(parse_axis("a.b=1,3..4,-2..-1").values,
            (std::vector<std::string>{"1", "3", "4", "-2", "-1"}));
  const Axis eye = parse_axis("camera.eye=[1, 2, 3],[4,5,6]");
  EXPECT_EQ(eye.key, "camera.eye");
  EXPECT_EQ(eye.values, (std::vector<std::string>{"[1, 2, 3]", "[4,5,6]"}));
  EXPECT_EQ(parse_axis("precision.profile=\"a,b\",vizard2").values,
            (std::vector<std::string>{"\"a,b\"", "vizard2"}));
}

TEST(SweepAxis, BadSyntaxIsAOneLineErrorNamingTheSpec) {
  const struct {
    const char* spec;
    const char* message;
  } cases[] = {
      {"precision.weight_bits", "--vary precision.weight_bits: expected KEY=V1,V2,..."},
      {"=1,2", "--vary =1,2: the key before '=' is empty"},
      {"precision.weight_bits=8..3", "--vary precision.weight_bits=8..3: range 8..3 is empty"},
      {"render.oversampling=1.5..2", "range 1.5..2 must be two integers A..B"},
      {"precision.weight_bits=1,,2", "--vary precision.weight_bits=1,,2: empty value"},
      {"precision.weight_bits=", "empty value"},
      {"precision.weight_bits=3,3", "value 3 is given twice"},
      {"camera.eye=[1,2", "unbalanced brackets"},
      {"a b=1", "'a b' is not a scene key"},
  };
  for (const auto& c : cases) {
    const std::string e = error_of([&] { parse_axis(c.spec); });
    EXPECT_NE(e.find(c.message), std::string::npos) << c.spec << " -> " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
}

TEST(SweepShard, ParsesAndPartitionsThePoints) {
  const Shard s = parse_shard("2/3");
  EXPECT_EQ(s.index, 2);
  EXPECT_EQ(s.count, 3);
  for (const char* bad : {"3/3", "-1/3", "1/0", "1", "a/b", "1/2/3"})
    EXPECT_THROW(parse_shard(bad), voxcast::Error) << bad;
  // Every point belongs to exactly one of n shards.
  for (std::size_t p = 0; p < 50; ++p) {
    int owners = 0;
    for (int i = 0; i < 4; ++i) owners += Shard{i, 4}.owns(p) ? 1 : 0;
    EXPECT_EQ(owners, 1) << p;
  }
}

TEST(SweepPlan, TheFirstAxisVariesSlowest) {
  const Plan plan = make_plan(scene(), {"render.width=12"},
                              {"render.oversampling=1,2", "precision.weight_bits=5..7"}, {});
  ASSERT_EQ(plan.size(), 6u);
  EXPECT_EQ(plan.values(0), (std::vector<std::string>{"1", "5"}));
  EXPECT_EQ(plan.values(2), (std::vector<std::string>{"1", "7"}));
  EXPECT_EQ(plan.values(3), (std::vector<std::string>{"2", "5"}));
  EXPECT_EQ(plan.values(5), (std::vector<std::string>{"2", "7"}));
  const auto s = plan.scene(4);
  EXPECT_EQ(s.render.oversampling, 2.0);
  EXPECT_EQ(s.precision.weight_bits, 6);
  EXPECT_EQ(s.render.width, 12);
}

TEST(SweepPlan, UnknownKeysAndBadValuesFailBeforeAnythingRuns) {
  const struct {
    std::vector<std::string> vary;
    std::vector<std::string> sets;
    const char* message;
  } cases[] = {
      {{"precision.wieght_bits=3"},
       {},
       "--vary precision.wieght_bits=3: unknown key precision.wieght_bits (did you mean "
       "precision.weight_bits?)"},
      {{"precision.weight_bits=4..11"},
       {},
       "--vary precision.weight_bits=11: precision.weight_bits = 11 is outside [1, 10]"},
      {{"render.oversampling=1", "render.oversampling=2"},
       {},
       "--vary render.oversampling: the key is varied twice"},
      {{"render.oversampling=1,2"},
       {"render.oversampling=4"},
       "--vary render.oversampling: the key is also fixed by --set render.oversampling=4"},
      {{}, {}, "sweep: give at least one --vary"},
      {{"render.oversampling=1,2"}, {"render.width=0"}, "render.width = 0 is outside"},
  };
  for (const auto& c : cases) {
    const std::string e = error_of([&] { make_plan(scene(), c.sets, c.vary, {}); });
    EXPECT_NE(e.find(c.message), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
  }
  // The truth must sample at least as densely as every point.
  const std::string e = error_of([&] {
    make_plan(scene(), {}, {"render.oversampling=2,8"}, voxcast::cosim::TruthSettings{4.0});
  });
  EXPECT_NE(e.find("truth oversampling 4 is below the scene's render.oversampling 8"),
            std::string::npos)
      << e;
}

}  // namespace
