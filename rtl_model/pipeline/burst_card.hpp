// The VIZARD II design on a DDR4 card (the Alveo U250 of issue 23;
// docs/sdram.md §10): N ray pipelines at the board's core clock, four DDR4
// channels at the memory clock, per channel a brick cache and two clocked
// asynchronous FIFOs between the domains.
//
//   per pipeline (core clock):
//     ray setup -> [ray slots] -> issue (address generator, cache look-up)
//       -> sample buffer (waits for the sample's bursts) -> interpolation ->
//       classification -> shading -> compositor -> output
//   shared (core clock): per channel a brick cache (burst_layout's
//     4x2x2-skewed-blocks bursts, brick_cache.hpp), miss registers and a miss
//     queue; one request per channel and core clock crosses to the memory
//     clock (burst_channel.hpp), one returning burst per channel and core
//     clock crosses back.
//
// Every arithmetic result comes from the hls units, called in hls::cast_ray's
// order as RayPipeline calls them (ray_setup, address_generator, gather +
// interpolation_processor on a bank view of the sample's eight corners,
// classify_entry, segment_opacity, reflect, shade, composite, ert_reached,
// mip_update / mip_pixel, output, and the space-leaping unit's
// sample_block_empty / leap_run), so the image equals the hls engine's bit
// for bit; the units behind interpolation are the very functions RayPipeline
// runs (sample_datapath.hpp). The corners come from the bursts: a hit copies them out of the
// cache line, a miss from the returning burst, whose voxels are the memory
// image's at the burst's address (brick_image.hpp).
//
// Timing, per core clock:
//   - Pixel i of the traversal belongs to pipeline i mod N. A pipeline sets up
//     one pixel every ray_setup_interval clocks; a ray that enters the volume
//     waits for a free ray slot and is ready ray_setup clocks later.
//   - Issue: one sample per pipeline and clock, from the oldest ready ray to
//     its end (or its early termination), if the sample buffer has room and
//     every channel its misses need has room in its miss queue and a free miss
//     register. The look-up of the sample's bursts (layout::cell_bursts, one
//     to eight) happens at issue; each is a hit (data copied), a pending hit
//     (the sample waits for the burst already requested) or a miss (the line
//     is replaced, a miss register and a request allocated). The pipelines
//     take their turns at the shared caches in a rotating order.
//   - The sample buffer's head goes to interpolation once its bursts are in
//     and the address generator's latency has passed; interpolation,
//     classification and shading are one pipeline of their summed latency with
//     one sample per clock; the compositor takes one per clock in order.
//   - Samples of a ray ended by early ray termination are dropped at
//     interpolation or at the compositor; its slot is freed when none is left.
// Not modelled: the caches' port count (any number of look-ups per clock),
// the data path's width from the return FIFO into the lines (one burst per
// channel and core clock), write traffic (the volume is loaded before the
// frame), and the PCIe upload.
//
// The frame ends when every pixel is written and every FIFO, miss register
// and controller is empty; no progress for deadlock_cycles core clocks is an
// error, as is anything left at the end.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "hls/vizard2_top.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/error.hpp"
#include "refmodel/render/quant_image.hpp"
#include "rtl_model/layout/burst_layout.hpp"
#include "rtl_model/layout/vizard2_layout.hpp"
#include "rtl_model/pipeline/brick_cache.hpp"
#include "rtl_model/pipeline/brick_image.hpp"
#include "rtl_model/pipeline/burst_channel.hpp"
#include "rtl_model/pipeline/burst_config.hpp"
#include "rtl_model/pipeline/config.hpp"
#include "rtl_model/pipeline/ray_pipeline.hpp"
#include "rtl_model/pipeline/sample_datapath.hpp"
#include "rtl_model/pipeline/stats.hpp"
#include "rtl_model/sim/fifo.hpp"

namespace voxcast::rtl::pipeline {

template <class P>
class BurstCard {
 public:
  using G = hls::GeometryParams<P>;
  using C = hls::CompositorParams<P>;
  using Voxel = hls::VoxelWordFx<P>;

