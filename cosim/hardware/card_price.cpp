// The DDR4 card of rtl_model/pipeline/burst_card.hpp priced on the board's
// part (issue 23, docs/resources.md "N pipelines on the U250"): what N ray
// pipelines, their shared tables and the four channels' caches, crossings
// and controllers take, by the operator model of report.cpp.
#include <algorithm>
#include <bit>
#include <cmath>
#include <sstream>

#include "cosim/hardware/report.hpp"
#include "hls/widths.hpp"
#include "refmodel/error.hpp"
#include "rtl_model/board/board.hpp"
#include "rtl_model/layout/burst_layout.hpp"
#include "rtl_model/scene_config.hpp"

namespace voxcast::cosim {
// A named namespace around the file's helpers: in CI's unity build this file
// and report.cpp share a translation unit, whose anonymous namespace has its
// own bits_for.
namespace card_pricing {
namespace {

int bits_for(long long n) { return hls::widths::bits_for(n); }

// A burst is 64 bytes (BL8 on the DIMM's 64 data bits, JESD79-4B) holding a
// 4x2x2 brick of 32-bit voxel words (rtl_model/layout/burst_layout.hpp).
constexpr int kLineBits = 512;
constexpr int kVoxelWordBits = 32;
constexpr int kWordsPerLine = kLineBits / kVoxelWordBits;
// A sample's trilinear cell touches one to eight bursts (layout::cell_bursts):
// the look-up hardware is sized for eight.
constexpr int kBurstsPerSample = 8;

// The DDR4 controller and PHY of one 72-bit channel (the MIG, AMD PG150),
// with its calibration MicroBlaze. ASSUMPTION: PG150 publishes its figures on
// AMD's resource-utilisation pages, which were not at hand; these round
// numbers are the order of magnitude of one such instance in an Alveo
// platform, not a measurement. They are one place, so a synthesis result
// replaces them.
Resources ddr4_controller() { return {12000, 14000, 0, 52, 0}; }
constexpr const char* kControllerSource =
    "assumption: about 12,000 LUT, 14,000 FF and 26 RAMB36 (52 RAMB18) per 72-bit DDR4 "
    "controller and PHY with its calibration processor (AMD PG150's utilisation tables were not "
    "at hand; replace with a synthesis result)";

// Burst addresses of one channel: bank (group and bank), row, burst-aligned
// column: 4 + 17 + 7 = 28 bits on the U250's 16 GB DIMM, whose 2^28 bursts
// are also the bricks a channel holds.
int burst_address_bits(const rtl::sdram::DimmConfig& d) {
  const auto& g = d.geometry;
  const long long bursts_per_row = std::max<long long>(1, g.columns / std::max(1, d.burst_length));
  return bits_for(g.banks - 1) + bits_for(g.rows - 1) + bits_for(bursts_per_row - 1);
}

CardItem priced(Op op, const Part& part) {
  CardItem it{std::move(op), {}};
  it.res = op_resources(it.op, part);
  return it;
}

// Per pipeline, at issue: the brick look-up of the sample's bursts.
std::vector<CardItem> issue_items(int index_bits, int tag_bits, const Part& part) {
  std::vector<CardItem> v;
  // layout::brick_cache_line: the top log2(lines) bits of index x 0x9E3779B97F4A7C15 mod 2^64.
  v.push_back(priced({OpKind::Mul, "cache line: Fibonacci hash of the brick index",
                      kBurstsPerSample, index_bits, 64, false, false},
                     part));
  v.push_back(priced(
      {OpKind::Cmp, "tag compare (the line's brick against the sample's)", kBurstsPerSample,
       tag_bits + 1, 0},
      part));
  v.push_back(priced({OpKind::Mux, "corner word out of its 64-byte line", kBurstsPerSample,
                      kVoxelWordBits, kWordsPerLine},
                     part));
  return v;
}

// One copy of a channel's brick cache: its lines and its tags, the store a
// read port per look-up would replicate (ported_card_total).
std::vector<CardItem> cache_store_items(const rtl::pipeline::BurstCardConfig& card, int tag_bits,
                                        const Part& part) {
  const int mshr_bits = bits_for(card.mshrs - 1);
  const int lines = static_cast<int>(card.cache_lines);
  return {priced({OpKind::Ram, "brick cache lines (64-byte bursts)", 1, lines, kLineBits}, part),
          priced({OpKind::Ram, "brick cache tags (brick, valid, pending, miss register)", 1, lines,
                  tag_bits + 2 + mshr_bits},
                 part)};
}

// Per channel: the brick cache, the miss registers and queue, the two
// crossings (burst_channel.hpp).
std::vector<CardItem> channel_items(const rtl::pipeline::BurstCardConfig& card, int address_bits,
                                    int tag_bits, const Part& part) {
  const int line_bits = std::countr_zero(card.cache_lines);
  const int mshr_bits = bits_for(card.mshrs - 1);
  const int pointer_bits = bits_for(card.crossing_depth - 1) + 1;  // Gray code, wrap bit
  std::vector<CardItem> v = cache_store_items(card, tag_bits, part);
  v.push_back(priced({OpKind::Ram, "miss registers (burst address, line)", 1, card.mshrs,
                      address_bits + line_bits},
                     part));
  v.push_back(priced({OpKind::Fifo, "miss queue", 1, card.miss_queue, mshr_bits}, part));
  v.push_back(priced({OpKind::Fifo, "request crossing to the memory clock (async FIFO)", 1,
                      card.crossing_depth, address_bits + mshr_bits},
                     part));
  v.push_back(priced({OpKind::Fifo, "return crossing: the burst and its miss register (async FIFO)",
                      1, card.crossing_depth, kLineBits + mshr_bits},
                     part));
  v.push_back(priced({OpKind::Reg, "Gray-code pointer synchronisers (2 FIFOs x 2 pointers)", 1,
                      4 * card.sync_stages * pointer_bits, 0},
                     part));
  return v;
}

// A table every pipeline reads each clock (a ROM or RAM of the datapath) in
// block RAM: its blocks are shared by two pipelines (two ports), its read
// register is each pipeline's.
bool shared_by_two(const Op& op, const Resources& r) {
  return (op.kind == OpKind::Rom || op.kind == OpKind::Ram) && (r.brams > 0 || r.urams > 0);
}

bool fits(const Resources& r, const Part& part) { return binding_share(r, part) <= 1.0; }

}  // namespace
}  // namespace card_pricing

using card_pricing::burst_address_bits;
using card_pricing::cache_store_items;
using card_pricing::channel_items;
using card_pricing::ddr4_controller;
using card_pricing::fits;
using card_pricing::issue_items;
using card_pricing::kControllerSource;
using card_pricing::shared_by_two;

Resources card_total(const CardPrice& c, int n) {
  Resources t = static_cast<double>(n) * c.per_pipeline;
  t += static_cast<double>((n + 1) / 2) * c.per_pair;
  t += static_cast<double>(c.channels) * c.per_channel;
  return t;
}

Resources ported_card_total(const CardPrice& c, int n) {
  Resources t = card_total(c, n);
  t += static_cast<double>(c.channels * (n - 1)) * c.cache_store;
  return t;
}

CardPrice price_card(const ref::Elaboration& e, const rtl::pipeline::PipelineConfig& pipeline,
                     const rtl::pipeline::BurstCardConfig& card, const Part& part,
                     const std::string& board) {
  if (card.pipelines < 1 || card.pipelines > CardPrice::kMaxPipelines)
    throw Error("DDR4 card: " + std::to_string(card.pipelines) +
                " pipelines is out of range 1.." + std::to_string(CardPrice::kMaxPipelines));
  if (!std::has_single_bit(card.cache_lines))
    throw Error("DDR4 card: the brick cache's lines per channel must be a power of two, not " +
                std::to_string(card.cache_lines));
  CardPrice c;
  c.board = board;
  c.pipelines = card.pipelines;
  c.channels = rtl::layout::kBurstChannels;
  c.cache_lines = card.cache_lines;
  for (const UnitOps& u : unit_operators(e, pipeline))
    for (const Op& op : u.ops) {
      const Resources r = op_resources(op, part);
      if (shared_by_two(op, r)) {
        c.per_pair += {0, 0, 0, r.brams, r.urams};
        c.per_pipeline += {r.luts, r.ffs, r.dsps, 0, 0};
      } else {
        c.per_pipeline += r;
      }
    }
  const int address_bits = burst_address_bits(pipeline.dimm);
  const int tag_bits = std::max(0, address_bits - std::countr_zero(card.cache_lines));
  c.issue = issue_items(address_bits, tag_bits, part);
  for (const CardItem& it : c.issue) c.per_pipeline += it.res;
  c.channel = channel_items(card, address_bits, tag_bits, part);
  for (const CardItem& it : c.channel) c.per_channel += it.res;
  for (const CardItem& it : cache_store_items(card, tag_bits, part)) c.cache_store += it.res;
  c.controller = ddr4_controller();
  c.controller_source = kControllerSource;
  c.per_channel += c.controller;
  c.total = card_total(c, c.pipelines);
  c.fits = fits(c.total, part);
  for (int n = 1; n <= CardPrice::kMaxPipelines; ++n) {
    if (fits(card_total(c, n), part)) c.largest_fit = n;
    if (fits(ported_card_total(c, n), part)) c.ported_largest_fit = n;
  }
  return c;
}

std::optional<CardPrice> price_scene_card(const ref::Scene& scene, const ref::Elaboration& e,
                                          const Part& part) {
  const rtl::board::Board board = rtl::board::load_board(scene.rtl.board);
  if (board.memory.type != "ddr4") return std::nullopt;
  const rtl::RtlConfig config = rtl::rtl_config(scene.rtl);
  return price_card(e, config.pipeline, config.card, part, board.name);
}

std::string default_part(const ref::Scene& scene) {
  const rtl::board::Board board = rtl::board::load_board(scene.rtl.board);
  if (board.memory.type != "ddr4") return "xc7a200t";
  return find_device_part(board.fpga.part).name;
}

}  // namespace voxcast::cosim
