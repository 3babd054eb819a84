#include "rtl_model/trace/vcd_writer.hpp"

#include <algorithm>
#include <map>
#include <ostream>
#include <sstream>

#include "refmodel/error.hpp"

namespace voxcast::rtl::trace {

VcdWriter::VcdWriter(std::ostream& out, Cycle first, Cycle last, std::int64_t cycle_ps)
    : out_(out), first_(first), last_(last), cycle_ps_(cycle_ps) {
  if (first < 0 || last < first)
    throw Error("VCD window " + std::to_string(first) + ":" + std::to_string(last) +
                " is empty or negative (START:END, 0 <= START <= END)");
  if (cycle_ps <= 0) throw Error("VCD: clock period must be > 0");
}

// Identifier codes: printable ASCII '!'..'~', base 94 (§18.2.1).
std::string VcdWriter::code_of(std::size_t index) {
  std::string s;
  do {
    s += static_cast<char>('!' + index % 94);
    index /= 94;
  } while (index > 0);
  return s;
}

int VcdWriter::add(const std::string& scope, const std::string& name, int width,
                   std::uint64_t init) {
  if (begun_) throw Error("VCD: variable " + name + " declared after the header");
  if (width < 1 || width > 64) throw Error("VCD: variable " + name + " width out of 1..64");
  Var v;
  v.scope = scope;
  v.name = name;
  v.width = width;
  v.value = v.written = init;
  v.code = code_of(vars_.size());
  vars_.push_back(v);
  return static_cast<int>(vars_.size()) - 1;
}

void VcdWriter::begin(const std::string& comment) {
  begun_ = true;
  // The timescale: the clock period as 1, 10 or 100 of a unit when it is
  // one (10 ns at 100 MHz: one time unit per cycle), else 1 ps with
  // timestamps scaled by the period.
  static const std::pair<std::int64_t, const char*> units[] = {
      {1'000'000'000, "ms"}, {1'000'000, "us"}, {1'000, "ns"}, {1, "ps"}};
  std::string timescale;
  for (const auto& [ps, unit] : units)
    for (std::int64_t k : {1, 10, 100})
      if (timescale.empty() && cycle_ps_ == k * ps) timescale = std::to_string(k) + " " + unit;
  if (timescale.empty()) {
    timescale = "1 ps";
    scale_ = cycle_ps_;
  }
  out_ << "$date voxcast $end\n"
       << "$version voxcast rtl_model cycle model $end\n"
       << "$comment time in clock cycles of " << cycle_ps_ << " ps; window " << first_ << ":" << last_
       << (comment.empty() ? "" : "; ") << comment << " $end\n"
       << "$timescale " << timescale << " $end\n";
  // Scopes as a tree: sorted paths, so a module shared by several
  // (card in card.dimm0, card.pipeline) is opened once.
  std::map<std::vector<std::string>, std::vector<std::size_t>> by_scope;
  for (std::size_t i = 0; i < vars_.size(); ++i) {
    std::vector<std::string> parts;
    std::stringstream ss(vars_[i].scope);
    for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
    by_scope[parts].push_back(i);
  }
  std::vector<std::string> open;
  for (const auto& [parts, members] : by_scope) {
    std::size_t common = 0;
    while (common < open.size() && common < parts.size() && open[common] == parts[common]) ++common;
    while (open.size() > common) {
      out_ << "$upscope $end\n";
      open.pop_back();
    }
    for (std::size_t k = common; k < parts.size(); ++k) {
      out_ << "$scope module " << parts[k] << " $end\n";
      open.push_back(parts[k]);
    }
    for (std::size_t i : members) {
      const Var& v = vars_[i];
      out_ << "$var wire " << v.width << " " << v.code << " " << v.name;
      if (v.width > 1) out_ << " [" << v.width - 1 << ":0]";
      out_ << " $end\n";
    }
  }
  for (; !open.empty(); open.pop_back()) out_ << "$upscope $end\n";
  out_ << "$enddefinitions $end\n";
}

void VcdWriter::write_value(const Var& v) {
  if (v.width == 1) {
    out_ << (v.value & 1u) << v.code << "\n";
    return;
  }
  std::string bits;
  for (int b = v.width - 1; b >= 0; --b) bits += ((v.value >> b) & 1u) ? '1' : '0';
  const auto lead = bits.find('1');
  out_ << 'b' << (lead == std::string::npos ? "0" : bits.substr(lead)) << " " << v.code << "\n";
}

// Writes the values that changed at `t` if `t` is inside the window (its
// cycles and the one after, which closes the last interval); the window's
// first timestamp carries every value ($dumpvars).
void VcdWriter::flush(Cycle t) {
  const bool inside = t >= first_ && t <= last_ + 1 && !finished_;
  if (inside && !dumped_) {
    dump_all(t);
    return;
  }
  for (int id : changed_) {
    Var& v = vars_[static_cast<std::size_t>(id)];
    v.changed = false;
    if (!inside || v.value == v.written) {
      if (!dumped_) v.written = v.value;  // before the window: remembered, not written
      continue;
    }
    stamp(t);
    write_value(v);
    v.written = v.value;
  }
  changed_.clear();
}

void VcdWriter::stamp(Cycle t) {
  if (t == last_stamp_) return;
  out_ << "#" << t * scale_ << "\n";
  last_stamp_ = t;
}

void VcdWriter::dump_all(Cycle t) {
  dumped_ = true;
  stamp(t);
  out_ << "$dumpvars\n";
  for (Var& v : vars_) {
    write_value(v);
    v.written = v.value;
    v.changed = false;
  }
  out_ << "$end\n";
  changed_.clear();
}

void VcdWriter::change(int id, std::uint64_t value) {
  Var& v = vars_.at(static_cast<std::size_t>(id));
  if (v.width < 64) value &= (std::uint64_t{1} << v.width) - 1;
  v.value = value;
  if (!v.changed) {
    v.changed = true;
    changed_.push_back(id);
  }
}

// Moves time to `t` with nothing changed in between: when the window opens
// strictly inside (now_, t), its first timestamp is written at first_.
void VcdWriter::step_to(Cycle t) {
  if (!dumped_ && now_ < first_ && first_ < t) {
    now_ = first_;
    flush(first_);
  }
  now_ = t;
}

// Writes what changed at now_, then ends the pulses at now_ + 1 (on their
// own timestamp when t is later still, else together with t's changes).
void VcdWriter::advance(Cycle t) {
  if (t < now_)
    throw Error("VCD: time went backwards (" + std::to_string(t) + " after " +
                std::to_string(now_) + ")");
  if (t == now_) return;
  flush(now_);
  if (!rest_at_next_.empty()) {
    for (const Pending& p : rest_at_next_) change(p.id, p.rest);
    rest_at_next_.clear();
    if (now_ + 1 == t) {
      now_ = t;
      return;
    }
    step_to(now_ + 1);
    flush(now_);
  }
  step_to(t);
}

void VcdWriter::set(int id, std::uint64_t value, Cycle now) {
  if (!begun_) throw Error("VCD: set() before begin()");
  advance(now);
  change(id, value);
}

void VcdWriter::pulse(int id, std::uint64_t value, std::uint64_t rest, Cycle now) {
  set(id, value, now);
  rest_at_next_.push_back({id, rest});
}

// The last timestamp, min(now, last) + 1, closes the final interval.
void VcdWriter::finish(Cycle now) {
  if (finished_) return;
  const Cycle end = std::min(now, last_) + 1;
  if (now_ < end) advance(end);
  if (now_ == end) flush(end);
  if (!dumped_)
    dump_all(std::max(first_, end));  // nothing inside the window: its values, once
  else if (last_stamp_ < end)
    stamp(end);
  finished_ = true;
  out_.flush();
}

}  // namespace voxcast::rtl::trace