  // `frame`, `memory` and `layout` must outlive the card. Throws
  // voxcast::Error for an invalid configuration or an unknown policy.
  BurstCard(const hls::FrameState<P>& frame, const bittrue::VoxelMemory& memory,
            const layout::BurstLayout& layout, const PipelineConfig& config,
            const BurstCardConfig& card, const std::string& scheduler, const std::string& refresh)
      : f_(frame),
        config_(RayPipeline<P>::elaborated(config, frame)),
        card_(card),
        dims_(memory.dims),
        corner_of_(memory.dims),
        voxels_(memory),
        layout_(layout),
        image_map_(layout, memory.dims),
        mip_(frame.mode == hls::FrameMode::Mip),
        shaded_(frame.mode == hls::FrameMode::Shaded),
        leap_(frame.leap.enabled && frame.mode != hls::FrameMode::Mip) {
    at_least(card.pipelines, "pipelines");
    at_least(config.ray_slots, "ray_slots");
    at_least(config.sample_buffer, "sample_buffer");
    at_least(config.output_depth, "output_depth");
    at_least(config.fifo_depth, "fifo_depth");
    at_least(config.latency.ray_setup_interval, "latency.ray_setup_interval");
    at_least(card.mshrs, "mshrs");
    at_least(card.miss_queue, "miss_queue");
    if (config.issue != IssuePolicy::kOldest || config.issue_burst != 0)
      throw Error(
          "DDR4 card: the pipelines issue from the oldest ray to its end (rtl.issue = "
          "\"oldest\", rtl.issue_burst = 0)");
    const auto& b = layout.brick();
    brick_ = b;
    voxels_per_burst_ = b[0] * b[1] * b[2];
    datapath_latency_ =
        config_.latency.interpolation + config_.latency.classification + config_.latency.shading;
    for (int c = 0; c < layout::kBurstChannels; ++c) {
      channels_.push_back(std::make_unique<BurstChannel>(
          c, config.dimm, scheduler, config.scheduler_params, refresh, config.controller, card));
      caches_.emplace_back(card.cache_lines);
      line_data_.emplace_back(static_cast<std::size_t>(card.cache_lines) *
                              static_cast<std::size_t>(voxels_per_burst_));
      misses_.emplace_back("channel" + std::to_string(c) + ".misses",
                           static_cast<std::size_t>(card.miss_queue));
      mshr_[static_cast<std::size_t>(c)].resize(static_cast<std::size_t>(card.mshrs));
      for (int m = card.mshrs; m-- > 0;)
        free_mshr_[static_cast<std::size_t>(c)].push_back(static_cast<std::uint32_t>(m));
    }
    pipes_.resize(static_cast<std::size_t>(card.pipelines));
    for (Pipe& p : pipes_) {
      p.slots.resize(static_cast<std::size_t>(config.ray_slots));
      for (int i = 0; i < config.ray_slots; ++i) p.free_slots.push_back(i);
      p.buf.resize(static_cast<std::size_t>(config.sample_buffer));
    }
  }

  // Runs one frame of width x height pixels. Throws voxcast::Error on a
  // deadlock or undrained state. Call once.
  ref::QuantImage run(int width, int height, RtlStats& stats) {
    const auto order = pixel_order(width, height, config_.traversal, config_.tile);
    for (std::size_t i = 0; i < order.size(); ++i)
      pipes_[i % pipes_.size()].pixels.push_back(order[i]);
    ref::QuantImage image(width, height, P::out_bits);
    image_ = &image;
    stats_ = RtlStats{};
    stats_.rays = order.size();
    const std::int64_t core_ps = card_.core_period_ps;
    const std::int64_t mem_ps = config_.dimm.clock.period_ps();
    if (core_ps < 1 || mem_ps < 1) throw Error("DDR4 card: clock periods must be positive");
    // The two clocks' edges in time order; at a common instant the memory
    // edge first (the core then sees what the memory side did at that edge
    // only through the synchronisers, so the order changes nothing else).
    std::int64_t t_core = 0, t_mem = 0;
    Cycle core = 0, mem = 0, last_progress = 0;
    std::uint64_t last_events = 0;
    while (true) {
      if (t_mem <= t_core) {
        for (auto& ch : channels_) ch->memory_clock(mem);
        ++mem;
        t_mem += mem_ps;
        continue;
      }
      core_clock(core);
      ++core;
      t_core += core_ps;
      if (written_ == order.size() && quiet()) break;
      if (events_ != last_events) {
        last_events = events_;
        last_progress = core;
      } else if (core - last_progress >= config_.deadlock_cycles) {
        deadlock(core);
      }
    }
    stats_.cycles = core;
    stats_.evaluated_cycles = core;
    stats_.clock_mhz = 1e6 / static_cast<double>(core_ps);
    stats_.card.memory_cycles = mem;
    expect_drained();
    collect(core_ps, mem_ps);
    stats = stats_;
    image_ = nullptr;
    return image;
  }

