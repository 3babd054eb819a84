#include "cosim/explore/burst_study.hpp"

#include <algorithm>
#include <cstddef>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cosim/engines/engines.hpp"
#include "cosim/reports/files.hpp"
#include "cosim/reports/text.hpp"
#include "hls/host_frame.hpp"
#include "hls/vizard2_top.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/error.hpp"
#include "refmodel/parallel.hpp"
#include "refmodel/render/raycaster.hpp"
#include "rtl_model/board/board.hpp"
#include "rtl_model/board/board_config.hpp"
#include "rtl_model/pipeline/config.hpp"
#include "rtl_model/scene_config.hpp"
#include "rtl_model/trace/request_trace.hpp"

namespace voxcast::cosim {

namespace {

using rtl::layout::BankGroupMap;
using rtl::layout::BurstCounter;
using rtl::layout::BurstLayout;
using rtl::layout::Reuse;
using rtl::layout::RowMap;

// A recorded sample: its cell's i0, 10 bits per axis, and bit 31 on a ray's
// first sample.
constexpr int kAxisBits = 10;
constexpr std::uint32_t kAxisMask = (1u << kAxisBits) - 1u;
constexpr std::uint32_t kRayStart = 1u << 31;

// The hls top's tracer (hls/vizard2_top.hpp, NullTracer): every sample the
// ray interpolates, in order, as the cell the interpolation unit reads.
template <class P>
struct CellRecorder {
  const hls::GeometryRegisters<P>* regs = nullptr;
  std::vector<std::uint32_t>* out = nullptr;
  bool first = true;

