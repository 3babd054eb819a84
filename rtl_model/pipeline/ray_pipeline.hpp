// The VIZARD II ray-casting pipeline as a clocked model at the core clock
// (= the SDRAM clock, 100 MHz on the card):
//
//   ray setup -> [ray slots] -> address generator -> 4 request FIFOs ->
//   4 DIMM controllers -> sample buffer (a sample's four words matched back)
//   -> interpolation -> classification -> shading -> compositor -> output
//
// Every arithmetic result comes from the hls units (hls::ray_setup,
// hls::address_generator, hls::gather + hls::interpolation_processor on a bank
// view of the four DIMM words, hls::classify, hls::reflect, hls::shade,
// hls::composite, hls::ert_reached, hls::mip_update / mip_pixel, hls::output),
// called in the order hls::cast_ray calls them, so the image equals the hls
// engine's bit for bit. Control, ordering and timing are this model's:
//   - Ray setup takes the pixels in traversal order, one every
//     ray_setup_interval clocks; a ray that enters the volume waits for a free
//     ray slot and is ready `ray_setup` clocks later. A ray that misses takes
//     no slot and leaves a background pixel after the same latency.
//   - The address generator issues one sample per clock, one request to each
//     DIMM, if the sample buffer and all four request FIFOs have room. It
//     takes the sample from the oldest ready ray (issue_burst samples at a
//     time, or the whole ray), or with IssuePolicy::kRowHit from the oldest
//     ready ray whose next sample hits the rows it last requested.
//   - The controllers (rtl_model/sdram) serve the requests; each completion
//     fills its sample's word by the request id (any order). The interpolation
//     stage takes samples in issue order once all four words are in.
//   - Samples of a ray that has ended by early ray termination are dropped at
//     interpolation or at the compositor; the ray's slot is freed when none of
//     its samples is left in flight.
//   - render.partial_segments (docs/pipeline.md §7a): the classification
//     stage's entry takes the segment-opacity unit's weighted alpha for a
//     ray's first and last samples (hls::segment_opacity, the weights from
//     hls::segment_weights at set-up); its clocks overlap the shading stage.
//   - render.classification = "preintegrated" (§4a): the classification
//     stage reads the pre-integration table at (the slot's previous value,
//     the sample's value) instead, one clock deeper (hls::preintegration_depth).
//   - Each unit is a pipeline of its latency with one result per clock; the
//     FIFO after it has latency + fifo_depth entries (valid/ready).
// A frame ends when the last pixel is written and every sample still in
// flight behind an early-terminated ray has drained. No progress for
// deadlock_cycles is an error, and so is anything left in a FIFO, a controller
// or a ray slot at the end.
//
// Units are evaluated from the output back to ray setup in each cycle, so a
// result moves at most one stage per clock (registers between the stages).
#pragma once

#include <algorithm>
#include <array>
#include <cassert>
#include <cstdint>
#include <functional>
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
#include "rtl_model/layout/address_mapping.hpp"
#include "rtl_model/layout/bricked_mapping.hpp"
#include "rtl_model/layout/vizard2_layout.hpp"
#include "rtl_model/pipeline/config.hpp"
#include "rtl_model/pipeline/fast_in_order_port.hpp"
#include "rtl_model/pipeline/fast_lookahead_port.hpp"
#include "rtl_model/pipeline/memory_port.hpp"
#include "rtl_model/pipeline/reference_port.hpp"
#include "rtl_model/pipeline/sample_datapath.hpp"
#include "rtl_model/pipeline/stats.hpp"
#include "rtl_model/sdram/controller.hpp"
#include "rtl_model/sim/fifo.hpp"
#include "rtl_model/trace/pipeline_trace.hpp"

namespace voxcast::rtl::pipeline {

template <class P>
class RayPipeline {
 public:
  using G = hls::GeometryParams<P>;
  using C = hls::CompositorParams<P>;