 private:
  // ---- State --------------------------------------------------------------------------------
  struct Slot {
    int x = 0, y = 0;
    Cycle ready_at = 0;
    std::uint64_t n = 0, issued = 0, composited = 0;
    std::uint64_t next = 0;  // the next sample's index: issued + leapt over
    bool issue_done = false;
    int outstanding = 0;  // samples issued and not yet composited or dropped
    bool finished = false;
    bool in_issue = false;
    bool free = true;
    typename G::pos_t p[3];
    typename G::step_t s[3];
    hls::Accumulator<P> acc;
    typename C::value_t peak = 0;
    hls::SegmentWeights<P> weights;
    hls::Sample<P> front;  // §4a: the previous sample at classification
  };
  // A burst a sample needs: its channel and index there.
  struct BurstKey {
    int channel = 0;
    std::uint64_t index = 0;
  };
  static constexpr std::int8_t kOutside = -1;  // a corner outside the volume (reads zero)
  struct Entry {                               // one sample between issue and interpolation
    int slot = 0;
    std::uint64_t k = 0, pos = 0;
    Cycle ready = 0;  // the address generator's latency
    int missing = 0;  // bursts not yet in
    hls::BankAccess<P> access;
    std::array<int, 3> i0{};
    int bursts = 0;
    std::array<BurstKey, 8> burst{};
    std::array<std::int8_t, 8> corner_burst{};  // corner o (dx | dy << 1 | dz << 2): its burst
    Voxel corner[8];                            // by offset from i0
  };
  struct Staged {  // interpolated, classified and shaded, on its way to the compositor
    Cycle ready = 0;
    int slot = 0;
    std::uint64_t k = 0, pos = 0;
    typename C::value_t value = 0;  // MIP
    typename C::alpha_t alpha = 0;
    hls::ShadedColor<P> c;
  };
  struct Pixel {
    int x = 0, y = 0;
    hls::OutputPixel<P> px;
  };
  struct MissPixel {
    Cycle ready = 0;
    int x = 0, y = 0;
  };
  struct Pipe {
    std::vector<std::pair<int, int>> pixels;
    std::size_t next_pixel = 0;
    std::size_t setup_for = static_cast<std::size_t>(-1);
    hls::RaySetup<P> setup_ray;
    Cycle setup_next = 0;
    std::vector<Slot> slots;
    std::deque<int> free_slots, issue_q, leapt;
    std::vector<Entry> buf;
    std::size_t head = 0, count = 0;
    std::deque<Staged> datapath;
    std::deque<MissPixel> miss;
    std::deque<Pixel> out;
    std::uint64_t issues = 0;  // samples issued and leaps: the clocks its issue stage was busy
  };
  struct Mshr {
    layout::BurstAddress address;  // the burst requested
    std::uint64_t index = 0;
    std::size_t line = 0;
    std::vector<std::pair<int, std::size_t>> waiters;  // (pipeline, sample buffer entry)
  };

  static void at_least(std::int64_t v, const char* what) {
    if (v < 1) throw Error(std::string("DDR4 card: ") + what + " must be at least 1");
  }

  // ---- One core clock -----------------------------------------------------------------------
  void core_clock(Cycle now) {
    for (auto& ch : channels_) ch->core_clock();
    for (std::size_t c = 0; c < channels_.size(); ++c) take_return(c);
    // The pipelines take turns at the shared caches, rotating each clock.
    const std::size_t n = pipes_.size();
    const std::size_t first = static_cast<std::size_t>(now) % n;
    for (std::size_t j = 0; j < n; ++j) {
      const std::size_t p = first + j < n ? first + j : first + j - n;
      Pipe& pipe = pipes_[p];
      write_output(pipe);
      composite(pipe, now);
      interpolate(pipe, now);
      issue(static_cast<int>(p), pipe, now);
      setup(pipe, now);
    }
    for (std::size_t c = 0; c < channels_.size(); ++c) send_miss(c);
  }

  // ---- Memory side --------------------------------------------------------------------------
  void send_miss(std::size_t c) {
    if (!misses_[c].valid() || !channels_[c]->can_send()) return;
    const std::uint32_t id = misses_[c].pop();
    const layout::BurstAddress& a = mshr_[c][id].address;
    BurstRequest r;
    r.mshr = id;
    r.address.bank =
        static_cast<std::uint32_t>(a.bank_group) * config_.dimm.geometry.banks_per_group() +
        static_cast<std::uint32_t>(a.bank);
    r.address.row = a.row;
    r.address.column = a.column;
    channels_[c]->send(r);
    ++stats_.card.bursts[c];
    ++events_;
  }

