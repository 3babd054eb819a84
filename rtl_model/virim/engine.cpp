#include "rtl_model/virim/engine.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "hls/virim/host.hpp"
#include "refmodel/error.hpp"
#include "refmodel/parallel.hpp"
#include "rtl_model/sim/clock.hpp"
#include "rtl_model/sim/fifo.hpp"

namespace voxcast::rtl::virim {
namespace {

using sim::ClockDomain;
using sim::Cycle;
using sim::Fifo;
using sim::Picoseconds;

constexpr Picoseconds kNever = std::numeric_limits<Picoseconds>::max() / 4;

struct Clocks {
  ClockDomain rotator, bus, dsp;
};

// The image lines of one module and where their pixels go.
struct ModuleJob {
  int index = 0;
  std::vector<int> lines;  // view-cube planes k, in the order the rotator serves them
  std::uint32_t* level = nullptr;  // [k * W + x]
  std::uint8_t* background = nullptr;
};

// One module: its rotator (geometry processor, 8-unit parity memory with two
// banks per unit, interpolation and gradient processors), its rotator-DSP bus
// and its DSPs, each a FIFO and the slice processor. The rotator serves the
// module's lines in groups of one line per DSP and, within a group, row j of
// every line before row j + 1 of any (the geometry processor's per-plane
// perspective scale s_j makes the constant-depth plane its natural unit), so
// all DSPs of a module work at once. Every unit is in order with one input
// queue, so the model advances each unit's own clock and settles the bus and
// the DSPs lazily, when the rotator needs room: the same cycles a
// clock-by-clock simulation gives, at a cost per word instead of per clock.
template <class HP>
class Module {
  using V = hls::virim::VirimParams<HP>;
  using density_t = typename V::density_t;
  using light_t = typename V::light_t;
  using acc_t = typename V::acc_t;
  using bus_t = typename V::bus_t;

  struct BusEntry {
    bus_t word{};
    int dsp = 0;
    Picoseconds ready = 0;  // the gradient processor has the word on its output
  };
  struct DspEntry {
    bus_t word{};
    Picoseconds arrival = 0;  // visible in the DSP's FIFO
  };
  struct Dsp {
    explicit Dsp(const std::string& name, std::size_t depth) : fifo(name, depth) {}
    Fifo<DspEntry> fifo;
    Picoseconds free = 0;        // when it may start its next word
    std::vector<int> lines;      // the lines it computes, in order
    std::size_t next_line = 0;
    std::int64_t pos = 0;        // words of the current line done
    std::vector<light_t> t0, t45;
    std::vector<acc_t> acc;
  };

 public:
  Module(const hls::virim::VirimFrame<HP>& frame, const std::uint16_t* const banks[16],
         const VirimRtlConfig& cfg, const Clocks& clocks, ModuleJob job)
      : f_(frame), cfg_(cfg), clk_(clocks), job_(std::move(job)), W_(frame.geometry.W),
        D_(frame.geometry.D),
        bus_fifo_("module " + std::to_string(job_.index) + " bus buffer",
                  static_cast<std::size_t>(cfg.bus_fifo_words)) {
    for (int b = 0; b < 16; ++b) mem_.bank[b] = banks[b];
    mem_.regs = frame.memory;
    mem_.stats = hls::virim::MemoryStats{};
    mem_.reset();
    const int n = static_cast<int>(job_.lines.size());
    const int ndsp = std::min(cfg.dsps_per_module, std::max(n, 1));
    for (int d = 0; d < ndsp; ++d) {
      dsps_.emplace_back("module " + std::to_string(job_.index) + " DSP " + std::to_string(d) +
                             " FIFO",
                         static_cast<std::size_t>(cfg.dsp_fifo_words));
      dsps_.back().t0.resize(static_cast<std::size_t>(W_));
      dsps_.back().t45.resize(static_cast<std::size_t>(W_));
      dsps_.back().acc.resize(static_cast<std::size_t>(W_));
    }
    for (int l = 0; l < n; ++l)
      dsps_[static_cast<std::size_t>(l % cfg.dsps_per_module)].lines.push_back(
          job_.lines[static_cast<std::size_t>(l)]);
    ring_.resize(static_cast<std::size_t>(ndsp) * 3 * static_cast<std::size_t>(W_));
  }