  // `frame`, `memory` and `mapping` must outlive the pipeline. Throws
  // voxcast::Error for an invalid configuration or an unknown policy name.
  RayPipeline(const hls::FrameState<P>& frame, const bittrue::VoxelMemory& memory,
              const layout::AddressMapping& mapping, const PipelineConfig& config,
              const std::string& scheduler, const std::string& refresh)
      : f_(frame),
        config_(elaborated(config, frame)),
        layout_(memory.dims),
        memory_(memory),
        mapping_(mapping),
        bricked_(dynamic_cast<const layout::BrickedMapping*>(&mapping)),
        mip_(frame.mode == hls::FrameMode::Mip),
        shaded_(frame.mode == hls::FrameMode::Shaded),
        leap_(frame.leap.enabled && frame.mode != hls::FrameMode::Mip),
        free_("ray.free", checked(config.ray_slots, "ray_slots")),
        issue_q_("ray.issue", static_cast<std::size_t>(config.ray_slots)),
        miss_("setup.miss", depth(config_.latency.ray_setup)),
        leapt_("issue.leapt", static_cast<std::size_t>(config.ray_slots)),
        interp_("interpolation.out", depth(config_.latency.interpolation)),
        class_("classification.out", depth(config_.latency.classification)),
        shade_("shading.out", depth(config_.latency.shading)),
        out_("output", checked(config.output_depth, "output_depth")) {
    checked(config.sample_buffer, "sample_buffer");
    checked(config.latency.ray_setup_interval, "latency.ray_setup_interval");
    slots_.resize(static_cast<std::size_t>(config.ray_slots));
    view_.resize(slots_.size());
    buf_.resize(static_cast<std::size_t>(config.sample_buffer));
    buf_size_ = buf_.size();
    for (int i = 0; i < config.ray_slots; ++i) free_.push(i);
    if (config.issue == IssuePolicy::kRowHit && config.issue_burst != 0)
      throw Error("rtl pipeline: issue_burst applies to the oldest-ray issue policy only");
    if (config.issue_bypass_limit < 0)
      throw Error("rtl pipeline: issue_bypass_limit must be at least 0");
    for (auto& rows : last_row_) rows.assign(mapping.geometry().banks, kNoRow);
    for (int d = 0; d < layout::kDimms; ++d) {
      req_.emplace_back("dimm" + std::to_string(d) + ".request", depth(config_.latency.address));
      ports_.push_back(make_memory_port(config.memory_model, scheduler, refresh, config.dimm,
                                        config.controller, config.fast_forward,
                                        config.scheduler_params));
      completions_[static_cast<std::size_t>(d)] = &ports_.back()->completions();
      fast_[static_cast<std::size_t>(d)] = dynamic_cast<FastInOrderPort*>(ports_.back().get());
      lookahead_[static_cast<std::size_t>(d)] =
          dynamic_cast<FastLookAheadPort*>(ports_.back().get());
      reference_[static_cast<std::size_t>(d)] = dynamic_cast<ReferencePort*>(ports_.back().get());
    }
    auto all = [](const auto& ports) {
      return std::all_of(ports.begin(), ports.end(), [](const auto* p) { return p != nullptr; });
    };
    all_fast_ = all(fast_);
    all_lookahead_ = all(lookahead_);
    all_reference_ = all(reference_);
  }

  // Records the frame into `t` (rtl_model/trace/pipeline_trace.hpp); call
  // before run(). Without it, tracing costs a null test per cycle.
  void attach_trace(trace::PipelineTrace& t) {
    trace_ = &t;
    traced_.clear();
    auto add = [&](const std::string& scope, const std::string& name, const auto& fifo) {
      traced_.push_back({t.add_fifo(scope, name), [&fifo] { return fifo.valid(); },
                         [&fifo] { return fifo.ready(); }});
    };
    add("pipeline", "ray_free", free_);
    add("pipeline", "ray_issue", issue_q_);
    add("pipeline", "setup_miss", miss_);
    add("pipeline", "interpolation_out", interp_);
    add("pipeline", "classification_out", class_);
    add("pipeline", "shading_out", shade_);
    add("pipeline", "output", out_);
    for (std::size_t d = 0; d < ports_.size(); ++d) {
      const std::string scope = "dimm" + std::to_string(d);
      add(scope, "request", req_[d]);
      add(scope, "completions", ports_[d]->completions());
      ports_[d]->set_observer(t.dimm(static_cast<int>(d)));
    }
    t.begin();
  }

  // The configuration with the latencies of the units this frame's design
  // contains (elaborate_latencies): MIP, unshaded and parallel frames skip the
  // stages of the units they leave out.
  static PipelineConfig elaborated(PipelineConfig c, const hls::FrameState<P>& frame) {
    c.latency = elaborate_latencies(
        c.latency, {frame.mode == hls::FrameMode::Mip, frame.mode == hls::FrameMode::Shaded,
                    frame.geometry.perspective,
                    frame.leap.enabled && frame.mode != hls::FrameMode::Mip,
                    frame.segments.enabled && frame.mode != hls::FrameMode::Mip,
                    frame.preint.enabled && frame.mode != hls::FrameMode::Mip});
    return c;
  }

  // Runs one frame of width x height pixels. Throws voxcast::Error on a
  // deadlock or undrained state. Call once per pipeline.
  ref::QuantImage run(int width, int height, RtlStats& stats) {
    order_ = pixel_order(width, height, config_.traversal, config_.tile);
    ref::QuantImage image(width, height, P::out_bits);
    image_ = &image;
    stats_ = RtlStats{};
    stats_.clock_mhz = config_.dimm.clock.frequency_mhz();
    stats_.rays = order_.size();
    Cycle now = 0;
    Cycle last_progress = 0;
    std::uint64_t last_events = 0;
    // The FIFOs account their occupancy when it changes (sim::Fifo's
    // sample_on_change), not in every clock: most clocks change few of them.
    for_each_fifo([this](auto& f) { f.sample_on_change(&now_); });
    // The frame ends when the last pixel is written and the samples still in
    // flight behind an early-terminated ray have drained.
    while (written_ < order_.size() || !quiet()) {
      const std::uint64_t events_before = events_;
      ports_acted_ = false;
      stalled_count_ = 0;
      now_ = now;
      cycle(now);
      if (trace_) trace_fifos(now);
      ++stats_.evaluated_cycles;
      // Progress: a FIFO moved or a controller issued or retired (checked
      // every 256 evaluated cycles).
      if ((stats_.evaluated_cycles & 255) == 0 || events_ == events_before) {
        const std::uint64_t e = events_ + commands();
        if (e != last_events) {
          last_events = e;
          last_progress = now;
        } else if (now - last_progress >= config_.deadlock_cycles) {
          deadlock(now);
        }
      }
      // Fast-forward: a cycle in which nothing moved and no controller acted
      // repeats until the first cycle at which a timed condition can change
      // (a unit's result becomes ready, a ray's set-up ends, a controller can
      // act); its stalls repeat with it (the FIFOs' occupancies hold).
      Cycle next = now + 1;
      if (config_.fast_forward && events_ == events_before && !ports_acted_) {
        next = std::max(next, next_event(now));
        if (next - last_progress > config_.deadlock_cycles) deadlock(now);
        const Cycle skipped = next - now - 1;
        if (skipped > 0) repeat_stalls(skipped);
      }
      now = next;
    }
    stats_.cycles = now;
    now_ = now;
    for_each_fifo([now](auto& f) { f.sample_until(now); });
    if (trace_) {
      trace_->finish(now);
      for (auto& p : ports_) p->set_observer(nullptr);
    }
    expect_drained();
    collect();
    stats = stats_;
    image_ = nullptr;
    return image;
  }

