// A bounded FIFO of real depth with valid/ready semantics, as the hardware
// FIFOs between the card's units (request queues, read-data return, the PCI
// and core clock-crossing buffers) will be.
//
// Contract:
//   - ready() (not full) is the producer's permission to push this cycle;
//     valid() (not empty) is the consumer's permission to pop. Pushing when
//     full or popping when empty is a protocol error in the model that uses
//     the FIFO, reported as voxcast::Error naming the FIFO, never a silent
//     drop or stall.
//   - Storage is a ring of exactly depth() slots allocated up front.
//   - sample() is called once per clock of the FIFO's domain by its owner;
//     it accumulates the occupancy statistics (mean, maximum, full and empty
//     cycles). push/pop counts are kept independently of sampling.
//   - Or the owner gives the FIFO its domain's cycle counter
//     (sample_on_change) and calls sample_until(end) before reading stats():
//     the same statistics as sample() at the end of every clock before
//     `end`, accounted only when the occupancy changes (a model with many
//     FIFOs, most of them unchanged in most clocks, pays per change instead
//     of per clock and FIFO). sample() then does nothing.
//   - drained() / expect_drained(): data left in a FIFO at the end of a run is
//     a lost transaction; expect_drained() throws naming the FIFO.
#pragma once

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "refmodel/error.hpp"

namespace voxcast::rtl::sim {

struct FifoStats {
  std::uint64_t pushes = 0;
  std::uint64_t pops = 0;
  std::uint64_t sampled_cycles = 0;
  std::uint64_t occupancy_sum = 0;  // sum over sampled cycles
  std::uint64_t full_cycles = 0;    // sampled cycles with the FIFO full
  std::uint64_t empty_cycles = 0;   // sampled cycles with the FIFO empty
  std::size_t max_occupancy = 0;    // after any push

  double mean_occupancy() const {
    return sampled_cycles == 0
               ? 0.0
               : static_cast<double>(occupancy_sum) / static_cast<double>(sampled_cycles);
  }
};

inline std::ostream& operator<<(std::ostream& os, const FifoStats& s) {
  return os << "pushes " << s.pushes << ", pops " << s.pops << ", max occupancy " << s.max_occupancy
            << ", mean occupancy " << s.mean_occupancy() << " over " << s.sampled_cycles
            << " cycles (full " << s.full_cycles << ", empty " << s.empty_cycles << ")";
}

template <typename T>
requires std::default_initializable<T> && std::movable<T>
class Fifo {
 public:
  // Throws voxcast::Error for depth 0.
  Fifo(std::string name, std::size_t depth) : name_(std::move(name)), slots_(depth), depth_(depth) {
    if (depth == 0) fail("depth 0 (a FIFO holds at least one entry)");
  }

  const std::string& name() const { return name_; }
  std::size_t depth() const { return depth_; }
  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  bool full() const { return count_ == depth_; }
  bool ready() const { return !full(); }   // the producer may push
  bool valid() const { return !empty(); }  // the consumer may pop

  // Every push is emplace() with the entry assigned.
  void push(T value) { emplace() = std::move(value); }

  // push() for a value the caller keeps (a large record copied from the
  // producer's own storage, as the SDRAM completions): copied into its slot
  // as one block, where push()'s parameter by value is copied member by
  // member. push() stays by value: a value built for the FIFO is then
  // written straight into its slot.
  void push_copy(const T& value) { emplace() = value; }

  const T& front() const {
    if (empty()) fail("front() while empty");
    return slots_[head_];
  }

  T pop() {
    if (empty()) fail("pop while empty");
    T value = std::move(slots_[head_]);
    discard();
    return value;
  }

  // pop() for a consumer that has read front() and needs no copy of it (an
  // entry of a pipeline FIFO is 50-100 bytes; the model moves several per
  // simulated clock).
  void discard() {
    if (empty()) fail("pop while empty");
    head_ = wrap(head_ + 1);
    count_pop();
  }

  // push() of an entry built in place: returns the new last entry, which
  // holds whatever an earlier entry left there; the producer assigns every
  // member before the consumer can see it (in the same clock).
  T& emplace() {
    if (full()) fail("push while full");
    T& slot = slots_[wrap(head_ + count_)];
    ++count_;
    if (clock_) pushed_at(*clock_);
    ++stats_.pushes;
    stats_.max_occupancy = std::max(stats_.max_occupancy, count_);
    return slot;
  }

  // The i-th entry from the front (0 = front()); for a consumer that picks
  // among the entries (a collapsing issue queue).
  const T& at(std::size_t i) const {
    if (i >= count_) fail("at() past the last entry");
    return slots_[wrap(head_ + i)];
  }

  // Removes and returns the i-th entry; the entries behind it move up one
  // place, so the order of the rest is kept (take(0) == pop()).
  T take(std::size_t i) {
    if (i >= count_) fail("take() past the last entry");
    T value = std::move(slots_[wrap(head_ + i)]);
    for (std::size_t k = i; k + 1 < count_; ++k)
      slots_[wrap(head_ + k)] = std::move(slots_[wrap(head_ + k + 1)]);
    count_pop();
    return value;
  }

