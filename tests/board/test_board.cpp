// The board description: the shipped boards, the schema's errors, and the
// cycle model configured from it (rtl_model/board/).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "board_text.hpp"
#include "refmodel/error.hpp"
#include "rtl_model/board/board.hpp"
#include "rtl_model/board/board_config.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/scene_config.hpp"
#include "rtl_model/sdram/timing.hpp"

namespace voxcast {
namespace VOXCAST_UNITY_ID {

using rtl::board::Board;
using test::board_with;

TEST(Board, ShippedBoardsParse) {
  const auto names = rtl::board::shipped_board_names();
  ASSERT_EQ(names, (std::vector<std::string>{"alveo_u250", "vizard2_pci"}));
  for (const auto& n : names) {
    const Board b = rtl::board::shipped_board(n);
    EXPECT_EQ(b.name, n);
    EXPECT_EQ(b.memory.dimms, 4) << n;  // the VIZARD II scheme: four channels
  }
}

// The 2001 card's description holds the datasheet numbers of the model's
// presets (docs/sdram.md §2): PC100 CL2 on the MT4LSDT864A, 100 MHz, 33 MHz PCI.
TEST(Board, Vizard2CardIsThePc100Preset) {
  const Board b = rtl::board::shipped_board("vizard2_pci");
  const auto p = rtl::sdram::presets::pc100_cl2();
  const auto& t = b.memory.timing;
  EXPECT_EQ(t.name, p.name);
  EXPECT_EQ(t.part, p.part);
  EXPECT_EQ(t.tCK_min_ns, p.tCK_min_ns);
  EXPECT_EQ(t.cas_latency, p.cas_latency);
  EXPECT_EQ(t.tRCD_ns, p.tRCD_ns);
  EXPECT_EQ(t.tRP_ns, p.tRP_ns);
  EXPECT_EQ(t.tRAS_ns, p.tRAS_ns);
  EXPECT_EQ(t.tRAS_max_ns, p.tRAS_max_ns);
  EXPECT_EQ(t.tRC_ns, p.tRC_ns);
  EXPECT_EQ(t.tRRD_ns, p.tRRD_ns);
  EXPECT_EQ(t.tWR_ns, p.tWR_ns);
  EXPECT_EQ(t.tRFC_ns, p.tRFC_ns);
  EXPECT_EQ(t.tREF_ms, p.tREF_ms);
  EXPECT_EQ(t.refresh_count, p.refresh_count);
  EXPECT_EQ(t.tCCD_ck, p.tCCD_ck);
  EXPECT_EQ(t.tCDL_ck, p.tCDL_ck);
  EXPECT_EQ(t.tMRD_ck, p.tMRD_ck);
  const auto g = rtl::sdram::geometries::mt4lsdt864a();
  EXPECT_EQ(b.memory.geometry.banks, g.banks);
  EXPECT_EQ(b.memory.geometry.rows, g.rows);
  EXPECT_EQ(b.memory.geometry.columns, g.columns);
  EXPECT_EQ(b.memory.geometry.bus_bits, g.bus_bits);
  EXPECT_EQ(b.memory.geometry.bytes(), 64u << 20);
  EXPECT_EQ(b.memory_clock().period_ps, rtl::sim::clocks::pc100().period_ps());
  EXPECT_EQ(b.core().period_ps, 10'000);  // generated from the SDRAM clock x1
  EXPECT_EQ(b.host_clock().period_ps, rtl::sim::clocks::pci33().period_ps());
  EXPECT_EQ(b.host.bus_bits, 32);
}

// vizard2_baseline() reads the board, and the model's defaults (RtlConfig{})
// equal it, so neither can drift from the description.
TEST(Board, BaselineIsTheBoard) {
  const Board b = rtl::board::shipped_board("vizard2_pci");
  const rtl::RtlConfig base = rtl::vizard2_baseline();
  const rtl::RtlConfig defaults{};
  for (const auto* c : {&base, &defaults}) {
    EXPECT_EQ(c->pipeline.dimm.clock.period_ps(), b.memory_clock().period_ps);
    EXPECT_EQ(c->pipeline.dimm.timing.name, b.memory.timing.name);
    EXPECT_EQ(c->pipeline.dimm.timing.tRC_ns, b.memory.timing.tRC_ns);
    EXPECT_EQ(c->pipeline.dimm.geometry.rows, b.memory.geometry.rows);
    EXPECT_EQ(c->pipeline.dimm.burst_length, b.memory.burst_length);
  }
  const auto pci = rtl::pci_config_for_board(b);
  EXPECT_EQ(pci.clock.period_ps(), 30'000);
  EXPECT_EQ(pci.bus_bytes, 4);
}

// The scene's rtl.board selects the description the model reads: a board file
// whose SDRAM runs at 8 ns with CL3 gives the scene's model that clock and
// ceil(ns / 8) cycles (tRCD 20 ns -> 3, tRC 70 ns -> 9), with the file named
// relative to the scene's folder; rtl.sdram = "pc100-cl2" overrides the timing.
TEST(Board, SceneBoardKeyDrivesTheModel) {
  const auto dir = std::filesystem::temp_directory_path() / "voxcast_scene_board";
  std::filesystem::create_directories(dir);
  std::string text = board_with("vizard2_pci", "period_ns = 10.0", "period_ns = 8.0");
  const auto replace = [&](const std::string& from, const std::string& to) {
    text.replace(text.find(from), from.size(), to);
  };
  replace("tCK_min_ns = 10.0", "tCK_min_ns = 8.0");
  replace("cas_latency = 2", "cas_latency = 3");
  std::ofstream(dir / "fast.toml") << text;

  const auto cycles = [](const rtl::RtlConfig& c) {
    return rtl::sdram::to_cycles(c.pipeline.dimm.timing, c.pipeline.dimm.clock,
                                 c.pipeline.dimm.burst_length);
  };
  const ref::Scene deflt = ref::default_scene();
  EXPECT_EQ(deflt.rtl.board, "vizard2_pci");
  EXPECT_EQ(cycles(rtl::rtl_config(deflt.rtl)).tRCD, 2);

  const ref::Scene fast = ref::parse_scene(ref::default_scene_text(), (dir / "scene.toml").string(),
                                           dir.string(), {"rtl.board=\"fast.toml\""});
  EXPECT_EQ(fast.rtl.board, (dir / "fast.toml").string());
  const rtl::RtlConfig c = rtl::rtl_config(fast.rtl);
  EXPECT_DOUBLE_EQ(c.pipeline.dimm.clock.period_ns(), 8.0);
  EXPECT_EQ(cycles(c).tRCD, 3);
  EXPECT_EQ(cycles(c).tRC, 9);
  EXPECT_EQ(cycles(c).CL, 3);

  ref::RtlDesc preset = fast.rtl;
  preset.sdram = "pc100-cl2";
  EXPECT_EQ(rtl::rtl_config(preset).pipeline.dimm.timing.name,
            rtl::sdram::presets::pc100_cl2().name);

  ref::RtlDesc missing;
  missing.board = "no_such_board";
  try {
    (void)rtl::rtl_config(missing);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind("rtl.board = \"no_such_board\": ", 0), 0u) << e.what();
  }
}

// The modern board runs as the DDR4 card (rtl_model/pipeline/burst_card.hpp)
// at its own core clock; one it cannot lay the volume out on is refused,
// naming the board file and the key.
TEST(Board, ModernBoardIsTheDdr4Card) {
  const Board b = rtl::board::shipped_board("alveo_u250");
  EXPECT_EQ(b.memory_clock().period_ps, 833);  // 3333 ps x 1 / 4, nearest ps: DDR4-2400 tCK
  EXPECT_EQ(b.core().period_ps, 3333);         // memory / 4 = the 300 MHz reference
  EXPECT_EQ(b.memory.geometry.bytes(), std::uint64_t{16} << 30);
  const rtl::RtlConfig c = rtl::rtl_config_for_board(b);
  EXPECT_TRUE(c.card.enabled);
  EXPECT_EQ(c.card.core_period_ps, b.core().period_ps);
  EXPECT_EQ(c.pipeline.dimm.clock.period_ps(), b.memory_clock().period_ps);
  std::string text = rtl::board::shipped_board_text("alveo_u250");
  text.replace(text.find("dimms = 4"), 9, "dimms = 2");
  try {
    (void)rtl::rtl_config_for_board(rtl::board::parse_board(text, "two_channels.toml"));
    FAIL() << "a DDR4 board of two channels must be refused";
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("two_channels.toml"), std::string::npos) << what;
    EXPECT_NE(what.find("memory.dimms = 2"), std::string::npos) << what;
  }
  EXPECT_THROW((void)rtl::pci_config_for_board(b), Error);
}

// Every malformed description is one line naming file:line and the key.
struct BadCase {
  const char* from;
  const char* to;
  const char* expect;  // substrings of the message: "file:line: key ..."
};

TEST(Board, ErrorsNameFileLineAndKey) {
  const std::string file = "constraints/boards/vizard2_pci.toml";
  const std::vector<BadCase> cases = {
      {"tRCD_ns = 20.0", "tRCD_ns = 20.0\ntRCD_typo = 1",
       "memory.timing.tRCD_typo is not a board key"},
      {"tRCD_ns = 20.0\n", "", "memory.timing.tRCD_ns is missing"},
      {"tRCD_ns = 20.0", "tRCD_ns = \"20\"", "memory.timing.tRCD_ns must be a number, not string"},
      {"tRCD_ns = 20.0", "tRCD_ns = -20.0", "memory.timing.tRCD_ns = -20 is outside"},
      {"period_ns = 10.0", "period_ns = 0.0", "clocks.sdram.period_ns = 0 is outside"},
      {"period_ns = 10.0", "period_ns = nan",
       "clocks.sdram.period_ns = nan is not a finite number"},
      {"tRC_ns = 70.0", "tRC_ns = 60.0", "memory.timing.tRC_ns is below tRAS_ns + tRP_ns"},
      {"dimms = 4", "dimms = 4.0", "memory.dimms must be an integer"},
      {"rows = 4096", "rows = 4000", "memory.geometry.rows = 4000 is not a power of two"},
      {"from = \"sdram\"", "from = \"osc\"", "clocks.core.from = \"osc\" is not a clock"},
      {"clock_max_ns = 0.8", "clock_max_ns = 0.5", "memory.io.trace.clock_max_ns is below"},
      {"tOH_ns = 3.0", "tOH_ns = 7.0", "memory.io.tOH_ns must be below tAC_ns"},
      {"core_clock = \"core\"", "core_clock = \"fast\"", "core_clock = \"fast\" is not a clock"},
      {"tCK_min_ns = 10.0", "tCK_min_ns = 12.0", "faster than memory.timing.tCK_min_ns"},
      {"interface = \"pci\"", "interface = \"isa\"", "host.interface = \"isa\" is not one of"},
  };
  for (const BadCase& c : cases) {
    const std::string text = board_with("vizard2_pci", c.from, c.to);
    try {
      (void)rtl::board::parse_board(text, file);
      ADD_FAILURE() << "accepted: " << c.to;
    } catch (const Error& e) {
      const std::string m = e.what();
      EXPECT_EQ(m.rfind(file + ":", 0), 0u) << m;
      EXPECT_NE(m.find(c.expect), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
      // The line number is the line of the key (or of its table when missing).
      const auto colon = m.find(':', file.size() + 1);
      const int line = std::stoi(m.substr(file.size() + 1, colon - file.size() - 1));
      EXPECT_GT(line, 1) << m;
    }
  }
}

TEST(Board, GeneratedClockCycleIsAnError) {
  std::string text =
      board_with("vizard2_pci", "[clocks.sdram]\nperiod_ns = 10.0\nport = \"sdram_clk\"",
                 "[clocks.sdram]\nfrom = \"core\"\npin = \"x/CLK0\"");
  EXPECT_THROW((void)rtl::board::parse_board(text, "b.toml"), Error);
  try {
    (void)rtl::board::parse_board(text, "b.toml");
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("derived from itself"), std::string::npos) << e.what();
  }
}

TEST(Board, NamesAndPaths) {
  EXPECT_EQ(rtl::board::load_board("vizard2_pci").name, "vizard2_pci");
  EXPECT_EQ(rtl::board::load_board(std::string(VOXCAST_SOURCE_DIR) +
                                   "/constraints/boards/alveo_u250.toml")
                .name,
            "alveo_u250");
  try {
    (void)rtl::board::load_board("vizard3");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vizard2_pci"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)rtl::board::load_board("/nonexistent/board.toml"), Error);
}

// The shipped text is the file in the tree (compiled in by CMake).
TEST(Board, EmbeddedTextIsTheFile) {
  for (const auto& n : rtl::board::shipped_board_names()) {
    std::ifstream f(std::string(VOXCAST_SOURCE_DIR) + "/constraints/boards/" + n + ".toml");
    std::ostringstream ss;
    ss << f.rdbuf();
    EXPECT_EQ(ss.str(), rtl::board::shipped_board_text(n)) << n;
  }
}

TEST(Board, EveryKeyIsDocumented) {
  std::ifstream f(std::string(VOXCAST_SOURCE_DIR) + "/docs/constraints.md");
  std::ostringstream ss;
  ss << f.rdbuf();
  const std::string doc = ss.str();
  ASSERT_FALSE(doc.empty());
  for (const std::string& k : rtl::board::known_board_keys())
    EXPECT_NE(doc.find("`" + k + "`"), std::string::npos) << k << " is not in docs/constraints.md";
}

}  // namespace
}  // namespace voxcast
