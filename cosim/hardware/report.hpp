// `voxcast report`: the operators each hardware unit instantiates at the
// profile's widths, mapped to FPGA resources of a chosen part, with pipeline
// latency and initiation interval (issue 6, part 4). The estimation model and
// its measured error against Yosys are in docs/resources.md.
//
// Widths come from the precision profile through the functions the hls Params
// structs build their types with (hls/widths.hpp), called on the scene's
// profile; tests/report/test_report.cpp (ReportWidths) instantiates those
// structs for the presets and for other profiles and checks every operator
// width the report lists against the kernels' types. Which units exist and
// their table sizes come from the elaboration (refmodel/scene/elaboration.hpp);
// latencies from the cycle model's elaborated UnitLatencies
// (rtl_model/pipeline/config.hpp), whose defaults are the units' depths declared
// next to their kernels in hls/ (tests/report/test_unit_depths.cpp).
#pragma once

#include "cosim/reports/files.hpp"

#include <iosfwd>
#include <string>
#include <vector>

#include "refmodel/precision/profile.hpp"
#include "refmodel/scene/elaboration.hpp"
#include "refmodel/scene/scene.hpp"
#include "rtl_model/pipeline/config.hpp"

namespace voxcast::cosim {

// ---- Operators -----------------------------------------------------------------------------
enum class OpKind {
  Mul,   // a x b bits (operand widths incl. sign; a_signed / b_signed)
  Add,   // a-bit adder or subtractor
  Cmp,   // a-bit magnitude comparator
  Mux,   // a bits wide, b inputs
  Div,   // a quotient bits, b divisor bits (pipelined restoring divider)
  Reg,   // a flip-flops (registers not belonging to an operator: per-frame registers, state)
  Rom,   // a entries x b bits, read-only to the datapath (host-loaded table)
  Ram,   // a entries x b bits (the host writes, the datapath reads)
  Fifo,  // a entries x b bits
};
const char* to_string(OpKind k);

struct Op {
  OpKind kind = OpKind::Add;
  std::string what;  // e.g. "d = A + px·B + py·C (§1.1)"
  int count = 1;
  int a = 0, b = 0;
  bool a_signed = false, b_signed = false;  // Mul only
};

struct UnitOps {
  std::string name;     // e.g. "reflectance_map"
  std::string section;  // docs/pipeline.md section
  std::vector<Op> ops;
  int latency = 0;      // pipeline stages (cycles), from the elaborated UnitLatencies
  int ii = 1;           // initiation interval (cycles between samples or rays)
};

// The units present in the elaborated design and their operators.
std::vector<UnitOps> unit_operators(const ref::Elaboration& e,
                                    const rtl::pipeline::PipelineConfig& pipeline = {});

// ---- Parts and the resource model -----------------------------------------------------------
enum class Family { VirtexE, Virtex2, Series7 };

struct Part {
  std::string name;    // e.g. "xc7a200t"
  Family family = Family::Series7;
  std::string note;    // the datasheet the numbers come from
  int luts = 0;        // LUT4 (Virtex-E, Virtex-II) or LUT6 (7-series)
  int ffs = 0;
  int dsps = 0;        // DSP48E1 (7-series), MULT18X18 (Virtex-II), 0 (Virtex-E)
  int brams = 0;       // RAMB18E1 (7-series: 2 per RAMB36), RAMB16 (Virtex-II), 4-kbit BlockSelectRAM (Virtex-E)
};
const std::vector<Part>& parts();
const Part& find_part(const std::string& name);  // throws voxcast::Error naming the known parts

struct Resources {
  double luts = 0, ffs = 0, dsps = 0, brams = 0;
  Resources& operator+=(const Resources& r);
};

// The model, per operator (docs/resources.md).
int dsp_count(const Op& mul, Family f);  // 0 if the multiplier goes to LUTs
int bram_count(int depth, int width, Family f);  // 0 if the memory goes to LUT RAM
Resources op_resources(const Op& op, Family f);

struct UnitResources {
  UnitOps unit;
  Resources res;
};

struct ResourceReport {
  std::string scene;
  std::string profile_name;
  Part part;
  ref::Elaboration elaboration;
  std::vector<UnitResources> units;
  Resources total;
  int latency_ray_setup = 0;  // cycles from pixel to first sample address
  int latency_sample = 0;     // cycles from a sample's address to its composited result
  int ii = 1;
};

// The extension point for the sweep: the estimate for an elaborated design.
ResourceReport estimate_resources(const ref::Elaboration& e, const Part& part);
// ... and for a scene (loads its volume to elaborate).
ResourceReport estimate_resources(const ref::Scene& scene, const Part& part);

// One number to minimise (voxcast tune): the fraction of the part used by the
// scarcest resource, then the sum of fractions as a tie-break.
double cost(const Resources& r, const Part& part);

std::string report_markdown(const ResourceReport& r);
std::string report_json(const ResourceReport& r);
// Writes `text` to `path`; throws voxcast::Error naming the path if it cannot.
}  // namespace voxcast::cosim
