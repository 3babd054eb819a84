// Classification unit (hls/classification_table.hpp, docs/pipeline.md §4), the
// three checks of STYLE.md for the vizard2, balanced and precise presets:
//  (a) hls == bit-true (refmodel/bittrue/shading.hpp) exactly: every table entry,
//      every sample value of the small formats, the rounding boundaries of every
//      address plus a fixed-seed sample of the wide one;
//  (b) the fixed-point table against the float transfer function with a bound
//      derived from the widths;
//  (c) closed forms: the vizard2 SRAM layout (2 KB, two 32-bit words per entry,
//      pack/unpack round trips), entry points addressing themselves, saturation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "hls/classification_table.hpp"
#include "refmodel/bittrue/frame_setup.hpp"
#include "refmodel/bittrue/quantize.hpp"
#include "refmodel/bittrue/shading.hpp"
#include "refmodel/precision/preset_profiles.hpp"
#include "refmodel/render/raycaster.hpp"

#include "preset_types.hpp"

namespace VOXCAST_UNITY_ID {

using namespace voxcast;
namespace bt = voxcast::bittrue;

using test::Profile;
using Presets = test::ThreePresets;
using PresetNames = test::ThreePresetNames;

// The default scene's transfer function (scenes/default.toml), its control points
// spread over the profile's value range, and its material.
ref::TransferFunction scene_tf(const PrecisionProfile& p) {
  const double top = std::ldexp(1.0, p.value_bits) - 1.0;
  const std::vector<ref::TfPoint> pts = {
      {0.0 * top, {0.0, 0.0, 0.0}, 0.0},    {0.118 * top, {0.9, 0.6, 0.5}, 0.0},
      {0.176 * top, {0.9, 0.6, 0.5}, 0.01}, {0.235 * top, {1.0, 0.9, 0.4}, 0.35},
      {0.353 * top, {0.4, 0.7, 1.0}, 0.6},  {0.784 * top, {1.0, 1.0, 1.0}, 0.02},
      {1.0 * top, {1.0, 1.0, 1.0}, 0.05}};
  return ref::TransferFunction(pts, ref::TfInterpolation::Ramp,
                               ref::Material{0.15, 0.75, 0.35, 24});
}

constexpr double kStep = 0.5;  // oversampling 2, as in the default scene

template <class T>
class ClassificationTableTest : public ::testing::Test {
 protected:
  static constexpr PrecisionProfile kP = T::value;
  using Params = hls::ClassificationParams<ProfileTraits<kP>>;
  using value_t = typename Params::value_t;

  void SetUp() override {
    tf_ = scene_tf(kP);
    fs_.profile = kP;
    fs_.class_table = bt::make_class_table(kP, tf_, kStep);
    table_ = std::make_unique<hls::ClassificationTable<ProfileTraits<kP>>>();
    ASSERT_TRUE(hls::host::load_class_table<ProfileTraits<kP>>(*table_, fs_.class_table));
  }

  static value_t value_from_raw(std::uint64_t raw) {
    value_t v;
    v.range() = raw;
    return v;
  }
  static double value_of_raw(std::uint64_t raw) {
    return std::ldexp(static_cast<double>(raw), -kP.sample_frac_bits);
  }
  // Largest raw sample value: 2^vb - 1 on the sf grid.
  static constexpr std::uint64_t kMaxRaw = ((std::uint64_t{1} << kP.value_bits) - 1)
                                           << kP.sample_frac_bits;

  // (a) for one raw sample value: address and entry, hls against bit-true.
  void expect_same(std::uint64_t raw) {
    const double x = value_of_raw(raw);
    const auto addr = hls::class_address<ProfileTraits<kP>>(value_from_raw(raw));
    ASSERT_EQ(addr.to_uint(), static_cast<unsigned>(bt::bt_class_address(kP, x))) << "value " << x;
    const bt::ClassEntry got =
        hls::host::entry_to_raw<ProfileTraits<kP>>(hls::classify(*table_, value_from_raw(raw)));
    const bt::ClassEntry& want = bt::bt_classify(fs_, x);
    ASSERT_TRUE(got.r == want.r && got.g == want.g && got.b == want.b && got.alpha == want.alpha &&
                got.ka == want.ka && got.kd == want.kd && got.ks == want.ks)
        << "value " << x;
  }

