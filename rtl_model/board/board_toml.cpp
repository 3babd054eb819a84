// The board TOML reader (docs/constraints.md): a schema per table, every key
// required unless it is listed as optional, one-line errors naming file:line
// and the dotted key, in the style of refmodel/scene/scene_toml.cpp (whose
// reader is private to the scene parser and knows the scene's schema).
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <ostream>
#include <set>
#include <sstream>

#include "refmodel/error.hpp"
#include "rtl_model/board/board.hpp"

namespace voxcast::rtl::board {
namespace {

// --- Schema: the keys each table accepts --------------------------------------
// "clocks.*" is every clock's table. Optional keys are marked with '?'.
const std::map<std::string, std::vector<std::string>>& schema() {
  static const std::map<std::string, std::vector<std::string>> s = {
      {"",
       {"name", "description", "core_clock", "core_source", "fpga", "clocks", "memory", "host"}},
      {"fpga", {"part", "tool_part", "source"}},
      {"clocks.*", {"period_ns?", "port?", "from?", "multiply?", "divide?", "pin?", "source"}},
      {"memory",
       {"type", "clock", "dimms", "burst_length", "ports", "source", "geometry", "timing", "io"}},
      {"memory.geometry",
       {"module", "component", "banks", "bank_groups?", "rows", "columns", "bus_bits", "source"}},
      // The DDR4 keys (cwl, the _ck/_ns pairs) are required with memory.type
      // = "ddr4" and refused with "sdr" (read_memory checks).
      {"memory.timing",
       {"name",       "part",          "tCK_min_ns", "cas_latency", "tRCD_ns",    "tRP_ns",
        "tRAS_ns",    "tRAS_max_ns",   "tRC_ns",     "tRRD_ns",     "tWR_ns",     "tRFC_ns",
        "tREF_ms",    "refresh_count", "tCCD_ck",    "tCDL_ck",     "tMRD_ck",    "source",
        "cwl?",       "tRRD_S_ck?",    "tRRD_S_ns?", "tRRD_L_ck?",  "tRRD_L_ns?", "tFAW_ck?",
        "tFAW_ns?",   "tCCD_S_ck?",    "tCCD_S_ns?", "tCCD_L_ck?",  "tCCD_L_ns?", "tWTR_S_ck?",
        "tWTR_S_ns?", "tWTR_L_ck?",    "tWTR_L_ns?", "tRTP_ck?",    "tRTP_ns?"}},
      {"memory.io", {"interface", "tAC_ns?", "tOH_ns?", "tIS_ns?", "tIH_ns?", "source", "trace?"}},
      {"memory.io.trace", {"clock_min_ns", "clock_max_ns", "data_min_ns", "data_max_ns", "source"}},
      {"host", {"interface", "clock", "bus_bits", "lanes?", "ports", "source", "io"}},
      {"host.io",
       {"interface", "tval_min_ns?", "tval_max_ns?", "tval_ptp_max_ns?", "tsu_ns?", "tsu_ptp_ns?",
        "th_ns?", "source"}},
  };
  return s;
}

std::string bare(const std::string& key) {
  return !key.empty() && key.back() == '?' ? key.substr(0, key.size() - 1) : key;
}

std::string fmt(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// Reads one table against its schema entry: every accessor checks presence,
// type and range and names the key; the constructor rejects unknown keys.
class Reader {
 public:
  Reader(const toml::table* table, std::string path, std::string schema_key, std::string file,
         int line)
      : table_(table),
        path_(std::move(path)),
        schema_key_(std::move(schema_key)),
        file_(std::move(file)),
        line_(line) {
    reject_unknown_keys();
  }

  int line() const { return line_; }
  bool has(const std::string& key) const { return table_->contains(key); }
  std::string key_path(const std::string& key) const {
    return path_.empty() ? key : path_ + "." + key;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    const toml::node* n = table_->get(key);
    const int line =
        n && n->source().begin.line > 0 ? static_cast<int>(n->source().begin.line) : line_;
    throw Error(file_ + ":" + std::to_string(line) + ": " + key_path(key) + " " + what);
  }

  // A number in [lo, hi]; integers are accepted as numbers.
  double number(const std::string& key, double lo, double hi) const {
    const toml::node& n = required(key);
    double v = 0;
    if (auto d = n.value_exact<double>())
      v = *d;
    else if (auto i = n.value_exact<int64_t>())
      v = static_cast<double>(*i);
    else
      fail(key, "must be a number, not " + type_name(n));
    if (!std::isfinite(v)) fail(key, "= " + fmt(v) + " is not a finite number");
    if (v < lo || v > hi)
      fail(key, "= " + fmt(v) + " is outside [" + fmt(lo) + ", " + fmt(hi) + "]");
    return v;
  }
  double number_or(const std::string& key, double def, double lo, double hi) const {
    return has(key) ? number(key, lo, hi) : def;
  }

  int integer(const std::string& key, int lo, int hi) const {
    const toml::node& n = required(key);
    const auto v = n.value_exact<int64_t>();
    if (!v) fail(key, "must be an integer, not " + type_name(n));
    if (*v < lo || *v > hi)
      fail(key, "= " + std::to_string(*v) + " is outside [" + std::to_string(lo) + ", " +
                    std::to_string(hi) + "]");
    return static_cast<int>(*v);
  }
  int integer_or(const std::string& key, int def, int lo, int hi) const {
    return has(key) ? integer(key, lo, hi) : def;
  }

  std::string string(const std::string& key, const std::vector<std::string>& allowed = {}) const {
    const toml::node& n = required(key);
    const auto v = n.value_exact<std::string>();
    if (!v) fail(key, "must be a string, not " + type_name(n));
    if (v->empty()) fail(key, "must not be empty");
    if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), *v) == allowed.end()) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "\"" : ", \"") + a + "\"";
      fail(key, "= \"" + *v + "\" is not one of " + list);
    }
    return *v;
  }
  std::string string_or(const std::string& key, const std::string& def) const {
    return has(key) ? string(key) : def;
  }

  Reader table(const std::string& key) const {
    const toml::node& n = required(key);
    if (!n.is_table()) fail(key, "must be a table, not " + type_name(n));
    return child(key, schema_child(key), n);
  }
  // Every entry of a table whose keys are names (clocks): each read against "<key>.*".
  std::vector<std::pair<std::string, Reader>> named_tables(const std::string& key) const {
    const Reader outer = table_of_names(key);
    std::vector<std::pair<std::string, Reader>> out;
    for (const auto& [k, v] : *outer.table_) {
      const std::string name(k.str());
      if (!v.is_table()) outer.fail(name, "must be a table, not " + type_name(v));
      out.emplace_back(name, outer.child(name, schema_child(key) + ".*", v));
    }
    return out;
  }

 private:
  Reader child(const std::string& key, const std::string& schema_key, const toml::node& n) const {
    const int line = n.source().begin.line > 0 ? static_cast<int>(n.source().begin.line) : line_;
    return Reader(n.as_table(), key_path(key), schema_key, file_, line);
  }
  Reader table_of_names(const std::string& key) const {
    const toml::node& n = required(key);
    if (!n.is_table()) fail(key, "must be a table, not " + type_name(n));
    if (n.as_table()->empty()) fail(key, "must name at least one entry");
    // A table of names has no schema of its own: an empty key list with the
    // marker "*" accepts any key.
    return Reader(n.as_table(), key_path(key), "*", file_,
                  n.source().begin.line > 0 ? static_cast<int>(n.source().begin.line) : line_);
  }
  const toml::node& required(const std::string& key) const {
    const toml::node* n = table_->get(key);
    if (!n) {
      throw Error(file_ + ":" + std::to_string(line_) + ": " + key_path(key) +
                  " is missing (required in " +
                  (path_.empty() ? "the top level" : "[" + path_ + "]") + ")");
    }
    return *n;
  }
  std::string schema_child(const std::string& key) const {
    return schema_key_.empty() ? key : schema_key_ + "." + key;
  }
  static std::string type_name(const toml::node& n) {
    std::ostringstream os;
    os << n.type();
    return os.str();
  }
  void reject_unknown_keys() const {
    if (schema_key_ == "*") return;
    const auto it = schema().find(schema_key_);
    if (it == schema().end()) throw Error("board schema has no table " + schema_key_);
    for (const auto& [k, v] : *table_) {
      const std::string key(k.str());
      const bool known = std::any_of(it->second.begin(), it->second.end(),
                                     [&](const std::string& s) { return bare(s) == key; });
      if (known) continue;
      std::string list;
      for (const auto& s : it->second) list += (list.empty() ? "" : ", ") + bare(s);
      const int line = v.source().begin.line > 0 ? static_cast<int>(v.source().begin.line) : line_;
      throw Error(file_ + ":" + std::to_string(line) + ": " + key_path(key) +
                  " is not a board key (known here: " + list + ")");
    }
  }

  const toml::table* table_;
  std::string path_;
  std::string schema_key_;
  std::string file_;
  int line_;
};