  // A returning burst: its voxels from the memory image at its address, into
  // its line (if the line still waits for it) and every waiting sample.
  void take_return(std::size_t c) {
    if (!channels_[c]->has_return()) return;
    const std::uint32_t id = channels_[c]->take_return().mshr;
    Mshr& m = mshr_[c][id];
    std::vector<Voxel>& data = scratch_;
    data.resize(static_cast<std::size_t>(voxels_per_burst_));
    read_burst(static_cast<int>(c), m.index, data.data());
    BrickLine& line = caches_[c].line(m.line);
    if (line.tag == m.index + 1 && line.pending && line.mshr == id) {
      std::copy(data.begin(), data.end(), line_data_[c].begin() + line_offset(m.line));
      line.pending = false;
    }
    for (const auto& [p, e] : m.waiters) {
      Entry& entry = pipes_[static_cast<std::size_t>(p)].buf[e];
      fill(entry, burst_number(entry, static_cast<int>(c), m.index), data.data());
      --entry.missing;
    }
    m.waiters.clear();
    free_mshr_[c].push_back(id);
    ++events_;
  }

  // The memory image: the voxels of the brick the layout put in burst `index`
  // of `channel`, x fastest within the brick.
  void read_burst(int channel, std::uint64_t index, Voxel* out) const {
    const std::array<int, 3>& o = image_map_.origin(channel, index);
    int k = 0;
    for (int z = 0; z < brick_[2]; ++z)
      for (int y = 0; y < brick_[1]; ++y)
        for (int x = 0; x < brick_[0]; ++x)
          out[k++] = voxel_or_zero({o[0] + x, o[1] + y, o[2] + z});
  }

  Voxel voxel_or_zero(const std::array<int, 3>& v) const {
    for (std::size_t k = 0; k < 3; ++k)
      if (v[k] >= dims_[k]) return zero_voxel();
    return voxels_.voxel(v[0], v[1], v[2]);
  }
  static Voxel zero_voxel() {
    Voxel v;
    v.value = 0;
    for (auto& g : v.g) g = 0;
    return v;
  }

  std::size_t line_offset(std::size_t line) const {
    return line * static_cast<std::size_t>(voxels_per_burst_);
  }
  static int burst_number(const Entry& e, int channel, std::uint64_t index) {
    for (int j = 0; j < e.bursts; ++j)
      if (e.burst[static_cast<std::size_t>(j)].channel == channel &&
          e.burst[static_cast<std::size_t>(j)].index == index)
        return j;
    throw Error("DDR4 card: a burst returned to a sample that did not ask for it");
  }

  // The corners of `e` held by its burst j, from the burst's voxels.
  void fill(Entry& e, int j, const Voxel* data) const {
    for (int o = 0; o < 8; ++o) {
      if (e.corner_burst[static_cast<std::size_t>(o)] != j) continue;
      const int x = e.i0[0] + (o & 1), y = e.i0[1] + ((o >> 1) & 1), z = e.i0[2] + (o >> 2);
      const int local = (x & (brick_[0] - 1)) +
                        brick_[0] * ((y & (brick_[1] - 1)) + brick_[1] * (z & (brick_[2] - 1)));
      e.corner[o] = data[local];
    }
  }

  // ---- Pipeline stages, from the output back --------------------------------------------------
  void write_output(Pipe& p) {
    if (p.out.empty()) return;
    const Pixel px = p.out.front();
    p.out.pop_front();
    auto& dst = image_->at(px.x, px.y);
    for (std::size_t c = 0; c < 4; ++c)
      dst[c] = static_cast<std::uint32_t>(px.px.ch[c].to_uint64());
    ++written_;
    ++events_;
  }

  bool out_ready(const Pipe& p) const {
    return p.out.size() < static_cast<std::size_t>(config_.output_depth);
  }