  void run() {
    const int n = static_cast<int>(job_.lines.size());
    const int per = cfg_.dsps_per_module;
    for (int g = 0; g * per < n; ++g) {
      const int slots = std::min(per, n - g * per);
      for (int j = 0; j < D_; ++j)
        for (int s = 0; s < slots; ++s) {
          const int k = job_.lines[static_cast<std::size_t>(g * per + s)];
          for (int i = 0; i < W_; ++i) row(s, j % 3)[i] = rotate_voxel(i, j, k);
          end_of_row(s, j);
        }
    }
    while (bus_fifo_.valid()) bus_step();
    Picoseconds end = clk_.rotator.time_of(rc_);
    for (Dsp& d : dsps_) {
      settle(d, kNever);
      end = std::max(end, d.free);
    }
    check_drained();
    stats_.frame_ns = static_cast<double>(end) * 1e-3;
    stats_.cycles = static_cast<std::uint64_t>(clk_.rotator.cycles_at_least(end));
  }

  const VirimRtlStats& stats() const { return stats_; }
  const hls::virim::MemoryStats& memory_stats() const { return mem_.stats; }

 private:
  density_t* row(int slot, int r) {
    return ring_.data() + (static_cast<std::size_t>(slot) * 3 + static_cast<std::size_t>(r)) *
                              static_cast<std::size_t>(W_);
  }

  // The geometry processor's address, the 8 unit reads through the hls parity
  // memory (which decides suppression and bounds exactly as hls does), the
  // timing of the reads that reach a RAM bank, and the interpolation.
  density_t rotate_voxel(int i, int j, int k) {
    const hls::virim::Address<HP> a = hls::virim::geometry_processor<HP>(f_.geometry, i, j, k);
    bool held[8];
    hls::uint_t<1> held_bank[8];
    typename V::word_addr_t held_addr[8];
    for (int u = 0; u < 8; ++u) {
      held[u] = mem_.held[u];
      held_bank[u] = mem_.held_bank[u];
      held_addr[u] = mem_.held_addr[u];
    }
    std::uint16_t value[8];
    bool valid[8];
    mem_.read8(a.x0, value, valid);
    const int p0 = (a.x0[0] & 1).to_int() + 2 * (a.x0[1] & 1).to_int() + 4 * (a.x0[2] & 1).to_int();
    const Cycle asked = rc_;
    Cycle issue = rc_;
    int bank[8];
    for (int u = 0; u < 8; ++u) {
      bank[u] = -1;
      ++stats_.unit_reads;
      const int c = u ^ p0;
      if (!valid[c]) {  // outside the bounds: 0 on the line, no RAM cycle
        ++stats_.out_of_range;
        if (cfg_.zero_out_of_range) continue;
        // Without the feature the unit reads its RAM (and the 0 is forced
        // after): the bank is the address's bit 1 of x, as for any read.
        const int b = cfg_.ping_pong ? static_cast<int>(((a.x0[0] + (c & 1)).to_int() >> 1) & 1) : 0;
        bank[u] = b;
        issue = std::max(issue, bank_free_[u][b]);
        continue;
      }
      const bool repeat =
          held[u] && mem_.held_bank[u] == held_bank[u] && mem_.held_addr[u] == held_addr[u];
      if (repeat && cfg_.suppress_repeats) {  // old data held on the line
        ++stats_.suppressed;
        continue;
      }
      const int b = mem_.held_bank[u].to_int();
      ++stats_.ram_reads;
      ++stats_.bank_reads[b];
      bank[u] = cfg_.ping_pong ? b : 0;  // without ping-pong the unit is one bank
      issue = std::max(issue, bank_free_[u][bank[u]]);
    }
    for (int u = 0; u < 8; ++u) {
      if (bank[u] < 0) continue;
      bank_free_[u][bank[u]] = issue + cfg_.bank_cycle_clocks;
      stats_.access_cycles += static_cast<std::uint64_t>(issue - asked + cfg_.bank_cycle_clocks);
    }
    stats_.stalls.rotator_bank_busy += static_cast<std::uint64_t>(issue - asked);
    stats_.rotating_cycles += static_cast<std::uint64_t>(issue - asked + 1);
    ++stats_.voxels;
    last_issue_ = issue;
    rc_ = issue + 1;
    hls::uint_t<3 * HP::weight_bits> addr = 0;
    hls::write_bits(addr, HP::weight_bits - 1, 0, a.q[0].to_uint64());
    hls::write_bits(addr, 2 * HP::weight_bits - 1, HP::weight_bits, a.q[1].to_uint64());
    hls::write_bits(addr, 3 * HP::weight_bits - 1, 2 * HP::weight_bits, a.q[2].to_uint64());
    return hls::virim::interpolation_processor<HP>(f_.tables, addr, value, valid);
  }