 private:
  // ---- State --------------------------------------------------------------------------------
  struct Slot {
    // (When it may issue, and its row hits: IssueView.)
    int x = 0, y = 0;
    std::uint64_t n = 0, issued = 0, composited = 0;
    std::uint64_t next = 0;  // the next sample's index: issued + skipped by space leaping
    bool issue_done = false; // every sample issued or skipped
    int outstanding = 0;     // samples issued and not yet composited or dropped
    bool finished = false;   // last sample composited, or early ray termination
    bool in_issue = false;   // in the address generator's queue
    bool free = true;
    typename G::pos_t p[3];
    typename G::step_t s[3];
    hls::Accumulator<P> acc;
    typename C::value_t peak = 0;
    hls::SegmentWeights<P> weights;  // §7a: the first and last samples' segment weights
    // §4a: the ray's previous sample at the classification stage (the front
    // of the next segment: its value and gradient), a register per ray slot.
    hls::Sample<P> front;
    // The next sample's bank access and DIMM addresses, computed once and
    // held until it is issued (row-hit issue compares them every clock).
    // forget_next() clears it.
    bool next_known = false;
    hls::BankAccess<P> next_access;
    std::array<layout::WordCoord, layout::kDimms> next_coord{};
    std::array<sdram::Address, layout::kDimms> next_addr{};
  };
  // What the issue stage asks of every ray in its queue in every clock, per
  // ray slot in a compact array of its own (the simulation's layout: the
  // row-hit pick walks up to 32 rays a clock, and a Slot is ~400 bytes).
  struct IssueView {
    Cycle ready_at = 0;  // the ray may issue from this clock on
    // Row-hit issue: row_hits() of the next sample, valid while the last-row
    // registers are those of hits_epoch (they change at a row change, not at
    // every issue) and the next sample is the one they were counted for.
    std::uint64_t hits_epoch = kNoEpoch;
    int hits = 0;
  };
  // Samples carry k, their place among the ray's issued samples, and pos,
  // their place among all its samples (issued or leapt over), 0 .. n-1.
  struct Buffered {  // one sample between address generator and interpolation
    int slot = 0;
    std::uint64_t k = 0, pos = 0;
    unsigned arrived = 0;  // bit d: DIMM d's word is in
    hls::BankAccess<P> access;
    std::array<layout::WordCoord, layout::kDimms> coord{};
    std::array<layout::DimmWord<P>, layout::kDimms> word{};
  };
  struct TimedRequest {
    Cycle ready = 0;
    sdram::Request request;
  };
  struct MissPixel {
    Cycle ready = 0;
    int x = 0, y = 0;
  };
  struct Interpolated {
    Cycle ready = 0;
    int slot = 0;
    std::uint64_t k = 0, pos = 0;
    hls::Sample<P> s;
  };
  struct Classified {
    Cycle ready = 0;
    int slot = 0;
    std::uint64_t k = 0, pos = 0;
    hls::Sample<P> s;
    hls::ClassEntry<P> e;
  };
  struct Shaded {
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

  static std::size_t checked(int v, const char* what) {
    if (v < 1) throw Error(std::string("rtl pipeline: ") + what + " must be at least 1");
    return static_cast<std::size_t>(v);
  }
  std::size_t depth(int latency) const {
    if (latency < 0 || config_.fifo_depth < 1)
      throw Error("rtl pipeline: latencies must be >= 0 and fifo_depth >= 1");
    return static_cast<std::size_t>(latency + config_.fifo_depth);
  }

  std::uint64_t commands() const {
    std::uint64_t n = 0;
    for (const auto& p : ports_) n += p->activity();
    return n;
  }

  // The first cycle after `now` at which a unit or controller can act when
  // nothing moved and no controller acted at `now` (a far-future cycle if
  // nothing is timed: deadlock). A unit whose input was ready at `now` and
  // did not move is blocked by a FIFO, a slot or a controller queue, which
  // only an event frees; what waits for time is the results not yet ready,
  // a ray still in set-up, the set-up interval and the controllers.
  Cycle next_event(Cycle now) const {
    Cycle t = std::numeric_limits<Cycle>::max() / 2;
    auto at = [&t, now](Cycle c) { t = std::min(t, std::max(c, now + 1)); };
    auto later = [&at, now](Cycle c) {
      if (c > now) at(c);
    };
    for (const auto& p : ports_) at(p->wake());
    for (const auto& rq : req_)
      if (rq.valid()) later(rq.front().ready);
    if (miss_.valid()) later(miss_.front().ready);
    if (interp_.valid()) later(interp_.front().ready);
    if (class_.valid()) later(class_.front().ready);
    if (shade_.valid()) later(shade_.front().ready);
    if (config_.issue == IssuePolicy::kRowHit) {
      for (std::size_t k = 0; k < issue_q_.size(); ++k)
        later(view_[static_cast<std::size_t>(issue_q_.at(k))].ready_at);
    } else if (issue_q_.valid()) {
      later(view_[static_cast<std::size_t>(issue_q_.front())].ready_at);
    }
    if (next_pixel_ < order_.size()) later(setup_next_);
    return t;
  }

