// GoogleTest typed-test parameters for the hls units: a profile as a type,
// and the three presets with readable test names.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "refmodel/precision/preset_profiles.hpp"

namespace voxcast::test {

template <PrecisionProfile P>
struct Profile {
  static constexpr PrecisionProfile value = P;
};

using ThreePresets = ::testing::Types<Profile<kVizard2>, Profile<kBalanced>, Profile<kPrecise>>;

struct ThreePresetNames {
  template <class T>
  static std::string GetName(int i) {
    static const char* const names[] = {"vizard2", "balanced", "precise"};
    return names[i];
  }
};

}  // namespace voxcast::test