// --- Ranges ----------------------------------------------------------------------
// Wide enough for any SDRAM generation and FPGA clock, narrow enough to catch
// unit mistakes (ps for ns, MHz for ns).
constexpr double kMinPeriodNs = 0.1;     // 10 GHz
constexpr double kMaxPeriodNs = 1000.0;  // 1 MHz
constexpr double kMaxDatasheetNs = 1.0e6;
constexpr double kMaxTraceNs = 20.0;  // 3 m of FR-4: no card trace is longer

// --- Tables -------------------------------------------------------------------------
Clock read_clock(const std::string& name, const Reader& r) {
  Clock c;
  c.name = name;
  c.line = r.line();
  c.source = r.string("source");
  c.port = r.string_or("port", "");
  c.from = r.string_or("from", "");
  if (c.port.empty() == c.from.empty())
    r.fail(c.from.empty() ? "port" : "from",
           "is needed: a clock is either a port clock (port, period_ns) or generated "
           "(from, multiply, divide, pin), not both");
  if (!c.port.empty()) {
    for (const char* k : {"multiply", "divide", "pin"})
      if (r.has(k)) r.fail(k, "belongs to a generated clock, but this one has a port");
    c.period_ps = sim::ps_from_ns(r.number("period_ns", kMinPeriodNs, kMaxPeriodNs));
  } else {
    if (r.has("period_ns"))
      r.fail("period_ns", "is derived for a generated clock (master * divide / multiply)");
    c.multiply = r.integer_or("multiply", 1, 1, 64);
    c.divide = r.integer_or("divide", 1, 1, 64);
    c.pin = r.string("pin");
  }
  return c;
}

