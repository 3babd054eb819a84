// The Vitis HLS scripts: run under tclsh with the Vitis commands stubbed to
// record their arguments; the recorded calls must name the real top function
// and files, and the board's part and core clock.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cosim/hardware/synth_script.hpp"
#include "refmodel/error.hpp"
#include "refmodel/scene/scene_toml.hpp"
#include "rtl_model/board/board.hpp"

namespace voxcast {
namespace VOXCAST_UNITY_ID {

namespace fs = std::filesystem;

std::string read(const fs::path& p) {
  std::ifstream f(p);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// Runs `script` under tclsh with every Vitis HLS command of the script a proc
// that appends "command arg arg ..." to a log; returns the log's lines.
std::vector<std::string> run_with_stubs(const fs::path& script, bool expect_ok = true) {
  const fs::path dir = script.parent_path();
  const fs::path log = dir / "calls.log";
  const fs::path driver = dir / "driver.tcl";
  std::ofstream d(driver);
  // Each stub checks its arguments against the command's synopsis (Vitis HLS
  // user guide UG1399, "Tcl Commands"): {flags taking no value} {options
  // taking a value} min max positional arguments, then records the call.
  d << "set log [open {" << log.string() << "} w]\n"
    << R"tcl(
proc stub {cmd flags valued minpos maxpos argv} {
  global log
  set pos 0
  for {set i 0} {$i < [llength $argv]} {incr i} {
    set a [lindex $argv $i]
    if {[string index $a 0] eq "-"} {
      if {[lsearch -exact $flags $a] >= 0} continue
      if {[dict exists $valued $a]} {
        incr i
        if {$i >= [llength $argv]} { error "$cmd: $a needs a value" }
        set allowed [dict get $valued $a]
        if {$allowed ne "*" && [lsearch -exact $allowed [lindex $argv $i]] < 0} {
          error "$cmd: $a [lindex $argv $i] is not one of $allowed"
        }
        continue
      }
      error "$cmd: unknown option $a"
    }
    incr pos
  }
  if {$pos < $minpos || $pos > $maxpos} { error "$cmd: $pos positional arguments" }
  set words [list $cmd]
  foreach a $argv { lappend words "{$a}" }
  puts $log [join $words { }]
}
proc open_project {args} { stub open_project {-reset -upgrade} {} 1 1 $args }
proc set_top {args} { stub set_top {} {} 1 1 $args }
proc add_files {args} { stub add_files {-tb -blackbox} {-cflags * -csimflags *} 1 1000 $args }
proc open_solution {args} { stub open_solution {-reset} {-flow_target {vitis vivado}} 1 1 $args }
proc set_part {args} { stub set_part {} {} 1 1 $args }
proc create_clock {args} { stub create_clock {} {-period * -name *} 0 0 $args }
proc csynth_design {args} { stub csynth_design {} {} 0 0 $args }
proc csim_design {args} {
  stub csim_design {-clean -O -setup -profile} {-argv * -ldflags * -mflags * -compiler {gcc clang}} 0 0 $args
}
proc cosim_design {args} {
  stub cosim_design {-O -setup -disable_dependency_check} {-argv * -ldflags * -mflags * -rtl {verilog vhdl} -trace_level {none all port port_hier} -tool *} 0 0 $args
}
proc export_design {args} {
  stub export_design {} {-format {ip_catalog xo syn_dcp sysgen} -rtl {verilog vhdl} -output *} 0 0 $args
}
rename exit tcl_exit
# tclsh itself calls exit 1 when the script fails: keep its code.
proc exit {{code 0}} { global log; puts $log exit; close $log; tcl_exit $code }
)tcl"
    << "source {" << script.string() << "}\n";
  d.close();
  const std::string cmd =
      "tclsh '" + driver.string() + "' > '" + (dir / "tclsh.out").string() + "' 2>&1";
  const int rc = std::system(cmd.c_str());
  if (expect_ok) {
    EXPECT_EQ(rc, 0) << "tclsh failed (is the tcl package installed? .ci/deps.sh): "
                     << read(dir / "tclsh.out");
  } else {
    EXPECT_NE(rc, 0) << "the stubs accepted " << read(script);
    EXPECT_NE(read(dir / "tclsh.out").find("while executing"), std::string::npos)
        << "tclsh itself must run: " << read(dir / "tclsh.out");
  }
  std::vector<std::string> lines;
  std::istringstream in(read(log));
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

const std::string* find_call(const std::vector<std::string>& calls, const std::string& prefix) {
  for (const auto& c : calls)
    if (c.rfind(prefix, 0) == 0) return &c;
  return nullptr;
}

// The argument words of a recorded call: "cmd {a} {b}" -> {a, b}.
std::vector<std::string> args_of(const std::string& call) {
  std::vector<std::string> out;
  for (std::size_t at = call.find('{'); at != std::string::npos; at = call.find('{', at)) {
    const auto end = call.find("} ", at);
    const auto stop = end == std::string::npos ? call.rfind('}') : end;
    out.push_back(call.substr(at + 1, stop - at - 1));
    at = stop + 1;
  }
  return out;
}

class SynthScript : public ::testing::Test {
 protected:
  fs::path dir =
      fs::temp_directory_path() /
      ("voxcast_synth_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
       ::testing::UnitTest::GetInstance()->current_test_info()->name());
  void SetUp() override { fs::remove_all(dir); }
  void TearDown() override { fs::remove_all(dir); }
};

TEST_F(SynthScript, VitisScriptRunsAndNamesTheRealDesign) {
  const std::string root = VOXCAST_SOURCE_DIR;
  for (const std::string board_name : {"vizard2_pci", "alveo_u250"}) {
    for (const std::string profile : {"vizard2", "balanced", "precise"}) {
      SCOPED_TRACE(board_name + " " + profile);
      // A small image: the csim data holds the frame the hls engine renders.
      const auto scene = ref::default_scene({"precision.profile=" + profile,
                                             "volume.source=phantom:shepp-logan?size=128",
                                             "render.width=32", "render.height=24"});
      const auto board = rtl::board::shipped_board(board_name);
      const auto paths = cosim::write_synth_scripts(scene, "scenes/default.toml", board, "vitis",
                                                    dir.string(), root);
      ASSERT_EQ(paths.size(), 3u);  // elaborated_config.hpp, the script, the csim data
      EXPECT_EQ(fs::path(paths[2]).filename(), cosim::kCsimDataFile);
      {  // tag, voxel-word chunks, width, height (hls/tb/vizard2_frame_tb.cpp reads them)
        const std::string data = read(paths[2]);
        ASSERT_GE(data.size(), 32u);
        ASSERT_EQ(data.size() % 8, 0u);
        auto word = [&data](std::size_t i) {
          std::uint64_t w = 0;
          for (int b = 7; b >= 0; --b)
            w = (w << 8) | static_cast<unsigned char>(data[i * 8 + static_cast<std::size_t>(b)]);
          return w;
        };
        EXPECT_EQ(data.substr(0, 8), "VXFRAME1");
        EXPECT_EQ(word(0), cosim::kCsimDataTag);
        EXPECT_EQ(word(1), profile == "precise" ? 2u : 1u);  // 76-bit words need two chunks
        EXPECT_EQ(word(2), 32u);
        EXPECT_EQ(word(3), 24u);
      }
      const auto calls = run_with_stubs(paths[1]);
      ASSERT_FALSE(calls.empty());
      EXPECT_EQ(calls.back(), "exit");

      // set_top names a function defined in the added source file.
      const auto* top = find_call(calls, "set_top ");
      ASSERT_NE(top, nullptr);
      const std::string function = args_of(*top).at(0);
      EXPECT_EQ(function, "vizard2_frame_top");
      const auto* add = find_call(calls, "add_files ");
      ASSERT_NE(add, nullptr);
      const auto add_args = args_of(*add);
      ASSERT_EQ(add_args.size(), 3u);  // file -cflags flags
      EXPECT_TRUE(fs::is_regular_file(add_args[0])) << add_args[0];
      EXPECT_NE(read(add_args[0]).find("void " + function + "("), std::string::npos);
      EXPECT_EQ(add_args[1], "-cflags");
      // The profile flag names the traits type of the scene's preset.
      const std::string constant = profile == "vizard2"    ? "Vizard2Traits"
                                   : profile == "balanced" ? "BalancedTraits"
                                                           : "PreciseTraits";
      EXPECT_NE(add_args[2].find("-DVOXCAST_SYNTH_PROFILE=" + constant), std::string::npos);
      EXPECT_NE(read(root + "/refmodel/precision/profile_traits.hpp").find("struct " + constant),
                std::string::npos);
      EXPECT_NE(add_args[2].find("-I" + fs::path(root).lexically_normal().string()),
                std::string::npos);
      // The vendor front ends' dialect; the host loaders stay out of csim too.
      EXPECT_NE(add_args[2].find("-std=c++14"), std::string::npos);
      EXPECT_NE(add_args[2].find("-DVOXCAST_HLS_KERNELS_ONLY"), std::string::npos);
      // The scene's units: the elaborated configuration written beside the script.
      EXPECT_NE(add_args[2].find("-include " + paths[0]), std::string::npos) << add_args[2];
      // Every added file exists; the testbench is one (-tb) and runs on the data.
      int testbenches = 0;
      for (const auto& c : calls) {
        if (c.rfind("add_files ", 0) == 0) {
          const auto a = args_of(c);
          const bool tb = a.at(0) == "-tb";
          testbenches += tb ? 1 : 0;
          EXPECT_TRUE(fs::is_regular_file(a.at(tb ? 1 : 0))) << c;
        }
      }
      EXPECT_EQ(testbenches, 1);
      const auto* csim = find_call(calls, "csim_design ");
      ASSERT_NE(csim, nullptr);
      EXPECT_EQ(args_of(*csim).at(1), fs::path(paths[2]).parent_path().string());

      // Part and clock from the board.
      const auto* part = find_call(calls, "set_part ");
      ASSERT_NE(part, nullptr);
      EXPECT_EQ(args_of(*part).at(0), board.fpga.tool_part);
      const auto* clock = find_call(calls, "create_clock ");
      ASSERT_NE(clock, nullptr);
      const auto clock_args = args_of(*clock);
      ASSERT_GE(clock_args.size(), 2u);
      EXPECT_EQ(clock_args[0], "-period");
      EXPECT_NEAR(std::stod(clock_args[1]), board.core().period_ns(), 0.0005);
      // The flow in order.
      std::vector<std::string> order;
      for (const auto& c : calls) order.push_back(c.substr(0, c.find(' ')));
      const std::vector<std::string> want = {
          "open_project", "set_top",      "add_files",   "add_files",     "add_files",
          "add_files",    "open_solution", "set_part",   "create_clock",  "csim_design",
          "csynth_design", "export_design", "exit"};
      EXPECT_EQ(order, want);
    }
  }
}

// The stubs are a real check: what the synopsis does not allow fails the run.
TEST_F(SynthScript, StubsRejectWhatVitisWouldReject) {
  fs::create_directories(dir);
  const std::vector<std::string> bad = {"open_solution -flow_target fpga s\n",
                                        "open_project -reset\n",
                                        "create_clock -period\n",
                                        "set_part a b\n",
                                        "export_design -format bitstream\n",
                                        "add_files x.cpp -cflag -O2\n",
                                        "config_nonexistent\n"};
  for (const std::string& line : bad) {
    std::ofstream(dir / "bad.tcl") << line;
    (void)run_with_stubs(dir / "bad.tcl", false);
  }
}

TEST_F(SynthScript, ProfilesThatAreNotCompiledAreRefused) {
  const auto scene = ref::default_scene({"precision.value_bits=10"});
  const auto board = rtl::board::shipped_board("vizard2_pci");
  try {
    (void)cosim::write_synth_scripts(scene, "s.toml", board, "vitis", dir.string(),
                                     VOXCAST_SOURCE_DIR);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("vizard2, balanced, precise"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW((void)cosim::write_synth_scripts(ref::default_scene(), "s.toml", board, "catapult",
                                                dir.string(), VOXCAST_SOURCE_DIR),
               Error);
  // A source tree without the design is an error, not a script naming missing files.
  EXPECT_THROW((void)cosim::write_synth_scripts(ref::default_scene(), "s.toml", board, "vitis",
                                                dir.string(), "/nonexistent"),
               Error);
}

}  // namespace
}  // namespace voxcast