  // A unit stalled in this cycle: its counter, and which counters a
  // fast-forward repeats (each counts at most once per cycle; a list of the
  // few that did, instead of a copy of every counter per cycle).
  void stall(Cycle& counter) {
    assert(stalled_count_ < kStallingUnits);
    ++counter;
    stalled_[stalled_count_++] = &counter;
  }

  void repeat_stalls(Cycle times) {
    for (std::size_t k = 0; k < stalled_count_; ++k) *stalled_[k] += times;
  }

  // ---- One clock ------------------------------------------------------------------------------
  void cycle(Cycle now) {
    write_output();
    composite(now);
    shade(now);
    classify(now);
    interpolate(now);
    memory(now);
    issue(now);
    setup(now);
  }

  // Frame buffer: one pixel per clock.
  void write_output() {
    if (!out_.valid()) return;
    const Pixel p = out_.pop();
    ++events_;
    auto& dst = image_->at(p.x, p.y);
    for (std::size_t c = 0; c < 4; ++c) dst[c] = static_cast<std::uint32_t>(p.px.ch[c].to_uint64());
    ++written_;
  }

  void composite(Cycle now) {
    bool pushed = false;
    if (shade_.valid() && shade_.front().ready <= now) {
      const Shaded& e = shade_.front();
      Slot& s = slots_[static_cast<std::size_t>(e.slot)];
      const int slot = e.slot;
      if (s.finished) {  // after early ray termination
        shade_.discard();
        ++events_;
        drop(slot);
      } else if (!out_.ready()) {
        stall(stats_.stalls.composite_blocked);
      } else {
        if (e.k != s.composited) order_error("compositor", slot, e.k, s.composited);
        ++s.composited;
        ++stats_.samples;
        bool done = s.issue_done && s.composited == s.issued;
        if (composite_sample<P>(f_, mip_, s.acc, s.peak, e.value, e.c, e.alpha)) {
          count_early_end(stats_, s.n, s.next, s.issued, e.pos, e.k);
          done = true;
        }
        shade_.discard();
        ++events_;
        --s.outstanding;
        if (done) {
          out_.push(Pixel{s.x, s.y, hls::output<P>(ray_result<P>(f_, mip_, s.acc, s.peak))});
          pushed = true;
          s.finished = true;
          if (s.in_issue) ++finished_in_issue_;
        }
        try_free(slot);
      }
    }
    // A ray whose last samples were leapt over after the others composited.
    if (!pushed && leapt_.valid() && out_.ready()) {
      const int slot = leapt_.pop();
      Slot& s = slots_[static_cast<std::size_t>(slot)];
      out_.push(Pixel{s.x, s.y, hls::output<P>(s.acc)});
      s.finished = true;
      pushed = true;
      ++events_;
      try_free(slot);
    }
    // The background pixels of missed rays share the output port.
    if (!pushed && miss_.valid() && miss_.front().ready <= now && out_.ready()) {
      const MissPixel m = miss_.pop();
      out_.push(Pixel{m.x, m.y, hls::output<P>(hls::Accumulator<P>{})});
      ++events_;
    }
  }

  void shade(Cycle now) {
    if (!class_.valid() || class_.front().ready > now || !shade_.ready()) return;
    // Built in place (Fifo::emplace): every member is assigned below.
    const Classified& in = class_.front();
    Shaded& out = shade_.emplace();
    out.ready = now + config_.latency.shading;
    out.slot = in.slot;
    out.k = in.k;
    out.pos = in.pos;
    out.value = in.s.value;
    out.alpha = mip_ ? typename C::alpha_t(0) : in.e.alpha;
    if (out.alpha != 0) {
      out.c = shade_sample<P>(f_, in.e, in.s, shaded_);
    } else {
      out.c = hls::ShadedColor<P>{};  // (not composited)
    }
    class_.discard();
    ++events_;
  }

  void classify(Cycle now) {
    if (!interp_.valid() || interp_.front().ready > now || !class_.ready()) return;
    // Built in place (Fifo::emplace): every member is assigned below.
    const Interpolated& in = interp_.front();
    Classified& out = class_.emplace();
    out.ready = now + config_.latency.classification;
    out.slot = in.slot;
    out.k = in.k;
    out.pos = in.pos;
    if (!mip_) {
      // §4a: a ray's samples reach this stage in order.
      Slot& s = slots_[static_cast<std::size_t>(in.slot)];
      out.e = classify_sample<P>(f_, in.s, in.pos, s.n, s.weights, s.front, out.s);
    } else {
      out.s = in.s;
      out.e = hls::ClassEntry<P>{};  // (MIP composites the value)
    }
    interp_.discard();
    ++events_;
  }