  void composite(Pipe& p, Cycle now) {
    bool pushed = false;
    if (!p.datapath.empty() && p.datapath.front().ready <= now) {
      const Staged e = p.datapath.front();
      Slot& s = p.slots[static_cast<std::size_t>(e.slot)];
      if (s.finished) {  // after early ray termination
        p.datapath.pop_front();
        ++events_;
        drop(p, e.slot);
      } else if (!out_ready(p)) {
        ++stats_.stalls.composite_blocked;
      } else {
        if (e.k != s.composited) order_error(e.slot, e.k, s.composited);
        ++s.composited;
        ++stats_.samples;
        bool done = s.issue_done && s.composited == s.issued;
        if (composite_sample<P>(f_, mip_, s.acc, s.peak, e.value, e.c, e.alpha)) {
          count_early_end(stats_, s.n, s.next, s.issued, e.pos, e.k);
          done = true;
        }
        p.datapath.pop_front();
        ++events_;
        --s.outstanding;
        if (done) {
          p.out.push_back(Pixel{s.x, s.y, hls::output<P>(ray_result<P>(f_, mip_, s.acc, s.peak))});
          pushed = true;
          s.finished = true;
        }
        try_free(p, e.slot);
      }
    }
    // A ray whose last samples were leapt over after the others composited.
    if (!pushed && !p.leapt.empty() && out_ready(p)) {
      const int slot = p.leapt.front();
      p.leapt.pop_front();
      Slot& s = p.slots[static_cast<std::size_t>(slot)];
      p.out.push_back(Pixel{s.x, s.y, hls::output<P>(s.acc)});
      s.finished = true;
      pushed = true;
      ++events_;
      try_free(p, slot);
    }
    // The background pixels of missed rays share the output port.
    if (!pushed && !p.miss.empty() && p.miss.front().ready <= now && out_ready(p)) {
      const MissPixel m = p.miss.front();
      p.miss.pop_front();
      p.out.push_back(Pixel{m.x, m.y, hls::output<P>(hls::Accumulator<P>{})});
      ++events_;
    }
  }

  // Interpolation, classification and shading of the buffer's head, in the
  // order of RayPipeline's stages (one sample per clock through their summed
  // latency).
  void interpolate(Pipe& p, Cycle now) {
    if (p.count == 0) return;
    Entry& e = p.buf[p.head];
    if (e.missing > 0 || e.ready > now) {
      ++stats_.stalls.interp_wait_memory;
      return;
    }
    Slot& s = p.slots[static_cast<std::size_t>(e.slot)];
    if (s.finished) {  // after early ray termination
      const int slot = e.slot;
      advance(p);
      drop(p, slot);
      return;
    }
    if (p.datapath.size() >= static_cast<std::size_t>(datapath_latency_ + config_.fifo_depth)) {
      ++stats_.stalls.interp_blocked;
      return;
    }
    // Bank b of the hls parity interleave holds the corner at offset b ^ parity.
    struct CornerBanks {
      const Voxel* corner;
      unsigned parity;
      Voxel read(int b, const typename hls::InterpolationParams<P>::word_addr_t&) const {
        return corner[(static_cast<unsigned>(b) ^ parity) & 7u];
      }
    };
    const CornerBanks view{e.corner, e.access.parity};
    Voxel corner[8];
    hls::gather<P>(view, e.access, corner);
    const hls::Sample<P> sample = hls::interpolation_processor<P>(corner, e.access.fq);
    Staged out;
    out.ready = now + datapath_latency_;
    out.slot = e.slot;
    out.k = e.k;
    out.pos = e.pos;
    out.value = sample.value;
    out.alpha = 0;
    if (!mip_) {
      hls::Sample<P> lit;
      const hls::ClassEntry<P> c =
          classify_sample<P>(f_, sample, e.pos, s.n, s.weights, s.front, lit);
      out.alpha = c.alpha;
      if (c.alpha != 0) out.c = shade_sample<P>(f_, c, lit, shaded_);
    }
    p.datapath.push_back(out);
    advance(p);
  }

  void advance(Pipe& p) {
    p.head = p.head + 1 == p.buf.size() ? 0 : p.head + 1;
    --p.count;
    ++events_;
  }

