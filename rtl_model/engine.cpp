#include "rtl_model/engine.hpp"

#include <memory>
#include <ostream>
#include <string>

#include "hls/host_frame.hpp"
#include "refmodel/error.hpp"
#include "rtl_model/board/board_config.hpp"
#include "rtl_model/burst_engine.hpp"
#include "rtl_model/layout/vizard2_layout.hpp"
#include "rtl_model/pipeline/ray_pipeline.hpp"

namespace voxcast::rtl {
namespace {

template <class P>
RtlResult render(const bittrue::FrameSetup& fs, const bittrue::VoxelMemory& memory,
                 const RtlConfig& config, const trace::TraceOptions* trace) {
  if (memory.dims != fs.regs.dims) throw Error("rtl engine: voxel memory and frame set-up differ in dims");
  const auto frame = hls::host::load_frame_state<P>(fs, "rtl engine");
  const layout::Vizard2Layout layout(memory.dims);
  const auto mapping =
      layout::make_address_mapping(config.mapping, layout.grid(), config.pipeline.dimm.geometry);
  pipeline::RayPipeline<P> pipe(*frame, memory, *mapping, config.pipeline, config.scheduler,
                                config.refresh);
  std::unique_ptr<trace::PipelineTrace> tracer;
  if (trace) {
    tracer = std::make_unique<trace::PipelineTrace>(*trace, config.pipeline.dimm.clock.period_ps(),
                                                    config.pipeline.dimm.geometry, layout::kDimms);
    pipe.attach_trace(*tracer);
  }
  RtlResult r;
  r.image = pipe.run(fs.regs.width, fs.regs.height, r.stats);
  if (tracer) r.traced_commands = tracer->commands_in_window();
  return r;
}

}  // namespace

std::ostream& operator<<(std::ostream& os, const RtlConfig& c) {
  if (c.card.enabled)
    return os << c.pipeline << "; " << c.card << ", scheduler " << c.scheduler << ", refresh "
              << c.refresh << "; " << c.pipeline.dimm;
  return os << c.pipeline << "; layout " << c.mapping << ", scheduler " << c.scheduler
            << (c.scheduler == "in-order" ? "" : " (window " +
                    std::to_string(c.pipeline.scheduler_params.reorder_window) + ")")
            << ", refresh " << c.refresh << "; " << c.pipeline.dimm;
}

// From the shipped board description (constraints/boards/vizard2_pci.toml), the
// one source of the card's clocks and SDRAM timing; parsed once.
RtlConfig vizard2_baseline() {
  static const RtlConfig c = rtl_config_for_board(board::shipped_board(kVizard2BoardName));
  return c;
}

RtlResult rtl_render(const bittrue::FrameSetup& setup, const bittrue::VoxelMemory& memory,
                     const RtlConfig& config, const trace::TraceOptions* trace) {
  if (config.card.enabled) {
    if (trace) throw Error("rtl engine: the DDR4 card model writes no VCD trace (--vcd)");
    return render_ddr4_card(setup, memory, config);
  }
  RtlResult r;
  const auto run = [&]<class P>() { r = render<P>(setup, memory, config, trace); };
  if (!hls::host::dispatch_profile(setup.profile, run))
    throw Error(std::string("this precision profile is not compiled into the rtl engine (") +
                hls::host::kCompiledProfileNames + ")");
  return r;
}

bool rtl_supports(const PrecisionProfile& p) {
  return hls::host::dispatch_profile(p, []<class>() {});
}

std::string rtl_supported_profiles() { return hls::host::kCompiledProfileNames; }

ref::FrameStats frame_stats(const RtlStats& s) {
  ref::FrameStats f;
  f.rays = s.rays;
  f.rays_hit = s.rays_hit;
  f.rays_terminated_early = s.rays_ert;
  f.samples = s.samples;
  f.samples_skipped = s.samples_skipped - s.samples_skipped_discarded;
  return f;
}

}  // namespace voxcast::rtl