  void interpolate(Cycle now) {
    if (buf_count_ == 0) return;
    Buffered& b = buf_[buf_head_];
    if (b.arrived != (1u << layout::kDimms) - 1u) {
      stall(stats_.stalls.interp_wait_memory);
      return;
    }
    if (slots_[static_cast<std::size_t>(b.slot)].finished) {  // after early ray termination
      const int slot = b.slot;
      advance_buffer();
      drop(slot);
      return;
    }
    if (!interp_.ready()) {
      stall(stats_.stalls.interp_blocked);
      return;
    }
    const layout::Dimm4Banks<P> view{b.word.data(), b.access.parity};
    hls::VoxelWordFx<P> corner[8];
    hls::gather<P>(view, b.access, corner);
    Interpolated& out = interp_.emplace();  // every member assigned
    out.ready = now + config_.latency.interpolation;
    out.slot = b.slot;
    out.k = b.k;
    out.pos = b.pos;
    out.s = hls::interpolation_processor<P>(corner, b.access.fq);
    advance_buffer();
  }

  void advance_buffer() {
    buf_[buf_head_].arrived = 0;
    buf_head_ = buf_head_ + 1 == buf_size_ ? 0 : buf_head_ + 1;
    --buf_count_;
    ++events_;
  }

  void memory(Cycle now) {
    // The ports are called as their final class (four in every clock): their
    // per-cycle members inline instead of going through MemoryPort's vtable.
    if (all_fast_) {
      for (std::size_t d = 0; d < layout::kDimms; ++d) memory_port(now, d, *fast_[d]);
    } else if (all_lookahead_) {
      for (std::size_t d = 0; d < layout::kDimms; ++d) memory_port(now, d, *lookahead_[d]);
    } else if (all_reference_) {
      for (std::size_t d = 0; d < layout::kDimms; ++d) memory_port(now, d, *reference_[d]);
    } else {
      for (std::size_t d = 0; d < layout::kDimms; ++d) memory_port(now, d, *ports_[d]);
    }
  }

  // DIMM d's request FIFO, port and completions in one cycle.
  template <class Port>
  void memory_port(Cycle now, std::size_t d, Port& port) {
    auto& rq = req_[d];
    if (rq.valid() && rq.front().ready <= now && port.ready()) {
      sdram::Request r = rq.front().request;
      rq.discard();
      r.arrival = now;
      port.push(r);
      ++events_;
    }
    if (now >= port.wake()) {  // (no call while it waits)
      const std::uint64_t activity = port.activity();
      port.tick(now);
      ports_acted_ |= port.activity() != activity;
    }
    auto& completions = *completions_[d];
    if (completions.valid()) {
      const std::uint64_t id = completions.front().request.id;
      completions.discard();
      port.popped(now);
      Buffered& b = buf_[id];
      b.word[d] = memory_.word(static_cast<int>(d), b.coord[d]);
      b.arrived |= 1u << d;
      ++events_;
    }
  }

  void issue(Cycle now) {
    retire_finished_rays();
    if (!issue_q_.valid()) {
      stall(next_pixel_ == order_.size() ? stats_.stalls.issue_idle : stats_.stalls.issue_no_ray);
      return;
    }
    const Pick pick = pick_ray(now);
    if (pick.place == kNone) {
      stall(stats_.stalls.issue_no_ray);
      return;
    }
    const std::size_t j = pick.place;
    const int i = issue_q_.at(j);
    Slot& s = slots_[static_cast<std::size_t>(i)];
    if (leap_ && try_leap(now, j, s)) return;
    if (buf_count_ == buf_size_) {
      stall(stats_.stalls.issue_buffer_full);
      return;
    }
    for (const auto& rq : req_)
      if (!rq.ready()) {
        stall(stats_.stalls.issue_memory_full);
        return;
      }
    if (config_.issue == IssuePolicy::kRowHit) count_bypass(j != pick.oldest);
    // The sample's bank access (hls address generator), its neighbourhood's
    // four DIMM words, one request to each DIMM.
    know_next_sample(s);
    std::size_t tail = buf_head_ + buf_count_;
    if (tail >= buf_size_) tail -= buf_size_;
    Buffered& b = buf_[tail];
    b.slot = i;
    b.k = s.issued;
    b.pos = s.next;
    b.arrived = 0;
    b.access = s.next_access;
    b.coord = s.next_coord;
    for (std::size_t d = 0; d < layout::kDimms; ++d)
      memory_.prefetch(static_cast<int>(d), b.coord[d]);  // host cache only: no model effect
    ++buf_count_;
    const Cycle ready = now + config_.latency.address + config_.latency.leap_lookup;
    for (std::size_t d = 0; d < layout::kDimms; ++d) {
      TimedRequest& t = req_[d].emplace();  // every member assigned
      t.ready = ready;
      t.request = sdram::Request{tail, sdram::RequestKind::kRead, s.next_addr[d], 0};
      std::uint32_t& last = last_row_[d][s.next_addr[d].bank];
      if (last != s.next_addr[d].row) {
        last = s.next_addr[d].row;
        ++row_epoch_;  // every ray's cached row_hits() is stale
      }
    }
    ++events_;
    ++s.outstanding;
    ++s.issued;
    ++stats_.samples_issued;
    ++s.next;
    hls::step_position<P>(s.p, s.s);
    forget_next(i, s);
    if (s.next == s.n) {
      end_issue(j, i, s);
    } else if (config_.issue_burst > 0 && ++burst_count_ >= config_.issue_burst) {
      burst_count_ = 0;
      issue_q_.push(issue_q_.pop());
    }
  }