  void issue(int pi, Pipe& p, Cycle now) {
    while (!p.issue_q.empty() && p.slots[static_cast<std::size_t>(p.issue_q.front())].finished) {
      const int i = p.issue_q.front();
      p.issue_q.pop_front();
      p.slots[static_cast<std::size_t>(i)].in_issue = false;
      ++events_;
      try_free(p, i);
    }
    if (p.issue_q.empty()) {
      ++(p.next_pixel == p.pixels.size() ? stats_.stalls.issue_idle : stats_.stalls.issue_no_ray);
      return;
    }
    const int i = p.issue_q.front();
    Slot& s = p.slots[static_cast<std::size_t>(i)];
    if (s.ready_at > now) {
      ++stats_.stalls.issue_no_ray;
      return;
    }
    if (leap_ && try_leap(p, i, s, now)) return;
    if (p.count == p.buf.size()) {
      ++stats_.stalls.issue_buffer_full;
      return;
    }
    // The sample's bank access (hls address generator), its cell and the
    // bursts holding the cell.
    const hls::BankAccess<P> access = hls::address_generator<P>(f_.geometry, s.p);
    const std::array<int, 3> i0 = corner_of_.corner<P>(access);
    std::array<layout::BurstAddress, 8> bursts;
    const int nb = layout_.cell_bursts(i0, bursts);
    // The look-ups in order: a burst whose line an earlier burst of the same
    // sample replaces misses too (the line then holds the other tag).
    std::array<CacheOutcome, 8> outcome{};
    std::array<std::size_t, 8> line{};
    std::array<int, layout::kBurstChannels> need{};
    for (std::size_t j = 0; j < static_cast<std::size_t>(nb); ++j) {
      const layout::BurstAddress& b = bursts[j];
      const BrickCache& cache = caches_[static_cast<std::size_t>(b.channel)];
      line[j] = cache.line_of(b.index);
      outcome[j] = cache.probe(b.index);
      for (std::size_t q = 0; q < j; ++q)
        if (bursts[q].channel == b.channel && line[q] == line[j] &&
            outcome[q] == CacheOutcome::kMiss)
          outcome[j] = CacheOutcome::kMiss;
      if (outcome[j] == CacheOutcome::kMiss) ++need[static_cast<std::size_t>(b.channel)];
    }
    for (std::size_t c = 0; c < need.size(); ++c)
      if (need[c] > 0 &&
          (misses_[c].depth() - misses_[c].size() < static_cast<std::size_t>(need[c]) ||
           free_mshr_[c].size() < static_cast<std::size_t>(need[c]))) {
        ++stats_.stalls.issue_memory_full;
        return;
      }
    std::size_t tail = p.head + p.count;
    if (tail >= p.buf.size()) tail -= p.buf.size();
    Entry& e = p.buf[tail];
    e.slot = i;
    e.k = s.issued;
    e.pos = s.next;
    e.ready = now + config_.latency.address + config_.latency.leap_lookup;
    e.missing = 0;
    e.access = access;
    e.i0 = i0;
    e.bursts = nb;
    for (int j = 0; j < nb; ++j)
      e.burst[static_cast<std::size_t>(j)] = {bursts[static_cast<std::size_t>(j)].channel,
                                              bursts[static_cast<std::size_t>(j)].index};
    map_corners(e);
    ++p.count;
    for (int j = 0; j < nb; ++j)
      look_up(pi, tail, e, j, bursts[static_cast<std::size_t>(j)],
              outcome[static_cast<std::size_t>(j)]);
    ++events_;
    ++p.issues;
    ++s.outstanding;
    ++s.issued;
    ++stats_.samples_issued;
    ++s.next;
    hls::step_position<P>(s.p, s.s);
    if (s.next == s.n) end_issue(p, i, s);
  }

  // Which of the entry's bursts holds each corner (kOutside: a corner beyond
  // a one-voxel extent, read as zero like the hls design's padding).
  void map_corners(Entry& e) const {
    for (int o = 0; o < 8; ++o) {
      const std::array<int, 3> v{e.i0[0] + (o & 1), e.i0[1] + ((o >> 1) & 1), e.i0[2] + (o >> 2)};
      std::int8_t j = kOutside;
      if (v[0] < dims_[0] && v[1] < dims_[1] && v[2] < dims_[2]) {
        const layout::BurstAddress a = layout_.burst_of(v);
        j = static_cast<std::int8_t>(burst_number(e, a.channel, a.index));
      } else {
        e.corner[o] = zero_voxel();
      }
      e.corner_burst[static_cast<std::size_t>(o)] = j;
    }
  }

  void look_up(int pi, std::size_t entry, Entry& e, int j, const layout::BurstAddress& b,
               CacheOutcome o) {
    const auto c = static_cast<std::size_t>(b.channel);
    BrickCache& cache = caches_[c];
    cache.count(o);
    const std::size_t li = cache.line_of(b.index);
    BrickLine& line = cache.line(li);
    if (o == CacheOutcome::kHit) {
      fill(e, j, &line_data_[c][line_offset(li)]);
      return;
    }
    ++e.missing;
    if (o == CacheOutcome::kPendingHit) {
      mshr_[c][line.mshr].waiters.emplace_back(pi, entry);
      return;
    }
    const std::uint32_t id = free_mshr_[c].back();
    free_mshr_[c].pop_back();
    Mshr& m = mshr_[c][id];
    m.index = b.index;
    m.line = li;
    m.waiters.assign(1, {pi, entry});
    m.address = b;
    line.tag = b.index + 1;
    line.pending = true;
    line.mshr = id;
    misses_[c].push(id);
  }

