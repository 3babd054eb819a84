// A dual-clock FIFO for a clock-domain crossing, as the card's FPGA would
// build it between the PCI clock (33 MHz) and the core clock (Cummings,
// "Simulation and Synthesis Techniques for Asynchronous FIFO Design", SNUG
// 2002, style 1): a RAM of `depth` entries, a binary write pointer in the
// write domain and a read pointer in the read domain, each passed to the
// other domain as a Gray code (one bit changes per step, so a synchroniser
// never samples a torn value) through `sync_stages` flip-flops.
//
// Consequences the model keeps: the writer sees the read pointer
// sync_stages write-clock edges late, so "full" is pessimistic (a slot freed
// by a pop is reusable only after the synchroniser); the reader sees a
// pushed entry only at its sync_stages-th read-clock edge after the push.
// Nothing is lost or reordered whatever the two clocks.
//
// Contract: at each edge of a domain its owner first calls that domain's
// clock function (write_clock / read_clock: the synchroniser samples the
// other domain's pointer as it is at this instant), then may push (write
// domain, when ready()) or pop (read domain, when valid()). Pushing when not
// ready or popping when not valid throws voxcast::Error naming the FIFO.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "refmodel/error.hpp"

namespace voxcast::rtl::sim {

template <typename T>
class AsyncFifo {
 public:
  // Throws voxcast::Error unless depth is a power of two >= 2 (the Gray-code
  // pointers wrap at 2 x depth) and sync_stages >= 2 (one flop is not a
  // synchroniser: metastability).
  AsyncFifo(std::string name, std::size_t depth, int sync_stages = 2)
      : name_(std::move(name)),
        slots_(depth),
        w2r_(static_cast<std::size_t>(sync_stages > 0 ? sync_stages : 1), 0),
        r2w_(w2r_.size(), 0) {
    if (depth < 2 || (depth & (depth - 1)) != 0)
      fail("depth " + std::to_string(depth) + " (a power of two >= 2)");
    if (sync_stages < 2) fail("sync_stages " + std::to_string(sync_stages) + " (at least 2)");
  }

  const std::string& name() const { return name_; }
  std::size_t depth() const { return slots_.size(); }
  // Entries written and not yet read (neither domain sees this exactly).
  std::size_t size() const { return static_cast<std::size_t>(wptr_ - rptr_); }

  // ---- Write domain ----
  void write_clock() { shift(r2w_, gray(rptr_)); }
  bool ready() const { return wptr_ - binary(r2w_.back()) < slots_.size(); }
  void push(T value) {
    if (!ready()) fail("push while full (as the write domain sees it)");
    slots_[wptr_ & (slots_.size() - 1)] = std::move(value);
    ++wptr_;
  }

  // ---- Read domain ----
  void read_clock() { shift(w2r_, gray(wptr_)); }
  bool valid() const { return binary(w2r_.back()) != rptr_; }
  T pop() {
    if (!valid()) fail("pop while empty (as the read domain sees it)");
    T value = std::move(slots_[rptr_ & (slots_.size() - 1)]);
    ++rptr_;
    return value;
  }

  void expect_drained() const {
    if (size() != 0) fail("holds " + std::to_string(size()) + " entries at the end");
  }

 private:
  static std::uint64_t gray(std::uint64_t b) { return b ^ (b >> 1); }
  static std::uint64_t binary(std::uint64_t g) {
    for (int shift = 1; shift < 64; shift <<= 1) g ^= g >> shift;
    return g;
  }
  // One clock edge of a synchroniser chain: every flop takes its
  // predecessor's value, the first the other domain's pointer.
  static void shift(std::vector<std::uint64_t>& chain, std::uint64_t in) {
    for (std::size_t k = chain.size() - 1; k > 0; --k) chain[k] = chain[k - 1];
    chain[0] = in;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw Error("async FIFO '" + name_ + "': " + what);
  }

  std::string name_;
  std::vector<T> slots_;
  std::uint64_t wptr_ = 0, rptr_ = 0;       // binary, unbounded (hardware wraps at 2 x depth)
  std::vector<std::uint64_t> w2r_, r2w_;    // Gray codes, [0] the first flop
};

}  // namespace voxcast::rtl::sim
