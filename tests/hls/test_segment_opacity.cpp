// Segment opacity unit (hls/segment_opacity.hpp, docs/pipeline.md §7a), the
// three checks of STYLE.md for the vizard2, balanced and precise presets:
//  (a) hls == bit-true exactly (segment_opacity vs bt_segment_alpha), every
//      alpha of the vizard2 table, fixed-seed samples of the wide ones, against
//      weights on a grid, at random and next to 1;
//  (b) against 1 - (1 - alpha_c)^w (clamped to the format's 1 - 2^-ab) within
//      the bound §7a.6 derives from the widths,
//      2^-(ab+1) + (3 ln2 + 3)·2^-(ab+g+1) (0.82 alpha LSB for g = 3);
//  (c) closed forms: w = 1 gives the table's alpha bit for bit, w = 0 gives 0,
//      alpha_c = 0 gives 0; the ray weights sum to k_out - k_in0.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "hls/segment_opacity.hpp"
#include "preset_types.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/bittrue/shading.hpp"
#include "refmodel/precision/preset_profiles.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast;
namespace bt = voxcast::bittrue;

using Presets = test::ThreePresets;
using PresetNames = test::ThreePresetNames;

template <class T>
class SegmentOpacityTest : public ::testing::Test {
 protected:
  static constexpr PrecisionProfile kP = T::value;
  using Tr = ProfileTraits<kP>;
  using S = hls::SegmentOpacityParams<Tr>;
  using addr_t = typename hls::ClassificationParams<Tr>::addr_t;
  using alpha_t = typename S::alpha_t;
  using weight_t = typename S::weight_t;

  // The bound of §7a.6 in alpha units.
  static double bound() {
    const int ab = kP.alpha_bits;
    const int F = ab + hls::widths::segment_guard_bits;
    return std::ldexp(1.0, -(ab + 1)) + (3.0 * std::log(2.0) + 3.0) * std::ldexp(1.0, -(F + 1));
  }

  // A frame set-up whose classification table holds `alphas` (raw) at addresses 0, 1, ...
  // (the rest 0), its segment tables, and the hls tables loaded from them.
  void load(const std::vector<std::uint32_t>& alphas) {
    fs_.profile = kP;
    fs_.class_table.assign(std::size_t{1} << kP.tf_addr_bits, bt::ClassEntry{});
    for (std::size_t i = 0; i < alphas.size(); ++i) fs_.class_table[i].alpha = alphas[i];
    fs_.segments = bt::make_segment_tables(kP, fs_.class_table);
    tables_ = std::make_unique<hls::SegmentOpacityTables<Tr>>();
    ASSERT_TRUE(hls::host::load_segment_tables<Tr>(*tables_, *fs_.segments));
  }

  // Weights: a grid of 2^-6, 1 -+ one LSB, and fixed-seed random tf-bit values in [0, 2).
  std::vector<std::uint64_t> weights(int random) {
    std::vector<std::uint64_t> w;
    const int tf = kP.t_frac_bits;
    for (std::uint64_t i = 0; i < 128; ++i) w.push_back(i << (tf - 6));
    const std::uint64_t one = std::uint64_t{1} << tf;
    w.push_back(one - 1);
    w.push_back(one + 1);
    w.push_back(2 * one - 1);
    w.push_back(1);
    std::mt19937_64 rng(19);
    for (int i = 0; i < random; ++i) w.push_back(rng() % (2 * one));
    return w;
  }

  // Checks one (entry, weight): bit-exact and within the bound.
  void check(int addr, std::uint64_t w_raw) {
    const int tf = kP.t_frac_bits, ab = kP.alpha_bits;
    const double w = std::ldexp(static_cast<double>(w_raw), -tf);
    const double alpha_c = bt::from_raw(fs_.class_table[static_cast<std::size_t>(addr)].alpha, ab);
    const double b = bt::bt_segment_alpha(fs_, addr, alpha_c, w);
    weight_t wh;
    write_bits(wh, w_raw);
    alpha_t ac;
    write_bits(ac, fs_.class_table[static_cast<std::size_t>(addr)].alpha);
    addr_t a = static_cast<unsigned>(addr);
    const double h = hls::segment_opacity<Tr>(*tables_, a, ac, wh).to_double();
    ASSERT_EQ(h, b) << "address " << addr << " alpha_c " << alpha_c << " w " << w;
    const double top = 1.0 - std::ldexp(1.0, -ab);
    const double exact = std::min(1.0 - std::pow(1.0 - alpha_c, w), top);
    const double err = std::abs(b - exact);
    worst_ = std::max(worst_, err);
    ASSERT_LE(err, bound()) << "address " << addr << " alpha_c " << alpha_c << " w " << w;
  }

  bt::FrameSetup fs_;
  std::unique_ptr<hls::SegmentOpacityTables<Tr>> tables_;
  double worst_ = 0.0;
};

TYPED_TEST_SUITE(SegmentOpacityTest, Presets, PresetNames);

