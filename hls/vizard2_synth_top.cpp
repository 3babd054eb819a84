// The top function a vendor HLS tool synthesizes for one precision profile:
// vizard2_frame_top, at global scope (Vitis HLS takes a plain name for
// set_top), the preset chosen at compile time with
// -DVOXCAST_SYNTH_PROFILE=kVizard2 | kBalanced | kPrecise. The Tcl script of
// `voxcast synth-script` (docs/synthesis.md) passes that flag from the
// scene's profile; hls/CMakeLists.txt compiles this file as the vendor tool
// sees it (-D__SYNTHESIS__, no exceptions, no RTTI) for each preset.
#include <cstdint>

#include "hls/vizard2_top.hpp"
#include "refmodel/precision/preset_profiles.hpp"

#ifndef VOXCAST_SYNTH_PROFILE
#error "define VOXCAST_SYNTH_PROFILE as one of kVizard2, kBalanced, kPrecise"
#endif

namespace {
constexpr voxcast::PrecisionProfile kTopProfile = voxcast::VOXCAST_SYNTH_PROFILE;
using Word = voxcast::hls::InterpolationParams<kTopProfile>::packed_word_t;
}  // namespace

void vizard2_frame_top(const voxcast::hls::FrameState<kTopProfile>* frame, const Word* bank0,
                       const Word* bank1, const Word* bank2, const Word* bank3, const Word* bank4,
                       const Word* bank5, const Word* bank6, const Word* bank7, int width,
                       int height, voxcast::hls::OutputPixel<kTopProfile>* fb,
                       std::uint64_t* samples) {
  voxcast::hls::vizard2_frame<kTopProfile>(frame, bank0, bank1, bank2, bank3, bank4, bank5, bank6,
                                           bank7, width, height, fb, samples);
}