  // Space leaping, as RayPipeline::try_leap: if the ray's next sample lies in
  // an empty block, leap to the first sample after it (hls::leap_run); the
  // ray's issue waits latency.leap clocks. True if it leapt.
  bool try_leap(Pipe& p, int i, Slot& s, Cycle now) {
    typename hls::LeapParams<P>::bcoord_t b[3];
    if (!hls::sample_block_empty<P>(f_.geometry, f_.leap, f_.minmax, s.p, b)) return false;
    const std::uint64_t run = hls::leap_run<P>(f_.geometry, f_.leap, s.p, s.s, s.n - s.next, b);
    hls::step_position<P>(s.p, s.s);
    s.next += run;
    s.ready_at = now + static_cast<Cycle>(std::max(config_.latency.leap, 1));
    stats_.samples_skipped += run;
    ++stats_.leaps;
    ++p.issues;
    ++events_;
    if (s.next == s.n) end_issue(p, i, s);
    return true;
  }

  // Ray i (the issue queue's front) has no sample left to issue.
  void end_issue(Pipe& p, int i, Slot& s) {
    p.issue_q.pop_front();
    s.in_issue = false;
    s.issue_done = true;
    if (s.outstanding == 0 && !s.finished) p.leapt.push_back(i);
  }

  void setup(Pipe& p, Cycle now) {
    if (p.next_pixel == p.pixels.size() || now < p.setup_next) return;
    const auto [x, y] = p.pixels[p.next_pixel];
    if (p.setup_for != p.next_pixel) {
      p.setup_ray = hls::ray_setup<P>(f_.geometry, f_.rsqrt.seed, x, y);
      p.setup_for = p.next_pixel;
    }
    const hls::RaySetup<P>& ray = p.setup_ray;
    if (ray.hit && p.free_slots.empty()) {
      ++stats_.stalls.setup_no_slot;
      return;
    }
    const std::size_t miss_depth =
        static_cast<std::size_t>(config_.latency.ray_setup + config_.fifo_depth);
    if (!ray.hit && p.miss.size() >= miss_depth) return;
    const Cycle ready = now + config_.latency.ray_setup;
    if (ray.hit) {
      const int i = p.free_slots.front();
      p.free_slots.pop_front();
      Slot& s = p.slots[static_cast<std::size_t>(i)];
      s = Slot{};
      s.x = x;
      s.y = y;
      s.ready_at = ready;
      s.n = ray.n.to_uint64();
      s.weights =
          hls::segment_weights<P>(f_.segments, ray, hls::pixel_jitter<P>(f_.geometry, x, y));
      s.free = false;
      s.in_issue = true;
      for (int k = 0; k < 3; ++k) {
        s.p[k] = ray.p0[k];
        s.s[k] = ray.s[k];
      }
      p.issue_q.push_back(i);
      ++stats_.rays_hit;
    } else {
      p.miss.push_back(MissPixel{ready, x, y});
    }
    ++events_;
    ++p.next_pixel;
    p.setup_next = now + config_.latency.ray_setup_interval;
  }

  void drop(Pipe& p, int slot) {
    --p.slots[static_cast<std::size_t>(slot)].outstanding;
    ++stats_.samples_discarded;
    try_free(p, slot);
  }

  void try_free(Pipe& p, int slot) {
    Slot& s = p.slots[static_cast<std::size_t>(slot)];
    if (s.free || !s.finished || s.outstanding != 0 || s.in_issue) return;
    s.free = true;
    p.free_slots.push_back(slot);
    ++events_;
  }

  // ---- The end of the frame -----------------------------------------------------------------
  bool quiet() const {
    for (const Pipe& p : pipes_)
      if (p.count != 0 || !p.datapath.empty() || !p.out.empty() || !p.miss.empty() ||
          !p.leapt.empty() || p.free_slots.size() != p.slots.size())
        return false;
    for (std::size_t c = 0; c < channels_.size(); ++c)
      if (!misses_[c].empty() || free_mshr_[c].size() != mshr_[c].size() || !channels_[c]->idle())
        return false;
    return true;
  }

  [[noreturn]] void order_error(int slot, std::uint64_t got, std::uint64_t expected) const {
    std::ostringstream os;
    os << "DDR4 card: the compositor got sample " << got << " of ray slot " << slot
       << ", expected sample " << expected;
    throw Error(os.str());
  }