  // One clock of the FIFO's domain: accumulate the occupancy statistics.
  // Nothing while the FIFO samples on change: the owner's clock accounts
  // every cycle then, and a producer that also calls sample() (a memory
  // port, on the cycles it happens to run) must not count its own again.
  void sample() {
    if (clock_) return;
    ++stats_.sampled_cycles;
    stats_.occupancy_sum += count_;
    if (full()) ++stats_.full_cycles;
    if (empty()) ++stats_.empty_cycles;
  }

  // Sampling on change (see the contract): `clock` is the owner's current
  // cycle, read at every push, pop and take; the occupancy at the end of
  // cycles before the one of a change is the occupancy before the change.
  // Statistics so far are kept; the first change accounts from cycle `from`.
  void sample_on_change(const std::int64_t* clock, std::int64_t from = 0) {
    clock_ = clock;
    restart_at(from);
  }
  // Accounts the clocks up to `end` (exclusive) at the present occupancy, as
  // sample() at the end of each of them would (sample_on_change only), and
  // goes on accounting from `end`.
  void sample_until(std::int64_t end) {
    if (end <= since_) return;
    const auto n = static_cast<std::uint64_t>(end - since_);
    stats_.sampled_cycles += n;
    stats_.occupancy_sum +=
        static_cast<std::uint64_t>(static_cast<std::int64_t>(count_) * end + area_);
    stats_.full_cycles += full_ + (full() ? static_cast<std::uint64_t>(end - full_since_) : 0);
    stats_.empty_cycles += empty_ + (empty() ? static_cast<std::uint64_t>(end - empty_since_) : 0);
    restart_at(end);
  }

  bool drained() const { return empty(); }
  void expect_drained() const {
    if (!drained()) {
      std::ostringstream os;
      os << "holds " << count_ << " entr" << (count_ == 1 ? "y" : "ies")
         << " at the end (expected drained)";
      fail(os.str());
    }
  }

  const FifoStats& stats() const { return stats_; }

 private:
  // i mod depth for i < 2 * depth: a compare instead of a division per push
  // and pop (the pipeline moves several FIFO entries per simulated cycle).
  std::size_t wrap(std::size_t i) const { return i >= depth_ ? i - depth_ : i; }

  // Sampling on change keeps running terms that a push or pop updates with
  // an addition or two, no multiplication: the occupancy summed over the
  // clocks since_ <= c < T is count_ * T + area_ (an entry pushed at t and
  // popped at t' adds t' - t), and the full (empty) clocks are full_
  // (empty_) plus, while the FIFO is full (empty), T - full_since_
  // (T - empty_since_). A change at clock t holds from the end of clock t on.
  void restart_at(std::int64_t t) {
    since_ = t;
    area_ = -static_cast<std::int64_t>(count_) * t;
    full_ = empty_ = 0;
    full_since_ = empty_since_ = t;
  }
  // After a push at clock t (count_ already counts it).
  void pushed_at(std::int64_t t) {
    area_ -= t;
    if (count_ == 1) empty_ += static_cast<std::uint64_t>(t - empty_since_);
    if (count_ == depth_) full_since_ = t;
  }
  // One entry fewer (every pop): the count, and its statistics.
  void count_pop() {
    if (clock_) {
      const std::int64_t t = *clock_;
      area_ += t;
      if (count_ == depth_) full_ += static_cast<std::uint64_t>(t - full_since_);
      if (--count_ == 0) empty_since_ = t;
    } else {
      --count_;
    }
    ++stats_.pops;
  }

  [[noreturn]] void fail(std::string_view what) const {
    std::ostringstream os;
    os << "FIFO '" << name_ << "' (depth " << slots_.size() << "): " << what;
    throw Error(os.str());
  }

  std::string name_;
  std::vector<T> slots_;
  // slots_.size(), kept: the vector's size is a division by sizeof(T) (a
  // multiplication for most T), asked at every push, pop and ready().
  std::size_t depth_;
  std::size_t head_ = 0;
  std::size_t count_ = 0;
  FifoStats stats_;
  const std::int64_t* clock_ = nullptr;  // sample_on_change: the owner's cycle
  // sample_on_change's running terms (restart_at): clocks before since_ are
  // in stats_.
  std::int64_t since_ = 0;
  std::int64_t area_ = 0;
  std::uint64_t full_ = 0, empty_ = 0;
  std::int64_t full_since_ = 0, empty_since_ = 0;
};

template <typename T>
std::ostream& operator<<(std::ostream& os, const Fifo<T>& fifo) {
  return os << "FIFO '" << fifo.name() << "' " << fifo.size() << "/" << fifo.depth() << ": "
            << fifo.stats();
}

}  // namespace voxcast::rtl::sim
