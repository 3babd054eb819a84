// The profile and units of the synthesized VIZARD II top (TopProfile,
// TopUnits), the types of its ports and its declaration, shared by the top
// (hls/vizard2_synth_top.cpp) and its C simulation testbench
// (hls/tb/vizard2_frame_tb.cpp). Profile and units come from the scene's
// elaborated_config.hpp (`voxcast synth-script`, passed with -include), else
// the full design (AllUnits) for -DVOXCAST_SYNTH_PROFILE=Vizard2Traits |
// BalancedTraits | PreciseTraits (or the presets' value names kVizard2 |
// kBalanced | kPrecise, which the C++20 side uses). C++14.
#pragma once

#include <cstdint>
#include <type_traits>

#include "hls/interpolation_processor.hpp"
#include "hls/units.hpp"
#include "hls/vizard2_top.hpp"
#include "refmodel/precision/profile_traits.hpp"

// The preset VOXCAST_SYNTH_PROFILE names, as its traits type. An unknown name
// fails as "VOXCAST_PRESET_TRAITS_<name> was not declared".
#define VOXCAST_PRESET_TRAITS_Vizard2Traits Vizard2Traits
#define VOXCAST_PRESET_TRAITS_BalancedTraits BalancedTraits
#define VOXCAST_PRESET_TRAITS_PreciseTraits PreciseTraits
#define VOXCAST_PRESET_TRAITS_kVizard2 Vizard2Traits
#define VOXCAST_PRESET_TRAITS_kBalanced BalancedTraits
#define VOXCAST_PRESET_TRAITS_kPrecise PreciseTraits
#define VOXCAST_PRESET_CAT_(a, b) a##b
#define VOXCAST_PRESET_CAT(a, b) VOXCAST_PRESET_CAT_(a, b)
#define VOXCAST_SYNTH_PROFILE_TRAITS VOXCAST_PRESET_CAT(VOXCAST_PRESET_TRAITS_, VOXCAST_SYNTH_PROFILE)

namespace voxcast {
namespace hls {
namespace top {
#ifdef VOXCAST_ELABORATED_CONFIG  // elaborated_config.hpp, passed with -include
using TopProfile = elaborated::Profile;
using TopUnits = elaborated::Units;
#ifdef VOXCAST_SYNTH_PROFILE
static_assert(std::is_same<TopProfile, VOXCAST_SYNTH_PROFILE_TRAITS>::value,
              "elaborated_config.hpp was written for another precision profile");
#endif
// The sizes the elaboration derived from the data fit the profile's fields.
static_assert(elaborated::kValueStoreBits <= TopProfile::value_bits,
              "the volume's values do not fit the profile's value field");
static_assert(elaborated::kGradientStoreBits <= TopProfile::gradient_bits,
              "the gradients do not fit the profile's gradient field");
static_assert(elaborated::kClassEntries <= (1 << TopProfile::tf_addr_bits),
              "the transfer function needs more classification entries than the profile has");
#else
#ifndef VOXCAST_SYNTH_PROFILE
#error "define VOXCAST_SYNTH_PROFILE as one of Vizard2Traits, BalancedTraits, PreciseTraits (or kVizard2, kBalanced, kPrecise), or -include elaborated_config.hpp"
#endif
using TopProfile = VOXCAST_SYNTH_PROFILE_TRAITS;
using TopUnits = hls::AllUnits;
#endif
// The on-chip tables the top holds, as preprocessor flags for its storage
// pragmas (a pragma may name only a variable that exists): the elaborated
// configuration's VOXCAST_ELABORATED_HAS_* flags, else the full design. They
// must say what TopUnits says (checked here).
#ifdef VOXCAST_ELABORATED_CONFIG
#define VOXCAST_TOP_HAS_RSQRT VOXCAST_ELABORATED_HAS_PERSPECTIVE
#define VOXCAST_TOP_HAS_CLASSIFICATION VOXCAST_ELABORATED_HAS_CLASSIFICATION
#define VOXCAST_TOP_HAS_REFLECTANCE_MAP VOXCAST_ELABORATED_HAS_REFLECTANCE_MAP
#define VOXCAST_TOP_HAS_SPACE_LEAPING VOXCAST_ELABORATED_HAS_SPACE_LEAPING
#define VOXCAST_TOP_HAS_PARTIAL_SEGMENTS VOXCAST_ELABORATED_HAS_PARTIAL_SEGMENTS
#define VOXCAST_TOP_HAS_PREINTEGRATION VOXCAST_ELABORATED_HAS_PREINTEGRATION
#else
#define VOXCAST_TOP_HAS_RSQRT 1
#define VOXCAST_TOP_HAS_CLASSIFICATION 1
#define VOXCAST_TOP_HAS_REFLECTANCE_MAP 1
#define VOXCAST_TOP_HAS_SPACE_LEAPING 1
#define VOXCAST_TOP_HAS_PARTIAL_SEGMENTS 1
#define VOXCAST_TOP_HAS_PREINTEGRATION 1
#endif
static_assert((VOXCAST_TOP_HAS_RSQRT != 0) == TopUnits::perspective &&
                  (VOXCAST_TOP_HAS_CLASSIFICATION != 0) == TopUnits::classification &&
                  (VOXCAST_TOP_HAS_REFLECTANCE_MAP != 0) == TopUnits::reflectance_map &&
                  (VOXCAST_TOP_HAS_SPACE_LEAPING != 0) == TopUnits::space_leaping &&
                  (VOXCAST_TOP_HAS_PARTIAL_SEGMENTS != 0) == TopUnits::partial_segments &&
                  (VOXCAST_TOP_HAS_PREINTEGRATION != 0) == TopUnits::preintegration,
              "the storage flags (VOXCAST_ELABORATED_HAS_*) disagree with the elaborated units: "
              "regenerate elaborated_config.hpp with `voxcast synth-script`");
// The reflectance map's banks: bilinear mode reads entries k, k+1, k+side,
// k+side+1 of each table in one clock, two in each half of a cyclic split by
// two whatever side's parity, so two dual-port banks serve them; nearest mode
// reads one entry.
constexpr int kReflectanceBanks = hls::ReflectanceParams<TopProfile>::bilinear ? 2 : 1;

using Word = hls::InterpolationParams<TopProfile>::packed_word_t;
using Frame = hls::FrameState<TopProfile, TopUnits>;
using Pixel = hls::OutputPixel<TopProfile>;
}  // namespace top
}  // namespace hls
}  // namespace voxcast

// The top (hls/vizard2_synth_top.cpp; the testbench calls it): the frame state
// and the 8 voxel banks in, the frame buffer and the sample count out.
void vizard2_frame_top(const voxcast::hls::top::Frame* frame, const voxcast::hls::top::Word* bank0,
                       const voxcast::hls::top::Word* bank1, const voxcast::hls::top::Word* bank2,
                       const voxcast::hls::top::Word* bank3, const voxcast::hls::top::Word* bank4,
                       const voxcast::hls::top::Word* bank5, const voxcast::hls::top::Word* bank6,
                       const voxcast::hls::top::Word* bank7, int width, int height,
                       voxcast::hls::top::Pixel* fb, std::uint64_t* samples);