  // Row j of slot s is complete: the gradient processor releases row j - 1
  // (it needed row j below it) and, after the line's last row, row j itself,
  // each in descending x (the order the slice processor's 45 deg light needs).
  void end_of_row(int s, int j) {
    const int rows = (j >= 1 ? 1 : 0) + (j == D_ - 1 ? 1 : 0);
    const auto words = static_cast<std::size_t>(rows * W_);
    if (words > bus_fifo_.depth())
      throw Error("virim rtl: bus_fifo_words = " + std::to_string(bus_fifo_.depth()) +
                  " cannot hold the " + std::to_string(words) +
                  " words a line's row releases (W = " + std::to_string(W_) +
                  "): the rotator would deadlock");
    make_room(words);
    const Picoseconds ready = clk_.rotator.time_of(last_issue_ + cfg_.bank_cycle_clocks +
                                                   cfg_.interpolation_latency +
                                                   cfg_.gradient_latency);
    if (j >= 1) release_row(s, j - 1, ready);
    if (j == D_ - 1) release_row(s, j, ready);
  }

  void release_row(int s, int r, Picoseconds ready) {
    const density_t* above = r >= 1 ? row(s, (r + 2) % 3) : nullptr;
    const density_t* mid = row(s, r % 3);
    const density_t* below = r + 1 < D_ ? row(s, (r + 1) % 3) : nullptr;
    for (int x = W_ - 1; x >= 0; --x) {
      BusEntry e;
      e.word = hls::virim::pack_bus_word<HP>(
          hls::virim::gradient_processor<HP>(above, mid, below, x, W_));
      e.dsp = s;
      e.ready = ready;
      bus_fifo_.push(e);
    }
  }

  // Room for `words` more in the bus buffer: the transfers that must finish
  // first (the bus is settled lazily: its transfers depend only on earlier
  // ones), and the rotator waits until the last of them.
  void make_room(std::size_t words) {
    const std::size_t size = bus_fifo_.size(), depth = bus_fifo_.depth();
    const std::size_t need = size + words > depth ? size + words - depth : 0;
    Picoseconds freed = clk_.rotator.time_of(rc_);
    for (std::size_t t = 0; t < need; ++t) freed = bus_step();
    const Cycle resume = std::max(rc_, clk_.rotator.edge_at_or_after(freed));
    stats_.stalls.rotator_bus_full += static_cast<std::uint64_t>(resume - rc_);
    rc_ = resume;
  }

  Cycle earliest_bus_cycle() const {
    return std::max(bus_next_, clk_.bus.edge_at_or_after(bus_fifo_.front().ready));
  }

  // One word over the bus into the selected DSP's FIFO; returns when the
  // transfer has finished (the word has left the bus buffer).
  Picoseconds bus_step() {
    Cycle bc = earliest_bus_cycle();
    const BusEntry e = bus_fifo_.pop();
    Dsp& d = dsps_[static_cast<std::size_t>(e.dsp)];
    settle(d, clk_.bus.time_of(bc));
    if (d.fifo.full()) {  // only the selected DSP receives: the bus waits for it
      const Picoseconds pop = start_time(d);
      settle(d, pop);
      const Cycle later = std::max(bc, clk_.bus.edge_at_or_after(pop));
      stats_.stalls.bus_dsp_fifo_full += static_cast<std::uint64_t>(later - bc);
      bc = later;
    }
    const Picoseconds done = clk_.bus.time_of(bc + 1);
    d.fifo.push(DspEntry{e.word, done});
    ++stats_.bus_words;
    bus_next_ = bc + 1;
    return done;
  }

