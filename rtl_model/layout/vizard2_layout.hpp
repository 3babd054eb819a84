// The VIZARD II volume memory: four 64-bit DIMMs, each word a voxel and its
// x-neighbour, so one access to every DIMM at once yields the whole 2x2x2
// neighbourhood at any position (2001 paper, §2.2: "32 bits per voxel, and the
// volume replicated in one dimension in the other 32 bits").
//
//   DIMM d = (y & 1) | (z & 1) << 1 holds, at word (x, y >> 1, z >> 1), the
//   64-bit word [v(x+1, y, z) : v(x, y, z)] (v(x) in bits 31:0).
//
// v is the hls packed voxel word of the profile (hls::pack_voxel_word: value
// and three gradient components), zero-extended to 32 bits; voxels outside the
// volume (x + 1 = dims.x, and the padding of odd y, z extents) read as zero,
// as the hls design's padding words do. Profiles whose packed word exceeds 32
// bits (balanced 60, precise 76) need wider modules; the model then keeps the
// two halves as they are and the timing of one access per DIMM unchanged.
//
// The hls address generator (hls::address_generator) speaks the 8-bank
// parity interleave of docs/pipeline.md §3.3. Its bank b = (x&1)|(y&1)<<1|(z&1)<<2
// is, on the card, half (x-parity of the corner) of the word of DIMM b >> 1:
// Dimm4Banks below is that bank view, so hls::gather and
// hls::interpolation_processor run unchanged on the four DIMM words.
#pragma once

#include <array>
#include <bit>
#include <cstdint>
#include <memory>
#include <vector>

#include "hls/host_march.hpp"
#include "hls/interpolation_processor.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "rtl_model/layout/address_mapping.hpp"

namespace voxcast::rtl::layout {

inline constexpr int kDimms = 4;

// A divisor known when the frame starts: a shift when it is a power of two
// (every 2^n volume), a division otherwise.
class Divider {
 public:
  explicit Divider(std::uint64_t d = 1) : d_(d), pow2_(std::has_single_bit(d)) {
    shift_ = static_cast<int>(std::countr_zero(d));
  }
  std::uint64_t div(std::uint64_t n) const { return pow2_ ? n >> shift_ : n / d_; }
  std::uint64_t mod(std::uint64_t n) const { return pow2_ ? n & (d_ - 1u) : n % d_; }

 private:
  std::uint64_t d_;
  bool pow2_;
  int shift_ = 0;
};

class Vizard2Layout {
 public:
  explicit Vizard2Layout(std::array<int, 3> dims)
      : dims_(dims),
        grid_{static_cast<std::uint32_t>(dims[0]), static_cast<std::uint32_t>((dims[1] + 1) / 2),
              static_cast<std::uint32_t>((dims[2] + 1) / 2)},
        hx_(static_cast<std::uint64_t>((dims[0] + 1) / 2)),
        hy_(grid_.ny2) {}

  const std::array<int, 3>& dims() const { return dims_; }
  // The words of each DIMM.
  const WordGrid& grid() const { return grid_; }

  static int dimm_of(int y, int z) { return (y & 1) | (z & 1) << 1; }
  // The word holding voxel (x, y, z) in its low half (and x - 1's in the high
  // half of the word before it).
  static WordCoord word_of(int x, int y, int z) {
    return {static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y >> 1),
            static_cast<std::uint32_t>(z >> 1)};
  }
  // The voxel in half h (0 low, 1 high) of word c of DIMM d.
  static std::array<int, 3> voxel_of(int d, const WordCoord& c, int h) {
    return {static_cast<int>(c.x) + h, 2 * static_cast<int>(c.y2) + (d & 1),
            2 * static_cast<int>(c.z2) + (d >> 1)};
  }

  // The words of the 2x2x2 neighbourhood with lowest corner i0, one per DIMM:
  // DIMM d reads the corner whose y and z have d's parities.
  static std::array<WordCoord, kDimms> neighbourhood(const std::array<int, 3>& i0) {
    std::array<WordCoord, kDimms> w;
    for (int d = 0; d < kDimms; ++d) {
      const int y = i0[1] + (((d & 1) ^ i0[1]) & 1);
      const int z = i0[2] + (((d >> 1) ^ i0[2]) & 1);
      w[static_cast<std::size_t>(d)] = word_of(i0[0], y, z);
    }
    return w;
  }

  // The lowest corner i0 of an hls bank access: bank `parity` holds corner 0
  // at word addr[parity] = (i0x >> 1) + (i0y >> 1) HX + (i0z >> 1) HX HY
  // (docs/pipeline.md §3.3). The address translation of the card's memory
  // interface; no datapath arithmetic.
  template <class P>
  std::array<int, 3> corner(const hls::BankAccess<P>& acc) const {
    const std::uint64_t base = acc.addr[acc.parity].to_uint64();
    const std::uint64_t row = hx_.div(base);
    const auto x = 2 * hx_.mod(base) + (acc.parity & 1u);
    const auto y = 2 * hy_.mod(row) + ((acc.parity >> 1) & 1u);
    const auto z = 2 * hy_.div(row) + ((acc.parity >> 2) & 1u);
    return {static_cast<int>(x), static_cast<int>(y), static_cast<int>(z)};
  }

 private:
  std::array<int, 3> dims_;
  WordGrid grid_;
  Divider hx_, hy_;
};