  ref::TransferFunction tf_;
  bt::FrameSetup fs_;
  std::unique_ptr<hls::ClassificationTable<ProfileTraits<kP>>> table_;
};
TYPED_TEST_SUITE(ClassificationTableTest, Presets, PresetNames);

// ---- (a) bit-exact against the bit-true reference ----------------------------------------

TYPED_TEST(ClassificationTableTest, LoadsEveryEntryBitExactly) {
  constexpr PrecisionProfile P = TestFixture::kP;
  for (int i = 0; i < TestFixture::Params::entries; ++i) {
    const bt::ClassEntry got = hls::host::entry_to_raw<ProfileTraits<P>>(this->table_->entry[i]);
    const bt::ClassEntry& want = this->fs_.class_table[static_cast<std::size_t>(i)];
    ASSERT_TRUE(got.r == want.r && got.g == want.g && got.b == want.b && got.alpha == want.alpha &&
                got.ka == want.ka && got.kd == want.kd && got.ks == want.ks)
        << "entry " << i;
  }
}

TYPED_TEST(ClassificationTableTest, EverySampleValueMatchesBitTrue) {
  constexpr PrecisionProfile P = TestFixture::kP;
  constexpr std::uint64_t max_raw = TestFixture::kMaxRaw;
  if (max_raw < (std::uint64_t{1} << 21)) {
    // vizard2 (4081 values), balanced (1 048 321): every value on the sf grid.
    for (std::uint64_t raw = 0; raw <= max_raw; ++raw) this->expect_same(raw);
    return;
  }
  // precise: both sides of every rounding boundary (i + 1/2)·2^(vb - tf_addr_bits),
  // every entry point, and a fixed-seed sample.
  const int shift = P.value_bits - P.tf_addr_bits + P.sample_frac_bits;  // raw units per entry
  for (std::uint64_t i = 0; i < (std::uint64_t{1} << P.tf_addr_bits); ++i) {
    const std::uint64_t at = i << shift;
    const std::uint64_t half = at + (std::uint64_t{1} << (shift - 1));
    for (const std::uint64_t raw : {at, at + 1, half - 1, half, half + 1})
      if (raw <= max_raw) this->expect_same(raw);
  }
  std::mt19937_64 rng(0xC1A55);
  std::uniform_int_distribution<std::uint64_t> any(0, max_raw);
  for (int n = 0; n < 200000; ++n) this->expect_same(any(rng));
  this->expect_same(max_raw);
}

// ---- (b) against the float transfer function ------------------------------------------------
// Error of a classified field at a sample value x (on the sf grid):
//   * the table is addressed at v_i = addr·2^(vb - tf_addr_bits), |x - v_i| <= dv_max with
//     dv_max = 2^(vb - tf_addr_bits - 1) (rounding to the nearest entry) or, above the last
//     entry (2^tf_addr_bits - 1)·2^(vb - tf_addr_bits), the distance to it;
//   * the float field moves by at most L·dv_max between x and v_i, L its largest slope
//     (a ramp TF is piecewise linear). For alpha the opacity correction
//     f(a) = 1 - (1 - a)^step has f'(a) = step·(1 - a)^(step - 1), at most
//     step·(1 - a_max)^(step - 1) for step < 1: L_alpha = that · max |d alpha/dv|;
//   * U(·, F) rounds by <= 2^-(F+1) and saturates 1 to 1 - 2^-F: <= 2^-F.
// So |field - float| <= 2^-F + L·dv_max.
TYPED_TEST(ClassificationTableTest, WithinDerivedBoundOfFloatTransferFunction) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const auto& pts = this->tf_.points();
  double slope_alpha = 0.0, slope_colour = 0.0, alpha_max = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const double dv = pts[i].value - pts[i - 1].value;
    if (dv <= 0.0) continue;
    slope_alpha = std::max(slope_alpha, std::abs(pts[i].alpha - pts[i - 1].alpha) / dv);
    for (int k = 0; k < 3; ++k)
      slope_colour = std::max(slope_colour, std::abs(pts[i].color[k] - pts[i - 1].color[k]) / dv);
  }
  for (const auto& pt : pts) alpha_max = std::max(alpha_max, pt.alpha);
  const double opacity_slope = kStep < 1.0 ? kStep * std::pow(1.0 - alpha_max, kStep - 1.0) : kStep;
  const double entry_spacing = std::ldexp(1.0, P.value_bits - P.tf_addr_bits);
  const double last_entry = (std::ldexp(1.0, P.tf_addr_bits) - 1.0) * entry_spacing;
  const double dv_max =
      std::max(entry_spacing / 2.0, (std::ldexp(1.0, P.value_bits) - 1.0) - last_entry);
  const double bound_alpha = std::ldexp(1.0, -P.alpha_bits) + opacity_slope * slope_alpha * dv_max;
  const double bound_colour = std::ldexp(1.0, -P.color_bits) + slope_colour * dv_max;
  const double bound_k = std::ldexp(1.0, -P.k_bits);

  std::mt19937_64 rng(0xA1FA);
  std::uniform_int_distribution<std::uint64_t> any(0, TestFixture::kMaxRaw);
  double worst_alpha = 0.0, worst_colour = 0.0;
  for (int n = 0; n < 100000; ++n) {
    const std::uint64_t raw = n == 0 ? TestFixture::kMaxRaw : any(rng);
    const double x = TestFixture::value_of_raw(raw);
    const hls::ClassEntry<ProfileTraits<P>> e = hls::classify(*this->table_, TestFixture::value_from_raw(raw));
    const ref::Classified f = this->tf_.classify(x);
    const double da = std::abs(e.alpha.to_double() - ref::opacity_correct(f.alpha, kStep));
    ASSERT_LE(da, bound_alpha) << "value " << x;
    worst_alpha = std::max(worst_alpha, da);
    const double colour[3] = {e.r.to_double(), e.g.to_double(), e.b.to_double()};
    for (int k = 0; k < 3; ++k) {
      const double dc = std::abs(colour[k] - f.color[k]);
      ASSERT_LE(dc, bound_colour) << "value " << x << " channel " << k;
      worst_colour = std::max(worst_colour, dc);
    }
    ASSERT_LE(std::abs(e.ka.to_double() - f.ka), bound_k);
    ASSERT_LE(std::abs(e.kd.to_double() - f.kd), bound_k);
    ASSERT_LE(std::abs(e.ks.to_double() - f.ks), bound_k);
  }
  this->RecordProperty("worst_alpha_error_lsb",
                       std::to_string(std::ldexp(worst_alpha, P.alpha_bits)));
  this->RecordProperty("alpha_bound_lsb", std::to_string(std::ldexp(bound_alpha, P.alpha_bits)));
  this->RecordProperty("worst_colour_error_lsb",
                       std::to_string(std::ldexp(worst_colour, P.color_bits)));
  this->RecordProperty("colour_bound_lsb", std::to_string(std::ldexp(bound_colour, P.color_bits)));
}