// Generated clocks take their period from their master, which may itself be
// generated; a cycle or a missing master is an error.
void derive_generated_periods(std::vector<Clock>& clocks, const std::string& file) {
  auto find = [&](const std::string& name) -> Clock* {
    for (Clock& c : clocks)
      if (c.name == name) return &c;
    return nullptr;
  };
  for (Clock& c : clocks) {
    std::set<std::string> seen{c.name};
    const Clock* m = &c;
    std::int64_t mul = 1, div = 1;
    while (m->generated()) {
      mul *= m->multiply;
      div *= m->divide;
      const Clock* master = find(m->from);
      if (!master)
        throw Error(file + ":" + std::to_string(m->line) + ": clocks." + m->name + ".from = \"" +
                    m->from + "\" is not a clock of this board");
      if (!seen.insert(master->name).second)
        throw Error(file + ":" + std::to_string(m->line) + ": clocks." + m->name +
                    ".from: the clock is derived from itself");
      m = master;
    }
    if (c.generated()) {
      // Nearest picosecond, as the model's ClockDomain::from_mhz.
      c.period_ps = (m->period_ps * div + mul / 2) / mul;
      if (c.period_ps < sim::ps_from_ns(kMinPeriodNs))
        throw Error(file + ":" + std::to_string(c.line) + ": clocks." + c.name + ": period " +
                    fmt(c.period_ns()) + " ns is below " + fmt(kMinPeriodNs) + " ns");
    }
  }
}

Fpga read_fpga(const Reader& r) {
  return Fpga{
      .part = r.string("part"), .tool_part = r.string("tool_part"), .source = r.string("source")};
}

