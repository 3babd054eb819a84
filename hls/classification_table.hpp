// Classification unit: the look-up table from an interpolated sample value to
// (r, g, b, alpha, ka, kd, ks), VIZARD II section 2.1 ("classification ... two
// 32 bit SRAMs"); the datapath is docs/pipeline.md §4, its float twin
// ref::TransferFunction::classify + ref::opacity_correct.
//
// Layout of this header:
//   1. ClassificationParams<P>: every width and type of the unit, derived from P.
//   2. The synthesizable unit: ClassEntry<P>, ClassificationTable<P>,
//      class_address() (§4.1), classify(), and the vizard2 SRAM word layout
//      pack_vizard2_words() / unpack_vizard2_words() (§4.3).
//   3. host:: — loading the table from the raw integers the driver computes
//      (bittrue::make_class_table, §4.2). Not synthesized.
#pragma once

#include <cstdint>
#include <type_traits>

#include "hls/pragma.hpp"
#include "hls/types.hpp"
#include "hls/widths.hpp"

#if VOXCAST_HLS_HOST_CODE
#include <vector>

#include "refmodel/bittrue/frame_setup.hpp"
#endif


namespace voxcast {
namespace hls {

// ---- 1. Parameters ------------------------------------------------------------------------
template <class P>
struct ClassificationParams {
  static constexpr int value_bits = P::value_bits;              // vb
  static constexpr int sample_frac_bits = P::sample_frac_bits;  // sf
  static constexpr int addr_bits = P::tf_addr_bits;
  static constexpr int entries = widths::class_entries(profile_fields<P>());
  static constexpr int color_bits = P::color_bits;
  static constexpr int alpha_bits = P::alpha_bits;
  static constexpr int k_bits = P::k_bits;
  // Payload bits of one entry (the vizard2 SRAM words add 8 reserved bits, §4.3).
  static constexpr int entry_bits = widths::class_entry_bits(profile_fields<P>());
  static constexpr int sample_value_bits = widths::sample_value_bits(profile_fields<P>());

  // The interpolated sample value, vb.sf unsigned (§3.5). A narrower fixed type
  // converts into it exactly.
  using value_t = ufixed<sample_value_bits, value_bits>;
  // §4.1: the same bits read with the binary point moved: value · 2^(addr_bits - vb).
  using scaled_value_t = ufixed<sample_value_bits, addr_bits>;
  // §4.1: SAT(Q_RND(·, 0), 0, 2^addr_bits - 1) is one conversion into this type.
  using addr_round_t = ufixed<addr_bits, addr_bits, RND, SAT>;
  using addr_t = uint_t<addr_bits>;

  // §4.2 fields: unsigned fractions of 1.
  using color_t = ufixed<color_bits, 0>;
  using alpha_t = ufixed<alpha_bits, 0>;
  using k_t = ufixed<k_bits, 0>;

  static_assert(addr_bits >= 1 && addr_bits <= 20, "tf_addr_bits out of range");
  static_assert(sample_value_bits <= 64, "sample value wider than 64 bits");
};

// Pipeline depth (clocks; see hls/geometry_processor.hpp, "Pipeline depths"):
// §4.1 the address (one rounding, one clamp) 1, §4 the table read 1. classify()
// is inlined into the sample pipeline (HLS INLINE), and Vitis ignores the
// pragmas of an inlined function (UG1399, "Inline"), so this depth has no
// LATENCY pragma until the unit is a level of the hierarchy of its own.
constexpr int classification_depth = 2;

// ---- 2. The unit ----------------------------------------------------------------------------

// One table entry (§4.2).
template <class P>
struct ClassEntry {
  using Params = ClassificationParams<P>;
  typename Params::color_t r, g, b;
  typename Params::alpha_t alpha;  // opacity-corrected for the frame's step
  typename Params::k_t ka, kd, ks;
};

// The table: 2^tf_addr_bits entries, one per address, in one SRAM (read-only for
// the datapath; written by the load phase between frames). The synthesized top
// (hls/vizard2_synth_top.cpp) packs an entry into one word and binds the array
// to a single-port block RAM (AGGREGATE compact=bit, BIND_STORAGE ram_1p):
// one read per sample, as the paper's two 32-bit SRAMs read in parallel.
template <class P>
struct ClassificationTable {
  ClassEntry<P> entry[ClassificationParams<P>::entries];
};

// §4.1 for a table of Scaled's integer bits: the value's bits read as Scaled
// (the binary point moved: wiring, not arithmetic), one rounding and one clamp
// into Round, the integer as Addr. The classification and the pre-integration
// (§4a.1) tables share it at their own resolutions.
template <class Scaled, class Round, class Addr, class Value>
VOXCAST_HLS_HOST_INLINE Addr table_address(const Value& value) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  Scaled scaled;
  write_bits(scaled, read_bits(value));
  const Round rounded = scaled;  // one rounding, one clamp
  return int_cast<Addr>(rounded);  // integer-valued: exact
}

// §4.1: addr = SAT(Q_RND(value · 2^(tf_addr_bits - vb), 0), 0, 2^tf_addr_bits - 1).
template <class P>
VOXCAST_HLS_HOST_INLINE typename ClassificationParams<P>::addr_t class_address(
    const typename ClassificationParams<P>::value_t& value) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using Params = ClassificationParams<P>;
  return table_address<typename Params::scaled_value_t, typename Params::addr_round_t,
                       typename Params::addr_t>(value);
}