  Picoseconds start_time(const Dsp& d) const {
    return clk_.dsp.time_of(clk_.dsp.edge_at_or_after(std::max(d.free, d.fifo.front().arrival)));
  }

  // The DSP computes every word it can start by time t.
  void settle(Dsp& d, Picoseconds t) {
    while (d.fifo.valid()) {
      const Picoseconds start = start_time(d);
      if (start > t) return;
      if (d.pos > 0 && start > d.free)  // idle inside a line: starved
        stats_.stalls.dsp_starved += static_cast<std::uint64_t>(
            clk_.dsp.cycles_at_least(start - d.free));
      const DspEntry e = d.fifo.pop();
      slice(d, e.word);
      d.free = start + clk_.dsp.period_ps() * cfg_.dsp_cycles_per_voxel;
      stats_.dsp_busy_cycles += static_cast<std::uint64_t>(cfg_.dsp_cycles_per_voxel);
    }
  }

  // The slice processor on one bus word, as hls::virim::virim_line does it.
  void slice(Dsp& d, const bus_t& word) {
    if (d.next_line >= d.lines.size())
      throw Error("virim rtl: module " + std::to_string(job_.index) +
                  ": a DSP received a word beyond its lines");
    const auto Wz = static_cast<std::size_t>(W_);
    if (d.pos == 0) {
      std::fill(d.t0.begin(), d.t0.end(), light_t(1));
      std::fill(d.t45.begin(), d.t45.end(), light_t(1));
      std::fill(d.acc.begin(), d.acc.end(), acc_t(0));
    }
    const int x = W_ - 1 - static_cast<int>(d.pos % W_);
    const auto xs = static_cast<std::size_t>(x);
    const light_t out45 = hls::virim::slice_voxel<HP>(
        f_.slice, hls::virim::unpack_bus_word<HP>(word), d.t45[xs], d.t0[xs], d.acc[xs]);
    if (x + 1 < W_) d.t45[xs + 1] = out45;
    if (x == 0) d.t45[0] = 1;  // light enters the cube's side unattenuated
    if (++d.pos < static_cast<std::int64_t>(W_) * D_) return;
    const int k = d.lines[d.next_line++];
    for (std::size_t xx = 0; xx < Wz; ++xx) {
      job_.level[static_cast<std::size_t>(k) * Wz + xx] = hls::virim::output_level<HP>(d.acc[xx]);
      job_.background[static_cast<std::size_t>(k) * Wz + xx] = d.t0[xx] > f_.slice.threshold;
    }
    d.pos = 0;
  }

  void check_drained() const {
    bus_fifo_.expect_drained();
    for (std::size_t i = 0; i < dsps_.size(); ++i) {
      const Dsp& d = dsps_[i];
      d.fifo.expect_drained();
      if (d.next_line != d.lines.size() || d.pos != 0)
        throw Error("virim rtl: module " + std::to_string(job_.index) + " DSP " +
                    std::to_string(i) + " finished " + std::to_string(d.next_line) + " of " +
                    std::to_string(d.lines.size()) + " lines with " + std::to_string(d.pos) +
                    " words of a line left over");
    }
  }

