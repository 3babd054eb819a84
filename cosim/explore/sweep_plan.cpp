#include "cosim/explore/sweep_plan.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>

#include "refmodel/error.hpp"

namespace voxcast::cosim::sweep {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t") - b + 1);
}

// Splits at commas outside brackets and quotes.
std::vector<std::string> split_top_level(const std::string& list, const std::string& where) {
  std::vector<std::string> parts;
  std::string cur;
  int depth = 0;
  bool quoted = false;
  for (char c : list) {
    if (c == '"') quoted = !quoted;
    if (!quoted && (c == '[' || c == '{')) ++depth;
    if (!quoted && (c == ']' || c == '}')) --depth;
    if (depth < 0) throw Error(where + ": unbalanced ']' in the values");
    if (c == ',' && depth == 0 && !quoted) {
      parts.push_back(trim(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (depth != 0 || quoted) throw Error(where + ": unbalanced brackets or quotes in the values");
  parts.push_back(trim(cur));
  return parts;
}

bool parse_int(const std::string& s, long long& v) {
  const char* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, v);
  return r.ec == std::errc() && r.ptr == end && !s.empty();
}

// "A..B" with integers A <= B: the values A, A+1, ..., B. False if `v` is no range.
bool expand_range(const std::string& v, const std::string& where, std::vector<std::string>& out) {
  const auto dots = v.find("..");
  if (dots == std::string::npos || v.front() == '[' || v.front() == '"') return false;
  long long a = 0, b = 0;
  if (!parse_int(v.substr(0, dots), a) || !parse_int(v.substr(dots + 2), b))
    throw Error(where + ": range " + v + " must be two integers A..B");
  if (a > b) throw Error(where + ": range " + v + " is empty (A > B)");
  if (b - a >= static_cast<long long>(kMaxPoints))
    throw Error(where + ": range " + v + " has more than " + std::to_string(kMaxPoints) +
                " values");
  for (long long i = a; i <= b; ++i) out.push_back(std::to_string(i));
  return true;
}

}  // namespace

Axis parse_axis(const std::string& spec) {
  const std::string where = "--vary " + spec;
  const auto eq = spec.find('=');
  if (eq == std::string::npos)
    throw Error(where + ": expected KEY=V1,V2,... or KEY=A..B (e.g. render.oversampling=1,2,4)");
  Axis axis;
  axis.key = trim(spec.substr(0, eq));
  if (axis.key.empty()) throw Error(where + ": the key before '=' is empty");
  for (char c : axis.key)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '[' ||
          c == ']'))
      throw Error(where + ": '" + axis.key + "' is not a scene key (e.g. precision.weight_bits)");
  for (const std::string& v : split_top_level(spec.substr(eq + 1), where)) {
    if (v.empty()) throw Error(where + ": empty value in the list");
    if (!expand_range(v, where, axis.values)) axis.values.push_back(v);
  }
  for (std::size_t i = 0; i < axis.values.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if (axis.values[i] == axis.values[j])
        throw Error(where + ": value " + axis.values[i] + " is given twice");
  return axis;
}

Shard parse_shard(const std::string& spec) {
  const std::string where = "--shard " + spec;
  const auto slash = spec.find('/');
  long long i = 0, n = 0;
  if (slash == std::string::npos || !parse_int(spec.substr(0, slash), i) ||
      !parse_int(spec.substr(slash + 1), n))
    throw Error(where + ": expected i/n, e.g. 0/4 (shards are numbered from 0)");
  if (n < 1 || n > 100000) throw Error(where + ": n must be in [1, 100000]");
  if (i < 0 || i >= n)
    throw Error(where + ": i must be in [0, " + std::to_string(n - 1) +
                "] (shards are numbered from 0)");
  return {static_cast<int>(i), static_cast<int>(n)};
}

std::size_t Plan::size() const {
  std::size_t n = 1;
  for (const Axis& a : axes) n *= a.values.size();
  return n;
}

std::vector<std::string> Plan::values(std::size_t index) const {
  std::vector<std::string> v(axes.size());
  for (std::size_t k = axes.size(); k-- > 0;) {
    v[k] = axes[k].values[index % axes[k].values.size()];
    index /= axes[k].values.size();
  }
  return v;
}

ref::Overrides Plan::overrides(std::size_t index) const {
  ref::Overrides o = sets;
  const std::vector<std::string> v = values(index);
  for (std::size_t k = 0; k < axes.size(); ++k) o.push_back(axes[k].key + "=" + v[k]);
  return o;
}

ref::Scene Plan::scene(std::size_t index) const {
  const ref::Overrides o = overrides(index);
  try {
    return ref::load_scene_file(scene_path, o);
  } catch (const Error& e) {
    // The parser names an override as "--set KEY=VALUE"; the axes' were --vary.
    std::string msg = e.what();
    for (std::size_t k = sets.size(); k < o.size(); ++k)
      if (msg.rfind("--set " + o[k] + ":", 0) == 0) msg.replace(0, 5, "--vary");
    throw Error(msg);
  }
}

Plan make_plan(const std::string& scene_path, const ref::Overrides& sets,
               const std::vector<std::string>& vary_specs, const TruthSettings& truth) {
  Plan plan{scene_path, sets, {}, truth};
  if (vary_specs.empty()) throw Error("sweep: give at least one --vary KEY=V1,V2,...");
  std::size_t total = 1;
  for (const std::string& spec : vary_specs) {
    Axis a = parse_axis(spec);
    for (const Axis& b : plan.axes)
      if (b.key == a.key) throw Error("--vary " + a.key + ": the key is varied twice");
    for (const std::string& s : sets)
      if (trim(s.substr(0, s.find('='))) == a.key)
        throw Error("--vary " + a.key + ": the key is also fixed by --set " + s);
    total *= a.values.size();
    if (total > kMaxPoints)
      throw Error("sweep: more than " + std::to_string(kMaxPoints) + " points; split the sweep");
    plan.axes.push_back(std::move(a));
  }
  for (std::size_t i = 0; i < plan.size(); ++i) check_truth_settings(truth, plan.scene(i));
  return plan;
}

}  // namespace voxcast::cosim::sweep