  // Rays ended by early ray termination leave the issue queue: from its front
  // when the address generator takes the oldest ray (the baseline's queue),
  // from any place in the collapsing queue of row-hit issue.
  void retire_finished_rays() {
    auto retire = [this](std::size_t k) {
      const int i = issue_q_.take(k);
      --finished_in_issue_;
      ++events_;
      slots_[static_cast<std::size_t>(i)].in_issue = false;
      burst_count_ = 0;
      try_free(i);
    };
    if (config_.issue == IssuePolicy::kOldest) {
      while (issue_q_.valid() && slots_[static_cast<std::size_t>(issue_q_.front())].finished)
        retire(0);
      return;
    }
    if (finished_in_issue_ == 0) return;  // (the walk touches every ray's slot)
    for (std::size_t k = issue_q_.size(); k-- > 0;)
      if (slots_[static_cast<std::size_t>(issue_q_.at(k))].finished) retire(k);
  }

  // The place in the issue queue of the ray to issue from at `now`, and of
  // the oldest ready ray; kNone when that ray (oldest) or every ray (row-hit)
  // is still in set-up or waiting for a leap.
  struct Pick {
    std::size_t place = kNone;
    std::size_t oldest = kNone;
  };
  Pick pick_ray(Cycle now) {
    if (config_.issue == IssuePolicy::kOldest) {
      if (view_[static_cast<std::size_t>(issue_q_.front())].ready_at > now) return {};
      return {0, 0};
    }
    std::size_t oldest = kNone, best = kNone;
    int best_hits = 0;
    for (std::size_t k = 0; k < issue_q_.size(); ++k) {
      const int i = issue_q_.at(k);
      if (view_[static_cast<std::size_t>(i)].ready_at > now) continue;
      if (oldest == kNone) {
        oldest = k;
        if (bypass_ >= config_.issue_bypass_limit) return {oldest, oldest};
      }
      const int hits = row_hits(i);
      if (hits > best_hits) {
        best_hits = hits;
        best = k;
        if (hits == layout::kDimms) break;
      }
    }
    return {best == kNone ? oldest : best, oldest};
  }

  // How many of the ray's next sample's four DIMM words lie in the row last
  // requested in their bank.
  int row_hits(int i) {
    IssueView& v = view_[static_cast<std::size_t>(i)];
    if (v.hits_epoch == row_epoch_) return v.hits;
    Slot& s = slots_[static_cast<std::size_t>(i)];
    know_next_sample(s);
    int hits = 0;
    for (std::size_t d = 0; d < layout::kDimms; ++d)
      hits += last_row_[d][s.next_addr[d].bank] == s.next_addr[d].row ? 1 : 0;
    v.hits = hits;
    v.hits_epoch = row_epoch_;
    return hits;
  }

  // Row-hit issue: a sample from any ray but the oldest ready one bypasses it.
  void count_bypass(bool bypassed) {
    if (!bypassed) {
      bypass_ = 0;
      return;
    }
    ++bypass_;
    ++stats_.issue_bypasses;
    stats_.issue_longest_bypass =
        std::max(stats_.issue_longest_bypass, static_cast<std::uint64_t>(bypass_));
  }

  void know_next_sample(Slot& s) {
    if (s.next_known) return;
    s.next_access = hls::address_generator<P>(f_.geometry, s.p);
    s.next_coord = layout::Vizard2Layout::neighbourhood(layout_.corner<P>(s.next_access));
    if (bricked_) {  // called as its final class: its index inlines
      for (std::size_t d = 0; d < layout::kDimms; ++d)
        s.next_addr[d] = mapping_.split(bricked_->index(s.next_coord[d]));
    } else {
      for (std::size_t d = 0; d < layout::kDimms; ++d)
        s.next_addr[d] = mapping_.map(s.next_coord[d]);
    }
    s.next_known = true;
  }
  // Ray i moved on to another sample: its next sample and row hits are unknown.
  void forget_next(int i, Slot& s) {
    s.next_known = false;
    view_[static_cast<std::size_t>(i)].hits_epoch = kNoEpoch;
  }

  // Space leaping: if the chosen ray's next sample lies in an empty block, leap
  // to the first sample after the block (hls::leap_run) instead of issuing; the
  // ray's issue waits latency.leap clocks. True if it leapt. `j` is the ray's
  // place in the issue queue.
  bool try_leap(Cycle now, std::size_t j, Slot& s) {
    typename hls::LeapParams<P>::bcoord_t b[3];
    if (!hls::sample_block_empty<P>(f_.geometry, f_.leap, f_.minmax, s.p, b)) return false;
    const std::uint64_t run = hls::leap_run<P>(f_.geometry, f_.leap, s.p, s.s, s.n - s.next, b);
    hls::step_position<P>(s.p, s.s);
    s.next += run;
    const int i = issue_q_.at(j);
    forget_next(i, s);
    view_[static_cast<std::size_t>(i)].ready_at =
        now + static_cast<Cycle>(std::max(config_.latency.leap, 1));
    stats_.samples_skipped += run;
    ++stats_.leaps;
    ++events_;
    if (s.next == s.n) end_issue(j, i, s);
    return true;
  }

