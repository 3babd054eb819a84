// The presets as constexpr PrecisionProfile values, and the bridge between a
// profile value (the C++20 side: the bit-true reference, the resource model,
// reports, tests) and a profile type (the hls kernels' template parameter,
// refmodel/precision/profile_traits.hpp):
//   profile_value<T>()  the value of a traits type (kVizard2 = profile_value<Vizard2Traits>());
//   ProfileTraits<V>    the traits type of any constexpr value V (the preset's own
//                       for a preset; tests' custom profiles get one of their own).
// A test checks that kVizard2 == preset_profile("vizard2") and so on.
#pragma once

#include "refmodel/precision/heidelberg_profile.hpp"
#include "refmodel/precision/profile.hpp"
#include "refmodel/precision/profile_traits.hpp"

namespace voxcast {

template <class T>
constexpr PrecisionProfile profile_value() {
  PrecisionProfile p;
#define VOXCAST_COPY_FIELD(name) p.name = T::name;
  VOXCAST_PRECISION_PROFILE_FIELDS(VOXCAST_COPY_FIELD)
  return p;
}

template <class T>
constexpr HeidelbergProfile heidelberg_value() {
  HeidelbergProfile p;
  VOXCAST_HEIDELBERG_PROFILE_FIELDS(VOXCAST_COPY_FIELD)
  return p;
}
#undef VOXCAST_COPY_FIELD

inline constexpr PrecisionProfile kVizard2 = profile_value<Vizard2Traits>();
inline constexpr PrecisionProfile kBalanced = profile_value<BalancedTraits>();
inline constexpr PrecisionProfile kPrecise = profile_value<PreciseTraits>();

// A traits type with V's widths; for a preset, the preset's own traits type
// (ProfileTraits<kBalanced> is BalancedTraits), so the engines' and the tests'
// instantiations are one.
#define VOXCAST_TRAIT_FIELD(name) static constexpr int name = V.name;
template <PrecisionProfile V>
struct ValueTraits {
  VOXCAST_PRECISION_PROFILE_FIELDS(VOXCAST_TRAIT_FIELD)
};
template <HeidelbergProfile V>
struct HeidelbergValueTraits {
  VOXCAST_HEIDELBERG_PROFILE_FIELDS(VOXCAST_TRAIT_FIELD)
};
#undef VOXCAST_TRAIT_FIELD

template <PrecisionProfile V>
struct ProfileTraitsOf {
  using type = ValueTraits<V>;
};
template <>
struct ProfileTraitsOf<kVizard2> {
  using type = Vizard2Traits;
};
template <>
struct ProfileTraitsOf<kBalanced> {
  using type = BalancedTraits;
};
template <>
struct ProfileTraitsOf<kPrecise> {
  using type = PreciseTraits;
};
template <PrecisionProfile V>
using ProfileTraits = typename ProfileTraitsOf<V>::type;

template <HeidelbergProfile V>
struct HeidelbergTraitsOf {
  using type = HeidelbergValueTraits<V>;
};
template <>
struct HeidelbergTraitsOf<kVirimProfile> {
  using type = VirimTraits;
};
template <HeidelbergProfile V>
using HeidelbergTraits = typename HeidelbergTraitsOf<V>::type;

// The structs' defaults are the published cards, and the traits say the same.
static_assert(kVizard2 == PrecisionProfile{});
static_assert(heidelberg_value<VirimTraits>() == kVirimProfile);

}  // namespace voxcast
