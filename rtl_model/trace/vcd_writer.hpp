// A value-change-dump writer (IEEE Std 1364-2005 §18, the four-state VCD
// that GTKWave reads), restricted to what the cycle model needs: two-state
// scalars and vectors up to 64 bits in nested module scopes, time in clock
// cycles, and a window of cycles outside which nothing is written.
//
// Use: declare every variable (add), then begin(); then report values with
// set(id, value, cycle) in non-decreasing cycle order. pulse() sets a value
// for one cycle only (a command on a command bus): it returns to `rest` at
// cycle + 1 unless set again then. finish(cycle) closes the dump at
// min(cycle, window end) + 1. Inside the window each timestamp carries the
// values that changed since the last one written; the first timestamp of
// the window ($dumpvars) carries every value.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

#include "rtl_model/sim/clock.hpp"

namespace voxcast::rtl::trace {

using sim::Cycle;

class VcdWriter {
 public:
  // `cycle_ps`: the clock period the timestamps count. Throws voxcast::Error
  // for an empty or inverted window or a period <= 0.
  VcdWriter(std::ostream& out, Cycle first, Cycle last, std::int64_t cycle_ps);

  // Declares a variable of `width` bits (1..64) named `name` inside `scope`
  // (dot-separated modules, e.g. "card.dimm0"), initial value `init`;
  // returns its id. Only before begin().
  int add(const std::string& scope, const std::string& name, int width, std::uint64_t init = 0);
  // Writes the header; `comment` (one line) goes into its $comment.
  void begin(const std::string& comment = "");

  void set(int id, std::uint64_t value, Cycle now);
  void pulse(int id, std::uint64_t value, std::uint64_t rest, Cycle now);
  void finish(Cycle now);

  Cycle first() const { return first_; }
  Cycle last() const { return last_; }

 private:
  struct Var {
    std::string scope, name, code;
    int width = 1;
    std::uint64_t value = 0, written = 0;
    bool changed = false;
  };
  void advance(Cycle t);
  void step_to(Cycle t);
  void flush(Cycle t);
  void dump_all(Cycle t);
  void stamp(Cycle t);
  void write_value(const Var& v);
  void change(int id, std::uint64_t value);
  static std::string code_of(std::size_t index);

  std::ostream& out_;
  Cycle first_, last_;
  std::int64_t cycle_ps_;
  std::int64_t scale_ = 1;  // timestamp units per cycle
  std::vector<Var> vars_;
  std::vector<int> changed_;
  struct Pending {
    int id;
    std::uint64_t rest;
  };
  std::vector<Pending> rest_at_next_;  // pulses that end at now_ + 1
  Cycle now_ = 0;
  Cycle last_stamp_ = -1;
  bool begun_ = false, dumped_ = false, finished_ = false;
};

}  // namespace voxcast::rtl::trace