sdram::Geometry read_geometry(const Reader& r) {
  sdram::Geometry g;
  g.module = r.string("module");
  g.component = r.string("component");
  g.source = r.string("source");
  auto pow2 = [&](const char* key, int lo, int hi) {
    const int v = r.integer(key, lo, hi);
    if ((v & (v - 1)) != 0) r.fail(key, "= " + std::to_string(v) + " is not a power of two");
    return static_cast<std::uint32_t>(v);
  };
  g.banks = pow2("banks", 1, 64);
  if (r.has("bank_groups")) {
    g.bank_groups = pow2("bank_groups", 1, 16);
    if (g.banks % g.bank_groups != 0) r.fail("bank_groups", "does not divide banks");
  }
  g.rows = pow2("rows", 2, 1 << 20);
  g.columns = pow2("columns", 2, 1 << 16);
  g.bus_bits = pow2("bus_bits", 8, 1024);
  return g;
}

sdram::TimingNs read_timing(const Reader& r) {
  sdram::TimingNs t;
  t.name = r.string("name");
  t.part = r.string("part");
  t.source = r.string("source");
  const auto ns = [&](const char* key) { return r.number(key, 0.1, kMaxDatasheetNs); };
  t.tCK_min_ns = r.number("tCK_min_ns", kMinPeriodNs, kMaxPeriodNs);
  t.cas_latency = r.integer("cas_latency", 1, 64);
  t.tRCD_ns = ns("tRCD_ns");
  t.tRP_ns = ns("tRP_ns");
  t.tRAS_ns = ns("tRAS_ns");
  t.tRAS_max_ns = ns("tRAS_max_ns");
  t.tRC_ns = ns("tRC_ns");
  t.tRRD_ns = ns("tRRD_ns");
  t.tWR_ns = ns("tWR_ns");
  t.tRFC_ns = ns("tRFC_ns");
  t.tREF_ms = r.number("tREF_ms", 1, 1000);
  t.refresh_count = r.integer("refresh_count", 1, 1 << 20);
  t.tCCD_ck = r.integer("tCCD_ck", 1, 64);
  t.tCDL_ck = r.integer("tCDL_ck", 1, 64);
  t.tMRD_ck = r.integer("tMRD_ck", 1, 64);
  // Relations every SDRAM satisfies (a row cycle is an activate plus a precharge).
  if (t.tRAS_max_ns < t.tRAS_ns) r.fail("tRAS_max_ns", "is below tRAS_ns");
  if (t.tRC_ns + 1e-9 < t.tRAS_ns + t.tRP_ns) r.fail("tRC_ns", "is below tRAS_ns + tRP_ns");
  if (t.tREFI_ns() <= t.tRFC_ns) r.fail("refresh_count", "gives tREFI <= tRFC");
  return t;
}

// The parameters DDR4 adds (JESD79-4B): CWL and each max(nCK, ns) pair as
// NAME_ck and NAME_ns.
sdram::Ddr4Ns read_ddr4_timing(const Reader& r) {
  sdram::Ddr4Ns d;
  d.cwl = r.integer("cwl", 9, 18);
  const auto pair = [&](const std::string& name) {
    return sdram::ClocksOrNs{r.integer(name + "_ck", 0, 256), r.number(name + "_ns", 0, 1000)};
  };
  d.tRRD_S = pair("tRRD_S");
  d.tRRD_L = pair("tRRD_L");
  d.tFAW = pair("tFAW");
  d.tCCD_S = pair("tCCD_S");
  d.tCCD_L = pair("tCCD_L");
  d.tWTR_S = pair("tWTR_S");
  d.tWTR_L = pair("tWTR_L");
  d.tRTP = pair("tRTP");
  return d;
}

constexpr const char* kDdr4TimingKeys[] = {
    "cwl",       "tRRD_S_ck", "tRRD_S_ns", "tRRD_L_ck", "tRRD_L_ns", "tFAW_ck",
    "tFAW_ns",   "tCCD_S_ck", "tCCD_S_ns", "tCCD_L_ck", "tCCD_L_ns", "tWTR_S_ck",
    "tWTR_S_ns", "tWTR_L_ck", "tWTR_L_ns", "tRTP_ck",   "tRTP_ns"};

Window read_window(const Reader& r, const std::string& what) {
  const Window w{r.number(what + "_min_ns", 0, kMaxTraceNs),
                 r.number(what + "_max_ns", 0, kMaxTraceNs)};
  if (w.max_ns < w.min_ns) r.fail(what + "_max_ns", "is below " + what + "_min_ns");
  return w;
}