// §4: one table read per sample.
template <class P>
VOXCAST_HLS_HOST_INLINE ClassEntry<P> classify(
    const ClassificationTable<P>& table, const typename ClassificationParams<P>::value_t& value) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  return table.entry[class_address<P>(value).to_uint()];
}

// §4.3: the vizard2 entry as two 32-bit SRAM words, each field its raw unsigned integer:
//   word[0] bits [31:24] r, [23:16] g, [15:8] b, [7:0] alpha
//   word[1] bits [31:24] ka, [23:16] kd, [15:8] ks, [7:0] reserved, written 0
// 256 entries x 8 bytes = 2 KB, VIZARD II's table size.
struct Vizard2Words {
  uint_t<32> word[2];
};

// Profiles whose entries have the vizard2 field widths (8-bit r, g, b, alpha,
// ka, kd, ks); the packing below exists only for them.
template <class P>
struct Vizard2Layout
    : std::integral_constant<bool, P::color_bits == 8 && P::alpha_bits == 8 && P::k_bits == 8> {};

template <class P, typename std::enable_if<Vizard2Layout<P>::value, int>::type = 0>
Vizard2Words pack_vizard2_words(const ClassEntry<P>& e) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  Vizard2Words w;
  w.word[0] = 0;
  w.word[1] = 0;
  write_bits(w.word[0], 31, 24, read_bits(e.r));
  write_bits(w.word[0], 23, 16, read_bits(e.g));
  write_bits(w.word[0], 15, 8, read_bits(e.b));
  write_bits(w.word[0], 7, 0, read_bits(e.alpha));
  write_bits(w.word[1], 31, 24, read_bits(e.ka));
  write_bits(w.word[1], 23, 16, read_bits(e.kd));
  write_bits(w.word[1], 15, 8, read_bits(e.ks));
  return w;
}

// The inverse; the reserved bits [7:0] of word[1] are ignored.
template <class P, typename std::enable_if<Vizard2Layout<P>::value, int>::type = 0>
ClassEntry<P> unpack_vizard2_words(const Vizard2Words& w) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  ClassEntry<P> e;
  write_bits(e.r, read_bits(w.word[0], 31, 24));
  write_bits(e.g, read_bits(w.word[0], 23, 16));
  write_bits(e.b, read_bits(w.word[0], 15, 8));
  write_bits(e.alpha, read_bits(w.word[0], 7, 0));
  write_bits(e.ka, read_bits(w.word[1], 31, 24));
  write_bits(e.kd, read_bits(w.word[1], 23, 16));
  write_bits(e.ks, read_bits(w.word[1], 15, 8));
  return e;
}

// ---- 3. Host side (not synthesized) -------------------------------------------------------
#if VOXCAST_HLS_HOST_CODE
namespace host {

// One entry from the driver's raw integers (§4.2), and back.
template <class P>
ClassEntry<P> entry_from_raw(const bittrue::ClassEntry& raw) {
  ClassEntry<P> e;
  write_bits(e.r, std::uint64_t{raw.r});
  write_bits(e.g, std::uint64_t{raw.g});
  write_bits(e.b, std::uint64_t{raw.b});
  write_bits(e.alpha, std::uint64_t{raw.alpha});
  write_bits(e.ka, std::uint64_t{raw.ka});
  write_bits(e.kd, std::uint64_t{raw.kd});
  write_bits(e.ks, std::uint64_t{raw.ks});
  return e;
}

template <class P>
bittrue::ClassEntry entry_to_raw(const ClassEntry<P>& e) {
  bittrue::ClassEntry raw;
  raw.r = static_cast<unsigned>(read_bits(e.r));
  raw.g = static_cast<unsigned>(read_bits(e.g));
  raw.b = static_cast<unsigned>(read_bits(e.b));
  raw.alpha = static_cast<unsigned>(read_bits(e.alpha));
  raw.ka = static_cast<unsigned>(read_bits(e.ka));
  raw.kd = static_cast<unsigned>(read_bits(e.kd));
  raw.ks = static_cast<unsigned>(read_bits(e.ks));
  return raw;
}

// Loads the whole table (2^tf_addr_bits raw entries, bittrue::make_class_table).
// Returns false (and leaves the table unchanged) if the size does not match.
template <class P>
bool load_class_table(ClassificationTable<P>& table, const std::vector<bittrue::ClassEntry>& raw) {
  constexpr int n = ClassificationParams<P>::entries;
  if (raw.size() != static_cast<std::size_t>(n)) return false;
  [[gnu::unused]] load_class_entries : for (int i = 0; i < n; ++i) {
    table.entry[i] = entry_from_raw<P>(raw[static_cast<std::size_t>(i)]);
  }
  return true;
}

}  // namespace host
#endif
}  // namespace hls
}  // namespace voxcast