// The contents of one DIMM word, as the datapath sees them (both voxels).
template <class P>
struct DimmWord {
  hls::VoxelWordFx<P> lo, hi;  // v(x, y, z), v(x + 1, y, z)
};

// Reads DIMM words out of the volume: the card's memory image as a function of
// the host's voxel memory (bittrue::VoxelMemory, the same words the hls engine
// reads), so the model never holds a second copy of a 256^3 volume. Where the
// profile's fields fit 16 bits it reads the memory's packed words, as the hls
// engine does (hls::host::EngineBanks: the eight banks interleaved word by
// word), so a sample's eight voxels lie in one or two host cache lines
// instead of eight (the simulation's speed, not the card's).
template <class P>
class Vizard2Memory {
 public:
  explicit Vizard2Memory(const bittrue::VoxelMemory& memory)
      : memory_(memory),
        packed_(hls::host::engine_packed_words<P>(memory)),
        banks_(memory, packed_ ? packed_->data() : nullptr),
        hx_(static_cast<std::uint64_t>((memory.dims[0] + 1) / 2)),
        hxy_(hx_ * static_cast<std::uint64_t>((memory.dims[1] + 1) / 2)) {}

  // Voxel (x, y, z) of the volume, zero outside [0, dims.x) in x.
  hls::VoxelWordFx<P> voxel(int x, int y, int z) const {
    if (x >= memory_.dims[0]) return zero();
    const int b = (x & 1) | (y & 1) << 1 | (z & 1) << 2;
    const std::uint64_t w = static_cast<std::uint64_t>(x >> 1) +
                            static_cast<std::uint64_t>(y >> 1) * hx_ +
                            static_cast<std::uint64_t>(z >> 1) * hxy_;
    return banks_.read(b, typename hls::InterpolationParams<P>::word_addr_t(w));
  }

  // A host-cache hint for word(d, c), issued when the request leaves the
  // address generator (the simulation's speed, not the card's).
  void prefetch(int d, const WordCoord& c) const {
    const auto v = Vizard2Layout::voxel_of(d, c, 0);
    for (int h = 0; h < 2 && v[0] + h < memory_.dims[0]; ++h) {
      const int x = v[0] + h;
      const int b = (x & 1) | (v[1] & 1) << 1 | (v[2] & 1) << 2;
      const std::uint64_t w = static_cast<std::uint64_t>(x >> 1) +
                              static_cast<std::uint64_t>(v[1] >> 1) * hx_ +
                              static_cast<std::uint64_t>(v[2] >> 1) * hxy_;
      if (packed_)
        __builtin_prefetch(&(*packed_)[8 * w + static_cast<std::size_t>(b)]);
      else
        __builtin_prefetch(&memory_.banks[static_cast<std::size_t>(b)][w]);
    }
  }

  // voxel() of both halves, the word address of their (y, z) row computed once.
  DimmWord<P> word(int d, const WordCoord& c) const {
    const auto v = Vizard2Layout::voxel_of(d, c, 0);
    const std::uint64_t row =
        static_cast<std::uint64_t>(v[1] >> 1) * hx_ + static_cast<std::uint64_t>(v[2] >> 1) * hxy_;
    const int yz = (v[1] & 1) << 1 | (v[2] & 1) << 2;
    auto half = [&](int x) {
      if (x >= memory_.dims[0]) return zero();
      const std::uint64_t w = static_cast<std::uint64_t>(x >> 1) + row;
      return banks_.read((x & 1) | yz, typename hls::InterpolationParams<P>::word_addr_t(w));
    };
    return {half(v[0]), half(v[0] + 1)};
  }

  // The 64-bit word on the DIMM's bus: needs a packed voxel word of at most 32 bits.
  std::uint64_t bus_word(int d, const WordCoord& c) const
    requires(hls::InterpolationParams<P>::word_bits <= 32)
  {
    const DimmWord<P> w = word(d, c);
    return hls::pack_voxel_word<P>(w.lo).to_uint64() |
           hls::pack_voxel_word<P>(w.hi).to_uint64() << 32;
  }

 private:
  static hls::VoxelWordFx<P> zero() {
    hls::VoxelWordFx<P> v;
    v.value = 0;
    for (auto& g : v.g) g = 0;
    return v;
  }

  const bittrue::VoxelMemory& memory_;
  std::shared_ptr<const std::vector<bittrue::PackedVoxelWord>> packed_;  // null: the bank arrays
  hls::host::EngineBanks<P> banks_;
  std::uint64_t hx_, hxy_;
};

// The hls bank view on one sample's four DIMM words: bank b of the parity
// interleave is DIMM b >> 1 (its y and z parities), and the corner it holds
// has x-offset (b ^ parity) & 1, the half of the replicated word. The word
// address the hls gather passes is the one this sample's requests carried.
template <class P>
struct Dimm4Banks {
  const DimmWord<P>* words;  // [kDimms]
  unsigned parity;

  hls::VoxelWordFx<P> read(int b, const typename hls::InterpolationParams<P>::word_addr_t&) const {
    const auto ub = static_cast<unsigned>(b);
    const DimmWord<P>& w = words[ub >> 1];
    return ((ub ^ parity) & 1u) ? w.hi : w.lo;
  }
};

}  // namespace voxcast::rtl::layout
