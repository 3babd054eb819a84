#include "cosim/explore/burst_study.hpp"

#include <algorithm>
#include <cstddef>
#include <memory>
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
#include "rtl_model/pipeline/config.hpp"
#include "rtl_model/scene_config.hpp"

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
  r.layouts.resize(layouts.size());
  ref::parallel_for(
      static_cast<int>(layouts.size()),
      [&](int i) {
        const auto li = static_cast<std::size_t>(i);
        count(counters[li], stream.cells);
        r.layouts[li] = summarize(counters[li]);
      },
      scene.render.threads);
  if (!options.json.empty()) write_burst_study_json(options.json, r);
  return r;
}

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
  write_json_file(path, j);
}

}  // namespace voxcast::cosim
