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

#include <cstdint>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "refmodel/precision/profile.hpp"
#include "refmodel/scene/elaboration.hpp"
#include "refmodel/scene/scene.hpp"
#include "rtl_model/pipeline/burst_config.hpp"
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
enum class Family { VirtexE, Virtex2, Series7, UltraScalePlus };

struct Part {
  std::string name;    // e.g. "xc7a200t"
  Family family = Family::Series7;
  std::string note;    // the datasheet the numbers come from
  int luts = 0;        // LUT4 (Virtex-E, Virtex-II) or LUT6 (7-series, UltraScale+)
  int ffs = 0;
  // DSP48E2 (UltraScale+), DSP48E1 (7-series), MULT18X18 (Virtex-II), 0 (Virtex-E)
  int dsps = 0;
  // RAMB18E2 / RAMB18E1 (UltraScale+, 7-series: 2 per RAMB36), RAMB16 (Virtex-II),
  // 4-kbit BlockSelectRAM (Virtex-E)
  int brams = 0;
  int urams = 0;       // URAM288 (UltraScale+ parts that have UltraRAM), else 0
};
const std::vector<Part>& parts();
const Part& find_part(const std::string& name);  // throws voxcast::Error naming the known parts
// The table's part of a board's device name ("xcu250-figd2104-2L-e": the
// part name, then package and speed grade); throws voxcast::Error naming the
// device and the known parts if none matches.
const Part& find_device_part(const std::string& device);

struct Resources {
  double luts = 0, ffs = 0, dsps = 0, brams = 0, urams = 0;
  Resources& operator+=(const Resources& r);
};
Resources operator*(double n, const Resources& r);  // n copies

// The model, per operator (docs/resources.md).
int dsp_count(const Op& mul, Family f);  // 0 if the multiplier goes to LUTs
int bram_count(int depth, int width, Family f);  // 0 if the memory goes to LUT RAM
// URAM288 blocks (4K x 72, UG573) of a depth x width memory: cascaded
// ceil(depth / 4096) deep and ceil(width / 72) wide; 0 if the family has no
// UltraRAM or the memory goes to LUT RAM.
int uram_count(int depth, int width, Family f);
// A memory that would take block RAM takes URAM instead on a part with
// UltraRAM when that is the smaller share of the part's capacity.
bool prefers_uram(int depth, int width, const Part& part);
Resources op_resources(const Op& op, Family f);
// As above, with the part's URAM choice (prefers_uram); equal to
// op_resources(op, part.family) on a part without UltraRAM.
Resources op_resources(const Op& op, const Part& part);

struct UnitResources {
  UnitOps unit;
  Resources res;
};

// ---- The DDR4 card: N pipelines on the board's part (issue 23, card_price.cpp) --------------
// The card of rtl_model/pipeline/burst_card.hpp priced with the model above:
// per pipeline the units' datapath (unit_operators at the card's ray slots
// and sample buffer) and the card's brick look-up; per two pipelines the
// tables each pipeline reads every clock that sit in block RAM (BRAM and
// URAM have two ports: one copy serves two pipelines; LUT-RAM tables are per
// pipeline); per channel the brick cache's lines and tags, the miss
// registers and queue, the two clocked asynchronous FIFOs and the DDR4
// controller.
struct CardItem {
  Op op;          // the operator (count per pipeline or per channel)
  Resources res;  // its price on the part
};
struct CardPrice {
  std::string board;          // the board's name
  int pipelines = 1;          // N = rtl.pipelines
  int channels = 4;           // DDR4 channels (rtl::layout::kBurstChannels)
  std::uint32_t cache_lines = 0;  // per channel
  std::vector<CardItem> issue;    // per pipeline: the brick look-up at issue
  std::vector<CardItem> channel;  // per channel, the controller excepted
  Resources controller;           // per channel: the DDR4 controller and PHY
  std::string controller_source;  // where its figures come from
  Resources per_pipeline;  // the datapath (block-RAM tables excepted) and `issue`
  Resources per_pair;      // block-RAM tables, one dual-port copy per two pipelines
  Resources per_channel;   // `channel` and `controller`
  Resources total;         // card_total(*this, pipelines)
  bool fits = false;       // total within the part in every resource
  int largest_fit = 0;     // the largest N in 1..kMaxPipelines that fits; 0 if none
  // The bound the look-up ports set, which the cycle model does not (it lets
  // any number of pipelines look up a channel's cache in one clock): a
  // sample's cell needs at most two bursts of one channel (its bricks along
  // x; the channel is the bricks' y, z parity), so N pipelines need 2N reads
  // of each channel's tags and lines per clock, N dual-port copies of them.
  Resources cache_store;   // per channel, one copy: the lines and the tags
  int ported_largest_fit = 0;  // the largest N that fits with N copies
  static constexpr int kMaxPipelines = 64;  // rtl.pipelines' range
};
// n·per_pipeline + ceil(n/2)·per_pair + channels·per_channel.
Resources card_total(const CardPrice& c, int n);
// card_total(c, n) + channels·(n − 1)·cache_store: a read port per look-up.
Resources ported_card_total(const CardPrice& c, int n);
// Throws voxcast::Error unless 1 <= pipelines <= kMaxPipelines.
CardPrice price_card(const ref::Elaboration& e, const rtl::pipeline::PipelineConfig& pipeline,
                     const rtl::pipeline::BurstCardConfig& card, const Part& part,
                     const std::string& board);
// The scene's card if its board (rtl.board) is a DDR4 board, priced on
// `part`; nullopt for the SDR card. Throws voxcast::Error (naming rtl.board)
// for a board or [rtl] table the card model refuses.
std::optional<CardPrice> price_scene_card(const ref::Scene& scene, const ref::Elaboration& e,
                                          const Part& part);
// The part of `voxcast report` without --part: the board's FPGA for a DDR4
// board (find_device_part), else xc7a200t.
std::string default_part(const ref::Scene& scene);

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
  std::optional<CardPrice> card;  // the scene's board is a DDR4 board
};

// The extension point for the sweep: the estimate for an elaborated design.
ResourceReport estimate_resources(const ref::Elaboration& e, const Part& part);
// ... and for a scene (loads its volume to elaborate).
ResourceReport estimate_resources(const ref::Scene& scene, const Part& part);

// One number to minimise (voxcast tune): the fraction of the part used by the
// scarcest resource, then the sum of fractions as a tie-break.
double cost(const Resources& r, const Part& part);
// The share of the part the scarcest resource takes (1 = full): what decides
// whether a design fits.
double binding_share(const Resources& r, const Part& part);
// Its name ("LUT", "FF", "DSP", "BRAM", "URAM").
const char* binding_resource(const Resources& r, const Part& part);

std::string report_markdown(const ResourceReport& r);
std::string report_json(const ResourceReport& r);
// Writes `text` to `path`; throws voxcast::Error naming the path if it cannot.
}  // namespace voxcast::cosim
