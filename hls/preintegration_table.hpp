// Pre-integration table: classification of the segment between two
// consecutive samples of a ray (render.classification = "preintegrated";
// Engel, Kraus and Ertl, "High-Quality Pre-Integrated Volume Rendering Using
// Hardware-Accelerated Pixel Shading", Graphics Hardware 2001). A 2-D table
// addressed by the front and the back sample's values, holding the transfer
// function integrated along the segment with the value varying linearly
// between them: the segment's opacity (the frame's step already in it, as the
// post-classification table's opacity correction) and its self-attenuated
// colour divided by that opacity, so that the shader and the compositor take
// an entry exactly as they take a classification entry (docs/pipeline.md §4a,
// the float twin ref::preintegrate).
//
// The unit replaces the classification table's read for a frame that asks for
// it: same entry fields and widths (§4.2), a second address. A ray's first
// sample opens its first segment and ends none: its entry is transparent, so
// n samples give the n - 1 segments between them (the first sample standing
// for a step before the ray's entry cost 6 dB against the truth on
// default.toml, docs/pipeline.md §4a).
//
// Layout of this header:
//   1. PreintegrationParams<P>: widths and types, derived from P.
//   2. The synthesizable unit: PreintegrationTable<P>, preint_address() (§4a.1),
//      classify_segment() (§4a.2).
//   3. host:: — loading the table from the driver's raw entries
//      (bittrue::make_preint_table, §4a.3). Not synthesized.
#pragma once

#include <cstdint>

#include "hls/classification_table.hpp"
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
struct PreintegrationParams {
  static constexpr int addr_bits = P::preint_addr_bits;  // per segment end
  static constexpr int entries = widths::preint_entries(profile_fields<P>());
  using value_t = typename ClassificationParams<P>::value_t;
  // §4a.1: the classification address's rounding at this table's resolution.
  using scaled_value_t = ufixed<ClassificationParams<P>::sample_value_bits, addr_bits>;
  using addr_round_t = ufixed<addr_bits, addr_bits, RND, SAT>;
  using addr_t = uint_t<addr_bits>;
  using index_t = uint_t<2 * addr_bits>;  // front address in the high half

  static_assert(addr_bits >= 1 && addr_bits <= 10, "preint_addr_bits out of range (1..10)");
};

// Pipeline depth (clocks): §4a.1 the two addresses (one rounding and clamp each,
// in parallel) 1; §4a.2 the read 2: a 2^(2b)-entry table is a cascade of block
// RAMs (docs/pipeline.md §4a.5: 79-158 RAMB18 for 201^2 entries; 16 UltraRAM at
// b = 8), whose output multiplexer takes a register stage of its own at the
// card's clock (UG573, "Cascadable Block RAM"). One clock more than the
// classification table's.
constexpr int preintegration_depth = 3;

// The table: one ClassEntry per (front, back) address pair, front-major; read
// once per sample. `enabled` is the frame's register: the design reads this
// table instead of the classification table while it is set.
template <class P>
struct PreintegrationTable {
  bool enabled;
  ClassEntry<P> entry[PreintegrationParams<P>::entries];
};

// §4a.1: addr = SAT(Q_RND(value · 2^(preint_addr_bits - vb), 0), 0, 2^preint_addr_bits - 1),
// the classification address (§4.1) at the table's own resolution.
template <class P>
VOXCAST_HLS_HOST_INLINE typename PreintegrationParams<P>::addr_t preint_address(
    const typename PreintegrationParams<P>::value_t& value) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using Params = PreintegrationParams<P>;
  return table_address<typename Params::scaled_value_t, typename Params::addr_round_t,
                       typename Params::addr_t>(value);
}

// §4a: the entry of a sample that ends no segment (a ray's first): transparent.
template <class P>
VOXCAST_HLS_HOST_INLINE ClassEntry<P> no_segment() {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  ClassEntry<P> e;
  e.r = 0;
  e.g = 0;
  e.b = 0;
  e.alpha = 0;
  e.ka = 0;
  e.kd = 0;
  e.ks = 0;
  return e;
}

// §4a.2: the segment from the sample of value `front` to the next of value `back`.
template <class P>
VOXCAST_HLS_HOST_INLINE ClassEntry<P> classify_segment(
    const PreintegrationTable<P>& table, const typename PreintegrationParams<P>::value_t& front,
    const typename PreintegrationParams<P>::value_t& back) {
  VOXCAST_HLS_PRAGMA(HLS INLINE)
  using Params = PreintegrationParams<P>;
  typename Params::index_t index = 0;
  write_bits(index, 2 * Params::addr_bits - 1, Params::addr_bits,
             read_bits(preint_address<P>(front)));
  write_bits(index, Params::addr_bits - 1, 0, read_bits(preint_address<P>(back)));
  return table.entry[index.to_uint()];
}

// ---- 3. Host side (not synthesized) -------------------------------------------------------
#if VOXCAST_HLS_HOST_CODE
namespace host {

// Loads the frame's table (bittrue::make_preint_table's entries, front-major)
// and sets the register; false (table unchanged) if the size does not match.
template <class P>
bool load_preint_table(PreintegrationTable<P>& table,
                       const std::vector<bittrue::ClassEntry>& raw) {
  constexpr int n = PreintegrationParams<P>::entries;
  if (raw.size() != static_cast<std::size_t>(n)) return false;
  for (int i = 0; i < n; ++i) table.entry[i] = entry_from_raw<P>(raw[static_cast<std::size_t>(i)]);
  table.enabled = true;
  return true;
}

}  // namespace host
#endif
}  // namespace hls
}  // namespace voxcast
