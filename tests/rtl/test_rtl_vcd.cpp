// The VCD trace of a frame (rtl_model/trace/): a structural parse of the
// IEEE 1364 value change dump (header, scopes, every declared identifier
// used, timestamps strictly increasing, values of the declared widths), the
// SDRAM commands inside the window equal to the model's statistics, and a
// trace that changes neither cycles nor pixels.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "refmodel/error.hpp"
#include "rtl_frames.hpp"
#include "rtl_model/engine.hpp"
#include "rtl_model/trace/pipeline_trace.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast;

struct Var {
  int width = 0;
  std::string scope, name;
};

// The parsed dump: declarations and, per identifier, its value changes.
struct Vcd {
  std::string timescale;
  std::map<std::string, Var> vars;
  std::map<std::string, std::vector<std::pair<std::int64_t, std::uint64_t>>> changes;
  std::vector<std::int64_t> times;
};

Vcd parse_vcd(const std::string& text) {
  Vcd v;
  std::istringstream in(text);
  std::vector<std::string> scopes;
  std::string tok;
  bool body = false, in_dumpvars = false;
  std::int64_t now = -1;
  auto expect_end = [&in](const std::string& what) {
    std::string t;
    in >> t;
    if (t != "$end") throw std::runtime_error(what + " without $end");
  };
  auto record = [&](const std::string& id, std::uint64_t value, std::size_t bits) {
    if (now < 0) throw std::runtime_error("value change before the first timestamp");
    const auto it = v.vars.find(id);
    if (it == v.vars.end()) throw std::runtime_error("undeclared identifier " + id);
    if (bits == 0 || static_cast<int>(bits) > it->second.width)
      throw std::runtime_error("value of " + id + " wider than its declaration");
    v.changes[id].emplace_back(now, value);
  };
  while (in >> tok) {
    if (!body) {
      if (tok == "$date" || tok == "$version" || tok == "$comment" || tok == "$timescale") {
        std::string t, all;
        while (in >> t && t != "$end") all += (all.empty() ? "" : " ") + t;
        if (tok == "$timescale") v.timescale = all;
      } else if (tok == "$scope") {
        std::string kind, name;
        in >> kind >> name;
        if (kind != "module") throw std::runtime_error("scope kind " + kind);
        scopes.push_back(name);
        expect_end("$scope");
      } else if (tok == "$upscope") {
        if (scopes.empty()) throw std::runtime_error("$upscope without $scope");
        scopes.pop_back();
        expect_end("$upscope");
      } else if (tok == "$var") {
        std::string type, id, name, t;
        int width = 0;
        in >> type >> width >> id >> name;
        while (in >> t && t != "$end") {
        }
        if (type != "wire" || width < 1 || width > 64) throw std::runtime_error("bad $var " + name);
        if (v.vars.count(id)) throw std::runtime_error("identifier declared twice: " + id);
        if (scopes.empty()) throw std::runtime_error("$var outside a scope");
        std::string scope;
        for (const auto& s : scopes) scope += (scope.empty() ? "" : ".") + s;
        v.vars[id] = Var{width, scope, name};
      } else if (tok == "$enddefinitions") {
        expect_end("$enddefinitions");
        if (!scopes.empty()) throw std::runtime_error("unclosed $scope");
        body = true;
      } else {
        throw std::runtime_error("unexpected header token " + tok);
      }
      continue;
    }
    if (tok[0] == '#') {
      const std::int64_t t = std::stoll(tok.substr(1));
      if (!v.times.empty() && t <= v.times.back())
        throw std::runtime_error("timestamp " + tok + " does not increase");
      v.times.push_back(t);
      now = t;
    } else if (tok == "$dumpvars") {
      in_dumpvars = true;
    } else if (tok == "$end") {
      if (!in_dumpvars) throw std::runtime_error("stray $end");
      in_dumpvars = false;
    } else if (tok[0] == 'b') {
      std::string id;
      in >> id;
      const std::string bits = tok.substr(1);
      if (bits.find_first_not_of("01") != std::string::npos)
        throw std::runtime_error("illegal vector value " + tok);
      record(id, std::stoull(bits, nullptr, 2), bits.size());
    } else if (tok[0] == '0' || tok[0] == '1') {
      const std::string id = tok.substr(1);
      if (v.vars.count(id) && v.vars[id].width != 1)
        throw std::runtime_error("scalar value for vector " + id);
      record(id, static_cast<std::uint64_t>(tok[0] - '0'), 1);
    } else {
      throw std::runtime_error("unexpected body token " + tok);
    }
  }
  if (!body) throw std::runtime_error("no $enddefinitions");
  return v;
}

// Cycles in [first, end) during which variable `id` is not 0 (a command
// pulse lasts one cycle: the count of commands).
std::int64_t nonzero_cycles(const Vcd& v, const std::string& id, std::int64_t end) {
  std::int64_t n = 0;
  const auto& ch = v.changes.at(id);
  for (std::size_t i = 0; i < ch.size(); ++i) {
    const std::int64_t until = i + 1 < ch.size() ? ch[i + 1].first : end;
    if (ch[i].second != 0) n += until - ch[i].first;
  }
  return n;
}

struct Traced {
  rtl::RtlResult result;
  Vcd vcd;
  std::string text;
};