  std::string state() const {
    std::ostringstream os;
    os << "pixels written " << written_ << "/" << stats_.rays;
    for (std::size_t i = 0; i < pipes_.size(); ++i) {
      const Pipe& p = pipes_[i];
      os << "; pipeline " << i << ": set up " << p.next_pixel << "/" << p.pixels.size()
         << ", sample buffer " << p.count << "/" << p.buf.size();
      if (p.count > 0) os << " (head waits for " << p.buf[p.head].missing << " bursts)";
      os << ", datapath " << p.datapath.size() << ", free slots " << p.free_slots.size() << "/"
         << p.slots.size();
    }
    for (std::size_t c = 0; c < channels_.size(); ++c)
      os << "; " << channels_[c]->state() << ", " << misses_[c].size() << " misses queued, "
         << mshr_[c].size() - free_mshr_[c].size() << " miss registers busy";
    return os.str();
  }

  [[noreturn]] void deadlock(Cycle now) const {
    std::ostringstream os;
    os << "DDR4 card: deadlock, no progress for " << config_.deadlock_cycles
       << " core cycles at cycle " << now << ": " << state();
    throw Error(os.str());
  }

  void expect_drained() const {
    try {
      for (const auto& ch : channels_) ch->expect_drained();
      for (const auto& m : misses_) m.expect_drained();
      if (!quiet()) throw Error("state left");
    } catch (const Error& e) {
      throw Error(std::string("DDR4 card: undrained at the end of the frame: ") + e.what() + "; " +
                  state());
    }
  }

  void collect(std::int64_t core_ps, std::int64_t mem_ps) {
    CardStats& k = stats_.card;
    k.pipelines = static_cast<int>(pipes_.size());
    k.memory_mhz = 1e6 / static_cast<double>(mem_ps);
    k.burst_clocks = config_.dimm.burst_length / 2;  // DDR: two beats per clock
    k.burst_bytes =
        static_cast<int>(config_.dimm.geometry.bytes_per_beat()) * config_.dimm.burst_length;
    k.cache_lines = card_.cache_lines;
    for (const Pipe& p : pipes_)
      k.busiest_pipeline_issues = std::max(k.busiest_pipeline_issues, p.issues);
    for (std::size_t c = 0; c < channels_.size(); ++c) {
      const CacheStats& cs = caches_[c].stats();
      k.cache_hits += cs.hits;
      k.cache_pending_hits += cs.pending_hits;
      k.cache_misses += cs.misses;
      stats_.dimms[c].controller = channels_[c]->controller().stats();
      stats_.dimms[c].dimm = channels_[c]->controller().dimm().stats();
    }
    // The data buses' peak: a burst of burst_bytes per burst_clocks memory
    // clocks on each channel, in bytes per core clock.
    stats_.bus_bytes_per_cycle = static_cast<double>(layout::kBurstChannels * k.burst_bytes) /
                                 k.burst_clocks * static_cast<double>(core_ps) /
                                 static_cast<double>(mem_ps);
  }

  // ---- Members --------------------------------------------------------------------------------
  const hls::FrameState<P>& f_;
  PipelineConfig config_;
  BurstCardConfig card_;
  std::array<int, 3> dims_;
  layout::Vizard2Layout corner_of_;  // the hls bank access's lowest corner (address translation)
  layout::Vizard2Memory<P> voxels_;  // the host's voxel words, read through the memory image
  const layout::BurstLayout& layout_;
  BrickImage image_map_;
  std::array<int, 3> brick_{};
  int voxels_per_burst_ = 0;
  int datapath_latency_ = 0;
  bool mip_, shaded_, leap_;

  std::vector<Pipe> pipes_;
  std::vector<std::unique_ptr<BurstChannel>> channels_;
  std::vector<BrickCache> caches_;
  std::vector<std::vector<Voxel>> line_data_;     // per channel, the lines' voxels
  std::vector<sim::Fifo<std::uint32_t>> misses_;  // per channel, miss registers to request
  std::array<std::vector<Mshr>, layout::kBurstChannels> mshr_;
  std::array<std::vector<std::uint32_t>, layout::kBurstChannels> free_mshr_;
  std::vector<Voxel> scratch_;  // a returning burst's voxels
  std::size_t written_ = 0;
  std::uint64_t events_ = 0;
  ref::QuantImage* image_ = nullptr;
  RtlStats stats_;
};

}  // namespace voxcast::rtl::pipeline