// ---- (c) closed forms ------------------------------------------------------------------------

// Entry i sits at value i·2^(vb - tf_addr_bits) and that value addresses it; the largest
// sample value addresses the last entry.
TYPED_TEST(ClassificationTableTest, EntryPointsAddressThemselves) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const int shift = P.value_bits - P.tf_addr_bits + P.sample_frac_bits;
  for (std::uint64_t i = 0; i < (std::uint64_t{1} << P.tf_addr_bits); ++i)
    ASSERT_EQ(hls::class_address<ProfileTraits<P>>(TestFixture::value_from_raw(i << shift)).to_uint(), i);
  EXPECT_EQ(hls::class_address<ProfileTraits<P>>(TestFixture::value_from_raw(TestFixture::kMaxRaw)).to_uint(),
            (1u << P.tf_addr_bits) - 1u);
}

// alpha = 0 stays 0, alpha = 1 saturates to 1 - 2^-alpha_bits, an intermediate alpha
// is opacity-corrected 1 - (1 - a)^step; colour 1 saturates to 1 - 2^-color_bits.
TYPED_TEST(ClassificationTableTest, OpacityCorrectionAndSaturation) {
  constexpr PrecisionProfile P = TestFixture::kP;
  const double top = std::ldexp(1.0, P.value_bits) - 1.0;
  const ref::TransferFunction tf({{0.0, {1.0, 0.0, 0.5}, 0.0},
                                  {top / 3, {1.0, 0.0, 0.5}, 0.3},
                                  {2 * top / 3, {1.0, 0.0, 0.5}, 1.0}},
                                 ref::TfInterpolation::Binary, ref::Material{1.0, 0.0, 0.5, 8.0});
  const std::vector<bt::ClassEntry> t = bt::make_class_table(P, tf, 0.25);
  const auto one = [](int bits) { return (1u << bits) - 1u; };
  EXPECT_EQ(t.front().alpha, 0u);
  EXPECT_EQ(t.back().alpha, one(P.alpha_bits));
  EXPECT_EQ(t.front().r, one(P.color_bits));
  EXPECT_EQ(t.front().g, 0u);
  EXPECT_EQ(t.front().b, 1u << (P.color_bits - 1));
  EXPECT_EQ(t.front().ka, one(P.k_bits));
  EXPECT_EQ(t.front().kd, 0u);
  const std::size_t mid = t.size() / 2;  // value top/2: the 0.3 step of the binary TF
  const double corrected = 1.0 - std::pow(0.7, 0.25);
  EXPECT_EQ(t[mid].alpha,
            static_cast<std::uint32_t>(std::floor(std::ldexp(corrected, P.alpha_bits) + 0.5)));
}