TYPED_TEST(SegmentOpacityTest, BitExactAndWithinTheDerivedBound) {
  constexpr PrecisionProfile P = TestFixture::kP;
  // Every alpha of an 8-bit table; a fixed-seed sample (with both ends) of a wide one.
  std::vector<std::uint32_t> alphas;
  const std::uint64_t top = (std::uint64_t{1} << P.alpha_bits) - 1;
  const std::size_t entries = std::size_t{1} << P.tf_addr_bits;
  std::mt19937_64 rng(7);
  for (std::size_t i = 0; i < std::min<std::size_t>(entries, 256); ++i)
    alphas.push_back(static_cast<std::uint32_t>(
        P.alpha_bits <= 8 ? std::min<std::uint64_t>(i, top)
                          : (i < 2 ? i : (i == 2 ? top : rng() % (top + 1)))));
  this->load(alphas);
  const std::vector<std::uint64_t> ws = this->weights(P.alpha_bits <= 8 ? 200 : 100);
  for (std::size_t i = 0; i < alphas.size(); ++i)
    for (const std::uint64_t w : ws) {
      this->check(static_cast<int>(i), w);
      if (::testing::Test::HasFatalFailure()) return;
    }
  // The bound is not loose by more than the final rounding's half LSB.
  EXPECT_GT(this->worst_, std::ldexp(1.0, -(P.alpha_bits + 1)) * 0.9);
  this->RecordProperty("worst_error_lsb", std::to_string(std::ldexp(this->worst_, P.alpha_bits)));
}

TYPED_TEST(SegmentOpacityTest, ClosedForms) {
  constexpr PrecisionProfile P = TestFixture::kP;
  using Traits = typename TestFixture::Tr;
  const std::uint64_t top = (std::uint64_t{1} << P.alpha_bits) - 1;
  this->load({0, 1, static_cast<std::uint32_t>(top / 3), static_cast<std::uint32_t>(top)});
  for (int addr = 0; addr < 4; ++addr) {
    typename TestFixture::alpha_t ac;
    write_bits(ac, this->fs_.class_table[static_cast<std::size_t>(addr)].alpha);
    typename TestFixture::addr_t a = static_cast<unsigned>(addr);
    typename TestFixture::weight_t one = 1, zero = 0;
    // w = 1: the table's alpha, bit for bit; w = 0: transparent.
    EXPECT_EQ(hls::segment_opacity<Traits>(*this->tables_, a, ac, one).to_double(), ac.to_double());
    EXPECT_EQ(hls::segment_opacity<Traits>(*this->tables_, a, ac, zero).to_double(), 0.0);
  }
  // alpha_c = 0 is transparent for any weight.
  for (const std::uint64_t w : this->weights(20)) {
    typename TestFixture::weight_t wh;
    write_bits(wh, w);
    typename TestFixture::addr_t a = 0u;
    EXPECT_EQ(hls::segment_opacity<Traits>(*this->tables_, a, typename TestFixture::alpha_t(0), wh)
                  .to_double(),
              0.0);
  }
}

// §7a.1: the first and last samples' weights and the ones between sum to the
// ray's length from its entry, k_out - k_in0 (k_in0 = k_in - jitter), for rays
// of one and of several samples.
TYPED_TEST(SegmentOpacityTest, RayWeightsSumToTheLength) {
  constexpr PrecisionProfile P = TestFixture::kP;
  using Traits = typename TestFixture::Tr;
  using G = hls::GeometryParams<Traits>;
  hls::SegmentOpacityTables<Traits> t;
  t.enabled = true;
  const int tf = P.t_frac_bits;
  std::mt19937_64 rng(5);
  for (int it = 0; it < 2000; ++it) {
    const std::uint64_t k_in0 = rng() % (std::uint64_t{40} << tf);
    const std::uint64_t j = it % 3 == 0 ? 0 : rng() % (std::uint64_t{1} << tf);
    const std::uint64_t len = rng() % (static_cast<std::uint64_t>(it % 4 == 0 ? 2 : 30) << tf);
    if (len < j) continue;  // the jitter moves the only sample past the exit: a miss
    hls::RaySetup<Traits> ray;
    ray.hit = true;
    typename G::k_t kin, kout, jit;
    kin = std::ldexp(static_cast<double>(k_in0 + j), -tf);
    kout = std::ldexp(static_cast<double>(k_in0 + len), -tf);
    jit = std::ldexp(static_cast<double>(j), -tf);
    ray.k_in = kin;
    ray.k_out = kout;
    const std::uint64_t n = ((len - j) >> tf) + 1;  // floor(k_out - k_in) + 1
    ray.n = n;
    const hls::SegmentWeights<Traits> w = hls::segment_weights<Traits>(t, ray, jit);
    double sum = 0.0;
    for (std::uint64_t k = 0; k < n; ++k) sum += hls::sample_weight<Traits>(w, k, n).to_double();
    ASSERT_EQ(sum, std::ldexp(static_cast<double>(len), -tf)) << "n " << n << " j " << j;
    // The bit-true twin gives the same weights.
    bt::FrameSetup fs;
    fs.profile = P;
    fs.segments = bt::SegmentTables{};
    bt::BtRay br;
    br.hit = true;
    br.n = n;
    br.k_in = kin.to_double();
    br.k_out = kout.to_double();
    const bt::BtSegmentWeights bw = bt::bt_segment_weights(fs, br, 0, 0);  // no jitter register
    if (j == 0) {
      EXPECT_EQ(bw.first, w.first.to_double());
      EXPECT_EQ(bw.last, w.last.to_double());
    }
  }
}

}  // namespace VOXCAST_UNITY_ID