SdramIo read_sdram_io(const Reader& r) {
  SdramIo io;
  io.interface = r.string("interface", {"system_synchronous", "vendor_phy"});
  io.source = r.string("source");
  if (io.interface == "vendor_phy") {
    for (const char* k : {"tAC_ns", "tOH_ns", "tIS_ns", "tIH_ns", "trace"})
      if (r.has(k))
        r.fail(k, "is not used with interface = \"vendor_phy\" (the PHY closes its own timing)");
    return io;
  }
  io.tAC_ns = r.number("tAC_ns", 0.1, 50);
  io.tOH_ns = r.number("tOH_ns", 0, 50);
  io.tIS_ns = r.number("tIS_ns", 0.1, 50);
  io.tIH_ns = r.number("tIH_ns", 0, 50);
  if (io.tOH_ns >= io.tAC_ns) r.fail("tOH_ns", "must be below tAC_ns (the data-valid window)");
  const Reader tr = r.table("trace");
  io.clock_trace = read_window(tr, "clock");
  io.data_trace = read_window(tr, "data");
  io.trace_source = tr.string("source");
  return io;
}

PciIo read_pci_io(const Reader& r) {
  PciIo io;
  io.interface = r.string("interface", {"pci_component", "hard_block"});
  io.source = r.string("source");
  const std::vector<const char*> keys = {"tval_min_ns", "tval_max_ns", "tval_ptp_max_ns",
                                         "tsu_ns",      "tsu_ptp_ns",  "th_ns"};
  if (io.interface == "hard_block") {
    for (const char* k : keys)
      if (r.has(k)) r.fail(k, "is not used with interface = \"hard_block\" (serial lanes)");
    return io;
  }
  io.tval_min_ns = r.number("tval_min_ns", 0, 100);
  io.tval_max_ns = r.number("tval_max_ns", 0.1, 100);
  io.tval_ptp_max_ns = r.number("tval_ptp_max_ns", 0.1, 100);
  io.tsu_ns = r.number("tsu_ns", 0.1, 100);
  io.tsu_ptp_ns = r.number("tsu_ptp_ns", 0.1, 100);
  io.th_ns = r.number("th_ns", 0, 100);
  if (io.tval_max_ns < io.tval_min_ns) r.fail("tval_max_ns", "is below tval_min_ns");
  return io;
}

Memory read_memory(const Reader& r) {
  Memory m;
  m.type = r.string("type", {"sdr", "ddr4"});
  m.clock = r.string("clock");
  m.dimms = r.integer("dimms", 1, 16);
  m.burst_length = r.integer("burst_length", 1, 16);
  m.ports = r.string("ports");
  if (m.ports.find("{i}") == std::string::npos)
    r.fail("ports", "= \"" + m.ports + "\" needs {i} for the DIMM index");
  m.source = r.string("source");
  m.geometry = read_geometry(r.table("geometry"));
  const Reader timing = r.table("timing");
  m.timing = read_timing(timing);
  if (m.type == "ddr4") {
    m.timing.ddr4 = read_ddr4_timing(timing);
  } else {
    for (const char* k : kDdr4TimingKeys)
      if (timing.has(k)) timing.fail(k, "is a DDR4 key (memory.type = \"" + m.type + "\")");
  }
  m.io = read_sdram_io(r.table("io"));
  if (m.type == "sdr" && m.io.interface != "system_synchronous")
    r.fail("io", "of SDR SDRAM must be interface = \"system_synchronous\"");
  return m;
}

Host read_host(const Reader& r) {
  Host h;
  h.interface = r.string("interface", {"pci", "pcie"});
  h.clock = r.string("clock");
  h.bus_bits = r.integer("bus_bits", 1, 64);
  h.lanes = r.integer_or("lanes", 0, 1, 32);
  h.ports = r.string("ports");
  h.source = r.string("source");
  h.io = read_pci_io(r.table("io"));
  if (h.interface == "pci") {
    if (h.bus_bits != 32 && h.bus_bits != 64) r.fail("bus_bits", "of PCI is 32 or 64");
    if (r.has("lanes")) r.fail("lanes", "belongs to PCIe");
    if (h.io.interface != "pci_component")
      r.fail("io", "of PCI must be interface = \"pci_component\"");
  } else {
    if (!r.has("lanes")) r.fail("lanes", "is needed for PCIe");
    if (h.io.interface != "hard_block") r.fail("io", "of PCIe must be interface = \"hard_block\"");
  }
  return h;
}

}  // namespace