Traced traced(const test::RtlFrame& f, const rtl::RtlConfig& c, const std::string& window) {
  std::ostringstream out;
  rtl::trace::TraceOptions o =
      window.empty() ? rtl::trace::TraceOptions{} : rtl::trace::parse_window(window, "window");
  o.out = &out;
  Traced t;
  t.result = rtl::rtl_render(f.setup, f.memory, c, &o);
  t.text = out.str();
  t.vcd = parse_vcd(t.text);
  return t;
}

std::int64_t commands_in(const Vcd& v, std::int64_t end) {
  std::int64_t n = 0;
  for (const auto& [id, var] : v.vars)
    if (var.name == "cmd") n += nonzero_cycles(v, id, end);
  return n;
}

TEST(RtlVcd, WholeFrameIsWellFormedAndCountsEveryCommand) {
  const test::RtlFrame f = test::make_rtl_frame("shepp-logan", 16, 12, {"precision.profile=vizard2"});
  for (const char* scheduler : {"in-order", "lookahead"}) {
    SCOPED_TRACE(scheduler);
    rtl::RtlConfig c = rtl::vizard2_baseline();
    c.scheduler = scheduler;
    const Traced t = traced(f, c, "");
    const rtl::RtlResult plain = rtl::rtl_render(f.setup, f.memory, c);
    EXPECT_EQ(t.result.stats.cycles, plain.stats.cycles);
    EXPECT_EQ(t.result.image.pixels, plain.image.pixels);
    EXPECT_EQ(t.vcd.timescale, "10 ns");  // one time unit per 100 MHz cycle
    // 4 DIMMs x (cmd, bank, row, request pair, completions pair) + 7 pipeline pairs.
    EXPECT_EQ(t.vcd.vars.size(), 4u * 7u + 14u);
    for (const auto& [id, var] : t.vcd.vars)
      EXPECT_TRUE(t.vcd.changes.count(id)) << var.scope << "." << var.name << " never used";
    for (const auto& [id, var] : t.vcd.vars) {
      if (var.name == "bank") {
        EXPECT_EQ(var.width, 2);  // 4 internal banks
      } else if (var.name == "row") {
        EXPECT_EQ(var.width, 12);  // 4096 rows
      } else if (var.name == "cmd") {
        EXPECT_EQ(var.width, 3);
      }
    }
    std::uint64_t stats_commands = 0;
    for (const auto& d : t.result.stats.dimms) stats_commands += d.dimm.commands;
    ASSERT_FALSE(t.vcd.times.empty());
    EXPECT_EQ(t.vcd.times.front(), 0);
    EXPECT_EQ(t.vcd.times.back(), t.result.stats.cycles + 1);
    EXPECT_EQ(static_cast<std::uint64_t>(commands_in(t.vcd, t.vcd.times.back())), stats_commands);
    EXPECT_EQ(t.result.traced_commands, stats_commands);
  }
}

TEST(RtlVcd, WindowHoldsExactlyItsCommands) {
  const test::RtlFrame f = test::make_rtl_frame("shepp-logan", 16, 12, {"precision.profile=vizard2"});
  const rtl::RtlConfig c = rtl::vizard2_baseline();
  const Traced whole = traced(f, c, "");
  const std::int64_t a = whole.result.stats.cycles / 3, b = 2 * whole.result.stats.cycles / 3;
  const Traced part = traced(f, c, std::to_string(a) + ":" + std::to_string(b));
  EXPECT_EQ(part.vcd.times.front(), a);
  EXPECT_EQ(part.vcd.times.back(), b + 1);
  // The window's commands, counted in the whole trace's cmd pulses inside [a, b].
  std::int64_t expected = 0;
  for (const auto& [id, var] : whole.vcd.vars) {
    if (var.name != "cmd") continue;
    const auto& ch = whole.vcd.changes.at(id);
    for (std::size_t i = 0; i < ch.size(); ++i) {
      const std::int64_t until = i + 1 < ch.size() ? ch[i + 1].first : whole.vcd.times.back();
      if (ch[i].second == 0) continue;
      expected += std::max<std::int64_t>(0, std::min(until, b + 1) - std::max(ch[i].first, a));
    }
  }
  EXPECT_GT(expected, 0);
  EXPECT_EQ(commands_in(part.vcd, b + 1), expected);
  EXPECT_EQ(static_cast<std::int64_t>(part.result.traced_commands), expected);
  // Every variable is in the window's $dumpvars.
  for (const auto& [id, var] : part.vcd.vars) EXPECT_EQ(part.vcd.changes.at(id).front().first, a);
}

TEST(RtlVcd, BadWindowsAreErrors) {
  EXPECT_THROW(rtl::trace::parse_window("10", "--vcd-window"), Error);
  EXPECT_THROW(rtl::trace::parse_window("20:10", "--vcd-window"), Error);
  EXPECT_THROW(rtl::trace::parse_window("a:b", "--vcd-window"), Error);
  EXPECT_THROW(rtl::trace::parse_window("-1:5", "--vcd-window"), Error);
  const auto o = rtl::trace::parse_window("100:", "--vcd-window");
  EXPECT_EQ(o.first, 100);
  EXPECT_GT(o.last, 1'000'000'000'000);
}

}  // namespace