  template <class Ray>
  void ray(const Ray&) {
    first = true;
  }
  template <class Pos, class... Rest>
  void sample(const Pos& p, const Rest&...) {
    std::uint32_t cell = first ? kRayStart : 0u;
    for (int k = 0; k < 3; ++k) {
      typename hls::InterpolationParams<P>::cpos_t cp;
      const std::uint64_t i0 = hls::sample_cell<P>(*regs, p[k], k, cp).to_uint64();
      cell |= static_cast<std::uint32_t>(i0) << (kAxisBits * k);
    }
    out->push_back(cell);
    first = false;
  }
  void skip(std::uint64_t) {}
  void ert(std::uint64_t) {}
};

// The packed voxel word's bytes on the card: 32 bits for the vizard2 profile
// (the 2001 card's voxel), 64 or 128 for wider profiles.
template <class P>
int voxel_bytes() {
  using I = hls::InterpolationParams<P>;
  constexpr int bits = I::vb + 3 * I::gb;
  return bits <= 32 ? 4 : bits <= 64 ? 8 : 16;
}

struct Stream {
  std::vector<std::uint32_t> cells;
  std::uint64_t rays = 0;
  int voxel_bytes = 0;
};

// Every ray of the first view in the card's traversal order; chunks of the
// order on the host's threads, joined in order (the same stream for any
// thread count).
Stream record_stream(const ref::Scene& scene, const bittrue::FrameSetup& fs,
                     const bittrue::VoxelMemory& memory) {
  const rtl::RtlConfig config = rtl::rtl_config(scene.rtl);
  const auto order = rtl::pipeline::pixel_order(fs.regs.width, fs.regs.height,
                                                config.pipeline.traversal, config.pipeline.tile);
  Stream stream;
  auto run = [&]<class P>() {
    const auto frame = hls::host::load_frame_state<P>(fs, "burst study");
    const hls::host::BitTrueBanks<P> banks(memory);
    constexpr std::size_t kChunk = 512;
    const std::size_t chunks = (order.size() + kChunk - 1) / kChunk;
    std::vector<std::vector<std::uint32_t>> parts(chunks);
    std::vector<std::uint64_t> rays(chunks, 0);
    ref::parallel_for(
        static_cast<int>(chunks),
        [&](int c) {
          const auto ci = static_cast<std::size_t>(c);
          CellRecorder<P> rec{&frame->geometry, &parts[ci]};
          const std::size_t end = std::min(order.size(), (ci + 1) * kChunk);
          for (std::size_t i = ci * kChunk; i < end; ++i) {
            std::uint64_t n = 0;
            hls::cast_ray<P>(*frame, banks, order[i].first, order[i].second, n, rec);
            rays[ci] += n > 0 ? 1u : 0u;
          }
        },
        scene.render.threads);
    std::size_t total = 0;
    for (const auto& part : parts) total += part.size();
    stream.cells.reserve(total);
    for (std::size_t c = 0; c < chunks; ++c) {
      stream.cells.insert(stream.cells.end(), parts[c].begin(), parts[c].end());
      stream.rays += rays[c];
    }
    stream.voxel_bytes = voxel_bytes<P>();
  };
  if (!hls::host::dispatch_profile(fs.profile, run))
    throw Error(std::string("burst study: this precision profile is not compiled in (") +
                hls::host::kCompiledProfileNames + ")");
  return stream;
}

void count(BurstCounter& counter, const std::vector<std::uint32_t>& cells) {
  for (const std::uint32_t c : cells) {
    if (c & kRayStart) counter.begin_ray();
    counter.sample({static_cast<int>(c & kAxisMask), static_cast<int>((c >> kAxisBits) & kAxisMask),
                    static_cast<int>((c >> (2 * kAxisBits)) & kAxisMask)});
  }
}

BurstLayoutResult summarize(const BurstCounter& counter) {
  const BurstLayout& layout = counter.layout();
  BurstLayoutResult r;
  r.name = layout.name();
  r.brick = layout.brick();
  r.channel_axes = layout.channel_axes();
  const double samples = static_cast<double>(std::max<std::uint64_t>(counter.samples(), 1));
  for (const Reuse reuse : rtl::layout::kAllReuse) {
    const auto& load = counter.load(reuse);
    const double bursts = static_cast<double>(load.bursts());
    std::uint64_t busiest = 0;
    for (const auto& c : load.channel) busiest = std::max(busiest, c.bursts);
    BurstReuseResult x;
    x.bursts_per_sample = bursts / samples;
    x.busiest_channel_share =
        bursts > 0 ? static_cast<double>(busiest) / (bursts / rtl::layout::kBurstChannels) : 0.0;
    x.same_group = bursts > 0 ? static_cast<double>(load.same_group()) / bursts : 0.0;
    x.row_hits = bursts > 0 ? static_cast<double>(load.row_hits()) / bursts : 0.0;
    x.bound_gsamples = counter.bound_samples_per_second(reuse) / 1e9;
    r.reuse.push_back(x);
  }
  return r;
}

// The board's channel must be the memory the layouts were laid out in.
void check_channel_matches(const rtl::sdram::DimmConfig& dimm, const rtl::layout::BurstMemory& m,
                           const std::string& board) {
  const rtl::sdram::Geometry& g = dimm.geometry;
  const bool same = g.bank_groups == rtl::layout::kBankGroups &&
                    g.banks_per_group() == static_cast<std::uint32_t>(m.banks_per_group) &&
                    g.columns == m.columns && g.rows >= m.rows &&
                    static_cast<int>(g.bytes_per_beat()) * dimm.burst_length == m.burst_bytes;
  if (!same)
    throw Error("burst study: board " + board +
                "'s memory is not the DDR4 channel the layouts "
                "assume (4 bank groups of " +
                std::to_string(m.banks_per_group) + " banks, " + std::to_string(m.columns) +
                " columns, " + std::to_string(m.burst_bytes) + "-byte bursts)");
}

// The board whose channels the channel run drives, checked against the
// layout's memory before any counting.
struct Channels {
  rtl::board::Board board;
  rtl::sdram::DimmConfig dimm;
};

Channels load_channels(const BurstStudyOptions& options, const BurstLayout& layout) {
  Channels c{rtl::board::load_board(options.board), {}};
  c.dimm = rtl::channel_config_for_board(c.board);
  check_channel_matches(c.dimm, layout.memory(), options.board);
  return c;
}

// The layout's fetches under one reuse scheme (recorded by `counter` as it
// counted the stream) through the board's four channels, for each number of
// pipelines (BurstStudyOptions::channel_layout).
ChannelRunResult run_channels(const BurstCounter& counter,
                              const std::vector<rtl::layout::Fetch>& fetches,
                              const Channels& channels, const BurstStudyOptions& options,
                              int threads) {
  const rtl::board::Board& board = channels.board;
  const rtl::sdram::DimmConfig& dimm = channels.dimm;
  const rtl::trace::AddressMapping mapping(dimm.geometry, dimm.burst_length);

  ChannelRunResult out;
  out.layout = counter.layout().name();
  out.reuse = rtl::layout::name(options.channel_reuse);
  out.board = board.name;
  out.timing = dimm.timing.name;
  out.memory_mhz = dimm.clock.frequency_mhz();
  out.core_mhz = options.core_mhz;
  out.queue_depth = options.queue_depth;
  out.requests = fetches.size();
  const auto samples = static_cast<double>(counter.samples());
  const std::size_t n = options.pipelines.size();
  std::vector<rtl::trace::TraceRunResult> runs(n * rtl::layout::kBurstChannels);
  ref::parallel_for(
      static_cast<int>(runs.size()),
      [&](int job) {
        const auto j = static_cast<std::size_t>(job);
        const int pipes = options.pipelines[j / rtl::layout::kBurstChannels];
        const int channel = static_cast<int>(j % rtl::layout::kBurstChannels);
        // Sample k leaves the pipelines at core clock k / N: memory clock
        // k x f_mem / (N x f_core).
        const double per_sample = out.memory_mhz / (pipes * options.core_mhz);
        std::vector<rtl::trace::TraceRequest> trace;
        for (const rtl::layout::Fetch& f : fetches) {
          if (f.burst.channel != channel) continue;
          rtl::sdram::Address a;
          a.bank =
              static_cast<std::uint32_t>(f.burst.bank_group) * dimm.geometry.banks_per_group() +
              static_cast<std::uint32_t>(f.burst.bank);
          a.row = f.burst.row;
          a.column = f.burst.column;
          rtl::trace::TraceRequest t;
          t.address = mapping.byte_address(a);
          t.cycle = static_cast<rtl::sdram::Cycle>(static_cast<double>(f.sample) * per_sample);
          trace.push_back(t);
        }
        runs[j] = rtl::trace::run_request_trace(
            dimm, trace, mapping, {.scheduler = "fr-fcfs", .queue_depth = options.queue_depth});
      },
      threads);
  for (std::size_t p = 0; p < n; ++p) {
    ChannelRunPoint pt;
    pt.pipelines = options.pipelines[p];
    pt.pipeline_us = samples / (pt.pipelines * options.core_mhz);
    std::uint64_t bytes = 0, hits = 0, requests = 0;
    const rtl::trace::TraceRunResult* busiest = nullptr;
    for (int c = 0; c < rtl::layout::kBurstChannels; ++c) {
      const rtl::trace::TraceRunResult& run =
          runs[p * rtl::layout::kBurstChannels + static_cast<std::size_t>(c)];
      const double us = static_cast<double>(run.cycles) * run.clock_ns / 1000.0;
      if (!busiest || us > pt.memory_us) {
        pt.memory_us = us;
        busiest = &run;
      }
      bytes += run.bytes;
      hits += run.row_hits;
      requests += run.requests;
      pt.refreshes += run.refreshes;
    }
    pt.frame_us = std::max(pt.memory_us, pt.pipeline_us);
    pt.gsamples = pt.frame_us > 0 ? samples / (pt.frame_us * 1e3) : 0.0;
    pt.ns_per_sample = samples > 0 ? pt.frame_us * 1e3 / samples : 0.0;
    pt.bandwidth_gbs = pt.frame_us > 0 ? static_cast<double>(bytes) / (pt.frame_us * 1e3) : 0.0;
    pt.row_hits = requests ? static_cast<double>(hits) / static_cast<double>(requests) : 0.0;
    pt.latency_mean_ns = busiest->latency_mean * busiest->clock_ns;
    pt.latency_p99_ns = static_cast<double>(busiest->latency_p99) * busiest->clock_ns;
    pt.bound = pt.memory_us > 1.02 * pt.pipeline_us ? "memory" : "pipelines";
    out.points.push_back(pt);
  }
  return out;
}

}  // namespace

BurstStudyResult run_burst_study(const ref::Scene& scene, const BurstStudyOptions& options) {
  BurstCounter::check_cache_lines(options.cache_lines);  // before the volume is loaded
  const SceneVolume sv = load_scene_volume(scene);
  check_fixed_point(scene, sv, /*hls=*/true);
  const std::array<int, 3> dims = sv.volume.dims;
  for (int k = 0; k < 3; ++k)
    if (dims[static_cast<std::size_t>(k)] > static_cast<int>(kAxisMask) + 1)
      throw Error(scene.origin + ": burst study: the volume's extent " +
                  std::to_string(dims[static_cast<std::size_t>(k)]) + " along axis " +
                  std::to_string(k) + " exceeds 1024 voxels");
  const bittrue::VoxelMemory memory =
      bittrue::make_voxel_memory(scene.precision, sv.volume, sv.gradients);
  const ref::RenderInputs in =
      ref::make_render_inputs(scene, sv.volume, sv.gradients, scene.camera.pose);
  const bittrue::FrameSetup fs = bittrue::make_frame_setup(scene.precision, scene, in);
  const Stream stream = record_stream(scene, fs, memory);

  BurstStudyResult r;
  r.scene = scene.origin;
  r.dims = dims;
  r.voxel_bytes = stream.voxel_bytes;
  r.voxels_per_burst = r.memory.burst_bytes / stream.voxel_bytes;
  r.rays = stream.rays;
  r.samples = stream.cells.size();
  r.cache_lines = options.cache_lines;
  std::vector<std::unique_ptr<BurstLayout>> layouts;
  for (const auto& shape : rtl::layout::burst_shapes(r.voxels_per_burst))
    for (const RowMap rows : {RowMap::kLinear, RowMap::kBlocks})
      for (const BankGroupMap g : {BankGroupMap::kPlain, BankGroupMap::kSkewed})
        layouts.push_back(
            std::make_unique<BurstLayout>(dims, shape, r.voxels_per_burst, g, r.memory, rows));
  // One layout per worker: each counts the whole stream in order. The
  // counters are made here, where their errors can be thrown.
  std::vector<BurstCounter> counters;
  counters.reserve(layouts.size());
  for (const auto& layout : layouts) counters.emplace_back(*layout, options.cache_lines);
  // The channel run's layout records its fetches while it counts.
  std::size_t chosen = layouts.size();
  std::optional<Channels> channels;
  std::vector<rtl::layout::Fetch> fetches;
  if (!options.channel_layout.empty()) {
    for (std::size_t i = 0; i < layouts.size(); ++i)
      if (layouts[i]->name() == options.channel_layout) chosen = i;
    if (chosen == layouts.size()) {
      std::string names;
      for (const auto& layout : layouts) names += (names.empty() ? "" : ", ") + layout->name();
      throw Error("burst study: no layout " + options.channel_layout + " (the layouts: " + names +
                  ")");
    }
    channels = load_channels(options, *layouts[chosen]);
    counters[chosen].record(options.channel_reuse, &fetches);
  }
  r.layouts.resize(layouts.size());
  ref::parallel_for(
      static_cast<int>(layouts.size()),
      [&](int i) {
        const auto li = static_cast<std::size_t>(i);
        count(counters[li], stream.cells);
        r.layouts[li] = summarize(counters[li]);
      },
      scene.render.threads);
  if (channels) {
    r.channel_run =
        run_channels(counters[chosen], fetches, *channels, options, scene.render.threads);
    r.has_channel_run = true;
  }
  if (!options.json.empty()) write_burst_study_json(options.json, r);
  return r;
}

namespace {

void print_channel_run(std::ostream& os, const ChannelRunResult& c) {
  os << "\nchannel run  " << c.layout << ", " << c.reuse << " reuse, through the " << c.board
     << " board's four " << c.timing << " channels at " << fixed_text(c.memory_mhz, 0)
     << " MHz (FR-FCFS, queue " << c.queue_depth << ", open page, refresh); " << c.requests
     << " bursts; pipelines at " << fixed_text(c.core_mhz, 0) << " MHz, a sample a clock each\n"
     << "pipelines  frame us  G samples/s  ns/sample  pipelines us  memory us  GB/s   row hits  "
        "latency mean/p99 ns  REF  bound\n";
  for (const ChannelRunPoint& p : c.points) {
    auto col = [&os](const std::string& text, std::size_t width) {
      os << text << std::string(width > text.size() ? width - text.size() : 1, ' ');
    };
    col(std::to_string(p.pipelines), 11);
    col(fixed_text(p.frame_us, 1), 10);
    col(fixed_text(p.gsamples, 3), 13);
    col(fixed_text(p.ns_per_sample, 3), 11);
    col(fixed_text(p.pipeline_us, 1), 14);
    col(fixed_text(p.memory_us, 1), 11);
    col(fixed_text(p.bandwidth_gbs, 1), 7);
    col(fixed_text(100.0 * p.row_hits, 1) + "%", 10);
    col(fixed_text(p.latency_mean_ns, 0) + "/" + fixed_text(p.latency_p99_ns, 0), 21);
    col(std::to_string(p.refreshes), 5);
    os << p.bound << "\n";
  }
}

}  // namespace

void print_burst_study(std::ostream& os, const BurstStudyResult& r) {
  const char* axis = "xyz";
  os << "burst study  " << r.scene << "  volume " << r.dims[0] << "x" << r.dims[1] << "x"
     << r.dims[2] << ", " << r.voxel_bytes << "-byte voxels, " << r.voxels_per_burst << " per "
     << r.memory.burst_bytes << "-byte burst, " << rtl::layout::kBurstChannels << " channels at "
     << fixed_text(r.memory.clock_mhz, 0) << " MHz\n"
     << "stream       " << r.rays << " rays, " << r.samples << " samples ("
     << fixed_text(r.rays ? static_cast<double>(r.samples) / static_cast<double>(r.rays) : 0.0, 1)
     << " per ray); cache reuse: " << r.cache_lines << " lines per channel, direct-mapped\n"
     << "per reuse scheme: bursts/sample, busiest channel / mean, same bank group %, row hits %, "
        "G samples/s the busiest data bus allows\n";
  os << "layout                 ch";
  for (const Reuse reuse : rtl::layout::kAllReuse)
    os << " | " << rtl::layout::name(reuse)
       << std::string(37 - std::string(rtl::layout::name(reuse)).size(), ' ');
  os << "\n";
  std::size_t best = 0;
  for (std::size_t i = 0; i < r.layouts.size(); ++i)
    if (r.layouts[i].reuse[1].bound_gsamples > r.layouts[best].reuse[1].bound_gsamples) best = i;
  for (std::size_t i = 0; i < r.layouts.size(); ++i) {
    const BurstLayoutResult& l = r.layouts[i];
    std::string name = l.name;
    name.resize(22, ' ');
    os << name << " " << axis[l.channel_axes[0]] << axis[l.channel_axes[1]];
    for (const BurstReuseResult& x : l.reuse) {
      std::string cell = fixed_text(x.bursts_per_sample, 3) + " " +
                         fixed_text(x.busiest_channel_share, 2) + " " +
                         fixed_text(100.0 * x.same_group, 1) + "% " +
                         fixed_text(100.0 * x.row_hits, 1) + "% " + fixed_text(x.bound_gsamples, 2);
      cell.resize(37, ' ');
      os << " | " << cell;
    }
    os << (i == best ? " <- most samples/s with ray reuse" : "") << "\n";
  }
  if (r.has_channel_run) print_channel_run(os, r.channel_run);
}

void write_burst_study_json(const std::string& path, const BurstStudyResult& r) {
  nlohmann::json j;
  j["scene"] = r.scene;
  j["dims"] = r.dims;
  j["voxel_bytes"] = r.voxel_bytes;
  j["voxels_per_burst"] = r.voxels_per_burst;
  j["rays"] = r.rays;
  j["samples"] = r.samples;
  j["cache_lines_per_channel"] = r.cache_lines;
  j["channels"] = rtl::layout::kBurstChannels;
  j["memory"] = {{"burst_bytes", r.memory.burst_bytes},
                 {"clock_mhz", r.memory.clock_mhz},
                 {"burst_clocks", r.memory.burst_clocks},
                 {"tCCD_S", r.memory.tCCD_S},
                 {"tCCD_L", r.memory.tCCD_L},
                 {"bursts_per_row", r.memory.bursts_per_row()},
                 {"banks_per_group", r.memory.banks_per_group}};
  nlohmann::json layouts = nlohmann::json::array();
  for (const BurstLayoutResult& l : r.layouts) {
    nlohmann::json e{{"name", l.name}, {"brick", l.brick}, {"channel_axes", l.channel_axes}};
    for (std::size_t k = 0; k < l.reuse.size(); ++k) {
      const BurstReuseResult& x = l.reuse[k];
      e[rtl::layout::name(rtl::layout::kAllReuse[k])] = {
          {"bursts_per_sample", x.bursts_per_sample},
          {"busiest_channel_share", x.busiest_channel_share},
          {"same_bank_group", x.same_group},
          {"row_hits", x.row_hits},
          {"bound_gsamples_per_second", x.bound_gsamples}};
    }
    layouts.push_back(e);
  }
  j["layouts"] = layouts;
  if (r.has_channel_run) {
    const ChannelRunResult& c = r.channel_run;
    nlohmann::json points = nlohmann::json::array();
    for (const ChannelRunPoint& p : c.points)
      points.push_back({{"pipelines", p.pipelines},
                        {"frame_us", p.frame_us},
                        {"gsamples_per_second", p.gsamples},
                        {"ns_per_sample", p.ns_per_sample},
                        {"pipeline_us", p.pipeline_us},
                        {"memory_us", p.memory_us},
                        {"bandwidth_gbs", p.bandwidth_gbs},
                        {"row_hits", p.row_hits},
                        {"latency_mean_ns", p.latency_mean_ns},
                        {"latency_p99_ns", p.latency_p99_ns},
                        {"refreshes", p.refreshes},
                        {"bound", p.bound}});
    j["channel_run"] = {
        {"layout", c.layout},           {"reuse", c.reuse},           {"board", c.board},
        {"timing", c.timing},           {"memory_mhz", c.memory_mhz}, {"core_mhz", c.core_mhz},
        {"queue_depth", c.queue_depth}, {"requests", c.requests},     {"points", points}};
  }
  write_json_file(path, j);
}

}  // namespace voxcast::cosim
