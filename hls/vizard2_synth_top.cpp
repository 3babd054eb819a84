// The top function a vendor HLS tool synthesizes: vizard2_frame_top, at global
// scope (Vitis HLS takes a plain name for set_top), for one precision profile
// and one set of units, both fixed at compile time.
//
// `voxcast synth-script SCENE` writes the scene's elaborated_config.hpp
// (ref::elaborate: which units the scene needs; cosim/synth_script.hpp) and
// its Tcl passes it with `-include`, so the top instantiates only those units
// (hls/units.hpp, docs/synthesis.md): a MIP top has no classification, shader
// or compositor, a parallel top no direction or rsqrt unit. Without the header
// the top is the full run-time-configurable design (kAllUnits) for the preset
// -DVOXCAST_SYNTH_PROFILE=kVizard2 | kBalanced | kPrecise names. CMake
// compiles this file as the vendor tool sees it (-D__SYNTHESIS__, no
// exceptions, no RTTI) for each preset (hls/CMakeLists.txt) and for two
// elaborated scenes (tests/CMakeLists.txt).
#include <cstdint>

#include "hls/units.hpp"
#include "hls/vizard2_top.hpp"
#include "refmodel/precision/preset_profiles.hpp"

namespace {
#ifdef VOXCAST_ELABORATED_CONFIG  // elaborated_config.hpp, passed with -include
constexpr voxcast::PrecisionProfile kTopProfile = voxcast::elaborated::kProfile;
constexpr voxcast::hls::Units kTopUnits = voxcast::elaborated::kUnits;
#ifdef VOXCAST_SYNTH_PROFILE
static_assert(kTopProfile == voxcast::VOXCAST_SYNTH_PROFILE,
              "elaborated_config.hpp was written for another precision profile");
#endif
// The sizes the elaboration derived from the data fit the profile's fields.
static_assert(voxcast::elaborated::kValueStoreBits <= kTopProfile.value_bits);
static_assert(voxcast::elaborated::kGradientStoreBits <= kTopProfile.gradient_bits);
static_assert(voxcast::elaborated::kClassEntries <= (1 << kTopProfile.tf_addr_bits));
#else
#ifndef VOXCAST_SYNTH_PROFILE
#error "define VOXCAST_SYNTH_PROFILE as one of kVizard2, kBalanced, kPrecise, or -include elaborated_config.hpp"
#endif
constexpr voxcast::PrecisionProfile kTopProfile = voxcast::VOXCAST_SYNTH_PROFILE;
constexpr voxcast::hls::Units kTopUnits = voxcast::hls::kAllUnits;
#endif
using Word = voxcast::hls::InterpolationParams<kTopProfile>::packed_word_t;
}  // namespace

void vizard2_frame_top(const voxcast::hls::FrameState<kTopProfile, kTopUnits>* frame,
                       const Word* bank0, const Word* bank1, const Word* bank2, const Word* bank3,
                       const Word* bank4, const Word* bank5, const Word* bank6, const Word* bank7,
                       int width, int height, voxcast::hls::OutputPixel<kTopProfile>* fb,
                       std::uint64_t* samples) {
  voxcast::hls::vizard2_frame<kTopProfile, kTopUnits>(frame, bank0, bank1, bank2, bank3, bank4,
                                                      bank5, bank6, bank7, width, height, fb,
                                                      samples);
}
