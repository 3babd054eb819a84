// Generated constraints against hand calculations, the model and the goldens.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include "board_text.hpp"
#include "cosim/hardware/constraints.hpp"
#include "refmodel/error.hpp"
#include "rtl_model/board/board_config.hpp"
#include "rtl_model/sdram/timing.hpp"

namespace voxcast {
namespace VOXCAST_UNITY_ID {

using cosim::ConstraintFormat;
using rtl::board::Board;

const cosim::IoDelay& find_delay(const std::vector<cosim::IoDelay>& ds, const std::string& group) {
  for (const auto& d : ds)
    if (d.group == group) return d;
  throw std::runtime_error("no delay group " + group);
}

// The numbers worked by hand from the datasheets (docs/constraints.md §3):
// Micron -8E at CL2: tAC 6, tOH 3, tIS 2, tIH 1 ns; traces clock 0.6-0.8,
// data 0.5-0.9 ns. PCI 2.2 at 33 MHz: Tcyc 30, Tval 2-11, Tval(ptp) 12,
// Tsu 7, Tsu(ptp) 10, Th 0 ns.
TEST(Constraints, Vizard2DelaysEqualHandCalculation) {
  const auto ds = cosim::io_delays(rtl::board::shipped_board("vizard2_pci"));
  ASSERT_EQ(ds.size(), 4u * 2u + 4u);
  for (int i = 0; i < 4; ++i) {
    const std::string dimm = "DIMM " + std::to_string(i);
    const auto& w = find_delay(ds, dimm + " address, command, write data (FPGA -> SDRAM)");
    EXPECT_NEAR(w.max_ns, 0.9 + 2.0 - 0.6, 1e-12);  // 2.3
    EXPECT_NEAR(w.min_ns, 0.5 - 1.0 - 0.8, 1e-12);  // -1.3
    EXPECT_EQ(w.clock, "dimm" + std::to_string(i) + "_ck");
    const auto& r = find_delay(ds, dimm + " read data (SDRAM -> FPGA)");
    EXPECT_NEAR(r.max_ns, 0.8 + 6.0 + 0.9, 1e-12);  // 7.7
    EXPECT_NEAR(r.min_ns, 0.6 + 3.0 + 0.5, 1e-12);  // 4.1
    // The FPGA keeps T - in_max = 2.3 ns for its input setup at 100 MHz.
    EXPECT_NEAR(10.0 - r.max_ns, 2.3, 1e-12);
  }
  EXPECT_DOUBLE_EQ(find_delay(ds, "PCI bused signals in").max_ns, 23.0);           // 30 - 7
  EXPECT_DOUBLE_EQ(find_delay(ds, "PCI bused signals in").min_ns, 0.0);            // Th
  EXPECT_DOUBLE_EQ(find_delay(ds, "PCI GNT# in (point to point)").max_ns, 20.0);   // 30 - 10
  EXPECT_DOUBLE_EQ(find_delay(ds, "PCI bused signals out").max_ns, 19.0);          // 30 - 11
  EXPECT_DOUBLE_EQ(find_delay(ds, "PCI bused signals out").min_ns, -2.0);          // -Tval,min
  EXPECT_DOUBLE_EQ(find_delay(ds, "PCI REQ# out (point to point)").max_ns, 18.0);  // 30 - 12
  // The component budget plus the spec's Tprop (10 ns) and skew (2 ns) fills
  // the cycle: Tval + Tprop + Tsu + Tskew = 11 + 10 + 7 + 2 = 30 (PCI 2.2 §4.2.3.2).
  EXPECT_DOUBLE_EQ(11.0 + 10.0 + 7.0 + 2.0, 30.0);
  const std::string xdc =
      cosim::generate_constraints(rtl::board::shipped_board("vizard2_pci"), ConstraintFormat::kXdc);
  for (const char* line :
       {"set_output_delay -clock dimm0_ck -max 2.300 ",
        "set_output_delay -clock dimm3_ck -min -1.300 ",
        "set_input_delay -clock dimm2_ck -max 7.700 [get_ports {dimm2_dq[*]}]",
        "set_input_delay -clock dimm1_ck -min 4.100 [get_ports {dimm1_dq[*]}]",
        "set_input_delay -clock pci -max 23.000 ", "set_input_delay -clock pci -min 0.000 ",
        "set_input_delay -clock pci -max 20.000 [get_ports {pci_gnt_n}]",
        "set_output_delay -clock pci -max 19.000 ", "set_output_delay -clock pci -min -2.000 ",
        "set_output_delay -clock pci -max 18.000 [get_ports {pci_req_n}]"})
    EXPECT_NE(xdc.find(line), std::string::npos) << line;
}

// The clocks of a constraint file: name -> period in ns (create_clock) and the
// generated ones' (master, multiply, divide).
struct ParsedClocks {
  std::map<std::string, double> period;
  std::map<std::string, std::tuple<std::string, int, int>> generated;
};

ParsedClocks parse_clocks(const std::string& text) {
  ParsedClocks p;
  const std::regex create(
      R"(^create_clock -name (\S+) -period ([0-9.]+) \[get_ports \{(\S+)\}\]$)");
  const std::regex gen(
      R"(^create_generated_clock -name (\S+) -source \[get_(?:ports|pins) \{(\S+)\}\] (?:-multiply_by (\d+) )?-divide_by (\d+) )");
  std::istringstream in(text);
  std::string line;
  std::smatch m;
  while (std::getline(in, line)) {
    if (std::regex_search(line, m, create)) p.period[m[1]] = std::stod(m[2]);
    if (std::regex_search(line, m, gen))
      p.generated[m[1]] = {m[2], m[3].matched ? std::stoi(m[3]) : 1, std::stoi(m[4])};
  }
  return p;
}

// Resolves a generated clock's period from the parsed file alone.
double resolved_period(const ParsedClocks& p, const Board& b, const std::string& name) {
  if (p.period.count(name)) return p.period.at(name);
  const auto& [src, mul, div] = p.generated.at(name);
  // The -source object is the master's port or pin.
  for (const auto& c : b.clocks)
    if (c.port == src || (c.generated() && c.pin == src))
      return resolved_period(p, b, c.name) * div / mul;
  throw std::runtime_error("no master for " + name);
}

// Every clock of the description is in both formats with its period, and the
// model's clocks are the same periods.
TEST(Constraints, EveryClockAppearsWithTheModelsPeriod) {
  for (const auto& name : rtl::board::shipped_board_names()) {
    const Board b = rtl::board::shipped_board(name);
    for (const auto f : {ConstraintFormat::kXdc, ConstraintFormat::kSdc}) {
      const ParsedClocks p = parse_clocks(cosim::generate_constraints(b, f));
      for (const auto& c : b.clocks) {
        ASSERT_TRUE(p.period.count(c.name) + p.generated.count(c.name) == 1)
            << name << " " << c.name;
        EXPECT_NEAR(resolved_period(p, b, c.name), c.period_ns(), 0.0005) << name << " " << c.name;
      }
    }
  }
  const Board v = rtl::board::shipped_board("vizard2_pci");
  const ParsedClocks p = parse_clocks(cosim::generate_constraints(v, ConstraintFormat::kXdc));
  const auto model = rtl::rtl_config_for_board(v);
  EXPECT_DOUBLE_EQ(p.period.at("sdram"), model.pipeline.dimm.clock.period_ns());
  EXPECT_DOUBLE_EQ(resolved_period(p, v, "core"), model.pipeline.dimm.clock.period_ns());
  EXPECT_DOUBLE_EQ(p.period.at("pci"), rtl::pci_config_for_board(v).clock.period_ns());
  EXPECT_NE(cosim::generate_constraints(v, ConstraintFormat::kXdc)
                .find("set_clock_groups -asynchronous -group [get_clocks {pci}] -group [get_clocks "
                      "{core sdram dimm0_ck dimm1_ck dimm2_ck dimm3_ck}]"),
            std::string::npos);
}

// Changing the SDRAM clock in the description moves the constraints' period
// and the model's cycle counts together, each cycle count ceil(ns / period).
TEST(Constraints, SdramClockDrivesConstraintsAndModel) {
  struct Case {
    const char* period;
    double ns;
    const char* tck_min;  // the grade rated for the clock: CL3 allows 8 ns
    const char* cl;
    long tRCD, tRAS, tRC, tRFC, tREFI;
  };
  // Hand-worked: 20/8 -> 3, 50/8 -> 7, 70/8 -> 9, 15625/8 -> 1953 (floor);
  // 20/12.5 -> 2, 50/12.5 -> 4, 70/12.5 -> 6, 15625/12.5 -> 1250.
  const Case cases[] = {{"10.0", 10.0, "10.0", "2", 2, 5, 7, 7, 1562},
                        {"8.0", 8.0, "8.0", "3", 3, 7, 9, 9, 1953},
                        {"12.5", 12.5, "10.0", "2", 2, 4, 6, 6, 1250}};
  for (const Case& c : cases) {
    std::string text =
        test::board_with("vizard2_pci", "period_ns = 10.0", std::string("period_ns = ") + c.period);
    const auto replace = [&](const std::string& from, const std::string& to) {
      text.replace(text.find(from), from.size(), to);
    };
    replace("tCK_min_ns = 10.0", std::string("tCK_min_ns = ") + c.tck_min);
    replace("cas_latency = 2", std::string("cas_latency = ") + c.cl);
    const Board b = rtl::board::parse_board(text, "changed.toml");
    const std::string xdc = cosim::generate_constraints(b, ConstraintFormat::kXdc);
    const ParsedClocks p = parse_clocks(xdc);
    // The constraints' comment states the cycles the model uses.
    EXPECT_NE(xdc.find("tRCD 20 ns = " + std::to_string(c.tRCD) + ","), std::string::npos);
    EXPECT_NE(xdc.find("tRC 70 ns = " + std::to_string(c.tRC) + ","), std::string::npos);
    EXPECT_DOUBLE_EQ(p.period.at("sdram"), c.ns);
    EXPECT_DOUBLE_EQ(resolved_period(p, b, "core"), c.ns);
    const auto model = rtl::rtl_config_for_board(b);
    EXPECT_DOUBLE_EQ(model.pipeline.dimm.clock.period_ns(), c.ns);
    const auto cyc = rtl::sdram::to_cycles(model.pipeline.dimm.timing, model.pipeline.dimm.clock,
                                           model.pipeline.dimm.burst_length);
    EXPECT_EQ(cyc.tRCD, c.tRCD) << c.period;
    EXPECT_EQ(cyc.tRAS, c.tRAS) << c.period;
    EXPECT_EQ(cyc.tRC, c.tRC) << c.period;
    EXPECT_EQ(cyc.tRFC, c.tRFC) << c.period;
    EXPECT_EQ(cyc.tREFI, c.tREFI) << c.period;
    EXPECT_EQ(cyc.tRCD, static_cast<long>(std::ceil(b.memory.timing.tRCD_ns / c.ns)));
    EXPECT_EQ(cyc.tRC, static_cast<long>(std::ceil(b.memory.timing.tRC_ns / c.ns)));
    EXPECT_EQ(cyc.tREFI, static_cast<long>(std::floor(b.memory.timing.tREFI_ns() / c.ns)));
  }
  // A clock faster than the grade allows is refused by the description.
  EXPECT_THROW(
      (void)rtl::board::parse_board(
          test::board_with("vizard2_pci", "period_ns = 10.0", "period_ns = 7.5"), "x.toml"),
      Error);
}

TEST(Constraints, GoldenFilesMatch) {
  std::ostringstream log;
  const std::string dir = std::string(VOXCAST_SOURCE_DIR) + "/tests/golden/constraints";
  EXPECT_EQ(cosim::check_constraint_goldens(dir, false, log), 0) << log.str();
}

TEST(Constraints, FormatNames) {
  EXPECT_EQ(cosim::parse_constraint_format("xdc"), ConstraintFormat::kXdc);
  EXPECT_EQ(cosim::parse_constraint_format("sdc"), ConstraintFormat::kSdc);
  EXPECT_THROW((void)cosim::parse_constraint_format("ucf"), Error);
}

}  // namespace
}  // namespace voxcast