  // Ray `i`, at place `j` of the issue queue, has no sample left to issue. If
  // none of its samples is in flight either (they composited, or all were
  // leapt over), its pixel leaves through leapt_; otherwise the compositor
  // ends it.
  void end_issue(std::size_t j, int i, Slot& s) {
    issue_q_.take(j);
    if (s.finished) --finished_in_issue_;
    s.in_issue = false;
    s.issue_done = true;
    burst_count_ = 0;
    if (s.outstanding == 0 && !s.finished) leapt_.push(i);
  }

  void setup(Cycle now) {
    if (next_pixel_ == order_.size() || now < setup_next_) return;
    const auto [x, y] = order_[next_pixel_];
    // The set-up of the next pixel is computed once and held until it can
    // leave: a hit needs a free ray slot, a miss room for its pixel.
    if (setup_for_ != next_pixel_) {
      setup_ray_ = hls::ray_setup<P>(f_.geometry, f_.rsqrt.seed, x, y);
      setup_for_ = next_pixel_;
    }
    const hls::RaySetup<P>& ray = setup_ray_;
    if (ray.hit && !free_.valid()) {
      stall(stats_.stalls.setup_no_slot);
      return;
    }
    if (!ray.hit && !miss_.ready()) return;
    const Cycle ready = now + config_.latency.ray_setup;
    if (ray.hit) {
      const int i = free_.pop();
      Slot& s = slots_[static_cast<std::size_t>(i)];
      s = Slot{};
      s.x = x;
      s.y = y;
      view_[static_cast<std::size_t>(i)] = IssueView{ready, kNoEpoch, 0};
      s.n = ray.n.to_uint64();
      s.weights = hls::segment_weights<P>(f_.segments, ray, hls::pixel_jitter<P>(f_.geometry, x, y));
      s.free = false;
      s.in_issue = true;
      for (int k = 0; k < 3; ++k) {
        s.p[k] = ray.p0[k];
        s.s[k] = ray.s[k];
      }
      issue_q_.push(i);
      ++stats_.rays_hit;
    } else {
      miss_.push(MissPixel{ready, x, y});
    }
    ++events_;
    ++next_pixel_;
    setup_next_ = now + config_.latency.ray_setup_interval;
  }

  template <class F>
  void for_each_fifo(F f) {
    f(free_);
    f(issue_q_);
    f(miss_);
    f(leapt_);
    for (auto& rq : req_) f(rq);
    for (auto* c : completions_) f(*c);  // the ports' (pushed in their ticks)
    f(interp_);
    f(class_);
    f(shade_);
    f(out_);
  }

  // ---- Ray slots ------------------------------------------------------------------------------
  void drop(int slot) {
    Slot& s = slots_[static_cast<std::size_t>(slot)];
    --s.outstanding;
    ++stats_.samples_discarded;
    try_free(slot);
  }

  void try_free(int slot) {
    Slot& s = slots_[static_cast<std::size_t>(slot)];
    if (s.free || !s.finished || s.outstanding != 0 || s.in_issue) return;
    s.free = true;
    free_.push(slot);
    ++events_;
  }

  // ---- Errors and the end of the frame --------------------------------------------------------
  bool quiet() const {
    if (buf_count_ != 0 || free_.size() != slots_.size() || !miss_.empty() || !leapt_.empty() ||
        !interp_.empty() ||
        !class_.empty() || !shade_.empty() || !out_.empty())
      return false;
    for (const auto& rq : req_)
      if (!rq.empty()) return false;
    for (const auto& p : ports_)
      if (!p->idle()) return false;
    return true;
  }

  [[noreturn]] void order_error(const char* unit, int slot, std::uint64_t got,
                                std::uint64_t expected) const {
    std::ostringstream os;
    os << "rtl pipeline: " << unit << " got sample " << got << " of ray slot " << slot
       << ", expected sample " << expected;
    throw Error(os.str());
  }

  std::string state() const {
    std::ostringstream os;
    os << "pixels set up " << next_pixel_ << "/" << order_.size() << ", written " << written_
       << ", sample buffer " << buf_count_ << "/" << buf_.size();
    if (buf_count_ > 0) {
      const Buffered& b = buf_[buf_head_];
      os << " (head: ray slot " << b.slot << " sample " << b.k << ", DIMM words in 0x" << std::hex
         << b.arrived << std::dec << ")";
    }
    os << "; " << free_ << "; " << issue_q_ << "; " << miss_;
    for (const auto& rq : req_) os << "; " << rq;
    os << "; " << interp_ << "; " << class_ << "; " << shade_ << "; " << out_;
    for (std::size_t d = 0; d < ports_.size(); ++d)
      os << "; DIMM " << d << " controller: " << ports_[d]->pending() << " pending, "
         << ports_[d]->in_flight() << " in flight";
    for (std::size_t i = 0; i < slots_.size(); ++i) {
      const Slot& s = slots_[i];
      if (s.free) continue;
      os << "; slot " << i << " pixel (" << s.x << ", " << s.y << ") issued " << s.issued << "/"
         << s.n << ", composited " << s.composited << ", outstanding " << s.outstanding
         << (s.finished ? ", finished" : "") << (s.in_issue ? ", in issue queue" : "");
    }
    return os.str();
  }

  [[noreturn]] void deadlock(Cycle now) const {
    std::ostringstream os;
    os << "rtl pipeline: deadlock, no progress for " << config_.deadlock_cycles
       << " cycles at cycle " << now << ": " << state();
    throw Error(os.str());
  }

