// VIRIM's kernels as a vendor HLS tool sees them (see hls/synth_check.cpp):
// compiled with -D__SYNTHESIS__ -fno-exceptions -fno-rtti.
#include "hls/virim/virim_top.hpp"

namespace voxcast::hls::virim {

void virim_frame_virim(const VirimFrame<kVirimProfile>* frame, const std::uint16_t* const banks[16],
                       int k_lo, int k_hi, std::uint32_t* level, bool* background,
                       MemoryStats* stats) {
  virim_frame<kVirimProfile>(frame, banks, k_lo, k_hi, level, background, stats);
}

}  // namespace voxcast::hls::virim
