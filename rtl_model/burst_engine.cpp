#include "rtl_model/burst_engine.hpp"

#include <string>

#include "hls/host_frame.hpp"
#include "refmodel/error.hpp"
#include "rtl_model/pipeline/burst_card.hpp"

namespace voxcast::rtl {
namespace {

// The packed voxel word's bytes in a burst: 32 bits for the vizard2 profile
// (the 2001 card's voxel), 64 or 128 for wider profiles.
template <class P>
int voxel_bytes() {
  using I = hls::InterpolationParams<P>;
  constexpr int bits = I::vb + 3 * I::gb;
  return bits <= 32 ? 4 : bits <= 64 ? 8 : 16;
}

template <class P>
RtlResult render(const bittrue::FrameSetup& fs, const bittrue::VoxelMemory& memory,
                 const RtlConfig& config) {
  if (memory.dims != fs.regs.dims)
    throw Error("rtl engine: voxel memory and frame set-up differ in dims");
  const auto frame = hls::host::load_frame_state<P>(fs, "rtl engine");
  const layout::BurstLayout layout =
      card_burst_layout(memory.dims, voxel_bytes<P>(), config.pipeline.dimm);
  pipeline::BurstCard<P> card(*frame, memory, layout, config.pipeline, config.card,
                              config.scheduler, config.refresh);
  RtlResult r;
  r.image = card.run(fs.regs.width, fs.regs.height, r.stats);
  return r;
}

}  // namespace

layout::BurstLayout card_burst_layout(const std::array<int, 3>& dims, int voxel_bytes,
                                      const sdram::DimmConfig& dimm) {
  layout::BurstMemory m;
  m.burst_bytes = static_cast<int>(dimm.geometry.bytes_per_beat()) * dimm.burst_length;
  m.banks_per_group = static_cast<int>(dimm.geometry.banks_per_group());
  m.columns = dimm.geometry.columns;
  m.rows = dimm.geometry.rows;
  m.clock_mhz = dimm.clock.frequency_mhz();
  m.burst_clocks = dimm.burst_length / 2;
  const int voxels = m.burst_bytes / voxel_bytes;
  const std::array<int, 3> brick = voxels == 16  ? std::array<int, 3>{4, 2, 2}
                                   : voxels == 8 ? std::array<int, 3>{2, 2, 2}
                                                 : std::array<int, 3>{2, 2, 1};
  if (voxels != brick[0] * brick[1] * brick[2])
    throw Error("DDR4 card: a " + std::to_string(m.burst_bytes) + "-byte burst holds " +
                std::to_string(voxels) + " voxels of " + std::to_string(voxel_bytes) +
                " bytes; the card lays out bursts of 4, 8 or 16");
  return layout::BurstLayout(dims, brick, voxels, layout::BankGroupMap::kSkewed, m,
                             layout::RowMap::kBlocks);
}

RtlResult render_ddr4_card(const bittrue::FrameSetup& setup, const bittrue::VoxelMemory& memory,
                           const RtlConfig& config) {
  RtlResult r;
  const auto run = [&]<class P>() { r = render<P>(setup, memory, config); };
  if (!hls::host::dispatch_profile(setup.profile, run))
    throw Error(std::string("this precision profile is not compiled into the rtl engine (") +
                hls::host::kCompiledProfileNames + ")");
  return r;
}

}  // namespace voxcast::rtl