// §4.3: the vizard2 SRAM layout.
using Vizard2Params = hls::ClassificationParams<ProfileTraits<kVizard2>>;

TEST(ClassificationVizard2, TableIsTwoKilobytesOfTwo32BitWordsPerEntry) {
  static_assert(Vizard2Params::entries == 256);
  static_assert(Vizard2Params::entry_bits + 8 == 64, "56 payload bits + 8 reserved");
  const ref::TransferFunction tf = scene_tf(kVizard2);
  const std::vector<bt::ClassEntry> raw = bt::make_class_table(kVizard2, tf, kStep);
  auto table = std::make_unique<hls::ClassificationTable<ProfileTraits<kVizard2>>>();
  ASSERT_TRUE(hls::host::load_class_table<ProfileTraits<kVizard2>>(*table, raw));
  std::vector<std::uint32_t> sram;  // the two SRAMs' image, entry by entry
  for (int i = 0; i < Vizard2Params::entries; ++i) {
    const hls::Vizard2Words w = hls::pack_vizard2_words(table->entry[i]);
    sram.push_back(static_cast<std::uint32_t>(w.word[0].to_uint64()));
    sram.push_back(static_cast<std::uint32_t>(w.word[1].to_uint64()));
  }
  EXPECT_EQ(sram.size() * sizeof(std::uint32_t), 2048u);
  for (int i = 0; i < Vizard2Params::entries; ++i) {
    hls::Vizard2Words w;
    w.word[0] = sram[2 * static_cast<std::size_t>(i)];
    w.word[1] = sram[2 * static_cast<std::size_t>(i) + 1];
    EXPECT_EQ(sram[2 * static_cast<std::size_t>(i) + 1] & 0xffu, 0u)
        << "reserved bits, entry " << i;
    const bt::ClassEntry back =
        hls::host::entry_to_raw<ProfileTraits<kVizard2>>(hls::unpack_vizard2_words<ProfileTraits<kVizard2>>(w));
    const bt::ClassEntry& want = raw[static_cast<std::size_t>(i)];
    ASSERT_TRUE(back.r == want.r && back.g == want.g && back.b == want.b &&
                back.alpha == want.alpha && back.ka == want.ka && back.kd == want.kd &&
                back.ks == want.ks)
        << "entry " << i;
  }
}

TEST(ClassificationVizard2, FieldPositionsAreThoseOfTheSpec) {
  bt::ClassEntry raw;
  raw.r = 0x12, raw.g = 0x34, raw.b = 0x56, raw.alpha = 0x78;
  raw.ka = 0x9a, raw.kd = 0xbc, raw.ks = 0xde;
  const hls::Vizard2Words w = hls::pack_vizard2_words(hls::host::entry_from_raw<ProfileTraits<kVizard2>>(raw));
  EXPECT_EQ(w.word[0].to_uint64(), 0x12345678u);
  EXPECT_EQ(w.word[1].to_uint64(), 0x9abcde00u);
}

TEST(ClassificationVizard2, PackUnpackRoundTrips) {
  std::mt19937_64 rng(0x2B);
  std::uniform_int_distribution<std::uint32_t> any;
  for (int n = 0; n < 100000; ++n) {
    hls::Vizard2Words w;
    const std::uint32_t w0 = any(rng), w1 = any(rng);
    w.word[0] = w0;
    w.word[1] = w1;  // reserved bits set: unpack must ignore them
    const hls::ClassEntry<ProfileTraits<kVizard2>> e = hls::unpack_vizard2_words<ProfileTraits<kVizard2>>(w);
    const hls::Vizard2Words again = hls::pack_vizard2_words(e);
    ASSERT_EQ(again.word[0].to_uint64(), w0);
    ASSERT_EQ(again.word[1].to_uint64(), w1 & 0xffffff00u);  // reserved written as zero
    const bt::ClassEntry raw = hls::host::entry_to_raw<ProfileTraits<kVizard2>>(e);
    const bt::ClassEntry back =
        hls::host::entry_to_raw<ProfileTraits<kVizard2>>(hls::unpack_vizard2_words<ProfileTraits<kVizard2>>(again));
    ASSERT_TRUE(back.r == raw.r && back.g == raw.g && back.b == raw.b && back.alpha == raw.alpha &&
                back.ka == raw.ka && back.kd == raw.kd && back.ks == raw.ks);
  }
}

}  // namespace