  void expect_drained() const {
    try {
      if (buf_count_ != 0) throw Error("the sample buffer is not empty");
      miss_.expect_drained();
      leapt_.expect_drained();
      for (const auto& rq : req_) rq.expect_drained();
      interp_.expect_drained();
      class_.expect_drained();
      shade_.expect_drained();
      out_.expect_drained();
      issue_q_.expect_drained();
      for (const auto& p : ports_) p->expect_drained();
      if (free_.size() != slots_.size()) throw Error("a ray slot is still busy");
    } catch (const Error& e) {
      throw Error(std::string("rtl pipeline: undrained at the end of the frame: ") + e.what() +
                  "; " + state());
    }
  }

  void collect() {
    for (std::size_t d = 0; d < ports_.size(); ++d) {
      stats_.dimms[d].controller = ports_[d]->controller_stats();
      // The card clocks its controllers in every cycle of the frame. The
      // ports' own count is of the ticks the simulation ran (it skips the
      // cycles in which a controller cannot act, and each port skips
      // others), not a property of the card.
      stats_.dimms[d].controller.cycles = stats_.cycles;
      stats_.dimms[d].dimm = ports_[d]->dimm_stats();
    }
    auto add = [this](const auto& fifo) {
      stats_.fifos.push_back(NamedFifoStats{fifo.name(), fifo.depth(), fifo.stats()});
    };
    add(issue_q_);
    add(miss_);
    for (const auto& rq : req_) add(rq);
    for (const auto& p : ports_) add(p->completions());
    add(interp_);
    add(class_);
    add(shade_);
    add(out_);
  }

  // The FIFOs' handshakes at the end of the cycle. Cycles the fast-forward
  // skips repeat the last evaluated one (nothing moved), so the values hold.
  void trace_fifos(Cycle now) {
    for (const TracedFifo& f : traced_) trace_->fifo(f.index, f.valid(), f.ready(), now);
  }

  // ---- Members --------------------------------------------------------------------------------
  const hls::FrameState<P>& f_;
  PipelineConfig config_;
  layout::Vizard2Layout layout_;
  layout::Vizard2Memory<P> memory_;
  const layout::AddressMapping& mapping_;
  const layout::BrickedMapping* bricked_;  // mapping_ if it is one
  bool mip_, shaded_, leap_;

  std::vector<std::pair<int, int>> order_;
  std::size_t next_pixel_ = 0;
  std::size_t setup_for_ = static_cast<std::size_t>(-1);  // the pixel setup_ray_ belongs to
  hls::RaySetup<P> setup_ray_;
  std::size_t written_ = 0;
  Cycle setup_next_ = 0;
  int burst_count_ = 0;
  int bypass_ = 0;  // row-hit issues in a row that bypassed the oldest ready ray
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  static constexpr std::uint32_t kNoRow = std::numeric_limits<std::uint32_t>::max();
  // Per DIMM and bank, the row of the last request the address generator sent.
  std::array<std::vector<std::uint32_t>, layout::kDimms> last_row_;
  static constexpr std::uint64_t kNoEpoch = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t row_epoch_ = 0;  // changes with any of last_row_
  std::uint64_t events_ = 0;
  // A port issued a command or completed an access in this cycle (its
  // activity() moved; only tick() moves it).
  bool ports_acted_ = false;
  // The stall counters this cycle raised (stall()): at most one per unit.
  static constexpr std::size_t kStallingUnits = 4;  // issue, interpolation, setup, compositor
  std::array<Cycle*, kStallingUnits> stalled_{};
  std::size_t stalled_count_ = 0;
  std::size_t finished_in_issue_ = 0;  // rays in issue_q_ that have finished (ERT)
  Cycle now_ = 0;  // the cycle being evaluated (the FIFOs' statistics clock)
  ref::QuantImage* image_ = nullptr;

  std::vector<Slot> slots_;
  std::vector<IssueView> view_;  // per ray slot
  sim::Fifo<int> free_;     // free ray slots
  sim::Fifo<int> issue_q_;  // rays with samples to issue, oldest first
  sim::Fifo<MissPixel> miss_;
  sim::Fifo<int> leapt_;  // rays whose pixel is due with nothing left in flight
  std::vector<sim::Fifo<TimedRequest>> req_;
  std::vector<std::unique_ptr<MemoryPort>> ports_;
  std::array<sim::Fifo<sdram::Completion>*, layout::kDimms> completions_{};  // ports_[d]'s
  std::array<FastInOrderPort*, layout::kDimms> fast_{};  // ports_[d] if it is one
  std::array<FastLookAheadPort*, layout::kDimms> lookahead_{};  // ports_[d] if it is one
  std::array<ReferencePort*, layout::kDimms> reference_{};  // ports_[d] if it is one
  bool all_fast_ = false, all_lookahead_ = false, all_reference_ = false;
  std::vector<Buffered> buf_;
  std::size_t buf_head_ = 0, buf_count_ = 0;
  std::size_t buf_size_ = 0;  // buf_.size(), kept (a division by the entry's size)
  sim::Fifo<Interpolated> interp_;
  sim::Fifo<Classified> class_;
  sim::Fifo<Shaded> shade_;
  sim::Fifo<Pixel> out_;
  RtlStats stats_;
  struct TracedFifo {
    int index;
    std::function<bool()> valid, ready;
  };
  trace::PipelineTrace* trace_ = nullptr;
  std::vector<TracedFifo> traced_;
};

}  // namespace voxcast::rtl::pipeline
