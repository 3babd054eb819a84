// The design as a vendor HLS tool sees it: compiled with -D__SYNTHESIS__
// -fno-exceptions -fno-rtti (hls/CMakeLists.txt), so host-only code is out and
// anything outside the synthesizable subset fails the build. One top per
// preset; generated wrappers (docs/synthesis.md) do the same for a scene's
// profile.
#include "hls/vizard2_top.hpp"
#include "refmodel/precision/preset_profiles.hpp"

namespace voxcast::hls {

#define VOXCAST_SYNTH_TOP(NAME, PROFILE)                                                          \
  void NAME(const FrameState<PROFILE>* frame,                                                     \
            const InterpolationParams<PROFILE>::packed_word_t* b0,                                \
            const InterpolationParams<PROFILE>::packed_word_t* b1,                                \
            const InterpolationParams<PROFILE>::packed_word_t* b2,                                \
            const InterpolationParams<PROFILE>::packed_word_t* b3,                                \
            const InterpolationParams<PROFILE>::packed_word_t* b4,                                \
            const InterpolationParams<PROFILE>::packed_word_t* b5,                                \
            const InterpolationParams<PROFILE>::packed_word_t* b6,                                \
            const InterpolationParams<PROFILE>::packed_word_t* b7, int width, int height,         \
            OutputPixel<PROFILE>* fb, std::uint64_t* samples) {                                   \
    vizard2_frame<PROFILE>(frame, b0, b1, b2, b3, b4, b5, b6, b7, width, height, fb, samples);    \
  }

VOXCAST_SYNTH_TOP(vizard2_frame_vizard2, kVizard2)
VOXCAST_SYNTH_TOP(vizard2_frame_balanced, kBalanced)
VOXCAST_SYNTH_TOP(vizard2_frame_precise, kPrecise)

}  // namespace voxcast::hls