  const hls::virim::VirimFrame<HP>& f_;
  const VirimRtlConfig& cfg_;
  const Clocks& clk_;
  ModuleJob job_;
  const int W_, D_;
  hls::virim::ParityMemory<HP> mem_;
  Cycle bank_free_[8][2] = {};
  Cycle rc_ = 0, last_issue_ = 0;  // rotator: next free clock, last issue
  Cycle bus_next_ = 0;             // bus: next free clock
  Fifo<BusEntry> bus_fifo_;
  std::vector<Dsp> dsps_;
  std::vector<density_t> ring_;  // per slot, the three rows the Sobel needs
  VirimRtlStats stats_;
};

void add(VirimRtlStats& to, const VirimRtlStats& s) {
  to.voxels += s.voxels;
  to.rotating_cycles += s.rotating_cycles;
  to.unit_reads += s.unit_reads;
  to.ram_reads += s.ram_reads;
  to.suppressed += s.suppressed;
  to.out_of_range += s.out_of_range;
  to.bank_reads[0] += s.bank_reads[0];
  to.bank_reads[1] += s.bank_reads[1];
  to.access_cycles += s.access_cycles;
  to.bus_words += s.bus_words;
  to.dsp_busy_cycles += s.dsp_busy_cycles;
  to.stalls.rotator_bank_busy += s.stalls.rotator_bank_busy;
  to.stalls.rotator_bus_full += s.stalls.rotator_bus_full;
  to.stalls.bus_dsp_fifo_full += s.stalls.bus_dsp_fifo_full;
  to.stalls.dsp_starved += s.stalls.dsp_starved;
  to.frame_ns = std::max(to.frame_ns, s.frame_ns);
  to.cycles = std::max(to.cycles, s.cycles);
}

template <class HP>
VirimRtlResult render(const bittrue::VirimSetup& setup, const bittrue::VirimMemory& memory,
                      const VirimRtlConfig& cfg, int threads) {
  const auto frame = hls::virim::host::load_virim_frame<HP>(setup);
  const std::uint16_t* banks[16];
  hls::virim::host::bank_pointers(memory, banks);
  const Clocks clocks{ClockDomain::from_mhz("rotator", cfg.rotator_mhz),
                      ClockDomain::from_mhz("bus", cfg.bus_mhz),
                      ClockDomain::from_mhz("dsp", cfg.dsp_mhz)};
  const auto pixels = static_cast<std::size_t>(setup.W) * static_cast<std::size_t>(setup.H);
  std::vector<std::uint32_t> level(pixels, 0);
  std::vector<std::uint8_t> background(pixels, 0);
  // Line k goes to module k mod modules: each module gets every M-th plane.
  std::vector<ModuleJob> jobs(static_cast<std::size_t>(cfg.modules));
  for (int m = 0; m < cfg.modules; ++m) {
    jobs[static_cast<std::size_t>(m)].index = m;
    jobs[static_cast<std::size_t>(m)].level = level.data();
    jobs[static_cast<std::size_t>(m)].background = background.data();
  }
  for (int k = 0; k < setup.H; ++k) jobs[static_cast<std::size_t>(k % cfg.modules)].lines.push_back(k);
  std::vector<VirimRtlStats> per_module(jobs.size());
  ref::parallel_for(
      cfg.modules,
      [&](int m) {
        Module<HP> mod(*frame, banks, cfg, clocks, jobs[static_cast<std::size_t>(m)]);
        mod.run();
        per_module[static_cast<std::size_t>(m)] = mod.stats();
      },
      threads);
  VirimRtlResult r;
  r.stats.modules = cfg.modules;
  r.stats.dsps = cfg.modules * cfg.dsps_per_module;
  r.stats.rotator_mhz = clocks.rotator.frequency_mhz();
  r.stats.dsp_mhz = clocks.dsp.frequency_mhz();
  for (const VirimRtlStats& s : per_module) add(r.stats, s);
  r.image = ref::QuantImage(setup.W, setup.H, HP::out_bits);
  const auto full = static_cast<std::uint32_t>(r.image.full_scale());
  for (int k = 0; k < setup.H; ++k)
    for (int x = 0; x < setup.W; ++x) {
      const std::size_t p = static_cast<std::size_t>(k) * static_cast<std::size_t>(setup.W) +
                            static_cast<std::size_t>(x);
      const std::uint32_t v = level[p];
      r.image.at(x, setup.H - 1 - k) = background[p] ? std::array<std::uint32_t, 4>{0, 0, 0, 0}
                                                     : std::array<std::uint32_t, 4>{v, v, v, full};
    }
  return r;
}

}  // namespace

VirimRtlResult virim_rtl_render(const bittrue::VirimSetup& setup, const bittrue::VirimMemory& memory,
                                const VirimRtlConfig& config, int threads) {
  validate(config);
  VirimRtlResult r;
  const bool compiled = hls::virim::host::dispatch_heidelberg_profile(
      setup.profile, [&]<class HP>() { r = render<HP>(setup, memory, config, threads); });
  if (!compiled)
    throw Error("rtl engine: heidelberg.weight_bits = " + std::to_string(setup.profile.weight_bits) +
                " is not compiled in (compiled: " +
                hls::virim::host::kCompiledHeidelbergProfiles + ")");
  return r;
}

}  // namespace voxcast::rtl::virim