const Clock& Board::clock(const std::string& n) const {
  for (const Clock& c : clocks)
    if (c.name == n) return c;
  throw Error("board " + name + ": no clock '" + n + "'");
}

std::ostream& operator<<(std::ostream& os, const Board& b) {
  os << "board " << b.name << " (" << b.fpga.part << "; tools: " << b.fpga.tool_part << "): ";
  for (const Clock& c : b.clocks) os << c.name << " " << c.period_ns() << " ns, ";
  return os << b.memory.dimms << " x " << b.memory.geometry << " (" << b.memory.timing.name
            << "), host " << b.host.interface << " " << b.host.bus_bits << " bits";
}

Board parse_board(const std::string& text, const std::string& origin) {
  const std::string& file = origin;
  toml::table root;
  try {
    root = toml::parse(text, origin);
  } catch (const toml::parse_error& e) {
    throw Error(file + ":" + std::to_string(e.source().begin.line) + ": " +
                std::string(e.description()));
  }
  const Reader r(&root, "", "", file, 1);
  Board b;
  b.origin = origin;
  b.name = r.string("name");
  b.description = r.string("description");
  b.fpga = read_fpga(r.table("fpga"));
  for (auto& [name, cr] : r.named_tables("clocks")) b.clocks.push_back(read_clock(name, cr));
  derive_generated_periods(b.clocks, file);
  b.memory = read_memory(r.table("memory"));
  b.host = read_host(r.table("host"));
  b.core_clock = r.string("core_clock");
  b.core_source = r.string("core_source");
  // Every named clock exists.
  const auto check_clock = [&](const std::string& key, const std::string& value, int line) {
    for (const Clock& c : b.clocks)
      if (c.name == value) return;
    throw Error(file + ":" + std::to_string(line) + ": " + key + " = \"" + value +
                "\" is not a clock of this board");
  };
  const auto line_of = [&](const toml::node* n) {
    return n && n->source().begin.line > 0 ? static_cast<int>(n->source().begin.line) : 1;
  };
  check_clock("core_clock", b.core_clock, line_of(root.get("core_clock")));
  check_clock("memory.clock", b.memory.clock, line_of(root.at_path("memory.clock").node()));
  check_clock("host.clock", b.host.clock, line_of(root.at_path("host.clock").node()));
  // The memory clock must be one the SDRAM grade is rated for.
  if (b.memory_clock().period_ps < sim::ps_from_ns(b.memory.timing.tCK_min_ns))
    throw Error(
        file + ":" + std::to_string(line_of(root.at_path("memory.timing.tCK_min_ns").node())) +
        ": memory clock '" + b.memory.clock + "' (" + fmt(b.memory_clock().period_ns()) +
        " ns) is faster than memory.timing.tCK_min_ns = " + fmt(b.memory.timing.tCK_min_ns) +
        " ns");
  return b;
}

Board load_board_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot read board file " + path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse_board(ss.str(), path);
}

Board shipped_board(const std::string& name) {
  return parse_board(shipped_board_text(name), "constraints/boards/" + name + ".toml");
}

Board load_board(const std::string& name_or_path) {
  const auto names = shipped_board_names();
  if (std::find(names.begin(), names.end(), name_or_path) != names.end())
    return shipped_board(name_or_path);
  if (name_or_path.find('/') == std::string::npos &&
      name_or_path.find(".toml") == std::string::npos) {
    std::string list;
    for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
    throw Error("no shipped board '" + name_or_path + "' (shipped: " + list +
                "; or give a path to a board .toml)");
  }
  return load_board_file(name_or_path);
}

std::vector<std::string> known_board_keys() {
  std::vector<std::string> keys;
  for (const auto& [table, ks] : schema())
    for (const auto& k : ks) {
      const std::string b = bare(k);
      if (schema().count(table.empty() ? b : table + "." + b)) continue;  // a sub-table
      if (table == "" && b == "clocks") continue;
      keys.push_back(table.empty() ? b : table + "." + b);
    }
  std::sort(keys.begin(), keys.end());
  return keys;
}

}  // namespace voxcast::rtl::board
