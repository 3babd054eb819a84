#include "rtl_model/trace/pipeline_trace.hpp"

#include <bit>
#include <cctype>

#include "refmodel/error.hpp"

namespace voxcast::rtl::trace {
namespace {

bool parse_cycle(const std::string& s, Cycle& out) {
  if (s.empty() || s.size() > 18) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  out = std::stoll(s);
  return true;
}

int bits_for(std::uint32_t count) {
  return count <= 1 ? 1 : static_cast<int>(std::bit_width(count - 1));
}

std::string signal_name(std::string s) {
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return s;
}

}  // namespace

TraceOptions parse_window(const std::string& text, const std::string& what) {
  TraceOptions o;
  const auto colon = text.find(':');
  const std::string a = text.substr(0, colon);
  const std::string b = colon == std::string::npos ? "" : text.substr(colon + 1);
  if (colon == std::string::npos || !parse_cycle(a, o.first) ||
      (!b.empty() && !parse_cycle(b, o.last)) || o.last < o.first)
    throw Error(what + " '" + text +
                "' is not a window of cycles START:END (integers, START <= END; END may be empty)");
  return o;
}

class PipelineTrace::Dimm final : public sdram::CommandObserver {
 public:
  Dimm(PipelineTrace& t, int d) : t_(t), d_(d) {}
  void on_command(sdram::Command cmd, const sdram::Address& a, Cycle now) override {
    t_.command(d_, cmd, a, now);
  }
  int cmd_id = 0, bank_id = 0, row_id = 0;

 private:
  PipelineTrace& t_;
  int d_;
};

PipelineTrace::PipelineTrace(const TraceOptions& o, std::int64_t cycle_ps,
                             const sdram::Geometry& g, int dimms)
    : vcd_((o.out ? *o.out : throw Error("VCD trace: no output stream")), o.first, o.last,
           cycle_ps) {
  for (int d = 0; d < dimms; ++d) {
    auto p = std::make_unique<Dimm>(*this, d);
    const std::string scope = "card.dimm" + std::to_string(d);
    p->cmd_id = vcd_.add(scope, "cmd", 3);
    p->bank_id = vcd_.add(scope, "bank", bits_for(g.banks));
    p->row_id = vcd_.add(scope, "row", bits_for(g.rows));
    dimms_.push_back(std::move(p));
  }
}

PipelineTrace::~PipelineTrace() = default;

int PipelineTrace::add_fifo(const std::string& scope, const std::string& name) {
  Fifo f;
  const std::string s = "card." + scope;
  f.valid_id = vcd_.add(s, signal_name(name) + "_valid", 1, 0);
  f.ready_id = vcd_.add(s, signal_name(name) + "_ready", 1, 1);
  fifos_.push_back(f);
  return static_cast<int>(fifos_.size()) - 1;
}

void PipelineTrace::begin() { vcd_.begin(kCommandCodes); }

sdram::CommandObserver* PipelineTrace::dimm(int d) {
  return dimms_.at(static_cast<std::size_t>(d)).get();
}

void PipelineTrace::command(int d, sdram::Command cmd, const sdram::Address& a, Cycle now) {
  if (cmd == sdram::Command::kNop) return;
  const Dimm& p = *dimms_[static_cast<std::size_t>(d)];
  vcd_.pulse(p.cmd_id, sdram::index_of(cmd), 0, now);
  if (!sdram::is_rank_command(cmd)) {
    vcd_.set(p.bank_id, a.bank, now);
    vcd_.set(p.row_id, a.row, now);
  }
  if (now >= vcd_.first() && now <= vcd_.last()) ++commands_;
}

void PipelineTrace::finish(Cycle now) { vcd_.finish(now); }

}  // namespace voxcast::rtl::trace
